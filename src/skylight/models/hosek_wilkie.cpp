#include "skylight/models/hosek_wilkie.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/models/detail/hosek_kernel.h"

namespace skylight {
namespace {

constexpr int kAlbedoKnots = 2;
constexpr int kTurbidityKnots = 10;
constexpr int kControlPoints = 6;  // quintic Bezier
constexpr int kParams = 9;
// 2013 solar function: 45 cubic pieces per (band, turbidity), 4 coefficients each.
constexpr int kSolarPieces = 45;
constexpr int kSolarOrder = 4;
constexpr int kLimbDarkeningOrder = 6;  // 5th-order polynomial: 6 coefficients
// Wavelength resolution of the XYZ integrations of the spectral model [nm] (CMF table step).
constexpr double kIntegrationStepNm = 1.0;
constexpr double kCmfFirstNm = 360.0;

// One 2012 dataset: params[ch][albedo][turbidity][control point][9], radiance[ch][albedo][turb][cp]
// (the v1.4a C arrays' order: per channel, albedo 0 block of 10 turbidities, then albedo 1).
struct Dataset2012 {
  int channels = 0;
  std::vector<double> params, radiance;
  const double* params_at(int ch, int alb, int turb_index) const {
    return params.data() +
           ((static_cast<std::size_t>(ch) * kAlbedoKnots + alb) * kTurbidityKnots + turb_index) *
               kControlPoints * kParams;
  }
  const double* radiance_at(int ch, int alb, int turb_index) const {
    return radiance.data() +
           ((static_cast<std::size_t>(ch) * kAlbedoKnots + alb) * kTurbidityKnots + turb_index) *
               kControlPoints;
  }
};

// Channel column -> index: "X"/"Y"/"Z", "R"/"G"/"B", or a band wavelength 320..720.
int channel_index(HwDataset d, const std::string& key) {
  if (d == HwDataset::ciexyz) return key == "X" ? 0 : key == "Y" ? 1 : key == "Z" ? 2 : -1;
  if (d == HwDataset::rgb) return key == "R" ? 0 : key == "G" ? 1 : key == "B" ? 2 : -1;
  for (int b = 0; b < kHwBands; ++b)
    if (key == fmt::format("{}", static_cast<int>(kHwFirstBandNm + kHwBandStepNm * b))) return b;
  return -1;
}

// Integer key column with range check (files name the row on error).
int int_field(const data::CsvTable& t, std::size_t row, std::size_t col, int min, int max,
              std::string_view path) {
  const double v = t.number(row, col);
  if (v != std::floor(v) || v < min || v > max)
    throw IoError(fmt::format("{} row {}: {} = {} is not an integer in [{}, {}]", path, row + 2,
                              t.header()[col], v, min, max));
  return static_cast<int>(v);
}

Dataset2012 load_2012(HwDataset d, std::string_view params_path, std::string_view radiance_path) {
  Dataset2012 out;
  out.channels = d == HwDataset::spectral ? kHwBands : 3;
  out.params.assign(static_cast<std::size_t>(out.channels) * kAlbedoKnots * kTurbidityKnots *
                        kControlPoints * kParams,
                    0.0);
  out.radiance.assign(
      static_cast<std::size_t>(out.channels) * kAlbedoKnots * kTurbidityKnots * kControlPoints,
      0.0);
  {
    const auto t = data::load_table(params_path, true, 4 + kParams);
    std::vector<bool> seen(out.params.size() / kParams, false);
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const int ch = channel_index(d, t.text(r, 0));
      if (ch < 0)
        throw IoError(
            fmt::format("{} row {}: unknown channel '{}'", params_path, r + 2, t.text(r, 0)));
      const int alb = int_field(t, r, 1, 0, 1, params_path);
      const int turb = int_field(t, r, 2, 1, kTurbidityKnots, params_path);
      const int cp = int_field(t, r, 3, 0, kControlPoints - 1, params_path);
      const std::size_t slot =
          ((static_cast<std::size_t>(ch) * kAlbedoKnots + alb) * kTurbidityKnots + (turb - 1)) *
              kControlPoints +
          cp;
      if (seen[slot]) throw IoError(fmt::format("{} row {}: duplicate entry", params_path, r + 2));
      seen[slot] = true;
      // Columns A..G,I,H are copied in storage order (HwConfig keeps it).
      for (int k = 0; k < kParams; ++k) out.params[slot * kParams + k] = t.number(r, 4 + k);
    }
    if (std::find(seen.begin(), seen.end(), false) != seen.end())
      throw IoError(fmt::format("{}: missing entries", params_path));
  }
  {
    const auto t = data::load_table(radiance_path, true, 3 + kControlPoints);
    std::vector<bool> seen(out.radiance.size() / kControlPoints, false);
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const int ch = channel_index(d, t.text(r, 0));
      if (ch < 0)
        throw IoError(
            fmt::format("{} row {}: unknown channel '{}'", radiance_path, r + 2, t.text(r, 0)));
      const int alb = int_field(t, r, 1, 0, 1, radiance_path);
      const int turb = int_field(t, r, 2, 1, kTurbidityKnots, radiance_path);
      const std::size_t slot =
          (static_cast<std::size_t>(ch) * kAlbedoKnots + alb) * kTurbidityKnots + (turb - 1);
      if (seen[slot])
        throw IoError(fmt::format("{} row {}: duplicate entry", radiance_path, r + 2));
      seen[slot] = true;
      for (int k = 0; k < kControlPoints; ++k)
        out.radiance[slot * kControlPoints + k] = t.number(r, 3 + k);
    }
    if (std::find(seen.begin(), seen.end(), false) != seen.end())
      throw IoError(fmt::format("{}: missing entries", radiance_path));
  }
  return out;
}

