#include "skylight/daylight/irradiance.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/colorimetry.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"

namespace skylight::daylight {
namespace {

// The melanopic channel's wavelengths: s_mel's table range, 5 nm trapezoid (s_mel varies on a
// scale of tens of nm; the rule's error is measured in irradiance_test.cpp).
constexpr double kMelanopicFirstNm = 380.0, kMelanopicLastNm = 780.0, kMelanopicStepNm = 5.0;

const Vec3 kUp{0.0, 0.0, 1.0};

const std::string kPerez1990IrradianceOnly =
    "perez1990 transposes irradiance (its F1, F2 are the irradiance coefficients): no "
    "illuminance or melanopic values";

// The melanopic weights w_k = s_mel(lambda_k) * trapezoid step [nm].
std::vector<std::array<double, 2>> melanopic_weights() {
  std::vector<std::array<double, 2>> w;
  const int n =
      static_cast<int>(std::lround((kMelanopicLastNm - kMelanopicFirstNm) / kMelanopicStepNm));
  for (int k = 0; k <= n; ++k) {
    const double nm = kMelanopicFirstNm + k * kMelanopicStepNm;
    const double step = (k == 0 || k == n) ? 0.5 * kMelanopicStepNm : kMelanopicStepNm;
    w.push_back({nm, melanopic_sensitivity(nm) * step});
  }
  return w;
}

// Melanopic radiance [W m^-2 sr^-1] of a spectral function: sum of value(nm) w_k over the
// wavelengths it gives (nullopt: outside the model's range, left out; `missing` gets the share of
// s_mel's weight left out).
template <class F>
double melanopic_of(F&& spectral, double* missing = nullptr) {
  static const auto weights = melanopic_weights();
  static const double total = [] {
    double t = 0.0;
    for (const auto& [nm, w] : weights) t += w;
    return t;
  }();
  double sum = 0.0, left_out = 0.0;
  for (const auto& [nm, w] : weights) {
    if (w == 0.0) continue;
    const std::optional<double> v = spectral(nm);
    if (v)
      sum += *v * w;
    else
      left_out += w;
  }
  if (missing) *missing = left_out / total;
  return sum;
}

// How a front end gives a sky measured light: "--model perez with --dni and --dhi, or --epw".
std::string measured_light_flags() {
  return fmt::format("{} perez with {} and {}, or {}", spelled("model"), spelled("dni"),
                     spelled("dhi"), spelled("epw"));
}

std::string not_broadband(const SkyModel& model) {
  return fmt::format(
      "model '{}' gives luminance and spectra, not broadband irradiance: the W/m^2 values need "
      "measured light ({})",
      model.name(), measured_light_flags());
}

bool is_spectral(const SkyModel& model) {
  return model.spectral_radiance({0.0, 0.0, 1.0}, 555.0).has_value();
}

// One channel's horizontal light; `direct_normal` absent for a sky without a sun.
struct ChannelInput {
  std::optional<double> direct_normal;
  double diffuse_horizontal = 0.0;
};

// Applies a transposition to a channel; without a direct value, the direct and ground parts
// (and so the global value) are absent.
template <class F>
PlaneLight transposed(const ChannelInput& in, const SunPosition& sun, F&& transposition) {
  const HorizontalLight light{in.direct_normal.value_or(0.0), in.diffuse_horizontal, sun};
  PlaneLight p = transposition(light);
  if (!in.direct_normal) p.direct = p.ground_diffuse = std::nullopt;
  return p;
}

// The `sky` method's parts on a grid of values L (one unit), with the direct light on the plane
// and on the horizontal (nullopt: no sun), and the sky scaled by `scale`.
PlaneLight sky_parts_light(const SkyParts& parts, double scale, std::optional<double> direct,
                           std::optional<double> direct_horizontal, double diffuse_site,
                           double albedo, const Plane& plane) {
  PlaneLight p;
  p.sky_diffuse = parts.total * scale;
  p.circumsolar = parts.circumsolar * scale;
  p.horizon = parts.horizon * scale;
  p.isotropic = parts.rest * scale;
  p.direct = direct;
  p.ground_diffuse = std::nullopt;
  if (direct_horizontal)
    p.ground_diffuse = ground_on_plane(*direct_horizontal + diffuse_site, albedo, plane);
  return p;
}

// The melanopic sky on the spectral grid (one value per cell) [W m^-2 sr^-1].
std::vector<float> melanopic_sky(const SkyModel& model, const SkyGrid& grid, double& missing) {
  std::vector<float> m(grid.size());
  std::vector<double> miss(grid.size(), 0.0);
  parallel_for(grid.size(), 16, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const Vec3 d = grid.centre(i);
      m[i] = static_cast<float>(
          melanopic_of([&](double nm) { return model.spectral_radiance(d, nm); }, &miss[i]));
    }
  });
  missing = *std::max_element(miss.begin(), miss.end());
  return m;
}

