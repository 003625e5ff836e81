#include "skylight/sun/spa.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "skylight/core/error.h"
#include "skylight/sun/detail/spa_tables.h"

namespace skylight::sun {
namespace {

namespace tables = skylight::sun::detail;

// Every row of the transcribed tables is filled (a short initializer list would leave zero rows).
template <std::size_t N>
constexpr bool all_rows_filled(const std::array<tables::PeriodicTerm, N>& t) {
  for (const auto& row : t) {
    if (row.a == 0.0) return false;
  }
  return true;
}
static_assert(all_rows_filled(tables::kL0) && all_rows_filled(tables::kL1) &&
              all_rows_filled(tables::kL2) && all_rows_filled(tables::kL3) &&
              all_rows_filled(tables::kL4) && all_rows_filled(tables::kL5) &&
              all_rows_filled(tables::kB0) && all_rows_filled(tables::kB1) &&
              all_rows_filled(tables::kR0) && all_rows_filled(tables::kR1) &&
              all_rows_filled(tables::kR2) && all_rows_filled(tables::kR3) &&
              all_rows_filled(tables::kR4));
static_assert(tables::kNutation.back().a != 0.0);

constexpr double kSunRadius = 0.26667;      // apparent radius of the sun [deg] (A.2)
constexpr double kFlattening = 0.99664719;  // 1 - f of the Earth, eqs. 34 and 36
constexpr double kEarthRadius = 6378140.0;  // equatorial radius [m], eqs. 35-36

double sind(double x) {
  return std::sin(deg_to_rad(x));
}
double cosd(double x) {
  return std::cos(deg_to_rad(x));
}
double tand(double x) {
  return std::tan(deg_to_rad(x));
}
double asind(double x) {
  return rad_to_deg(std::asin(std::clamp(x, -1.0, 1.0)));
}
double atan2d(double y, double x) {
  return rad_to_deg(std::atan2(y, x));
}

// Step A.2.7: into [0, 1).
double limit_zero_to_one(double x) {
  const double f = x - std::floor(x);
  return f >= 1.0 ? 0.0 : f;
}

// Eqs. (9)-(10): sum of A cos(B + C JME) over the rows of one table.
template <std::size_t N>
double periodic_sum(const std::array<tables::PeriodicTerm, N>& terms, double JME) {
  double sum = 0.0;
  for (const auto& t : terms) sum += t.a * std::cos(t.b + t.c * JME);
  return sum;
}

// (x0 + x1 JME + x2 JME^2 + ...) / 1e8 as in eq. (11).
template <std::size_t N>
double series(const std::array<double, N>& x, double JME) {
  double s = 0.0;
  for (std::size_t i = N; i-- > 0;) s = s * JME + x[i];
  return s / 1e8;
}

// Steps 3.1-3.10 and 3.8: everything that does not depend on the observer, filled into `t`.
void geocentric_sun(double JD, double JDE, SpaTrace& t) {
  t.JD = JD;
  t.JDE = JDE;
  t.JC = spa::julian_century(JD);
  t.JCE = spa::julian_century(JDE);
  t.JME = spa::julian_ephemeris_millennium(t.JCE);
  const auto helio = spa::earth_heliocentric(t.JME);
  t.L_terms = helio.L_terms;
  t.B_terms = helio.B_terms;
  t.R_terms = helio.R_terms;
  t.L = helio.L;
  t.B = helio.B;
  t.R = helio.R;
  t.Theta = spa::limit_degrees(t.L + 180.0);  // eq. (13), 3.3.2
  t.beta = -t.B;                              // eq. (14)
  t.X = spa::nutation_arguments(t.JCE);
  const auto nut = spa::nutation(t.JCE, t.X);
  t.delta_psi = nut.delta_psi;
  t.delta_epsilon = nut.delta_epsilon;
  t.epsilon0 = spa::mean_obliquity(t.JME);
  t.epsilon = t.epsilon0 / 3600.0 + t.delta_epsilon;  // eq. (25)
  t.delta_tau = spa::aberration_correction(t.R);
  t.lambda = t.Theta + t.delta_psi + t.delta_tau;  // eq. (27)
  t.nu0 = spa::mean_sidereal_time(t.JD, t.JC);
  t.nu = t.nu0 + t.delta_psi * cosd(t.epsilon);  // eq. (29)
  t.alpha = spa::geocentric_right_ascension(t.lambda, t.epsilon, t.beta);
  t.delta = spa::geocentric_declination(t.lambda, t.epsilon, t.beta);
}

double h0_prime(const SpaInput& in) {
  return -(kSunRadius + rad_to_deg(in.atmos_refract));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
namespace spa {

double limit_degrees(double x) {
  const double r = x - 360.0 * std::floor(x / 360.0);
  return r >= 360.0 ? 0.0 : r;  // x just below 0 can round to 360
}

double julian_ephemeris_day(double JD, double delta_t) {
  return JD + delta_t / 86400.0;  // eq. (5)
}

double julian_century(double JD) {
  return (JD - 2451545.0) / 36525.0;  // eqs. (6), (7)
}

double julian_ephemeris_millennium(double JCE) {
  return JCE / 10.0;  // eq. (8)
}

EarthHeliocentric earth_heliocentric(double JME) {
  EarthHeliocentric h;
  h.L_terms = {periodic_sum(tables::kL0, JME), periodic_sum(tables::kL1, JME),
               periodic_sum(tables::kL2, JME), periodic_sum(tables::kL3, JME),
               periodic_sum(tables::kL4, JME), periodic_sum(tables::kL5, JME)};
  h.B_terms = {periodic_sum(tables::kB0, JME), periodic_sum(tables::kB1, JME)};
  h.R_terms = {periodic_sum(tables::kR0, JME), periodic_sum(tables::kR1, JME),
               periodic_sum(tables::kR2, JME), periodic_sum(tables::kR3, JME),
               periodic_sum(tables::kR4, JME)};
  h.L = limit_degrees(rad_to_deg(series(h.L_terms, JME)));  // eqs. (11)-(12), 3.2.6
  h.B = rad_to_deg(series(h.B_terms, JME));                 // 3.2.7
  h.R = series(h.R_terms, JME);                             // 3.2.8 [AU]
  return h;
}

std::array<double, 5> nutation_arguments(double JCE) {
  const double c = JCE, c2 = JCE * JCE, c3 = c2 * JCE;
  return {
      297.85036 + 445267.111480 * c - 0.0019142 * c2 + c3 / 189474.0,  // X0, eq. (15)
      357.52772 + 35999.050340 * c - 0.0001603 * c2 - c3 / 300000.0,   // X1, eq. (16)
      134.96298 + 477198.867398 * c + 0.0086972 * c2 + c3 / 56250.0,   // X2, eq. (17)
      93.27191 + 483202.017538 * c - 0.0036825 * c2 + c3 / 327270.0,   // X3, eq. (18)
      125.04452 - 1934.136261 * c + 0.0020708 * c2 + c3 / 450000.0,    // X4, eq. (19)
  };
}

Nutation nutation(double JCE, const std::array<double, 5>& X) {
  double sum_psi = 0.0, sum_eps = 0.0;
  for (const auto& row : tables::kNutation) {
    double arg = 0.0;  // sum_j X_j Y_ij [deg]
    for (std::size_t j = 0; j < 5; ++j) arg += X[j] * row.y[j];
    sum_psi += (row.a + row.b * JCE) * sind(arg);  // eq. (20) [0.0001 arcsec]
    sum_eps += (row.c + row.d * JCE) * cosd(arg);  // eq. (21)
  }
  return {sum_psi / 36000000.0, sum_eps / 36000000.0};  // eqs. (22), (23)
}

double mean_obliquity(double JME) {
  // Eq. (24) in Horner form, U = JME / 10.
  static constexpr std::array<double, 11> kCoeff{
      84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67, -39.05, 7.12, 27.87, 5.79, 2.45};
  const double U = JME / 10.0;
  double s = 0.0;
  for (std::size_t i = kCoeff.size(); i-- > 0;) s = s * U + kCoeff[i];
  return s;
}

double aberration_correction(double R) {
  return -20.4898 / (3600.0 * R);  // eq. (26)
}

double mean_sidereal_time(double JD, double JC) {
  const double nu0 = 280.46061837 + 360.98564736629 * (JD - 2451545.0) + 0.000387933 * JC * JC -
                     JC * JC * JC / 38710000.0;  // eq. (28)
  return limit_degrees(nu0);                     // 3.8.2
}

double geocentric_right_ascension(double lambda, double epsilon, double beta) {
  // Eq. (30), then 3.9.2.
  return limit_degrees(
      atan2d(sind(lambda) * cosd(epsilon) - tand(beta) * sind(epsilon), cosd(lambda)));
}

double geocentric_declination(double lambda, double epsilon, double beta) {
  return asind(sind(beta) * cosd(epsilon) + cosd(beta) * sind(epsilon) * sind(lambda));  // (31)
}

Topocentric topocentric_parallax(double phi, double E, double R, double H, double delta) {
  Topocentric p;
  p.xi = 8.794 / (3600.0 * R);                                                // eq. (33)
  const double u = std::atan(kFlattening * tand(phi));                        // eq. (34) [rad]
  const double x = std::cos(u) + E / kEarthRadius * cosd(phi);                // eq. (35)
  const double y = kFlattening * std::sin(u) + E / kEarthRadius * sind(phi);  // eq. (36)
  const double denom = cosd(delta) - x * sind(p.xi) * cosd(H);
  p.delta_alpha = atan2d(-x * sind(p.xi) * sind(H), denom);                             // (37)
  p.delta_prime = atan2d((sind(delta) - y * sind(p.xi)) * cosd(p.delta_alpha), denom);  // (39)
  return p;
}

double topocentric_elevation(double phi, double delta_prime, double H_prime) {
  return asind(sind(phi) * sind(delta_prime) + cosd(phi) * cosd(delta_prime) * cosd(H_prime));
}

double refraction_correction(double P, double T, double e0, double atmos_refract) {
  // "Delta e = 0 when the sun is below the horizon" (3.14.2): below means that even the refracted
  // upper limb is below, e0 < -(sun radius + refraction at the horizon). Above that limit the
  // tangent's argument stays above +1.3 deg, so eq. (42) is finite.
  if (e0 < -(kSunRadius + atmos_refract)) return 0.0;
  return P / 1010.0 * 283.0 / (273.0 + T) * 1.02 /
         (60.0 * tand(e0 + 10.3 / (e0 + 5.11)));  // eq. (42)
}

double astronomers_azimuth(double H_prime, double phi, double delta_prime) {
  // Eq. (45), limited to [0, 360) (3.15.1).
  return limit_degrees(
      atan2d(sind(H_prime), cosd(H_prime) * sind(phi) - tand(delta_prime) * cosd(phi)));
}

double incidence_angle(double theta, double omega, double Gamma, double gamma) {
  const double c =
      cosd(theta) * cosd(omega) + sind(omega) * sind(theta) * cosd(Gamma - gamma);  // eq. (47)
  return rad_to_deg(std::acos(std::clamp(c, -1.0, 1.0)));
}

double sun_mean_longitude(double JME) {
  const double j = JME;
  const double M = 280.4664567 + 360007.6982779 * j + 0.03032028 * j * j + j * j * j / 49931.0 -
                   j * j * j * j / 15300.0 - j * j * j * j * j / 2000000.0;  // eq. (A2)
  return limit_degrees(M);
}

double equation_of_time(double M, double alpha, double delta_psi, double epsilon) {
  double E = 4.0 * (M - 0.0057183 - alpha + delta_psi * cosd(epsilon));  // eq. (A1) [min]
  // A.1: "limit E if its absolute value is greater than 20 minutes, by adding or subtracting
  // 1440".
  if (E < -20.0) E += 1440.0;
  if (E > 20.0) E -= 1440.0;
  return E;
}

}  // namespace spa

// ---------------------------------------------------------------------------------------------

ParameterSpec time_spec(std::string absent) {
  return {
      .name = "time",
      .kind = ParameterKind::text,
      .default_value = Absent{std::move(absent)},
      .description =
          "date and time, ISO 8601 with seconds and UTC offset, e.g. 2003-10-17T12:30:30-07:00 or "
          "2003-10-17T19:30:30Z"};
}

const ParameterSchema<SpaInput>& spa_input_schema() {
  // Ranges: the SPA's own limits where the paper states them (3.1: Delta UT1; Delta T: the
  // report's +-8000 s for its -2000 .. 6000 years), else the physically sensible span. Defaults:
  // a standard atmosphere at sea level, Delta T of the 2020s.
  static const ParameterSchema<SpaInput> schema = [] {
    ParameterSchema<SpaInput> s;
    s.number(&SpaInput::latitude,
             {.name = "lat",
              .unit = "deg",
              .min = -90.0,
              .max = 90.0,
              .default_value = Required{},
              .description = "geodetic latitude of the observer, north positive"},
             kDegree)
        .number(&SpaInput::longitude,
                {.name = "lon",
                 .unit = "deg",
                 .min = -180.0,
                 .max = 180.0,
                 .default_value = Required{},
                 .description = "geographic longitude of the observer, east positive"},
                kDegree)
        .number(&SpaInput::elevation, {.name = "elevation",
                                       .unit = "m",
                                       .min = -12000.0,
                                       .max = 100000.0,
                                       .default_value = ParameterValue(0.0),
                                       .description = "observer elevation above sea level"})
        .number(&SpaInput::pressure,
                {.name = "pressure",
                 .unit = "mbar",
                 .min = 0.0,
                 .max = 2000.0,
                 .default_value = ParameterValue(1013.25),
                 .description = "annual average local air pressure (for refraction)"})
        .number(&SpaInput::temperature,
                {.name = "temperature",
                 .unit = "degC",
                 .min = -100.0,
                 .max = 100.0,
                 .default_value = ParameterValue(12.0),
                 .description = "annual average local air temperature (for refraction)"})
        .number(&SpaInput::delta_t, {.name = "delta-t",
                                     .unit = "s",
                                     .min = -8000.0,
                                     .max = 8000.0,
                                     .default_value = ParameterValue(69.0),
                                     .description = "Delta T = TT - UT (about 69 s in 2015-2025)"})
        .number(&SpaInput::delta_ut1, {.name = "delta-ut1",
                                       .unit = "s",
                                       .min = -1.0,
                                       .max = 1.0,
                                       .default_value = ParameterValue(0.0),
                                       .description = "Delta UT1 = UT1 - UTC"})
        .number(&SpaInput::atmos_refract,
                {.name = "atmos-refract",
                 .unit = "deg",
                 .min = 0.0,
                 .max = 3.0,
                 .default_value = ParameterValue(0.5667),
                 .description = "atmospheric refraction at sunrise and sunset"},
                kDegree)
        .number(&SpaInput::slope,
                {.name = "slope",
                 .unit = "deg",
                 .min = 0.0,
                 .max = 180.0,
                 .default_value = ParameterValue(0.0),
                 .description = "surface slope from horizontal (for the incidence angle)"},
                kDegree)
        .number(&SpaInput::azimuth_rotation,
                {.name = "azimuth-rotation",
                 .unit = "deg",
                 .min = -360.0,
                 .max = 360.0,
                 .default_value = ParameterValue(0.0),
                 .description = "surface azimuth from south, positive towards west"},
                kDegree);
    return s;
  }();
  return schema;
}

const std::vector<ParameterSpec>& spa_parameter_specs() {
  static const std::vector<ParameterSpec> specs = spa_input_schema().specs();
  return specs;
}

const ParameterSpec& spa_parameter_spec(std::string_view name) {
  const ParameterSpec* spec = spa_input_schema().find(name);
  SKYLIGHT_CHECK(spec != nullptr, "no SPA parameter named " + std::string(name));
  return *spec;
}

ParameterSpec spa_parameter_spec(std::string_view name, std::string absent) {
  ParameterSpec spec = spa_parameter_spec(name);
  spec.default_value = Absent{std::move(absent)};
  return spec;
}

void validate(const SpaInput& in) {
  validate(in.time, "SpaInput.time");
  if (in.time.year < -2000 || in.time.year > 6000) {
    throw InvalidArgument("SpaInput.time.year = " + std::to_string(in.time.year) +
                          " is out of range [-2000, 6000] (the SPA's validity)");
  }
  spa_input_schema().validate(in, "SpaInput");
}

SpaResult solar_position(const SpaInput& in) {
  validate(in);
  return solar_position_at(julian_day(in.time, in.delta_ut1), in);
}

SpaResult solar_position_at(double jd, const SpaInput& in) {
  validate(in);
  if (!std::isfinite(jd)) throw InvalidArgument(fmt::format("jd = {} is not finite", jd));
  SpaResult r;
  SpaTrace& t = r.trace;
  geocentric_sun(jd, spa::julian_ephemeris_day(jd, in.delta_t), t);

  const double phi = rad_to_deg(in.latitude);
  const double sigma = rad_to_deg(in.longitude);
  t.H = spa::limit_degrees(t.nu + sigma - t.alpha);  // eq. (32), 3.11
  const auto topo = spa::topocentric_parallax(phi, in.elevation, t.R, t.H, t.delta);
  t.xi = topo.xi;
  t.delta_alpha = topo.delta_alpha;
  t.delta_prime = topo.delta_prime;
  t.alpha_prime = t.alpha + t.delta_alpha;  // eq. (38)
  t.H_prime = t.H - t.delta_alpha;          // eq. (40)
  t.e0 = spa::topocentric_elevation(phi, t.delta_prime, t.H_prime);
  t.delta_e =
      spa::refraction_correction(in.pressure, in.temperature, t.e0, rad_to_deg(in.atmos_refract));
  t.e = t.e0 + t.delta_e;  // eq. (43)
  t.theta = 90.0 - t.e;    // eq. (44)
  t.Gamma = spa::astronomers_azimuth(t.H_prime, phi, t.delta_prime);
  t.Phi = spa::limit_degrees(t.Gamma + 180.0);  // eq. (46), 3.15.2
  t.I =
      spa::incidence_angle(t.theta, rad_to_deg(in.slope), t.Gamma, rad_to_deg(in.azimuth_rotation));
  t.M = spa::sun_mean_longitude(t.JME);
  t.E = spa::equation_of_time(t.M, t.alpha, t.delta_psi, t.epsilon);

  r.zenith = std::clamp(deg_to_rad(t.theta), 0.0, kPi);
  r.azimuth = deg_to_rad(t.Phi);
  if (r.azimuth >= 2 * kPi) r.azimuth = 0.0;
  r.incidence = deg_to_rad(t.I);
  r.equation_of_time = t.E;
  return r;
}

// ---------------------------------------------------------------------------------------------

RiseTransitSetUt rise_transit_set_ut_day(int year, int month, int day, const SpaInput& in) {
  validate(in);
  DateTime date;
  date.year = year;
  date.month = month;
  date.day = day;
  validate(date, "date");
  RiseTransitSetUt r;
  const double phi = rad_to_deg(in.latitude);
  const double sigma = rad_to_deg(in.longitude);
  const double h0p = h0_prime(in);

  // A.2.1: apparent sidereal time at Greenwich at 0 UT (eq. 29).
  const double jd0 = julian_day(year, month, static_cast<double>(day));
  SpaTrace t;
  geocentric_sun(jd0, spa::julian_ephemeris_day(jd0, in.delta_t), t);
  r.nu = t.nu;
  // A.2.2: geocentric alpha, delta (eqs. 30-31) at 0 TT of the days D-1, D, D+1.
  for (int i = 0; i < 3; ++i) {
    const double jde = jd0 + (i - 1);
    geocentric_sun(jde, jde, t);
    r.alpha[i] = t.alpha;
    r.delta[i] = t.delta;
  }
  // A.2.3: approximate sun transit time, eq. (A3).
  const double m0 = (r.alpha[1] - sigma - r.nu) / 360.0;
  // A.2.4: eq. (A4). Its argument num / den lies outside [-1, 1] when the sun never crosses h0'
  // (comparing num with den avoids dividing by cos(phi) = 0 at the poles).
  const double num = sind(h0p) - sind(phi) * sind(r.delta[1]);
  const double den = cosd(phi) * cosd(r.delta[1]);
  if (num < -den) {
    r.kind = DayKind::polar_day;
  } else if (num > den) {
    r.kind = DayKind::polar_night;
  } else {
    r.H0 = rad_to_deg(std::acos(std::clamp(num / den, -1.0, 1.0)));  // in [0, 180]
  }
  // A.2.5-A.2.7: eqs. (A5), (A6), limited to [0, 1).
  r.m = {limit_zero_to_one(m0), limit_zero_to_one(m0 - r.H0 / 360.0),
         limit_zero_to_one(m0 + r.H0 / 360.0)};

  // A.2.10: differences of alpha and delta between the days; |x| > 2 (alpha wrapping through
  // 360) is limited into [0, 1) as in A.2.7.
  const auto limited = [](double x) { return std::abs(x) > 2.0 ? limit_zero_to_one(x) : x; };
  const double a = limited(r.alpha[1] - r.alpha[0]), b = limited(r.alpha[2] - r.alpha[1]);
  const double ap = limited(r.delta[1] - r.delta[0]), bp = limited(r.delta[2] - r.delta[1]);
  const double c = b - a, cp = bp - ap;
  std::array<double, 3> delta_p{};
  for (int i = 0; i < 3; ++i) {
    const double nu_i = r.nu + 360.985647 * r.m[i];                     // A.2.8, eq. (A7)
    const double n_i = r.m[i] + in.delta_t / 86400.0;                   // A.2.9, eq. (A8)
    const double alpha_p = r.alpha[1] + n_i * (a + b + c * n_i) / 2.0;  // eq. (A9)
    delta_p[i] = r.delta[1] + n_i * (ap + bp + cp * n_i) / 2.0;         // eq. (A10)
    // A.2.11, eq. (A11): limited to +-360 first, then into [-180, 180].
    double Hp = std::fmod(nu_i + sigma - alpha_p, 360.0);
    if (Hp <= -180.0) Hp += 360.0;
    if (Hp >= 180.0) Hp -= 360.0;
    r.H_prime[i] = Hp;
    // A.2.12, eq. (A12).
    r.h[i] = asind(sind(phi) * sind(delta_p[i]) + cosd(phi) * cosd(delta_p[i]) * cosd(Hp));
  }
  r.transit = r.m[0] - r.H_prime[0] / 360.0;  // A.2.13, eq. (A13)
  if (r.kind == DayKind::normal) {
    // A.2.14, eq. (A14), and A.2.15.
    const auto correction = [&](int i) {
      return (r.h[i] - h0p) / (360.0 * cosd(delta_p[i]) * cosd(phi) * sind(r.H_prime[i]));
    };
    r.sunrise = r.m[1] + correction(1);
    r.sunset = r.m[2] + correction(2);
  }
  return r;
}

SunEvents sun_events(const SpaInput& in) {
  validate(in);
  const int offset = in.time.utc_offset_minutes;
  DateTime midnight = in.time;
  midnight.hour = midnight.minute = 0;
  midnight.second = 0.0;
  const double start = julian_day(midnight);  // local 00:00 as a UTC Julian Day
  const double end = start + 1.0;
  // 0 UT of the UT day that contains local midnight. The local day overlaps this UT day and the
  // next; A.2's events of a UT day can lie slightly outside it (R, S, T are m_i plus a small
  // correction), so the UT days before and after those two are searched as well.
  const double jd0 = std::floor(start - 0.5) + 0.5;
  const double ut1_to_utc = -in.delta_ut1 / 86400.0;

  SunEvents ev;
  const auto consider = [&](std::optional<SunEvent>& slot, double jd) {
    if (jd < start || jd >= end) return;
    if (slot && slot->jd <= jd) return;  // keep the first
    slot = SunEvent{jd, date_time_from_julian_day(jd, offset, 3)};
  };
  for (int k = -1; k <= 2; ++k) {
    const double day0 = jd0 + k;
    const DateTime d = date_time_from_julian_day(day0, 0);
    const auto rts = rise_transit_set_ut_day(d.year, d.month, d.day, in);
    consider(ev.transit, day0 + rts.transit + ut1_to_utc);
    if (rts.sunrise) consider(ev.sunrise, day0 + *rts.sunrise + ut1_to_utc);
    if (rts.sunset) consider(ev.sunset, day0 + *rts.sunset + ut1_to_utc);
  }
  if (!ev.sunrise && !ev.sunset) {
    // No crossing of h0' on this date: above or below all day, judged at the highest point.
    const double jd_noon = ev.transit ? ev.transit->jd : start + 0.5;
    const SpaResult noon = solar_position_at(jd_noon - ut1_to_utc, in);
    ev.kind = noon.trace.e0 >= h0_prime(in) ? DayKind::polar_day : DayKind::polar_night;
  }
  return ev;
}

}  // namespace skylight::sun