const Dataset2012& dataset(HwDataset d) {
  static const Dataset2012 spectral =
      load_2012(HwDataset::spectral, "hosek_wilkie/hw2012_spectral_params.csv",
                "hosek_wilkie/hw2012_spectral_radiance.csv");
  static const Dataset2012 xyz =
      load_2012(HwDataset::ciexyz, "hosek_wilkie/hw2012_ciexyz_params.csv",
                "hosek_wilkie/hw2012_ciexyz_radiance.csv");
  static const Dataset2012 rgb = load_2012(HwDataset::rgb, "hosek_wilkie/hw2012_rgb_params.csv",
                                           "hosek_wilkie/hw2012_rgb_radiance.csv");
  switch (d) {
    case HwDataset::spectral:
      return spectral;
    case HwDataset::ciexyz:
      return xyz;
    case HwDataset::rgb:
      return rgb;
  }
  return xyz;
}

// 2013 solar data: coefficients[band][turbidity 0..9][piece][c3, c2, c1, c0] and limb darkening.
struct SolarData {
  std::vector<double> coefficients;
  std::array<std::array<double, kLimbDarkeningOrder>, kHwBands> limb{};
  const double* piece(int band, int turb_index, int p) const {
    return coefficients.data() +
           ((static_cast<std::size_t>(band) * kTurbidityKnots + turb_index) * kSolarPieces + p) *
               kSolarOrder;
  }
};

const SolarData& solar_data() {
  static const SolarData s = [] {
    SolarData out;
    out.coefficients.assign(
        static_cast<std::size_t>(kHwBands) * kTurbidityKnots * kSolarPieces * kSolarOrder, 0.0);
    constexpr std::string_view kSolarPath = "hosek_wilkie/hw2013_solar_radiance.csv";
    const auto t = data::load_table(kSolarPath, true, 3 + kSolarOrder);
    std::vector<bool> seen(out.coefficients.size() / kSolarOrder, false);
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const int band = channel_index(HwDataset::spectral, t.text(r, 0));
      if (band < 0)
        throw IoError(
            fmt::format("{} row {}: unknown wavelength '{}'", kSolarPath, r + 2, t.text(r, 0)));
      const int turb = int_field(t, r, 1, 1, kTurbidityKnots, kSolarPath);
      const int p = int_field(t, r, 2, 0, kSolarPieces - 1, kSolarPath);
      const std::size_t slot =
          (static_cast<std::size_t>(band) * kTurbidityKnots + (turb - 1)) * kSolarPieces + p;
      if (seen[slot]) throw IoError(fmt::format("{} row {}: duplicate entry", kSolarPath, r + 2));
      seen[slot] = true;
      for (int k = 0; k < kSolarOrder; ++k)
        out.coefficients[slot * kSolarOrder + k] = t.number(r, 3 + k);  // c3, c2, c1, c0
    }
    if (std::find(seen.begin(), seen.end(), false) != seen.end())
      throw IoError(fmt::format("{}: missing entries", kSolarPath));

    constexpr std::string_view kLimbPath = "hosek_wilkie/hw2013_limb_darkening.csv";
    const auto l = data::load_table(kLimbPath, true, 1 + kLimbDarkeningOrder);
    std::array<bool, kHwBands> seen_band{};
    for (std::size_t r = 0; r < l.rows(); ++r) {
      const int band = channel_index(HwDataset::spectral, l.text(r, 0));
      if (band < 0 || seen_band[band])
        throw IoError(fmt::format("{} row {}: unknown or duplicate wavelength '{}'", kLimbPath,
                                  r + 2, l.text(r, 0)));
      seen_band[band] = true;
      for (int k = 0; k < kLimbDarkeningOrder; ++k) out.limb[band][k] = l.number(r, 1 + k);
    }
    for (bool b : seen_band)
      if (!b) throw IoError(fmt::format("{}: missing wavelengths", kLimbPath));
    return out;
  }();
  return s;
}

// Quintic Bezier weights (2012 eq. 10) C(5,k) (1-x)^(5-k) x^k, formed exactly as v1.4a writes
// them inline: v1.4a evaluates e.g. 5.0 * pow(1-x, 4) * x * m left to right, so (5 (1-x)^4 x) * m
// here is bit-identical, with the pow() calls done once per state instead of once per parameter.
std::array<double, kControlPoints> bezier5_weights(double x) {
  return {std::pow(1.0 - x, 5.0),
          5.0 * std::pow(1.0 - x, 4.0) * x,
          10.0 * std::pow(1.0 - x, 3.0) * std::pow(x, 2.0),
          10.0 * std::pow(1.0 - x, 2.0) * std::pow(x, 3.0),
          5.0 * (1.0 - x) * std::pow(x, 4.0),
          std::pow(x, 5.0)};
}

