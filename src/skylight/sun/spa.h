// The NREL Solar Position Algorithm (SPA): I. Reda & A. Andreas, "Solar position algorithm for
// solar radiation applications", Solar Energy 76(5), 577-589 (2004); NREL/TP-560-34302 (revised
// January 2008). Equation, step and table numbers below are the paper's. Claimed uncertainty
// +-0.0003 deg for the years -2000 .. 6000.
//
// Units: the public inputs and results use radians (project convention: zenith in [0, pi],
// azimuth from north towards east in [0, 2 pi), as SunPosition). The paper works in degrees, so
// the step functions in namespace `spa` and the trace structs take and return the paper's
// quantities in the paper's units (degrees unless stated) and notation, for verification
// against its worked example (Table A5.1).
#pragma once

#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include "skylight/core/math.h"
#include "skylight/core/parameters.h"
#include "skylight/sun/time.h"

namespace skylight::sun {

// Time, observer and surface. Every field is checked by validate() against
// spa_parameter_specs() (the ranges below are the specs'); a NaN or out-of-range value throws
// InvalidArgument naming the field.
struct SpaInput {
  DateTime time;              // local civil time and its UTC offset; year in [-2000, 6000]
  double delta_ut1 = 0.0;     // Delta UT1 = UT1 - UTC [s], [-1, 1] (eq. 3: |Delta UT1| < 1 s)
  double delta_t = 69.0;      // Delta T = TT - UT [s], [-8000, 8000] (eq. 2); ~69 s in 2015-2025
  double latitude = 0.0;      // phi, geodetic latitude [rad], [-pi/2, pi/2], north positive
  double longitude = 0.0;     // sigma, geographic longitude [rad], [-pi, pi], east positive
  double elevation = 0.0;     // E, observer elevation [m], [-12000, 100000]
  double pressure = 1013.25;  // P, annual average local pressure [mbar = hPa], [0, 2000]
  double temperature = 12.0;  // T, annual average local temperature [deg C], [-100, 100]
  double atmos_refract = 0.5667 * kDegree;  // refraction at sunrise/sunset [rad], [0, 3 deg]
  double slope = 0.0;                       // omega, surface tilt from horizontal [rad], [0, pi]
  double azimuth_rotation = 0.0;  // gamma, surface azimuth from south, + towards west [rad],
                                  // [-2 pi, 2 pi]
};

// The numeric inputs of SpaInput declared once (core/parameters.h): the spec names are the
// command-line flags (`--lat`, `--lon`, `--elevation`, `--pressure`, `--temperature`,
// `--delta-t`, `--delta-ut1`, `--atmos-refract`, `--slope`, `--azimuth-rotation`), angles in
// degrees; the schema binds them to the fields (radians). `time` is not in the schema: it is
// ISO 8601 text (parse_iso8601()).
const ParameterSchema<SpaInput>& spa_input_schema();
// The time of a solar position as text: --time, ISO 8601 with seconds and UTC offset (sun/time.h);
// `absent`: what an operation does without it.
ParameterSpec time_spec(std::string absent);
const std::vector<ParameterSpec>& spa_parameter_specs();
// The spec named `name` (a programming error if there is none).
const ParameterSpec& spa_parameter_spec(std::string_view name);
// The same spec without a default, for an operation that needs it only sometimes: `absent` says
// when (e.g. "needed with --from-time").
ParameterSpec spa_parameter_spec(std::string_view name, std::string absent);

// Checks in.time (validate(DateTime), year in [-2000, 6000]) and every number against
// spa_parameter_specs(); throws InvalidArgument naming the field.
void validate(const SpaInput& in);

// Every intermediate quantity of one SPA evaluation (paper's notation; degrees unless stated).
struct SpaTrace {
  double JD = 0.0, JDE = 0.0;             // Julian (Ephemeris) Day [day], eqs. 4-5
  double JC = 0.0, JCE = 0.0, JME = 0.0;  // Julian (Ephemeris) century / millennium, eqs. 6-8
  std::array<double, 6> L_terms{};        // L0..L5 [1e-8 rad], eq. 10 (Table A4.2)
  std::array<double, 2> B_terms{};        // B0, B1 [1e-8 rad]
  std::array<double, 5> R_terms{};        // R0..R4 [1e-8 AU]
  double L = 0.0;                         // Earth heliocentric longitude, eqs. 11-12, [0, 360)
  double B = 0.0;                         // Earth heliocentric latitude (3.2.7)
  double R = 0.0;                         // Earth radius vector [AU] (3.2.8)
  double Theta = 0.0, beta = 0.0;         // geocentric longitude and latitude, eqs. 13-14
  std::array<double, 5> X{};              // X0..X4, eqs. 15-19
  double delta_psi = 0.0, delta_epsilon = 0.0;  // nutation in longitude / obliquity, eqs. 22-23
  double epsilon0 = 0.0;                        // mean obliquity of the ecliptic [arcsec], eq. 24
  double epsilon = 0.0;                         // true obliquity of the ecliptic, eq. 25
  double delta_tau = 0.0;                       // aberration correction, eq. 26
  double lambda = 0.0;                          // apparent sun longitude, eq. 27
  double nu0 = 0.0, nu = 0.0;       // mean / apparent sidereal time at Greenwich, eqs. 28-29
  double alpha = 0.0, delta = 0.0;  // geocentric right ascension / declination, eqs. 30-31
  double H = 0.0;                   // observer local hour angle, eq. 32, [0, 360)
  double xi = 0.0;                  // equatorial horizontal parallax of the sun, eq. 33
  double delta_alpha = 0.0;         // parallax in the sun right ascension, eq. 37
  double alpha_prime = 0.0;         // topocentric right ascension, eq. 38
  double delta_prime = 0.0;         // topocentric declination, eq. 39
  double H_prime = 0.0;             // topocentric local hour angle, eq. 40
  double e0 = 0.0;                  // topocentric elevation without refraction, eq. 41
  double delta_e = 0.0;             // atmospheric refraction correction, eq. 42
  double e = 0.0;                   // topocentric elevation, eq. 43
  double theta = 0.0;               // topocentric zenith angle, eq. 44
  double Gamma = 0.0;               // astronomers' azimuth (westward from south), eq. 45
  double Phi = 0.0;                 // topocentric azimuth (eastward from north), eq. 46
  double I = 0.0;                   // surface incidence angle, eq. 47
  double M = 0.0;                   // sun mean longitude, eq. A2, [0, 360)
  double E = 0.0;                   // equation of time [minutes of time], eq. A1
};

struct SpaResult {
  double zenith = 0.0;            // topocentric zenith angle with refraction [rad], [0, pi]
  double azimuth = 0.0;           // topocentric azimuth from north towards east [rad], [0, 2 pi)
  double incidence = 0.0;         // angle between the sun and the surface normal [rad], [0, pi]
  double equation_of_time = 0.0;  // apparent minus mean solar time [minutes], [-20, 20]
  SpaTrace trace;
};

// The SPA at in.time (steps 3.1-3.16 and A.1).
SpaResult solar_position(const SpaInput& in);
// The same at the given Julian Day (UT); in.time and in.delta_ut1 are not used (in.time is still
// validated).
SpaResult solar_position_at(double jd, const SpaInput& in);

// ---------------------------------------------------------------------------------------------
// Sunrise, sun transit and sunset (App. A.2). Sunrise and sunset are the instants when the
// geocentric elevation of the sun's centre is h0' = -(0.26667 deg + atmos_refract) (the sun's
// radius plus the refraction at the horizon; -0.8333 deg in the paper).

enum class DayKind {
  normal,       // the sun rises and sets (A4 has a solution)
  polar_day,    // the sun stays above h0' all day
  polar_night,  // the sun stays below h0' all day
};

// A.2 as published, for the UT day year-month-day (0 UT to 24 UT). Fractions of that day, in UT;
// the published example converts them to local time as frac(x + utc_offset / 24 h), which can
// give an event of the neighbouring local day (see sun_events()).
struct RiseTransitSetUt {
  DayKind kind = DayKind::normal;
  double transit = 0.0;             // T [fraction of the UT day], eq. A13; always defined
  std::optional<double> sunrise;    // R [fraction of the UT day], eq. A14; only if kind == normal
  std::optional<double> sunset;     // S [fraction of the UT day], step A.2.15; only if normal
  double nu = 0.0;                  // apparent sidereal time at Greenwich at 0 UT (A.2.1)
  std::array<double, 3> alpha{};    // geocentric alpha at 0 TT of the days D-1, D, D+1 (A.2.2)
  std::array<double, 3> delta{};    // geocentric delta at 0 TT of the days D-1, D, D+1
  double H0 = 0.0;                  // local hour angle at sunrise/sunset, eq. A4; 0 unless normal
  std::array<double, 3> m{};        // m0, m1, m2 limited to [0, 1) (A3, A5, A6, A.2.7)
  std::array<double, 3> H_prime{};  // H'_i for transit, sunrise, sunset, eq. A11, [-180, 180]
  std::array<double, 3> h{};        // sun altitude h_i, eq. A12
};

// Uses in.latitude, in.longitude, in.delta_t and in.atmos_refract (all of `in` is validated).
RiseTransitSetUt rise_transit_set_ut_day(int year, int month, int day, const SpaInput& in);

struct SunEvent {
  double jd = 0.0;  // Julian Day of the event, in UTC (UT - Delta UT1)
  DateTime local;   // civil time at in.time's UTC offset, to the millisecond
};

// Sunrise, transit and sunset on the local calendar date of in.time (00:00 to 24:00 at its UTC
// offset), from A.2 applied to the UT days around it. An event that does not occur on that date
// is absent: sunrise and sunset both absent means kind is polar_day or polar_night (decided by
// the sun's elevation at transit); at high latitudes one of them may be absent on a normal day.
// If an event occurs twice on the date (possible only near the polar circles), the first is kept.
struct SunEvents {
  DayKind kind = DayKind::normal;
  std::optional<SunEvent> sunrise, transit, sunset;
};

SunEvents sun_events(const SpaInput& in);

// ---------------------------------------------------------------------------------------------
// The individual steps, in the paper's units (degrees unless stated), for tests and for callers
// that need one quantity. No validation.
namespace spa {

double julian_ephemeris_day(double JD, double delta_t);  // eq. 5
double julian_century(double JD);                        // eq. 6 (eq. 7 with JDE)
double julian_ephemeris_millennium(double JCE);          // eq. 8

struct EarthHeliocentric {
  std::array<double, 6> L_terms{};  // [1e-8 rad], eqs. 9-10
  std::array<double, 2> B_terms{};
  std::array<double, 5> R_terms{};
  double L = 0.0, B = 0.0, R = 0.0;  // [deg], [deg], [AU], eqs. 11-12, 3.2.6-3.2.8
};
EarthHeliocentric earth_heliocentric(double JME);

std::array<double, 5> nutation_arguments(double JCE);  // X0..X4, eqs. 15-19
struct Nutation {
  double delta_psi = 0.0, delta_epsilon = 0.0;  // eqs. 22-23
};
Nutation nutation(double JCE, const std::array<double, 5>& X);  // eqs. 20-23, Table A4.3

double mean_obliquity(double JME);                // epsilon0 [arcsec], eq. 24
double aberration_correction(double R);           // delta tau, eq. 26
double mean_sidereal_time(double JD, double JC);  // nu0, eq. 28 and 3.8.2
double geocentric_right_ascension(double lambda, double epsilon, double beta);  // eq. 30
double geocentric_declination(double lambda, double epsilon, double beta);      // eq. 31

struct Topocentric {
  double xi = 0.0;           // eq. 33
  double delta_alpha = 0.0;  // eq. 37
  double delta_prime = 0.0;  // eq. 39
};
// phi [deg], E [m], R [AU], H and delta [deg]: eqs. 33-37, 39.
Topocentric topocentric_parallax(double phi, double E, double R, double H, double delta);

double topocentric_elevation(double phi, double delta_prime, double H_prime);  // e0, eq. 41
// Delta e, eq. 42; 0 when the sun is below the horizon, taken as e0 < -(0.26667 + atmos_refract).
double refraction_correction(double P, double T, double e0, double atmos_refract);
double astronomers_azimuth(double H_prime, double phi, double delta_prime);      // Gamma, eq. 45
double incidence_angle(double theta, double omega, double Gamma, double gamma);  // I, eq. 47
double sun_mean_longitude(double JME);                                           // M, eq. A2
// E [minutes], eq. A1, limited to [-20, 20] minutes.
double equation_of_time(double M, double alpha, double delta_psi, double epsilon);

double limit_degrees(double x);  // 3.2.6: into [0, 360)

}  // namespace spa
}  // namespace skylight::sun
