#include "skylight/models/physical_sky.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/atmosphere/path_tracer.h"
#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/core/xyz_quadrature.h"
#include "skylight/models/evaluation.h"
#include "skylight/models/solar_disc.h"

namespace skylight {

using atmosphere::Atmosphere;
using atmosphere::AtmosphereParameters;
using atmosphere::AtmosphereTableCache;
using atmosphere::Spectral;

const ParameterSchema<OzoneLayerParameters>& OzoneLayerParameters::schema() {
  static const auto s = [] {
    ParameterSchema<OzoneLayerParameters> s;
    s.inherit(NishitaParameters::schema())
        .redefault("ozone", ParameterValue(atmosphere::kEarthOzoneColumn),
                   "ozone column of an absorbing layer at 10-40 km (Bruneton 2017 profile; 0: "
                   "none)");
    return s;
  }();
  return s;
}

PhysicalSkyModel::PhysicalSkyModel(const NishitaParameters& params) : SkyModel(params.sun) {
  single_ = std::make_unique<NishitaModel>(params);
  observer_ = single_->observer();
  sun_ = params.sun.direction();
  const Spectral& tables = single_->xyz_spectral();
  lut_nm_.push_back(kNishitaMinNm);
  lut_nm_.insert(lut_nm_.end(), tables.nm.begin(), tables.nm.end());
  lut_nm_.push_back(kNishitaMaxNm);
  std::array<double, kPhysicalXyzCount> nm{};
  for (int k = 0; k < kPhysicalXyzCount; ++k) nm[k] = kPhysicalXyzFirst + kPhysicalXyzStep * k;
  xyz_ = single_->spectral_at(nm);
  xyz_weights_ = spline_xyz_weights(nm, [this](double l) { return single_->irradiance(l); });
  for (int k = 0; k < kPhysicalXyzCount; ++k) xyz_lut_.push_back(lut_weight(nm[k]));
  sun_transmittance(xyz_, sun_transmittance_);
  const double r_obs = length(observer_);
  horizon_zenith_ =
      kPi / 2 + std::acos(std::min(1.0, atmosphere().parameters().ground_radius_m / r_obs));
}

namespace {

// The LUTs of the last models built: the report and the sweeps rebuild a model for the same
// atmosphere and sun many times (kSkyViewZeniths x kSkyViewAzimuths x 41 doubles = 0.7 MB each;
// the batch LUT 0.4 MB).
AtmosphereTableCache<std::vector<double>, 64>& sky_view_cache() {
  static AtmosphereTableCache<std::vector<double>, 64> cache;
  return cache;
}
AtmosphereTableCache<std::vector<float>, 16>& batch_cache() {
  static AtmosphereTableCache<std::vector<float>, 16> cache;
  return cache;
}

}  // namespace

void PhysicalSkyModel::build_sky_view(const std::string& tables_key) {
  const Spectral& xyz = xyz_;
  lut_key_ =
      fmt::format("{} {} | observer {:a} {:a} {:a} | sun {:a} {:a} | solar", name(), tables_key,
                  observer_.x, observer_.y, observer_.z, sun().zenith, sun().azimuth);
  for (double e : xyz.solar) lut_key_ += fmt::format(" {:a}", e);
  sky_ = sky_view_cache().get(lut_key_, [&] {
    std::vector<double> sky(
        static_cast<std::size_t>(kSkyViewZeniths) * kSkyViewAzimuths * kPhysicalXyzCount, 0.0);
    parallel_for(static_cast<std::size_t>(kSkyViewZeniths * kSkyViewAzimuths), 8,
                 [&](std::size_t b, std::size_t e) {
                   for (std::size_t job = b; job < e; ++job) {
                     const int i = static_cast<int>(job) / kSkyViewAzimuths;
                     const int j = static_cast<int>(job) % kSkyViewAzimuths;
                     const double zenith = sky_zenith(i, kSkyViewZeniths);
                     const double azimuth = sun().azimuth + kPi * j / (kSkyViewAzimuths - 1);
                     multiple_scattering(
                         direction_from_angles(zenith, azimuth), xyz, xyz_lut_,
                         std::span<double>(&sky[job * kPhysicalXyzCount], kPhysicalXyzCount));
                   }
                 });
    return sky;
  });
}

// Rows: the upper half (row < mid) l = 1 - row / mid, zenith = horizon (1 - l^2); the lower half
// l = (row - mid) / (rows - 1 - mid), zenith = horizon + (pi - horizon) l^2: both dense at the
// horizon, where the sky changes fastest.
double PhysicalSkyModel::sky_zenith(double row, int rows) const {
  const double mid = 0.5 * (rows - 1);
  if (row <= mid) {
    const double l = 1.0 - row / mid;
    return horizon_zenith_ * (1.0 - l * l);
  }
  const double l = (row - mid) / mid;
  return horizon_zenith_ + (kPi - horizon_zenith_) * l * l;
}

double PhysicalSkyModel::sky_row(double zenith, int rows) const {
  const double mid = 0.5 * (rows - 1);
  if (zenith <= horizon_zenith_)
    return mid * (1.0 - std::sqrt(std::max(0.0, 1.0 - zenith / horizon_zenith_)));
  return mid + mid * std::sqrt(std::min(1.0, (zenith - horizon_zenith_) / (kPi - horizon_zenith_)));
}

std::vector<float> PhysicalSkyModel::build_batch_lut() const {
  const int rows = kSkyBatchZeniths, cols = kSkyBatchAzimuths;
  std::vector<float> batch(static_cast<std::size_t>(rows) * cols * 3, 0.0f);
  parallel_for(static_cast<std::size_t>(rows * cols), 64, [&](std::size_t b, std::size_t e) {
    for (std::size_t job = b; job < e; ++job) {
      const int i = static_cast<int>(job) / cols, j = static_cast<int>(job) % cols;
      const double azimuth = sun().azimuth + kPi * j / (cols - 1);
      const Xyz c = tristimulus(direction_from_angles(sky_zenith(i, rows), azimuth));
      batch[3 * job] = static_cast<float>(c.X);
      batch[3 * job + 1] = static_cast<float>(c.Y);
      batch[3 * job + 2] = static_cast<float>(c.Z);
    }
  });
  return batch;
}

const std::vector<float>& PhysicalSkyModel::batch_lut() const {
  std::call_once(batch_once_, [this] {
    batch_ = batch_cache().get(lut_key_, [this] { return build_batch_lut(); });
  });
  return *batch_;
}

std::optional<GpuSky> PhysicalSkyModel::gpu_sky() const {
  GpuSky g;
  const std::string pi = fmt::format("{:.9e}", static_cast<float>(kPi));
  g.glsl = fmt::format(
      "uniform sampler2D skylight_sky_lut;  // {0} azimuths x {1} zeniths, XYZ\n"
      "uniform float skylight_sky_horizon;   // the observer's horizon zenith angle [rad]\n"
      "uniform float skylight_sky_sun_azimuth;  // [rad]\n"
      "float skylight_sky_row(float zenith) {{  // PhysicalSkyModel::sky_row\n"
      "  float mid = 0.5 * float({1} - 1), h = skylight_sky_horizon;\n"
      "  if (zenith <= h) return mid * (1.0 - sqrt(max(0.0, 1.0 - zenith / h)));\n"
      "  return mid + mid * sqrt(min(1.0, (zenith - h) / ({2} - h)));\n"
      "}}\n"
      "vec3 skylight_sky_lut_at(int j, int i) {{ return texelFetch(skylight_sky_lut, ivec2(j, i), "
      "0).xyz; }}\n"
      "vec3 skylight_physical(vec3 dir) {{  // PhysicalSkyModel::tristimulus_batch\n"
      "  float zenith = atan(length(dir.xy), dir.z);\n"
      "  float phi = abs(mod(atan(dir.x, dir.y) - skylight_sky_sun_azimuth + {2}, 2.0 * {2}) - "
      "{2});\n"
      "  float y = clamp(skylight_sky_row(zenith), 0.0, float({1} - 1));\n"
      "  float x = clamp(phi / {2}, 0.0, 1.0) * float({0} - 1);\n"
      "  int i = min(int(y), {1} - 2), j = min(int(x), {0} - 2);\n"
      "  float fy = y - float(i), fx = x - float(j);\n"
      "  return (1.0 - fy) * ((1.0 - fx) * skylight_sky_lut_at(j, i) + fx * skylight_sky_lut_at(j "
      "+ 1, i))\n"
      "       + fy * ((1.0 - fx) * skylight_sky_lut_at(j, i + 1) + fx * skylight_sky_lut_at(j + 1, "
      "i + 1));\n"
      "}}\n",
      kSkyBatchAzimuths, kSkyBatchZeniths, pi);
  g.expression = "skylight_physical(dir)";
  g.uniforms = {gpu_uniform("skylight_sky_horizon", {horizon_zenith_}),
                gpu_uniform("skylight_sky_sun_azimuth", {sun().azimuth})};
  g.tables.push_back({"skylight_sky_lut", kSkyBatchAzimuths, kSkyBatchZeniths, 3, batch_lut()});
  g.comment = fmt::format("{}: the whole-sky LUT of its batch path ({} x {}, bilinear)", name(),
                          kSkyBatchAzimuths, kSkyBatchZeniths);
  return g;
}

void PhysicalSkyModel::tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  SKYLIGHT_CHECK(out.size() == dirs.size(), "tristimulus_batch: size mismatch");
  const std::vector<float>& lut = batch_lut();
  const int rows = kSkyBatchZeniths, cols = kSkyBatchAzimuths;
  const double sun_az = sun().azimuth;
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    const double zenith = std::acos(std::clamp(static_cast<double>(dirs.z[k]), -1.0, 1.0));
    const double phi =
        std::abs(wrap_azimuth(std::atan2(dirs.x[k], dirs.y[k]) - sun_az + kPi) - kPi);
    const double y = std::clamp(sky_row(zenith, rows), 0.0, rows - 1.0);
    const double x = std::clamp(phi / kPi, 0.0, 1.0) * (cols - 1);
    const int i = std::min(static_cast<int>(y), rows - 2),
              j = std::min(static_cast<int>(x), cols - 2);
    const float fy = static_cast<float>(y - i), fx = static_cast<float>(x - j);
    const float* a = &lut[(static_cast<std::size_t>(i) * cols + j) * 3];
    const float* c = a + static_cast<std::size_t>(cols) * 3;
    float v[3];
    for (int ch = 0; ch < 3; ++ch)
      v[ch] =
          (1 - fy) * ((1 - fx) * a[ch] + fx * a[3 + ch]) + fy * ((1 - fx) * c[ch] + fx * c[3 + ch]);
    out.X[k] = v[0];
    out.Y[k] = v[1];
    out.Z[k] = v[2];
  }
}