// Sum in v1.4a's order over 6 control points `stride` apart.
double bezier5(const std::array<double, kControlPoints>& w, const double* m, int stride) {
  return w[0] * m[0] + w[1] * m[stride] + w[2] * m[2 * stride] + w[3] * m[3 * stride] +
         w[4] * m[4 * stride] + w[5] * m[5 * stride];
}

void check_state_parameters(const HwStateParameters& p) {
  require_in_range("turbidity", p.turbidity, kHwTurbidityMin, kHwTurbidityMax);
  require_in_range("albedo", p.albedo, 0.0, 1.0);
  // Up to pi/2 plus rounding slack (a 90 deg elevation converted from degrees may round up).
  require_in_range("solar_elevation [rad]", p.solar_elevation, 0.0, 0.5 * kPi * (1.0 + 1e-12));
}

// The piecewise cubic in elevation for one band and turbidity knot (arhosekskymodel_sr_internal).
double solar_piecewise(int band, int turb_index, double elevation) {
  // Piece p covers elevations from (p/45)^3 pi/2: pos = floor((2 h / pi)^(1/3) 45), at most 44.
  int pos = static_cast<int>(std::pow(2.0 * elevation / kPi, 1.0 / 3.0) * kSolarPieces);
  if (pos > kSolarPieces - 1) pos = kSolarPieces - 1;
  const double break_x =
      std::pow(static_cast<double>(pos) / static_cast<double>(kSolarPieces), 3.0) * (kPi * 0.5);
  const double* c = solar_data().piece(band, turb_index, pos);  // c3, c2, c1, c0
  const double x = elevation - break_x;
  double res = 0.0, x_exp = 1.0;
  for (int i = kSolarOrder - 1; i >= 0; --i) {
    res += x_exp * c[i];
    x_exp *= x;
  }
  return res;
}

// v1.4a's wavelength split for the sun: wl_low = floor((nm - 320) / 40), frac = fmod(nm, 40) / 40,
// 720 nm as band 9 with fraction 1.
void solar_band(double nm, int& wl_low, double& wl_frac) {
  wl_low = static_cast<int>((nm - kHwFirstBandNm) / kHwBandStepNm);
  wl_frac = std::fmod(nm, kHwBandStepNm) / kHwBandStepNm;
  if (wl_low == kHwBands - 1) {
    wl_low = kHwBands - 2;
    wl_frac = 1.0;
  }
}

void check_solar_nm(double nm) {
  require_in_range("wavelength [nm]", nm, kHwFirstBandNm, kHwLastBandNm);
}

// "sampleCosine": cosine across the disc from the angle gamma to the sun centre.
double sample_cosine(double gamma) {
  const double sol_rad_sin = std::sin(kHwSolarRadius);
  const double ar2 = 1.0 / (sol_rad_sin * sol_rad_sin);
  const double singamma = std::sin(gamma);
  double sc2 = 1.0 - ar2 * singamma * singamma;
  if (sc2 < 0.0) sc2 = 0.0;
  return std::sqrt(sc2);
}

// The piecewise cubic at both turbidity knots around T for every band, and v1.4a's turbidity split:
// turb_low = floor(T) - 1 (0-based knot), frac = T - floor(T); T = 10 as knot 9 with fraction 1.
struct SolarCentreTable {
  double turb_frac = 0.0;
  std::array<std::array<double, 2>, kHwBands> value{};  // [band][lower, upper turbidity knot]
};

SolarCentreTable solar_centre_table(double turbidity, double solar_elevation) {
  int turb_low = static_cast<int>(turbidity) - 1;
  SolarCentreTable t;
  t.turb_frac = turbidity - static_cast<double>(turb_low + 1);
  if (turb_low == kTurbidityKnots - 1) {
    turb_low = kTurbidityKnots - 2;
    t.turb_frac = 1.0;
  }
  const double h = std::min(solar_elevation, 0.5 * kPi);
  for (int b = 0; b < kHwBands; ++b)
    for (int k = 0; k < 2; ++k) t.value[b][k] = solar_piecewise(b, turb_low + k, h);
  return t;
}

// v1.4a's bilinear blend (same operations, same order) of the table at wavelength nm.
double solar_centre(const SolarCentreTable& t, double nm) {
  int wl_low = 0;
  double wl_frac = 0.0;
  solar_band(nm, wl_low, wl_frac);
  const double tf = t.turb_frac;
  return (1.0 - tf) * ((1.0 - wl_frac) * t.value[wl_low][0] + wl_frac * t.value[wl_low + 1][0]) +
         tf * ((1.0 - wl_frac) * t.value[wl_low][1] + wl_frac * t.value[wl_low + 1][1]);
}

// The sun's XYZ integral in closed form over the band intervals. On [band b, band b+1] with
// t = (nm - band b) / 40 both the centre radiance S and each limb-darkening coefficient l_k are
// linear in t (v1.4a's interpolation), so S l_k = (1-t)^2 S_b l_b + t(1-t) (S_b l_b+1 + S_b+1 l_b)
// + t^2 S_b+1 l_b+1. The 1 nm trapezoid integrals of (1-t)^2, t(1-t), t^2 times the CMFs are the
// same for every state: computed once here, they turn the per-state integration into sums.
// (The trapezoid rule is additive over intervals that end on nodes, so this equals the 1 nm
// trapezoid over 360-720 nm of the interpolated spectrum; band 1 = 360 nm, the CMFs' start.)
struct SunIntervalWeights {
  std::array<std::array<Xyz, 3>, kHwBands - 1> w{};  // [interval][(1-t)^2, t(1-t), t^2]
};

