#include "skylight/models/cie_sky.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "skylight/core/data.h"
#include "skylight/core/error.h"

namespace skylight {
namespace {

const std::vector<CieSkyType>& sky_types() {
  static const std::vector<CieSkyType> types = [] {
    const auto t = data::load_table("cie_standard_sky/cie_s011_2003_sky_types.csv", true, 8);
    std::vector<CieSkyType> out;
    for (std::size_t r = 0; r < t.rows(); ++r) {
      CieSkyType s;
      s.type = static_cast<int>(t.number(r, t.column("sky_type")));
      s.a = t.number(r, t.column("a"));
      s.b = t.number(r, t.column("b"));
      s.c = t.number(r, t.column("c"));
      s.d = t.number(r, t.column("d"));
      s.e = t.number(r, t.column("e"));
      if (s.type != static_cast<int>(r) + 1)
        throw IoError(
            fmt::format("cie_standard_sky/cie_s011_2003_sky_types.csv line {}: expected "
                        "sky_type {}, found {}",
                        r + 2, r + 1, s.type));
      out.push_back(s);
    }
    if (out.size() != 15)
      throw IoError("cie_standard_sky/cie_s011_2003_sky_types.csv: expected 15 sky types");
    return out;
  }();
  return types;
}

const std::vector<KittlerDarulaParameters>& kd_table() {
  static const std::vector<KittlerDarulaParameters> rows = [] {
    const char* path = "cie_standard_sky/kittler_darula_zenith_luminance.csv";
    const auto t = data::load_table(path, true, 10);
    std::vector<KittlerDarulaParameters> out;
    for (std::size_t r = 0; r < t.rows(); ++r) {
      if (t.number(r, 0) != static_cast<double>(r + 1))
        throw IoError(fmt::format("{} line {}: expected sky_type {}", path, r + 2, r + 1));
      KittlerDarulaParameters k;
      k.Tv = t.number(r, t.column("Tv"));
      k.A = t.number(r, t.column("A"));
      k.A1 = t.number(r, t.column("A1"));
      k.A2 = t.number(r, t.column("A2"));
      k.B = t.number(r, t.column("B"));
      k.C = t.number(r, t.column("C"));
      k.D = t.number(r, t.column("D"));
      k.E = t.number(r, t.column("E"));
      k.Dv_over_Ev = t.number(r, t.column("Dv_over_Ev"));
      out.push_back(k);
    }
    if (out.size() != 15) throw IoError(fmt::format("{}: expected 15 sky types", path));
    return out;
  }();
  return rows;
}

void require_type(int type, int max) {
  if (type < 1 || type > max)
    throw InvalidArgument(
        fmt::format("cie_type = {} is outside the valid range [1, {}]", type, max));
}

PerezCoefficients to_perez(const CieSkyType& t) {
  // phi f = (1 + a e^{b/cos Z}) (1 - c e^{d pi/2} + c e^{d chi} + e cos^2 chi)
  return {t.a, t.b, t.c, t.d, t.e, 1.0 - t.c * std::exp(t.d * 0.5 * kPi)};
}

double traditional_overcast(double Z) {
  return (1.0 + 2.0 * std::cos(Z)) / 3.0;
}

}  // namespace

const CieSkyType& cie_sky_type(int type) {
  require_type(type, 15);
  return sky_types()[static_cast<std::size_t>(type - 1)];
}

double cie_gradation(const CieSkyType& t, double Z) {
  return perez_function({t.a, t.b, 0.0, 0.0, 0.0, 1.0}, std::cos(Z), 0.0);
}

double cie_indicatrix(const CieSkyType& t, double chi) {
  PerezCoefficients indicatrix_only = to_perez(t);
  indicatrix_only.A = 0.0;  // gradation factor = 1
  return perez_function(indicatrix_only, 1.0, chi);
}

double cie_relative_luminance(int type, double Z, double chi, double Zs) {
  require_type(type, kCieTypeCount);
  if (type == 16) return traditional_overcast(Z);
  const CieSkyType& t = cie_sky_type(type);
  return cie_gradation(t, Z) * cie_indicatrix(t, chi) /
         (cie_gradation(t, 0.0) * cie_indicatrix(t, Zs));
}

const KittlerDarulaParameters& kittler_darula_parameters(int type) {
  require_type(type, 15);
  return kd_table()[static_cast<std::size_t>(type - 1)];
}

double kittler_darula_zenith_luminance(int type, double sun_elevation) {
  require_type(type, kCieTypeCount);
  const double gs = std::clamp(sun_elevation, 0.0, kKittlerDarulaClampElevation);
  const double s = std::sin(gs), c = std::cos(gs);
  if (type == 16) {
    const double dv_klx =
        kittler_darula_parameters(1).Dv_over_Ev * kExtraterrestrialIlluminanceKlx * s;
    return 1000.0 * 9.0 / (7.0 * kPi) * dv_klx;
  }
  const KittlerDarulaParameters& k = kittler_darula_parameters(type);
  double kcd = 0.0;
  if (type <= 6 || k.Tv > 12.0) {
    kcd = k.Dv_over_Ev * (k.B * std::pow(s, k.C) / std::pow(c, k.D) + k.E * s);
  } else {
    kcd = k.A * s + 0.7 * (k.Tv + 1.0) * std::pow(s, k.C) / std::pow(c, k.D) + 0.04 * k.Tv;
  }
  return 1000.0 * std::max(kcd, 0.0);
}

ZenithLuminanceBand kittler_darula_zenith_luminance_band(int type, double sun_elevation) {
  require_type(type, kCieTypeCount);
  ZenithLuminanceBand band;
  band.typical = kittler_darula_zenith_luminance(type, sun_elevation);
  const int own = type == 16 ? 1 : type;
  const KittlerDarulaParameters& k = kittler_darula_parameters(own);
  if (own <= 6 || k.Tv > 12.0) {
    // The overcast formula is proportional to Dv/Ev: scale by the range of the typical Dv/Ev.
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (int t = 1; t <= 15; ++t) {
      lo = std::min(lo, kittler_darula_parameters(t).Dv_over_Ev);
      hi = std::max(hi, kittler_darula_parameters(t).Dv_over_Ev);
    }
    band.low = band.typical * lo / k.Dv_over_Ev;
    band.high = band.typical * hi / k.Dv_over_Ev;
  } else {
    const double gs = std::clamp(sun_elevation, 0.0, kKittlerDarulaClampElevation);
    const double s = std::sin(gs), c = std::cos(gs);
    auto lvz = [&](double tv) {
      const double a = k.A1 * tv + k.A2;
      return 1000.0 *
             std::max(a * s + 0.7 * (tv + 1.0) * std::pow(s, k.C) / std::pow(c, k.D) + 0.04 * tv,
                      0.0);
    };
    band.low = lvz(kKittlerDarulaBandTvMin);
    band.high = lvz(kKittlerDarulaBandTvMax);
  }
  band.low = std::min(band.low, band.typical);
  band.high = std::max(band.high, band.typical);
  return band;
}

const ParameterSchema<CieParameters>& CieParameters::schema() {
  static const auto s = [] {
    ParameterSchema<CieParameters> s;
    s.integer(
        &CieParameters::type,
        {.name = "cie-type",
         .unit = "1",
         .kind = ParameterKind::integer,
         .min = 1,
         .max = kCieTypeCount,
         .default_value = ParameterValue(static_cast<double>(CieParameters{}.type)),
         .description = "sky type 1-15 (CIE S 011), 16 = traditional overcast (1 + 2 cos Z)/3"});
    s.optional_number(&CieParameters::zenith_luminance,
                      {.name = "zenith-luminance",
                       .unit = "cd/m^2",
                       .min = kMinZenithLuminance,
                       .max = kMaxZenithLuminance,
                       .default_value = Absent{"Kittler & Darula typical value for the type"},
                       .description = "absolute zenith luminance Lz"});
    return s;
  }();
  return s;
}

CieSkyModel::CieSkyModel(const CieParameters& p) : SkyModel(p.sun), params_(p), type_(p.type) {
  CieParameters::schema().validate(p, model_context(kName));
  sun_up_ = p.sun.zenith <= 0.5 * kPi;
  typical_luminance_ = !p.zenith_luminance.has_value();
  zenith_luminance_ = p.zenith_luminance
                          ? *p.zenith_luminance
                          : kittler_darula_zenith_luminance(type_, p.sun.elevation());
  distribution_.mode = PerezDistribution::Mode::luminance;
  distribution_.white = kD65WhiteSrgb;
  distribution_.sun = p.sun.direction();
  if (type_ <= 15) {
    const CieSkyType& t = cie_sky_type(type_);
    distribution_.coefficients[0] = to_perez(t);
    const double norm = cie_gradation(t, 0.0) * cie_indicatrix(t, p.sun.zenith);
    distribution_.scale[0] = sun_up_ ? zenith_luminance_ / norm : 0.0;
  }
}

Xyz CieSkyModel::tristimulus(Vec3 view) const {
  if (type_ == 16) {
    if (!sun_up_ || view.z < 0.0) return {};
    return xyY_to_xyz(kD65WhiteSrgb, zenith_luminance_ * (1.0 + 2.0 * view.z) / 3.0);
  }
  return distribution_.evaluate(view);
}

void CieSkyModel::tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  if (type_ != 16) return distribution_.evaluate_batch(dirs, out);
  // (1 + 2 cos Z) / 3 needs no transcendental: a plain loop the compiler vectorises.
  const Xyz w = xyY_to_xyz(kD65WhiteSrgb, 1.0);
  const float lz = sun_up_ ? static_cast<float>(zenith_luminance_) : 0.0f;
  const float wx = static_cast<float>(w.X), wz = static_cast<float>(w.Z);
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const float z = dirs.z[i];
    const float Y = z >= 0.0f ? lz * (1.0f + 2.0f * z) * (1.0f / 3.0f) : 0.0f;
    out.X[i] = wx * Y;
    out.Y[i] = Y;
    out.Z[i] = wz * Y;
  }
}