void PhysicalSkyModel::sun_transmittance(const Spectral& spec, std::span<double> out) const {
  const Atmosphere& atm = atmosphere();
  const AtmosphereParameters& a = atm.parameters();
  if (atmosphere::in_planet_shadow(observer_, sun_, a.ground_radius_m)) {
    std::fill(out.begin(), out.end(), 0.0);
    return;
  }
  const double to_top = atmosphere::ray_sphere_far(observer_, sun_, a.top_radius_m);
  if (to_top <= 0) {  // above the atmosphere, looking away from it
    std::fill(out.begin(), out.end(), 1.0);
    return;
  }
  atm.transmittance(observer_, sun_, to_top, spec, out);
}

double PhysicalSkyModel::sun_angular_radius() const {
  return kSolarAngularRadius;
}

Xyz PhysicalSkyModel::sun_tristimulus(Vec3 view) const {
  const Vec3 v = normalize(view);
  const double gamma = std::acos(std::clamp(dot(v, sun_), -1.0, 1.0));
  // The part of the disc behind the planet (below the horizon) is hidden by the ground.
  if (gamma > kSolarAngularRadius ||
      atmosphere::in_planet_shadow(observer_, v, atmosphere().parameters().ground_radius_m))
    return {};
  std::array<double, kPhysicalXyzCount> r{};
  for (int k = 0; k < kPhysicalXyzCount; ++k)
    r[k] = xyz_.solar[k] * sun_transmittance_[k] * solar_disc_factor(gamma, xyz_.nm[k]);
  return to_xyz(r);
}