// The melanopic solar disc on a plane of normal n [W/m^2].
double melanopic_sun(const SkyModel& model, Vec3 n, const io::HorizonProfile& horizon) {
  return sun_disc_on_plane(model, n, horizon, [&](Vec3 d) {
    return melanopic_of([&](double nm) { return model.sun_spectral_radiance(d, nm); });
  });
}

void note_missing_wavelengths(double missing, std::vector<std::string>& notes) {
  if (missing > 0.0)
    notes.push_back(fmt::format(
        "melanopic: s_mel's wavelengths outside the model's spectra are left out ({:.2g} of "
        "s_mel's integral over 380-780 nm)",
        missing));
}

// The `sky` method: the model's luminance (and melanopic radiance) integrated over the plane.
void sky_method(const SkyModel& model, const PlaneContext& c, double albedo, PlaneChannels& out) {
  const auto measured = model.measured_light();
  const SunPosition sun = model.sun();
  const Vec3 s = sun.direction(), n = c.plane.normal();
  const std::vector<float> L = sky_luminance_on_grid(model, *c.weights.grid);
  if (measured) {
    const PlaneChannels m = measured_sky_light(L, *measured, sun, c, albedo);
    out.illuminance = m.illuminance;
    out.irradiance = m.irradiance;
    out.sky_normalisation = m.sky_normalisation;
  } else {
    std::optional<double> direct, direct_h;
    if (model.has_sun()) {
      direct = sun_on_plane(model, n, *c.horizon);
      direct_h = sun_on_plane(model, kUp, *c.horizon);
    } else {
      out.notes.push_back(
          fmt::format("model '{}' has no sun: no direct or ground light, and no "
                      "global value",
                      model.name()));
    }
    const SkyParts parts = integrate_sky(c.weights, L, s);
    out.illuminance =
        sky_parts_light(parts, 1.0, direct, direct_h, parts.horizontal_open, albedo, c.plane);
    out.notes.push_back(not_broadband(model));
  }
  if (!is_spectral(model)) {
    out.notes.push_back(
        fmt::format("model '{}' gives no spectra: no melanopic illuminance", model.name()));
    return;
  }
  double missing = 0.0;
  const std::vector<float> m = melanopic_sky(model, *c.spectral_weights.grid, missing);
  note_missing_wavelengths(missing, out.notes);
  if (!model.has_sun()) return;
  const SkyParts mel = integrate_sky(c.spectral_weights, m, s);
  const double ground =
      ground_on_plane(melanopic_sun(model, kUp, *c.horizon) + mel.horizontal_open, albedo, c.plane);
  out.melanopic_edi_lx =
      (mel.total + melanopic_sun(model, n, *c.horizon) + ground) / kMelanopicEfficacyD65;
}

// The horizontal light of the channels a model gives, for the transpositions.
struct ModelInputs {
  std::optional<ChannelInput> irradiance, illuminance, melanopic;
};
ModelInputs model_inputs(const SkyModel& model, std::vector<std::string>& notes) {
  ModelInputs in;
  const io::HorizonProfile flat;
  const Vec3 s = model.sun().direction();
  if (const auto m = model.measured_light()) {
    in.irradiance = ChannelInput{m->dni_w_m2, m->dhi_w_m2};
    in.illuminance = ChannelInput{m->dni_lux, m->dhi_lux};
  } else {
    const SkyGrid& grid = default_sky_grid();
    const std::vector<float> L = sky_luminance_on_grid(model, grid);
    ChannelInput lx;
    for (std::size_t i = 0; i < grid.size(); ++i)
      lx.diffuse_horizontal += L[i] * grid.horizontal_weight(i);
    if (model.has_sun()) lx.direct_normal = sun_on_plane(model, s, flat);
    in.illuminance = lx;
  }
  if (is_spectral(model)) {
    const SkyGrid& grid = spectral_sky_grid();
    double missing = 0.0;
    const std::vector<float> m = melanopic_sky(model, grid, missing);
    note_missing_wavelengths(missing, notes);
    ChannelInput mel;
    for (std::size_t i = 0; i < grid.size(); ++i)
      mel.diffuse_horizontal += m[i] * grid.horizontal_weight(i);
    if (model.has_sun()) mel.direct_normal = melanopic_sun(model, s, flat);
    in.melanopic = mel;
  }
  return in;
}