ParameterValues CieSkyModel::parameter_values() const {
  return CieParameters::schema().values_of(params_);
}

Domain CieSkyModel::domain() const {
  Domain d = sun_below_horizon(Validity::undefined,
                               "the CIE general sky describes daylight only; sky is 0");
  if (!sun_up_) return d;
  const double gs = sun().elevation();
  if (typical_luminance_ && (gs < kKittlerDarulaMinElevation || gs > kKittlerDarulaMaxElevation)) {
    d.issues.push_back({"sun_elevation", Validity::extrapolated,
                        fmt::format("Kittler-Darula typical zenith luminance is recommended for "
                                    "solar elevations 10-80 deg, not {:.3g} deg",
                                    rad_to_deg(gs))});
  }
  return d;
}

namespace {

// The photo fit's ln L: ln(L / Lz) of the type p[0] (CIE S 011 eq. 1); -infinity where it is 0.
EstimationPolicy::LogLuminance prepare_relative_luminance(const SunPosition& sun,
                                                          std::span<const Vec3> views) {
  auto v = std::make_shared<std::vector<Vec3>>(views.begin(), views.end());
  return
      [v, sun](std::span<const double> p, std::span<const std::size_t> idx, std::span<double> out) {
        const Vec3 s = sun.direction();
        const int type = static_cast<int>(p[0]);
        for (std::size_t k = 0; k < idx.size(); ++k) {
          const Vec3 d = (*v)[idx[k]];
          const double rel = cie_relative_luminance(type, std::acos(clamp_cosine(d.z)),
                                                    angle_between(d, s), sun.zenith);
          out[k] = rel > 0.0 ? std::log(rel) : -std::numeric_limits<double>::infinity();
        }
      };
}

}  // namespace