const SunIntervalWeights& sun_interval_weights() {
  static const SunIntervalWeights weights = [] {
    SunIntervalWeights out;
    for (int b = 0; b + 1 < kHwBands; ++b) {
      const double lo = kHwFirstBandNm + kHwBandStepNm * b;
      if (lo < kCmfFirstNm) continue;  // 320-360 nm: outside the CMF table
      std::vector<double> nm, q0, q1, q2;
      for (double l = lo; l <= lo + kHwBandStepNm + 1e-9; l += kIntegrationStepNm) {
        const double t = (l - lo) / kHwBandStepNm;
        nm.push_back(l);
        q0.push_back((1.0 - t) * (1.0 - t));
        q1.push_back(t * (1.0 - t));
        q2.push_back(t * t);
      }
      out.w[b] = {spectral_radiance_to_xyz(nm, q0), spectral_radiance_to_xyz(nm, q1),
                  spectral_radiance_to_xyz(nm, q2)};
    }
    return out;
  }();
  return weights;
}

}  // namespace

HwChannelState hw_channel_state(HwDataset d, int channel, const HwStateParameters& p) {
  check_state_parameters(p);
  const Dataset2012& ds = dataset(d);
  SKYLIGHT_CHECK(channel >= 0 && channel < ds.channels, "hw_channel_state: channel out of range");
  const int int_turbidity = static_cast<int>(p.turbidity);
  const double turbidity_rem = p.turbidity - static_cast<double>(int_turbidity);
  const double x = std::pow(p.solar_elevation / (kPi / 2.0), 1.0 / 3.0);
  const std::array<double, kControlPoints> w = bezier5_weights(x);
  const double albedo = p.albedo;
  HwChannelState s;
  // Blend of the 4 (albedo knot, turbidity knot) corners, in v1.4a's order of accumulation.
  struct Corner {
    int alb, turb_index;
    double weight;
  };
  const Corner corners[4] = {{0, int_turbidity - 1, (1.0 - albedo) * (1.0 - turbidity_rem)},
                             {1, int_turbidity - 1, albedo * (1.0 - turbidity_rem)},
                             {0, int_turbidity, (1.0 - albedo) * turbidity_rem},
                             {1, int_turbidity, albedo * turbidity_rem}};
  // T = 10 has no upper knot (v1.4a returns after the first two corners).
  const int n_corners = int_turbidity == kTurbidityKnots ? 2 : 4;
  for (int k = 0; k < n_corners; ++k) {
    const Corner& c = corners[k];
    const double* m = ds.params_at(channel, c.alb, c.turb_index);
    for (int i = 0; i < kParams; ++i) s.config[i] += c.weight * bezier5(w, m + i, kParams);
    s.radiance += c.weight * bezier5(w, ds.radiance_at(channel, c.alb, c.turb_index), 1);
  }
  return s;
}

double hw_extended_perez(const HwConfig& c, double cos_theta, double gamma, double cos_gamma) {
  using namespace hw_index;
  cos_theta = std::clamp(cos_theta, 0.0, 1.0);
  const double expM = std::exp(c[E] * gamma);
  const double rayM = cos_gamma * cos_gamma;
  const double mieM =
      (1.0 + cos_gamma * cos_gamma) / std::pow((1.0 + c[H] * c[H] - 2.0 * c[H] * cos_gamma), 1.5);
  const double zenith = std::sqrt(cos_theta);
  return (1.0 + c[A] * std::exp(c[B] / (cos_theta + kHwCosThetaOffset))) *
         (c[C] + c[D] * expM + c[F] * rayM + c[G] * mieM + c[I] * zenith);
}

double hw_extended_perez(const HwConfig& c, HwViewAngles a) {
  return hw_extended_perez(c, std::cos(a.theta), a.gamma, std::cos(a.gamma));
}

HwTristimState hw_tristim_state(HwDataset d, const HwStateParameters& p) {
  return hw_tristim_state(d, p, {p.albedo, p.albedo, p.albedo});
}

HwTristimState hw_tristim_state(HwDataset d, const HwStateParameters& p,
                                const std::array<double, 3>& channel_albedo) {
  if (d == HwDataset::spectral)
    throw InvalidArgument("hw_tristim_state: the spectral dataset has 11 bands, not 3 channels");
  HwTristimState s;
  s.dataset = d;
  for (int ch = 0; ch < 3; ++ch) {
    HwStateParameters q = p;
    q.albedo = channel_albedo[ch];
    s.channels[ch] = hw_channel_state(d, ch, q);
  }
  return s;
}

double hw_tristim_radiance(const HwTristimState& s, HwViewAngles a, int channel) {
  SKYLIGHT_CHECK(channel >= 0 && channel < 3, "hw_tristim_radiance: channel out of range");
  const HwChannelState& c = s.channels[channel];
  return hw_extended_perez(c.config, a) * c.radiance;
}