void transposition_method(const SkyModel& model, const PlaneContext& c, double albedo,
                          PlaneChannels& out) {
  const SunPosition sun = model.sun();
  const auto measured = model.measured_light();
  if (c.method == Transposition::perez1990) {
    if (!measured)
      throw InvalidArgument(fmt::format(
          "{} perez1990 needs measured irradiance (its F1, F2 are fitted to the direct and "
          "diffuse irradiance): {}; model '{}' computes its own light (use {} sky or isotropic)",
          spelled("transposition"), measured_light_flags(), model.name(),
          spelled("transposition")));
    const PlaneChannels m = transposed_measured_light(*measured, sun, c, albedo);
    out.irradiance = m.irradiance;
    out.perez = m.perez;
    out.notes.insert(out.notes.end(), m.notes.begin(), m.notes.end());
    return;
  }
  const ModelInputs in = model_inputs(model, out.notes);
  const auto iso = [&](const HorizontalLight& l) {
    return isotropic_transposition(l, c.plane, albedo, *c.horizon, c.views);
  };
  if (in.irradiance) out.irradiance = transposed(*in.irradiance, sun, iso);
  if (in.illuminance) out.illuminance = transposed(*in.illuminance, sun, iso);
  if (in.melanopic && in.melanopic->direct_normal) {
    const PlaneLight mel = transposed(*in.melanopic, sun, iso);
    out.melanopic_edi_lx = *mel.global() / kMelanopicEfficacyD65;
  }
  if (!measured) out.notes.push_back(not_broadband(model));
  if (!model.has_sun() && !measured)
    out.notes.push_back(fmt::format(
        "model '{}' has no sun: no direct or ground light, and no global value", model.name()));
  if (!is_spectral(model))
    out.notes.push_back(
        fmt::format("model '{}' gives no spectra: no melanopic illuminance", model.name()));
}

}  // namespace

const ParameterSchema<PlaneSettings>& PlaneSettings::schema() {
  static const auto s = [] {
    ParameterSchema<PlaneSettings> s;
    s.number(&PlaneSettings::tilt_deg,
             {.name = "tilt",
              .unit = "deg",
              .min = 0.0,
              .max = 180.0,
              .default_value = ParameterValue(0.0),
              .description = "the plane's tilt from horizontal: 0 faces up, 90 is vertical"});
    s.number(&PlaneSettings::surface_azimuth_deg,
             {.name = "surface-azimuth",
              .unit = "deg",
              .min = 0.0,
              .max = 360.0,
              .default_value = ParameterValue(180.0),
              .description = "the way the plane faces, from north towards east (180: south)"});
    s.optional_number(&PlaneSettings::albedo,
                      {.name = "albedo",
                       .unit = "1",
                       .min = 0.0,
                       .max = 1.0,
                       .default_value = Absent{"the record's albedo with --epw, else 0.2"},
                       .description = "the ground's reflectance (Lambertian); a model with its "
                                      "own ground albedo (hosek) reads it too"});
    s.text(&PlaneSettings::horizon,
           {.name = "horizon",
            .default_value = Absent{"the geometric horizon"},
            .description = "skyline file: CSV azimuth_deg,elevation_deg or PVGIS's horizon "
                           "(CSV or JSON); it blocks the sky and the sun"});
    s.choice(&PlaneSettings::transposition,
             {.name = "transposition",
              .default_value = ParameterValue(std::string("sky")),
              .description = "sky: the model's own sky integrated over the plane's view; "
                             "perez1990: Perez et al. 1990's F1/F2 model; isotropic"},
             {{"sky", Transposition::sky},
              {"perez1990", Transposition::perez1990},
              {"isotropic", Transposition::isotropic}});
    return s;
  }();
  return s;
}

Plane PlaneSettings::plane() const {
  return {deg_to_rad(tilt_deg), deg_to_rad(surface_azimuth_deg)};
}