ModelInfo CieSkyModel::registry_entry() {
  return ModelInfo{
      .name = std::string(kName),
      .description =
          "ISO 15469 / CIE S 011:2003 Standard General Sky, types 1-15, and 16 = traditional "
          "overcast",
      .output = "luminance Y [cd/m^2]; XYZ at D65 chromaticity (0.3127, 0.3290)",
      .parameters = CieParameters::schema().specs(),
      .domain =
          "all sun positions above the horizon; the Kittler-Darula typical zenith luminance is "
          "recommended for solar elevations 10-80 deg (flagged extrapolated outside)",
      .luminance_only = true,
      .make = model_factory<CieSkyModel, CieParameters>(),
      .neural = NeuralPolicy{},
      // The 15 standard types of CIE S 011 ranked against the photo (type 16, the traditional
      // overcast sky, is not one of them).
      .estimation = EstimationPolicy{.method = EstimationPolicy::Method::ranking,
                                     .axes = {{.parameter = "cie-type",
                                               .label = "CIE sky type",
                                               .note = "(of 15, CIE S 011)",
                                               .min = 1,
                                               .max = 15,
                                               .grid_points = 15}},
                                     .prepare = prepare_relative_luminance,
                                     .description = "the best CIE S 011 standard sky type",
                                     .ranking_field = "cie_ranking",
                                     .ranking_key = "type"},
      // In the sun zenith, the type (--set cie-type=N) held fixed.
      .sh_fit = ShFitPolicy{},
      .bench = BenchPolicy{.by_default = true},
      .report =
          ReportPolicy{
              .title = "CIE", .axis = "cie-type", .axis_label = "type ", .colour = "#d62728"},
  };
}

std::optional<GpuSky> CieSkyModel::gpu_sky() const {
  if (type_ <= 15) {
    GpuSky g = distribution_.gpu_sky();
    g.comment = fmt::format("cie, type {}: {}", type_, g.comment);
    return g;
  }
  // Type 16, the traditional overcast sky: L_z (1 + 2 cos Z) / 3 (as tristimulus()).
  GpuSky g;
  g.glsl =
      "uniform float skylight_cie_zenith;  // L_z, 0 with the sun below the horizon\n"
      "uniform vec2 skylight_cie_white;   // X / Y and Z / Y\n"
      "vec3 skylight_cie_overcast(vec3 dir) {\n"
      "  if (dir.z < 0.0) return vec3(0.0);\n"
      "  float Y = skylight_cie_zenith * (1.0 + 2.0 * dir.z) / 3.0;\n"
      "  return vec3(skylight_cie_white.x * Y, Y, skylight_cie_white.y * Y);\n"
      "}\n";
  g.expression = "skylight_cie_overcast(dir)";
  const Xyz w = xyY_to_xyz(kD65WhiteSrgb, 1.0);
  g.uniforms = {gpu_uniform("skylight_cie_zenith", {sun_up_ ? zenith_luminance_ : 0.0}),
                gpu_uniform("skylight_cie_white", {w.X, w.Z})};
  g.comment = "cie, type 16: the traditional overcast sky";
  return g;
}

}  // namespace skylight