HwSpectralState hw_spectral_state(const HwStateParameters& p) {
  std::array<double, kHwBands> albedo;
  albedo.fill(p.albedo);
  return hw_spectral_state(p, albedo);
}

HwSpectralState hw_spectral_state(const HwStateParameters& p,
                                  const std::array<double, kHwBands>& band_albedo) {
  HwSpectralState s;
  s.turbidity = p.turbidity;
  s.solar_elevation = p.solar_elevation;
  for (int b = 0; b < kHwBands; ++b) {
    HwStateParameters q = p;
    q.albedo = band_albedo[b];
    s.bands[b] = hw_channel_state(HwDataset::spectral, b, q);
  }
  return s;
}

double hw_spectral_radiance(const HwSpectralState& s, HwViewAngles a, double nm) {
  if (!(nm >= kHwFirstBandNm && nm <= kHwLastBandNm)) return 0.0;
  const int low = static_cast<int>((nm - kHwFirstBandNm) / kHwBandStepNm);
  const double interp = std::fmod((nm - kHwFirstBandNm) / kHwBandStepNm, 1.0);
  auto band = [&](int b) { return hw_extended_perez(s.bands[b].config, a) * s.bands[b].radiance; };
  const double val_low = band(low);
  // v1.4a: a fraction below 1e-6 of the band step counts as the band itself.
  if (interp < 1e-6) return val_low;
  double result = (1.0 - interp) * val_low;
  if (low + 1 < kHwBands) result += interp * band(low + 1);
  return result;
}

double hw_solar_centre_radiance(double turbidity, double solar_elevation, double nm) {
  require_in_range("turbidity", turbidity, kHwTurbidityMin, kHwTurbidityMax);
  check_solar_nm(nm);
  if (!(solar_elevation >= 0.0)) return 0.0;  // v1.4a: pow of a negative number, NaN
  return solar_centre(solar_centre_table(turbidity, solar_elevation), nm);
}

std::array<double, 6> hw_limb_darkening(double nm) {
  check_solar_nm(nm);
  int wl_low = 0;
  double wl_frac = 0.0;
  solar_band(nm, wl_low, wl_frac);
  const auto& ld = solar_data().limb;
  std::array<double, 6> c{};
  for (int i = 0; i < kLimbDarkeningOrder; ++i)
    c[i] = (1.0 - wl_frac) * ld[wl_low][i] + wl_frac * ld[wl_low + 1][i];
  return c;
}

double hw_solar_direct_radiance(const HwSolarInputs& in, double nm) {
  const double direct = hw_solar_centre_radiance(in.turbidity, in.solar_elevation, nm);
  const std::array<double, 6> ld = hw_limb_darkening(nm);
  const double mu = sample_cosine(in.gamma);
  const double darkening = ld[0] + ld[1] * mu + ld[2] * std::pow(mu, 2.0) +
                           ld[3] * std::pow(mu, 3.0) + ld[4] * std::pow(mu, 4.0) +
                           ld[5] * std::pow(mu, 5.0);
  return direct * darkening;
}

double hw_solar_radiance(const HwSpectralState& s, HwViewAngles a, double nm) {
  const double direct = hw_solar_direct_radiance({s.turbidity, 0.5 * kPi - a.theta, a.gamma}, nm);
  return direct + hw_spectral_radiance(s, a, nm);
}

const std::array<Xyz, kHwBands>& hw_band_xyz_weights() {
  static const std::array<Xyz, kHwBands> w = [] {
    std::vector<double> nm;
    for (double l = kCmfFirstNm; l <= kHwLastBandNm + 1e-9; l += kIntegrationStepNm)
      nm.push_back(l);
    std::array<Xyz, kHwBands> out{};
    std::vector<double> hat(nm.size());
    for (int b = 0; b < kHwBands; ++b) {
      const double centre = kHwFirstBandNm + kHwBandStepNm * b;
      for (std::size_t i = 0; i < nm.size(); ++i)
        hat[i] = std::max(0.0, 1.0 - std::abs(nm[i] - centre) / kHwBandStepNm);
      out[b] = spectral_radiance_to_xyz(nm, hat);
    }
    return out;
  }();
  return w;
}

// ---- the model ----

const ParameterSchema<HosekParameters>& HosekParameters::schema() {
  static const auto s = [] {
    ParameterSchema<HosekParameters> s;
    const HosekParameters defaults;
    s.number(&HosekParameters::turbidity,
             {.name = "turbidity",
              .unit = "1",
              .min = kHwTurbidityMin,
              .max = kHwTurbidityMax,
              .default_value = ParameterValue(defaults.turbidity),
              .description = "atmospheric turbidity T (dataset knots 1..10, linear in between)"});
    s.number(&HosekParameters::albedo,
             {.name = "albedo",
              .unit = "1",
              .min = 0.0,
              .max = 1.0,
              .default_value = ParameterValue(defaults.albedo),
              .description = "ground albedo (dataset knots 0 and 1, linear)"});
    return s;
  }();
  return s;
}