std::optional<double> PhysicalSkyModel::sun_spectral_radiance(Vec3 view, double nm) const {
  if (!(nm >= kNishitaMinNm && nm <= kNishitaMaxNm)) return std::nullopt;
  const Vec3 v = normalize(view);
  const double gamma = std::acos(std::clamp(dot(v, sun_), -1.0, 1.0));
  if (gamma > kSolarAngularRadius ||
      atmosphere::in_planet_shadow(observer_, v, atmosphere().parameters().ground_radius_m))
    return 0.0;
  const double l[1] = {nm}, one[1] = {1.0};
  double t[1] = {0.0};
  sun_transmittance(atmosphere::make_spectral(atmosphere().parameters(), l, one), t);
  return single_->irradiance(nm) * t[0] * solar_disc_factor(gamma, nm);
}

Xyz PhysicalSkyModel::tristimulus(Vec3 view) const {
  std::array<double, kPhysicalXyzCount> r{};
  const Vec3 v = normalize(view);
  atmosphere().single_scattering(observer_, v, sun_, xyz_, r);
  // The multiple scattering from the sky-view LUT (bilinear; azimuth from the sun's, folded).
  const double zenith = std::acos(std::clamp(v.z, -1.0, 1.0));
  const double phi = std::abs(wrap_azimuth(std::atan2(v.x, v.y) - sun().azimuth + kPi) - kPi);
  const double y = std::clamp(sky_row(zenith, kSkyViewZeniths), 0.0, kSkyViewZeniths - 1.0);
  const double x = std::clamp(phi / kPi, 0.0, 1.0) * (kSkyViewAzimuths - 1);
  const int i = std::min(static_cast<int>(y), kSkyViewZeniths - 2);
  const int j = std::min(static_cast<int>(x), kSkyViewAzimuths - 2);
  const double fy = y - i, fx = x - j;
  const auto at = [&](int ii, int jj) {
    return &(*sky_)[(static_cast<std::size_t>(ii) * kSkyViewAzimuths + jj) * kPhysicalXyzCount];
  };
  const double *a = at(i, j), *b = at(i, j + 1), *c = at(i + 1, j), *d = at(i + 1, j + 1);
  for (int k = 0; k < kPhysicalXyzCount; ++k)
    r[k] += (1 - fy) * ((1 - fx) * a[k] + fx * b[k]) + fy * ((1 - fx) * c[k] + fx * d[k]);
  return to_xyz(r);
}