const SkyGrid& spectral_sky_grid() {
  static const SkyGrid grid(SkyGridSpec{.band_rings = 2, .upper_rings = 22, .sectors = 72});
  return grid;
}

PlaneContext plane_context(const Plane& plane, Transposition method,
                           const io::HorizonProfile& horizon) {
  PlaneContext c;
  c.plane = plane;
  c.method = method;
  c.horizon = &horizon;
  c.weights = plane_weights(default_sky_grid(), plane, horizon);
  c.spectral_weights = plane_weights(spectral_sky_grid(), plane, horizon);
  c.views = horizon_views(c.weights);
  return c;
}

PlaneChannels measured_sky_light(const std::vector<float>& L, const MeasuredLight& m,
                                 const SunPosition& sun, const PlaneContext& c, double albedo) {
  PlaneChannels out;
  const Vec3 s = sun.direction(), n = c.plane.normal();
  out.angle_of_incidence = angle_between(n, s);
  out.sun_open = sun.zenith < 0.5 * kPi && c.horizon->open(s);
  const SkyParts parts = integrate_sky(c.weights, L, s);
  // The sky's level is the measured light's: its grid integral on the horizontal is the measured
  // diffuse light (radiance: luminance over the diffuse efficacy, one factor for the whole sky).
  const double flat = parts.horizontal_flat;
  const double per_lx = flat > 0.0 ? m.dhi_lux / flat : 0.0;
  const double per_w = flat > 0.0 ? m.dhi_w_m2 / flat : 0.0;
  const double open_share = flat > 0.0 ? parts.horizontal_open / flat : 0.0;
  const double open = out.sun_open ? 1.0 : 0.0;
  const double cos_aoi = std::max(0.0, dot(n, s)) * open;
  const double cos_z = std::max(0.0, std::cos(sun.zenith)) * open;
  out.sky_normalisation = per_lx;
  out.illuminance = sky_parts_light(parts, per_lx, m.dni_lux * cos_aoi, m.dni_lux * cos_z,
                                    m.dhi_lux * open_share, albedo, c.plane);
  out.irradiance = sky_parts_light(parts, per_w, m.dni_w_m2 * cos_aoi, m.dni_w_m2 * cos_z,
                                   m.dhi_w_m2 * open_share, albedo, c.plane);
  return out;
}

PlaneChannels transposed_measured_light(const MeasuredLight& m, const SunPosition& sun,
                                        const PlaneContext& c, double albedo) {
  PlaneChannels out;
  const Vec3 s = sun.direction();
  out.angle_of_incidence = angle_between(c.plane.normal(), s);
  out.sun_open = sun.zenith < 0.5 * kPi && c.horizon->open(s);
  const ChannelInput w{m.dni_w_m2, m.dhi_w_m2}, lx{m.dni_lux, m.dhi_lux};
  if (c.method == Transposition::isotropic) {
    const auto iso = [&](const HorizontalLight& l) {
      return isotropic_transposition(l, c.plane, albedo, *c.horizon, c.views);
    };
    out.irradiance = transposed(w, sun, iso);
    out.illuminance = transposed(lx, sun, iso);
    return out;
  }
  SKYLIGHT_CHECK(c.method == Transposition::perez1990, "a transposition, not the sky method");
  if (m.dhi_w_m2 > 0.0)
    out.perez = perez1990_state({m.dni_w_m2, m.dhi_w_m2, sun}, m.air_mass, m.extraterrestrial_w_m2);
  const Perez1990 state = out.perez.value_or(Perez1990{});
  out.irradiance = transposed(w, sun, [&](const HorizontalLight& l) {
    return perez1990_transposition(l, c.plane, albedo, *c.horizon, c.views, state);
  });
  out.notes.push_back(kPerez1990IrradianceOnly);
  return out;
}

PlaneChannels plane_light(const SkyModel& model, const PlaneContext& c, double albedo) {
  PlaneChannels out;
  const SunPosition sun = model.sun();
  out.angle_of_incidence = angle_between(c.plane.normal(), sun.direction());
  out.sun_open = sun.zenith < 0.5 * kPi && c.horizon->open(sun.direction());
  if (c.method == Transposition::sky)
    sky_method(model, c, albedo, out);
  else
    transposition_method(model, c, albedo, out);
  return out;
}

}  // namespace skylight::daylight