HosekWilkieModel::HosekWilkieModel(const HosekParameters& p) : SkyModel(p.sun), params_(p) {
  HosekParameters::schema().validate(p, model_context(kName));
  sun_ = p.sun.direction();
  const double elevation = p.sun.elevation();
  sun_up_ = elevation >= 0.0;
  // Below the horizon nothing is evaluated; the states are left at the horizon for inspection.
  const HwStateParameters sp{p.turbidity, p.albedo, std::clamp(elevation, 0.0, 0.5 * kPi)};
  xyz_ = hw_tristim_state(HwDataset::ciexyz, sp);
  rgb_ = hw_tristim_state(HwDataset::rgb, sp);
  spectral_ = hw_spectral_state(sp);
  if (sun_up_) {
    // sun XYZ(mu) = sum_k mu^k K_m int S(nm) ld_k(nm) cmf(nm) dnm, S = the centre radiance.
    const SolarCentreTable table = solar_centre_table(p.turbidity, sp.solar_elevation);
    const auto& limb = solar_data().limb;
    const auto& W = sun_interval_weights().w;
    for (int b = 0; b + 1 < kHwBands; ++b) {
      const double S0 = solar_centre(table, kHwFirstBandNm + kHwBandStepNm * b);
      const double S1 = solar_centre(table, kHwFirstBandNm + kHwBandStepNm * (b + 1));
      for (int k = 0; k < kLimbDarkeningOrder; ++k) {
        const double c0 = S0 * limb[b][k], c2 = S1 * limb[b + 1][k];
        const double c1 = S0 * limb[b + 1][k] + S1 * limb[b][k];
        Xyz& acc = sun_xyz_[k];
        acc.X += c0 * W[b][0].X + c1 * W[b][1].X + c2 * W[b][2].X;
        acc.Y += c0 * W[b][0].Y + c1 * W[b][1].Y + c2 * W[b][2].Y;
        acc.Z += c0 * W[b][0].Z + c1 * W[b][1].Z + c2 * W[b][2].Z;
      }
    }
  }
}

bool HosekWilkieModel::view_angles(Vec3 view, double& cos_theta, double& gamma,
                                   double& cos_gamma) const {
  if (!sun_up_ || view.z < 0.0) return false;
  cos_theta = std::min(view.z, 1.0);
  gamma = angle_between(view, sun_);
  cos_gamma = std::cos(gamma);
  return true;
}

Xyz HosekWilkieModel::tristimulus(Vec3 view) const {
  double ct = 0, g = 0, cg = 0;
  if (!view_angles(view, ct, g, cg)) return {};
  auto ch = [&](int c) {
    const HwChannelState& s = xyz_.channels[c];
    // The fit dips below 0 exactly at the horizon for low suns: clamped (see the header).
    return std::max(0.0,
                    kMaxLuminousEfficacy * s.radiance * hw_extended_perez(s.config, ct, g, cg));
  };
  return {ch(0), ch(1), ch(2)};
}

Rgb HosekWilkieModel::rgb(Vec3 view) const {
  double ct = 0, g = 0, cg = 0;
  if (!view_angles(view, ct, g, cg)) return {};
  auto ch = [&](int c) {
    const HwChannelState& s = rgb_.channels[c];
    // The fit dips below 0 exactly at the horizon for low suns: clamped (see the header).
    return std::max(0.0,
                    kMaxLuminousEfficacy * s.radiance * hw_extended_perez(s.config, ct, g, cg));
  };
  return {ch(0), ch(1), ch(2)};
}

std::optional<double> HosekWilkieModel::spectral_radiance(Vec3 view, double nm) const {
  if (!(nm >= kHwFirstBandNm && nm <= kHwLastBandNm)) return std::nullopt;
  double ct = 0, g = 0, cg = 0;
  if (!view_angles(view, ct, g, cg)) return 0.0;
  const int low = static_cast<int>((nm - kHwFirstBandNm) / kHwBandStepNm);
  const double interp = std::fmod((nm - kHwFirstBandNm) / kHwBandStepNm, 1.0);
  auto band = [&](int b) {
    return hw_extended_perez(spectral_.bands[b].config, ct, g, cg) * spectral_.bands[b].radiance;
  };
  const double val_low = band(low);
  if (interp < 1e-6) return std::max(0.0, val_low);
  double result = (1.0 - interp) * val_low;
  if (low + 1 < kHwBands) result += interp * band(low + 1);
  return std::max(0.0, result);
}

Xyz HosekWilkieModel::tristimulus_from_spectral(Vec3 view) const {
  double ct = 0, g = 0, cg = 0;
  if (!view_angles(view, ct, g, cg)) return {};
  const auto& w = hw_band_xyz_weights();
  Xyz sum;
  for (int b = 0; b < kHwBands; ++b) {
    const double L = std::max(
        0.0, hw_extended_perez(spectral_.bands[b].config, ct, g, cg) * spectral_.bands[b].radiance);
    sum = {sum.X + L * w[b].X, sum.Y + L * w[b].Y, sum.Z + L * w[b].Z};
  }
  return sum;
}

