#include "skylight/models/evaluation.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/interleave.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/core/parameters.h"
#include "skylight/core/xyz_quadrature.h"

namespace skylight {

std::string_view to_string(SunMode mode) {
  switch (mode) {
    case SunMode::sky:
      return "sky";
    case SunMode::sky_and_sun:
      return "sky+sun";
    case SunMode::sun_only:
      return "sun-only";
  }
  return "sky";
}

const ParameterSchema<SolarDisc>& SolarDisc::schema() {
  static const ParameterSchema<SolarDisc> s = [] {
    ParameterSchema<SolarDisc> s;
    s.custom(
         {.name = "include-sun",
          .kind = ParameterKind::flag,
          .default_value = ParameterValue(false),
          .description = "add the solar disc (models with a sun)"},
         [](SolarDisc& m, const ParameterValue& v) {
           if (std::get<bool>(v)) m.mode = SunMode::sky_and_sun;
         },
         [](const SolarDisc& m) -> std::optional<ParameterValue> {
           return m.mode == SunMode::sky_and_sun;
         })
        .custom(
            {.name = "sun-only",
             .kind = ParameterKind::flag,
             .default_value = ParameterValue(false),
             .description = "the solar disc alone, without the sky"},
            [](SolarDisc& m, const ParameterValue& v) {
              if (std::get<bool>(v)) m.mode = SunMode::sun_only;
            },
            [](const SolarDisc& m) -> std::optional<ParameterValue> {
              return m.mode == SunMode::sun_only;
            });
    return s;
  }();
  return s;
}

void check_sun_mode(const SkyModel& model, SunMode mode) {
  if (mode != SunMode::sky && !model.has_sun())
    throw InvalidArgument(fmt::format("{}/{}: model '{}' has no sun", spelled("include-sun"),
                                      spelled("sun-only"), model.name()));
}

ParameterSpec model_spec() {
  std::string names;
  std::vector<std::string> choices;
  for (const auto& m : model_registry()) {
    names += (names.empty() ? "" : "|") + m.name;
    choices.push_back(m.name);
  }
  ParameterSpec s{.name = "model",
                  .kind = ParameterKind::text,
                  .default_value = Required{},
                  .description = "sky model: " + names + " (see `skylight models`)"};
  s.choices = std::move(choices);
  return s;
}

ParameterSpec sun_elevation_spec() {
  const ParameterSpec& z = sun_parameter_specs()[0];
  return {.name = "sun-elevation",
          .unit = "deg",
          .min = 90.0 - z.max,
          .max = 90.0 - z.min,
          .default_value = Absent{"90 - sun zenith"},
          .description = "solar elevation (alternative to --sun-zenith)"};
}

const ParameterSchema<EvaluationOptions>& EvaluationOptions::schema() {
  static const ParameterSchema<EvaluationOptions> s = [] {
    using E = EvaluationOptions;
    ParameterSchema<E> s;
    s.choice(
         &E::quantity,
         {.name = "quantity",
          .kind = ParameterKind::text,
          .default_value = ParameterValue(std::string("rgb")),
          .description =
              "rgb (linear sRGB), xyz (Y in cd/m^2), luminance (cd/m^2), spectral (W m^-2 sr^-1 "
              "nm^-1)"},
         {{"rgb", Quantity::rgb},
          {"xyz", Quantity::xyz},
          {"luminance", Quantity::luminance},
          {"spectral", Quantity::spectral}})
        .numbers(&E::wavelengths_nm,
                 {.name = "wavelengths",
                  .unit = "nm",
                  .kind = ParameterKind::numbers,
                  .min = 1.0,
                  .max = 10000.0,
                  .count = 0,
                  .default_value = Absent{"none"},
                  .description = "wavelengths for --quantity spectral, e.g. 450,550,650"});
    return s;
  }();
  return s;
}

void validate(const EvaluationOptions& o) {
  const bool spectral = o.quantity == Quantity::spectral;
  if (spectral && o.wavelengths_nm.empty())
    throw InvalidArgument(fmt::format("{} spectral needs {} NM[,NM...]", spelled("quantity"),
                                      spelled("wavelengths")));
  if (!spectral && !o.wavelengths_nm.empty())
    throw InvalidArgument(fmt::format("{} is only used with {} spectral", spelled("wavelengths"),
                                      spelled("quantity")));
}

void validate(const EvaluationOptions& o, const SkyModel& model) {
  validate(o);
  check_sun_mode(model, o.sun);
  if (o.quantity == Quantity::spectral && !find_model(model.name())->spectral)
    throw InvalidArgument(fmt::format("{} spectral: model '{}' has no spectral output",
                                      spelled("quantity"), model.name()));
}

std::vector<std::string> quantity_columns(const EvaluationOptions& o) {
  switch (o.quantity) {
    case Quantity::rgb:
      return {"r", "g", "b"};
    case Quantity::xyz:
      return {"x", "y", "z"};
    case Quantity::luminance:
      return {"luminance"};
    case Quantity::spectral: {
      std::vector<std::string> out;
      for (double nm : o.wavelengths_nm) out.push_back(fmt::format("L{}", nm));
      return out;
    }
  }
  return {};
}

const ParameterSchema<ReferenceOptions>& ReferenceOptions::schema() {
  static const ParameterSchema<ReferenceOptions> s = [] {
    ParameterSchema<ReferenceOptions> s;
    s.flag(&ReferenceOptions::reference,
           {.name = "reference",
            .description = "the model's reference integrator (the brute force or the Monte Carlo "
                           "path tracer its fast path is checked against), with a standard-error "
                           "column per value; the sky alone"})
        .custom(
            {.name = "paths",
             .unit = "1",
             .kind = ParameterKind::integer,
             .min = 2.0,
             .max = 1e9,
             .default_value = ParameterValue(20000.0),
             .description = "--reference: Monte Carlo paths per wavelength"},
            [](ReferenceOptions& r, const ParameterValue& v) {
              r.request.paths = static_cast<std::uint64_t>(std::get<double>(v));
            },
            [](const ReferenceOptions& r) -> std::optional<ParameterValue> {
              return static_cast<double>(r.request.paths);
            })
        .custom(
            {.name = "seed",
             .unit = "1",
             .kind = ParameterKind::integer,
             .min = 0.0,
             .max = 4294967295.0,
             .default_value = ParameterValue(1.0),
             .description = "--reference: the paths' seed"},
            [](ReferenceOptions& r, const ParameterValue& v) {
              r.request.seed = static_cast<std::uint64_t>(std::get<double>(v));
            },
            [](const ReferenceOptions& r) -> std::optional<ParameterValue> {
              return static_cast<double>(r.request.seed);
            });
    return s;
  }();
  return s;
}

ReferenceValue evaluate_reference(const ModelInfo& info, const SkyModel& model, Vec3 view,
                                  const EvaluationOptions& o, const ReferenceRequest& request) {
  if (!info.reference)
    throw InvalidArgument(
        fmt::format("{}: model '{}' has no reference integrator", spelled("reference"), info.name));
  if (o.sun != SunMode::sky)
    throw InvalidArgument(fmt::format("{} evaluates the sky alone (without {} or {})",
                                      spelled("reference"), spelled("include-sun"),
                                      spelled("sun-only")));
  return info.reference(model, view, o, request);
}

std::vector<double> evaluate(const SkyModel& model, Vec3 v, const EvaluationOptions& o) {
  const bool sky = o.sun != SunMode::sun_only, sun = o.sun != SunMode::sky;
  if (o.quantity == Quantity::spectral) {
    std::vector<double> out;
    for (double nm : o.wavelengths_nm) {
      double L = 0.0;
      if (sky) {
        const auto s = model.spectral_radiance(v, nm);
        if (!s)
          throw InvalidArgument(fmt::format("{}: {} nm is outside the range of model '{}'",
                                            spelled("wavelengths"), nm, model.name()));
        L += *s;
      }
      if (sun) {
        const auto s = model.sun_spectral_radiance(v, nm);
        if (!s)
          throw InvalidArgument(fmt::format("{}: {} nm is outside the sun's range of model '{}'",
                                            spelled("wavelengths"), nm, model.name()));
        L += *s;
      }
      out.push_back(L);
    }
    return out;
  }
  Xyz c;
  if (sky) c = model.tristimulus(v);
  if (sun) {
    const Xyz s = model.sun_tristimulus(v);
    c = {c.X + s.X, c.Y + s.Y, c.Z + s.Z};
  }
  switch (o.quantity) {
    case Quantity::xyz:
      return {c.X, c.Y, c.Z};
    case Quantity::luminance:
      return {c.Y};
    default: {
      const Rgb rgb = (sky && !sun) ? model.rgb(v) : xyz_to_linear_srgb(c);
      return {rgb.r, rgb.g, rgb.b};
    }
  }
}

namespace {

// Sub-chunks of kBatchChunk directions per parallel_for chunk.
constexpr std::size_t kBatchSubChunks = 16;

[[noreturn, gnu::noinline, gnu::cold]] void non_finite(const SkyModel& model, std::size_t i) {
  throw InvalidArgument(
      fmt::format("model '{}' gives a non-finite value in direction {}: its parameters overflow",
                  model.name(), i));
}

// Throws for the first non-finite value of directions [b, e).
void check_finite(const SkyModel& model, std::size_t b, std::size_t e, std::size_t cols,
                  const double* out) {
  for (std::size_t i = b * cols; i < e * cols; ++i)
    if (!std::isfinite(out[i])) non_finite(model, i / cols);
}

// n directions: direction(i) the unit vector of the i-th (called from the worker threads);
// fill(b, m, x, y, z) the batch path's float input of directions [b, b + m), false if one is bad.
template <class Direction, class Fill>
void evaluate_batch(const SkyModel& model, std::size_t n, Direction direction, Fill fill,

                    const EvaluationOptions& o, std::span<double> out, bool exact) {
  const std::size_t cols = quantity_columns(o).size();
  if (out.size() != n * cols)
    throw InvalidArgument(
        fmt::format("the output holds {} values, not {} x {}", out.size(), n, cols));
  double* dst = out.data();
  const bool batch = !exact && o.sun == SunMode::sky &&
                     (o.quantity == Quantity::xyz || o.quantity == Quantity::luminance);
  parallel_for(n, kBatchChunk * kBatchSubChunks, [&](std::size_t b, std::size_t e) {
    if (!batch) {
      for (std::size_t i = b; i < e; ++i) {
        const std::vector<double> v = evaluate(model, direction(i), o);
        std::copy(v.begin(), v.end(), dst + i * cols);
      }
      check_finite(model, b, e, cols, dst);
      return;
    }
    // One buffer per worker thread, kept between calls (no allocation per chunk).
    thread_local std::vector<float> buffer;
    if (buffer.size() < 6 * kBatchChunk) buffer.resize(6 * kBatchChunk);
    for (std::size_t sb = b; sb < e; sb += kBatchChunk) {
      const std::size_t m = std::min(kBatchChunk, e - sb), se = sb + m;
      float* x = buffer.data();
      float *y = x + m, *z = y + m, *X = z + m, *Y = X + m, *Z = Y + m;
      if (!fill(sb, m, x, y, z))
        for (std::size_t i = sb; i < se; ++i) direction(i);  // throws for the first bad one
      model.tristimulus_batch({{x, m}, {y, m}, {z, m}}, {{X, m}, {Y, m}, {Z, m}});
      const bool finite = cols == 1 ? widen(Y, m, dst + sb) : soa_to_rows(X, Y, Z, m, dst + 3 * sb);
      if (!finite) check_finite(model, sb, se, cols, dst);
    }
  });
}

}  // namespace

void evaluate_rows(const SkyModel& model, std::span<const double> directions,
                   const EvaluationOptions& o, std::span<double> out, bool exact) {
  if (directions.size() % 3 != 0)
    throw InvalidArgument(
        fmt::format("directions hold {} values, not a multiple of 3", directions.size()));
  const double* p = directions.data();
  const auto direction = [p](std::size_t i) { return row_direction(p, i); };
  const auto fill = [p](std::size_t b, std::size_t m, float* x, float* y, float* z) {
    return directions_to_soa(p + 3 * b, m, x, y, z);
  };
  evaluate_batch(model, directions.size() / 3, direction, fill, o, out, exact);
}

void evaluate_soa(const SkyModel& model, const DirectionsSoA& d, const XyzSoA& out) {
  const std::size_t n = d.size();
  if (d.y.size() != n || d.z.size() != n || out.X.size() != n || out.Y.size() != n ||
      out.Z.size() != n)
    throw InvalidArgument("x, y, z and the outputs must have one length");
  // Sub-chunks of kBatchChunk: the checks read what the kernel reads and writes in L1.
  parallel_for(n, kBatchChunk * kBatchSubChunks, [&](std::size_t cb, std::size_t ce) {
    for (std::size_t b = cb; b < ce; b += kBatchChunk) {
      const std::size_t m = std::min(kBatchChunk, ce - b);
      const XyzSoA o{out.X.subspan(b, m), out.Y.subspan(b, m), out.Z.subspan(b, m)};
      model.tristimulus_batch({d.x.subspan(b, m), d.y.subspan(b, m), d.z.subspan(b, m)}, o);
      // Checked after the kernel has brought the directions into L1 (its arithmetic overlaps the
      // memory reads better than a streaming check does).
      if (!unit_soa(d.x.data() + b, d.y.data() + b, d.z.data() + b, m))
        for (std::size_t i = b; i < b + m; ++i)
          if (!unit_soa(d.x.data() + i, d.y.data() + i, d.z.data() + i, 1))
            throw InvalidArgument(fmt::format(
                "direction {} = ({}, {}, {}) is not a unit vector (|v|^2 within {} of 1)", i,
                d.x[i], d.y[i], d.z[i], kFloatUnitLengthTolerance));
      for (const auto& channel : {o.X, o.Y, o.Z})
        if (!all_finite(channel.data(), m))
          for (std::size_t i = 0; i < m; ++i)
            if (!std::isfinite(channel[i])) non_finite(model, b + i);
    }
  });
}

void evaluate_angles(const SkyModel& model, std::span<const double> zenith_deg,
                     std::span<const double> azimuth_deg, const EvaluationOptions& o,
                     std::span<double> out, bool exact) {
  const std::size_t n = zenith_deg.size();
  if (azimuth_deg.size() != n)
    throw InvalidArgument("zenith_deg and azimuth_deg must have one length");
  for (std::size_t i = 0; i < n; ++i) {
    if (!(zenith_deg[i] >= 0.0 && zenith_deg[i] <= 180.0))
      throw InvalidArgument(
          fmt::format("zenith_deg[{}] = {} is outside [0, 180]", i, zenith_deg[i]));
    if (!(azimuth_deg[i] >= -360.0 && azimuth_deg[i] <= 360.0))
      throw InvalidArgument(
          fmt::format("azimuth_deg[{}] = {} is outside [-360, 360]", i, azimuth_deg[i]));
  }
  const auto direction = [&](std::size_t i) {
    return direction_from_angles(deg_to_rad(zenith_deg[i]),
                                 wrap_azimuth(deg_to_rad(azimuth_deg[i])));
  };
  const auto fill = [&](std::size_t b, std::size_t m, float* x, float* y, float* z) {
    for (std::size_t i = 0; i < m; ++i) {
      const Vec3 d = direction(b + i);
      x[i] = static_cast<float>(d.x);
      y[i] = static_cast<float>(d.y);
      z[i] = static_cast<float>(d.z);
    }
    return true;
  };
  evaluate_batch(model, n, direction, fill, o, out, exact);
}

std::vector<double> reference_wavelengths_of(const EvaluationOptions& o, std::string_view model,
                                             std::span<const double> xyz_nm, double min_nm,
                                             double max_nm) {
  if (o.quantity == Quantity::rgb)
    throw InvalidArgument(
        fmt::format("{} gives xyz, luminance or spectral (not rgb)", spelled("reference")));
  if (o.quantity != Quantity::spectral) return {xyz_nm.begin(), xyz_nm.end()};
  for (double nm : o.wavelengths_nm)
    if (!(nm >= min_nm && nm <= max_nm))
      throw InvalidArgument(fmt::format("{}: {} nm is outside the range of model '{}'",
                                        spelled("wavelengths"), nm, model));
  return o.wavelengths_nm;
}

ReferenceValue weighted_reference_value(const EvaluationOptions& o, std::span<const Cmf> weights,
                                        std::span<const double> radiance,
                                        std::span<const double> se) {
  SKYLIGHT_CHECK(radiance.size() == se.size(), "reference: size mismatch");
  ReferenceValue r;
  if (o.quantity == Quantity::spectral) {
    r.value.assign(radiance.begin(), radiance.end());
    r.standard_error.assign(se.begin(), se.end());
    return r;
  }
  const Xyz c = weighted_xyz(weights, radiance);  // checks the sizes
  // The standard errors of the weighted sums, the wavelengths' estimates being independent.
  Xyz v;
  for (std::size_t k = 0; k < weights.size(); ++k) {
    v.X += std::pow(weights[k].x * se[k], 2);
    v.Y += std::pow(weights[k].y * se[k], 2);
    v.Z += std::pow(weights[k].z * se[k], 2);
  }
  const double f = kMaxLuminousEfficacy;
  if (o.quantity == Quantity::luminance) {
    r.value = {c.Y};
    r.standard_error = {f * std::sqrt(v.Y)};
  } else {
    r.value = {c.X, c.Y, c.Z};
    r.standard_error = {f * std::sqrt(v.X), f * std::sqrt(v.Y), f * std::sqrt(v.Z)};
  }
  return r;
}

}  // namespace skylight