Xyz PhysicalSkyModel::to_xyz(std::span<const double> radiance) const {
  return weighted_xyz(xyz_weights_, radiance);
}

std::vector<double> PhysicalSkyModel::reference_wavelengths(const EvaluationOptions& o) const {
  return reference_wavelengths_of(o, name(), xyz_.nm, kNishitaMinNm, kNishitaMaxNm);
}

ReferenceValue PhysicalSkyModel::reference_value(const EvaluationOptions& o,
                                                 std::span<const double> radiance,
                                                 std::span<const double> se) const {
  return weighted_reference_value(o, xyz_weights_, radiance, se);
}

std::optional<double> PhysicalSkyModel::spectral_radiance(Vec3 view, double nm) const {
  if (!(nm >= kNishitaMinNm && nm <= kNishitaMaxNm)) return std::nullopt;
  // One Spectral for both parts (nishita's spectral_radiance would build its own).
  const Spectral spec = single_->spectral_at(std::span<const double>(&nm, 1));
  const Vec3 v = normalize(view);
  double single[1] = {0.0}, ms[1] = {0.0};
  atmosphere().single_scattering(observer_, v, sun_, spec, single);
  multiple_scattering(v, spec, {lut_weight(nm)}, ms);
  return single[0] + ms[0];
}

ModelInfo PhysicalSkyModel::registry_entry_of(std::string_view name, std::string_view orders,
                                              std::string_view error) {
  ModelInfo info = NishitaModel::registry_entry();
  info.name = std::string(name);
  info.no_gpu.clear();  // gpu_sky(): the whole-sky LUT
  info.output = fmt::format(
      "XYZ with Y [cd/m^2] for the ASTM G-173 extraterrestrial sun (41 wavelengths, 10 nm apart, "
      "380-780 nm, spline weights: docs/ATMOSPHERE.md); spectral radiance [W m^-2 sr^-1 nm^-1] "
      "360-830 nm; with --solar-irradiance E both per flat irradiance E; in-scattered light of {}; "
      "the ground reflects only with an explicit --albedo; --include-sun / --sun-only: the solar "
      "disc (0.2665 deg, limb-darkened, through the atmosphere's "
      "transmittance)",
      orders);
  info.domain = fmt::format(
      "nishita's: any observer altitude 0-10000 km, any view direction and sun elevation; {}: "
      "docs/ATMOSPHERE.md",
      error);
  info.reference = [](const SkyModel& m, Vec3 view, const EvaluationOptions& o,
                      const ReferenceRequest& rq) {
    const auto& p = static_cast<const PhysicalSkyModel&>(m);
    const NishitaModel& n = p.single_scattering();
    const std::vector<double> nm = p.reference_wavelengths(o);
    const auto spec = n.spectral_at(nm);
    atmosphere::PathTracerSettings s;
    s.paths = rq.paths;
    s.seed = rq.seed;
    const auto r = atmosphere::path_trace(n.atmosphere().parameters(), n.observer(),
                                          normalize(view), p.sun().direction(), spec, s);
    return p.reference_value(o, r.radiance, r.standard_error);
  };
  info.reference_description =
      "the Monte Carlo path tracer of the same atmosphere (atmosphere/path_tracer.h: every order "
      "of scattering, segments estimator; standard errors)";
  info.bench = BenchPolicy{.extra = BenchPolicy::Extra::precomputation};
  info.costly_setup = true;
  // A table per parameter set (hillaire 0.5 s, bruneton 12 s of CPU): the search is nishita's
  // (the same atmosphere, single scattering), this model gives the scale and the residual at the
  // parameters found (docs/MEASURED.md, "Aerosols").
  info.estimation = aerosol_estimation(info.name);
  info.estimation->surrogate = std::string(NishitaModel::kName);
  info.estimation->description += ", searched with nishita's single scattering";
  return info;
}

}  // namespace skylight