void HosekWilkieModel::tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  SKYLIGHT_CHECK(dirs.y.size() == dirs.size() && dirs.z.size() == dirs.size() &&
                     out.size() == dirs.size() && out.Y.size() == dirs.size() &&
                     out.Z.size() == dirs.size(),
                 "tristimulus_batch: span sizes differ");
  if (!sun_up_) {
    std::fill(out.X.begin(), out.X.end(), 0.0f);
    std::fill(out.Y.begin(), out.Y.end(), 0.0f);
    std::fill(out.Z.begin(), out.Z.end(), 0.0f);
    return;
  }
  using namespace hw_index;
  detail::HosekBatchParams p{};
  for (int c = 0; c < 3; ++c) {
    const HwChannelState& s = xyz_.channels[c];
    p.A[c] = static_cast<float>(s.config[A]);
    p.B[c] = static_cast<float>(s.config[B]);
    p.C[c] = static_cast<float>(s.config[C]);
    p.D[c] = static_cast<float>(s.config[D]);
    p.E[c] = static_cast<float>(s.config[E]);
    p.F[c] = static_cast<float>(s.config[F]);
    p.G[c] = static_cast<float>(s.config[G]);
    p.H[c] = static_cast<float>(s.config[H]);
    p.I[c] = static_cast<float>(s.config[I]);
    p.one_minus_H_sq[c] = static_cast<float>((1.0 - s.config[H]) * (1.0 - s.config[H]));
    p.scale[c] = static_cast<float>(kMaxLuminousEfficacy * s.radiance);
  }
  p.sx = static_cast<float>(sun_.x);
  p.sy = static_cast<float>(sun_.y);
  p.sz = static_cast<float>(sun_.z);
  detail::hosek_batch(p, dirs.x.data(), dirs.y.data(), dirs.z.data(), out.X.data(), out.Y.data(),
                      out.Z.data(), dirs.size());
}

bool HosekWilkieModel::disc_cosine(Vec3 view, double& mu) const {
  if (!sun_up_ || view.z < 0.0) return false;  // below the horizon the ground hides the disc
  const double gamma = angle_between(view, sun_);
  if (gamma > kHwSolarRadius) return false;
  mu = sample_cosine(gamma);
  return true;
}

Xyz HosekWilkieModel::sun_tristimulus(Vec3 view) const {
  double mu = 0.0;
  if (!disc_cosine(view, mu)) return {};
  Xyz sum;
  double mu_k = 1.0;
  for (int k = 0; k < 6; ++k) {
    sum = {sum.X + mu_k * sun_xyz_[k].X, sum.Y + mu_k * sun_xyz_[k].Y,
           sum.Z + mu_k * sun_xyz_[k].Z};
    mu_k *= mu;
  }
  return sum;
}

std::optional<double> HosekWilkieModel::sun_spectral_radiance(Vec3 view, double nm) const {
  if (!(nm >= kHwFirstBandNm && nm <= kHwLastBandNm)) return std::nullopt;
  double mu = 0.0;
  if (!disc_cosine(view, mu)) return 0.0;
  const double gamma = angle_between(view, sun_);
  return hw_solar_direct_radiance({params_.turbidity, sun().elevation(), gamma}, nm);
}

ParameterValues HosekWilkieModel::parameter_values() const {
  return HosekParameters::schema().values_of(params_);
}

Domain HosekWilkieModel::domain() const {
  return sun_below_horizon(Validity::undefined,
                           "the Hosek-Wilkie model has no twilight; sky and sun are 0");
}

namespace {

// The photo fit's ln L: ln Y of the model built for (T, albedo) at the sun (floored at the smallest
// double: the fit's negative values at the horizon are returned as 0).
EstimationPolicy::LogLuminance prepare_log_luminance(const SunPosition& sun,
                                                     std::span<const Vec3> views) {
  auto v = std::make_shared<std::vector<Vec3>>(views.begin(), views.end());
  return [v, sun](std::span<const double> p, std::span<const std::size_t> idx,
                  std::span<double> out) {
    const HosekWilkieModel model(HosekParameters{sun, p[0], p[1]});
    for (std::size_t k = 0; k < idx.size(); ++k)
      out[k] =
          std::log(std::max(model.tristimulus((*v)[idx[k]]).Y, std::numeric_limits<double>::min()));
  };
}

}  // namespace

ModelInfo HosekWilkieModel::registry_entry() {
  return ModelInfo{
      .name = std::string(kName),
      .description =
          "Hosek & Wilkie 2012 analytic sky (9-parameter extended Perez form fitted to "
          "simulations; ArHosekSkyModel v1.4a datasets) with the 2013 solar radiance function",
      .output =
          "XYZ = the CIE XYZ dataset x 683 (Y [cd/m^2]); rgb = the native RGB dataset x 683 "
          "(linear "
          "sRGB primaries, same photometric scale); spectral radiance [W m^-2 sr^-1 nm^-1] "
          "320-720 nm; sun disc radius 0.255 deg with limb darkening",
      .parameters = HosekParameters::schema().specs(),
      .domain =
          "turbidity 1-10 and albedo 0-1 (rejected outside: no dataset knots there); sun "
          "elevation 0-90 deg; sun below the horizon: sky and sun 0 (undefined); the fit's "
          "slightly "
          "negative values exactly at the horizon with a low sun are returned as 0",
      .spectral = true,
      .sun = true,
      .make = model_factory<HosekWilkieModel, HosekParameters>(),
      // the paper's Hosek protocol: T = 1..10 (validation 1.5..9.5); 683 = the native RGB dataset's
      // raw values; every network within 30 % at the 95th percentile on the held-out grid
      .neural = NeuralPolicy::over_turbidity(1.0, 10.0, 683.0).bounded(0.30),
      // Turbidity and ground albedo with a free scale: the grid T every 0.5 over the dataset's
      // knots, albedo at its ends and middle (docs/ESTIMATE.md).
      .estimation =
          EstimationPolicy{.method = EstimationPolicy::Method::grid_ransac,
                           .axes = {{.parameter = "turbidity",
                                     .label = "turbidity",
                                     .min = kHwTurbidityMin,
                                     .max = kHwTurbidityMax,
                                     .grid_points = 19},
                                    {.parameter = "albedo",
                                     .label = "albedo",
                                     .min = 0.0,
                                     .max = 1.0,
                                     .grid_points = 3}},
                           .prepare = prepare_log_luminance,
                           .description = "turbidity and ground albedo, free luminance scale"},
      // Hosek & Wilkie's own structure (docs/SH.md, "Hosek fits", where the study that chose
      // these is): one tau piece per turbidity interval of width 1 (the knots at the integers,
      // where Hosek interpolates linearly), degree 4 in T on 6 turbidities per piece (degree 2
      // misses the sun at the horizon between the knots by 6 %), degree 24 in Hosek's own
      // (elevation/90 deg)^(1/3): worst E_mean 0.29 % at 7 bands over T 1-10, sun 0-90 deg,
      // range ends included.
      .sh_fit = ShFitPolicy{.parameter = "turbidity",
                            .unit_pieces = true,
                            .degrees = std::array<int, 2>{24, 4},
                            .grid_tau = 6,
                            .theta_axis = sh::ThetaAxis::elevation_cbrt},
      .bench = BenchPolicy{.by_default = true},
      // The report's Hosek skies are over the ground albedo 0.3 of Hosek & Wilkie's figures.
      .report = ReportPolicy{.title = "Hosek-Wilkie",
                             .axis = "turbidity",
                             .axis_label = "T = ",
                             .fixed = ParameterValues().set("albedo", 0.3),
                             .colour = "#1f77b4",
                             // A clear sky's distribution on planes: turbidity 3.
                             .planes = ParameterValues().set("turbidity", 3.0)},
  };
}

std::optional<GpuSky> HosekWilkieModel::gpu_sky() const {
  // tristimulus(): the extended Perez function of each XYZ channel (hw_extended_perez, the 2012
  // paper's eq. 8-9) times 683 L_M, clamped at 0; the nine coefficients side by side.
  GpuSky g;
  g.glsl = fmt::format(
      "uniform vec3 skylight_hosek_A, skylight_hosek_B, skylight_hosek_C, skylight_hosek_D,\n"
      "    skylight_hosek_E, skylight_hosek_F, skylight_hosek_G, skylight_hosek_H,\n"
      "    skylight_hosek_I, skylight_hosek_radiance;  // 683 L_M\n"
      "uniform vec3 skylight_hosek_sun;  // unit vector, z up\n"
      "uniform int skylight_hosek_sun_up;\n"
      "vec3 skylight_hosek(vec3 dir) {{  // models/hosek_wilkie.h, hw_extended_perez\n"
      "  if (skylight_hosek_sun_up == 0 || dir.z < 0.0) return vec3(0.0);\n"
      "  float ct = clamp(dir.z, 0.0, 1.0);\n"
      "  float gamma = skylight_angle(dir, skylight_hosek_sun);\n"
      "  float cg = cos(gamma);\n"
      "  vec3 H = skylight_hosek_H;\n"
      "  vec3 mie = (1.0 + cg * cg) / pow(1.0 + H * H - 2.0 * H * cg, vec3(1.5));\n"
      "  vec3 f = (1.0 + skylight_hosek_A * exp(skylight_hosek_B / (ct + {})))\n"
      "      * (skylight_hosek_C + skylight_hosek_D * exp(skylight_hosek_E * gamma)\n"
      "         + skylight_hosek_F * (cg * cg) + skylight_hosek_G * mie\n"
      "         + skylight_hosek_I * sqrt(ct));\n"
      "  return max(vec3(0.0), skylight_hosek_radiance * f);\n"
      "}}\n",
      fmt::format("{:.9e}", kHwCosThetaOffset));
  g.expression = "skylight_hosek(dir)";
  const char* names = "ABCDEFGIH";  // hw_index order
  for (int k = 0; k < 9; ++k) {
    g.uniforms.push_back(gpu_uniform(
        fmt::format("skylight_hosek_{}", names[k]),
        {xyz_.channels[0].config[k], xyz_.channels[1].config[k], xyz_.channels[2].config[k]}));
  }
  g.uniforms.push_back(
      gpu_uniform("skylight_hosek_radiance", {kMaxLuminousEfficacy * xyz_.channels[0].radiance,
                                              kMaxLuminousEfficacy * xyz_.channels[1].radiance,
                                              kMaxLuminousEfficacy * xyz_.channels[2].radiance}));
  g.uniforms.push_back(gpu_uniform("skylight_hosek_sun", {sun_.x, sun_.y, sun_.z}));
  g.uniforms.push_back(gpu_int_uniform("skylight_hosek_sun_up", sun_up_ ? 1 : 0));
  g.comment =
      fmt::format("hosek, T = {}, albedo {}: the XYZ dataset", params_.turbidity, params_.albedo);
  return g;
}

}  // namespace skylight
