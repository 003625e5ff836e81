#include "skylight/models/pietras.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "skylight/core/camera.h"
#include "skylight/core/data.h"
#include "skylight/core/icosphere.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/core/parameters.h"
#include "skylight/io/file.h"
#include "skylight/models/neural_sky.h"
#include "skylight/nn/glsl.h"
#include "skylight/nn/sky_network.h"

namespace skylight {

const ParameterSchema<PietrasParameters>& PietrasParameters::schema() {
  static const auto s = [] {
    ParameterSchema<PietrasParameters> s;
    const PietrasParameters defaults;
    s.text(
        &PietrasParameters::weights,
        {.name = "weights",
         .kind = ParameterKind::text,
         .default_value =
             Absent{"the embedded log3 network trained on Earth's nishita (data/nn/log3.json)"},
         .description =
             "Pietras weights file (skylight nn train --network pietras|log3; docs/PIETRAS.md)"});
    s.number(
        &PietrasParameters::observer_altitude_m,
        {.name = "observer-altitude",
         .unit = "m",
         .min = 0.0,
         .max = kNishitaMaxAltitude,
         .default_value = ParameterValue(defaults.observer_altitude_m),
         .description = "observer above the ground: the network's density input exp(-h / H0)"});
    return s;
  }();
  return s;
}

nn::PietrasNetwork load_pietras_network_file(const std::filesystem::path& path) {
  const std::string text = io::read_text_file(path);
  if (!nn::is_pietras_json(text))
    throw InvalidArgument(
        fmt::format("{}: not a Pietras network ({}); a sky network ({}) is the model nn's",
                    path.string(), nn::kPietrasFormat, nn::kSkyNetworkFormat));
  return nn::pietras_from_json(text, path.string());
}

const nn::PietrasNetwork& embedded_pietras_network() {
  static const nn::PietrasNetwork net = nn::pietras_from_json(
      data::embedded_file(kEmbeddedPietrasNetwork), std::string("data/") + kEmbeddedPietrasNetwork);
  return net;
}

NishitaParameters nishita_parameters_of(const nn::PietrasNetwork& net) {
  NishitaParameters p;
  for (const auto& [k, v] : net.provenance.source_parameters) {
    if (k == "ground-radius")
      p.ground_radius_m = v;
    else if (k == "top-radius")
      p.top_radius_m = v;
    else if (k == "rayleigh-scale-height")
      p.rayleigh_scale_height_m = v;
    else if (k == "mie-scale-height")
      p.mie_scale_height_m = v;
    else if (k == "mie-g")
      p.mie_g = v;
    else if (k == "ozone")
      p.ozone_du = v;
    else if (k == "solar-irradiance")
      p.solar_irradiance = v;
    else
      throw InvalidArgument(
          fmt::format("provenance.source_parameters: '{}' is not a nishita "
                      "atmosphere parameter",
                      excerpt(k)));
  }
  return p;
}

PietrasSkyModel::PietrasSkyModel(const PietrasParameters& p)
    : PietrasSkyModel(p, p.weights.empty() ? embedded_pietras_network()
                                           : load_pietras_network_file(p.weights)) {}

PietrasSkyModel::PietrasSkyModel(const PietrasParameters& p, nn::PietrasNetwork network)
    : SkyModel(p.sun), params_(p), network_(std::move(network)) {
  PietrasParameters::schema().validate(p, model_context(kName));
  batch_ =
      std::make_unique<nn::PietrasBatch>(network_, p.observer_altitude_m, std::cos(p.sun.zenith));
}

ParameterValues PietrasSkyModel::parameter_values() const {
  return PietrasParameters::schema().values_of(params_);
}

Rgb PietrasSkyModel::rgb(Vec3 view) const {
  const Vec3 v = normalize(view);
  return network_.rgb_at(params_.observer_altitude_m, v.z, dot(v, sun().direction()),
                         std::cos(sun().zenith));
}

Xyz PietrasSkyModel::tristimulus(Vec3 view) const {
  return linear_srgb_to_xyz(rgb(view));
}

void PietrasSkyModel::tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  const std::size_t n = dirs.size();
  // cos alpha0 = z, cos beta0 = view . sun; then rgb into the output spans and the 3x3 matrix in
  // place.
  const Vec3 s = sun().direction();
  std::vector<float> cb(n);
  for (std::size_t i = 0; i < n; ++i)
    cb[i] = static_cast<float>(s.x * dirs.x[i] + s.y * dirs.y[i] + s.z * dirs.z[i]);
  batch_->rgb(dirs.z.data(), cb.data(), out.X.data(), out.Y.data(), out.Z.data(), n);
  linear_srgb_to_xyz_in_place(out);
}

Domain PietrasSkyModel::domain() const {
  return {};
}

PietrasSurfaceTerms pietras_surface_terms(const NishitaSampler& atmosphere, double altitude_m,
                                          Vec3 view, double distance_m, double albedo, Vec3 sun) {
  const double r0 = atmosphere.atmosphere().parameters().ground_radius_m;
  const Vec3 p{0.0, 0.0, r0 + altitude_m};
  const Vec3 q = p + distance_m * view;
  const double rq = length(q);
  const Vec3 up = (1.0 / rq) * q;  // the probe's zenith
  PietrasSurfaceTerms t;
  t.observer_altitude_m = altitude_m;
  t.probe_altitude_m = std::max(rq - r0, 0.0);
  t.cos_view_sun = dot(view, sun);
  t.observer_cos_view_zenith = view.z;
  t.observer_cos_sun_zenith = sun.z;
  t.probe_cos_view_zenith = dot(view, up);
  t.probe_cos_sun_zenith = dot(sun, up);
  t.transmittance = atmosphere.channel_transmittance(altitude_m, view, distance_m);
  t.reflected = atmosphere.reflected(altitude_m, view, distance_m, albedo, sun);
  return t;
}

Rgb pietras_surface(const PietrasSkyFunction& sky, const NishitaSampler& atmosphere,
                    double altitude_m, Vec3 view, double distance_m, double albedo, Vec3 sun) {
  const PietrasSurfaceTerms t =
      pietras_surface_terms(atmosphere, altitude_m, view, distance_m, albedo, sun);
  const Rgb obs = sky(t.observer_altitude_m, t.observer_cos_view_zenith, t.cos_view_sun,
                      t.observer_cos_sun_zenith);
  const Rgb probe =
      sky(t.probe_altitude_m, t.probe_cos_view_zenith, t.cos_view_sun, t.probe_cos_sun_zenith);
  const auto& tr = t.transmittance;
  const Rgb& refl = t.reflected;
  return {obs.r - tr[0] * probe.r + refl.r, obs.g - tr[1] * probe.g + refl.g,
          obs.b - tr[2] * probe.b + refl.b};
}

PietrasSkyFunction sky_function(const nn::PietrasNetwork& net) {
  return [&net](double h, double ca, double cb, double ct) { return net.rgb_at(h, ca, cb, ct); };
}

NetworkFile read_network_file(const std::filesystem::path& path) {
  const std::string text = io::read_text_file(path);
  NetworkFile f;
  if (nn::is_pietras_json(text))
    f.pietras = nn::pietras_from_json(text, path.string());
  else
    f.sky = nn::sky_network_from_json(text, path.string());
  return f;
}

std::unique_ptr<SkyModel> network_model(const NetworkFile& file, const std::string& path,
                                        const SunPosition& sun, std::optional<double> turbidity,
                                        std::optional<double> observer_altitude_m) {
  // What the file's kind of network has no input for.
  const auto refuse = [&](const char* parameter, const char* why) {
    throw InvalidArgument(fmt::format("{}: '{}' is {}", spelled(parameter), excerpt(path), why));
  };
  if (file.pietras) {
    if (turbidity)
      refuse("turbidity",
             "a Pietras network, which has no turbidity input (its atmosphere is the training "
             "planet's)");
    PietrasParameters p;
    p.sun = sun;
    p.weights = path;
    if (observer_altitude_m) p.observer_altitude_m = *observer_altitude_m;
    return std::make_unique<PietrasSkyModel>(p, *file.pietras);
  }
  if (observer_altitude_m)
    refuse("observer-altitude",
           "a sky network, which has no altitude input (only Pietras networks take it)");
  NeuralSkyParameters p;
  p.sun = sun;
  p.weights = path;
  if (turbidity) p.turbidity = *turbidity;
  return std::make_unique<NeuralSkyModel>(p, file.sky);
}

const ParameterSchema<PlanetViewOptions>& PlanetViewOptions::schema() {
  static const ParameterSchema<PlanetViewOptions> s = [] {
    using V = PlanetViewOptions;
    const V d;
    ParameterSchema<V> s;
    ParameterSpec zenith = sun_parameter_specs()[0];
    zenith.default_value = ParameterValue(d.sun_zenith_deg);
    zenith.description = "solar zenith angle at the point below the camera";
    ParameterSpec azimuth = sun_parameter_specs()[1];
    azimuth.default_value = ParameterValue(d.sun_azimuth_deg);
    azimuth.description = "solar azimuth from north towards east (the ground view looks north)";
    s.choice(&V::orbit,
             {.name = "view",
              .kind = ParameterKind::text,
              .default_value = ParameterValue(std::string("orbit")),
              .description = "from orbit or from the ground"},
             {{"orbit", true}, {"ground", false}})
        .number(&V::sun_zenith_deg, zenith)
        .number(&V::sun_azimuth_deg, azimuth)
        .optional_number(&V::altitude_m,
                         {.name = "altitude",
                          .unit = "m",
                          .min = 0.0,
                          .max = 1e10,
                          .default_value = Absent{"orbit: 2 planet radii; ground: 2 m"},
                          .description = "camera above the ground"})
        .number(&V::look_elevation_deg,
                {.name = "look-elevation",
                 .unit = "deg",
                 .min = -90.0,
                 .max = 90.0,
                 .default_value = ParameterValue(d.look_elevation_deg),
                 .description = "ground view: the view's elevation above the horizon"})
        .optional_number(
            &V::fov_deg,
            {.name = "fov",
             .unit = "deg",
             .min = 1.0,
             .max = 170.0,
             .default_value = Absent{"orbit: the atmosphere's disc fills 85 %; ground: 60"},
             .description = "vertical field of view"})
        .number(&V::albedo, {.name = "albedo",
                             .unit = "1",
                             .min = 0.0,
                             .max = 1.0,
                             .default_value = ParameterValue(d.albedo),
                             .description = "grey Lambertian albedo of the ground (Pietras §IV)"})
        .integer(&V::subdivisions,
                 {.name = "subdivisions",
                  .unit = "1",
                  .kind = ParameterKind::integer,
                  .min = 0,
                  .max = kMaxIcosphereSubdivisions,
                  .default_value = ParameterValue(static_cast<double>(d.subdivisions)),
                  .description =
                      "icosphere level of the ground and the shell (10 * 4^n + 2 vertices each)"})
        .integer(&V::width, {.name = "width",
                             .unit = "px",
                             .kind = ParameterKind::integer,
                             .min = 1,
                             .max = kMaxImageSide,
                             .default_value = ParameterValue(static_cast<double>(d.width)),
                             .description = "image width"})
        .integer(&V::height, {.name = "height",
                              .unit = "px",
                              .kind = ParameterKind::integer,
                              .min = 1,
                              .max = kMaxImageSide,
                              .default_value = ParameterValue(static_cast<double>(d.height)),
                              .description = "image height"});
    return s;
  }();
  return s;
}

double PlanetViewOptions::altitude(double r0) const {
  // From orbit, the default camera altitude is two planet radii; from the ground 2 m.
  constexpr double kOrbitAltitudeRadii = 2.0, kGroundAltitudeM = 2.0;
  return altitude_m.value_or(orbit ? kOrbitAltitudeRadii * r0 : kGroundAltitudeM);
}

std::optional<double> PlanetViewOptions::vertical_fov_deg() const {
  constexpr double kGroundFovDeg = 60.0;
  if (fov_deg) return fov_deg;
  if (!orbit) return kGroundFovDeg;
  return std::nullopt;
}

ModelInfo PietrasSkyModel::registry_entry() {
  return ModelInfo{
      .name = std::string(kName),
      .description =
          "Pietras's per-vertex sky network (Pietras §III): small MLPs trained on nishita "
          "(skylight "
          "nn train --network pietras|log3), the paper's 4 x 4-8-4-1 or the log-luminance 3 x "
          "4-16-16-1; any observer altitude, twilight, night exactly dark (the shadow test of the "
          "view ray); fixed cost per direction",
      .output =
          "rgb = the network's linear sRGB in the units of its source's rgb() (nishita: Y in "
          "cd/m^2 for the ASTM G-173 sun), views meeting the ground see the air up to it; XYZ = "
          "rgb converted (D65)",
      .parameters = PietrasParameters::schema().specs(),
      .domain =
          "the training planet's nishita sky (weights file provenance) at any view, sun and "
          "observer altitude; its error against nishita is `skylight nn validate` "
          "(docs/PIETRAS.md); "
          "no spectral output, no solar disc",
      .make = model_factory<PietrasSkyModel, PietrasParameters>(),
      .neural = NeuralPolicy{},
      .sh_fit = ShFitPolicy{},
      // Pietras §III: the network replaces nishita's fast path.
      .bench = BenchPolicy{.baseline = std::string(NishitaModel::kName),
                           .extra = BenchPolicy::Extra::network_kinds},
      // The embedded log3 network, trained on Earth's nishita (data/nn/log3.json), on the ground.
      .report = ReportPolicy{.title = "pietras (log3)",
                             .colour = "#bcbd22",
                             .source = std::string(NishitaModel::kName)},
  };
}

std::optional<GpuSky> PietrasSkyModel::gpu_sky() const {
  // rgb_at(): the network (nn/glsl.h) with its shadow test of the view ray, every view.
  GpuSky g;
  g.glsl = nn::glsl_pietras_sky(network()) +
           "uniform vec3 skylight_sun;  // unit vector, z up\nuniform float skylight_altitude;\n";
  g.expression = "skylight_pietras_at(skylight_altitude, dir, skylight_sun)";
  g.output = GpuSky::Output::rgb;
  const Vec3 s = sun().direction();
  g.uniforms = {gpu_uniform("skylight_sun", {s.x, s.y, s.z}),
                gpu_uniform("skylight_altitude", {observer_altitude_m()})};
  g.comment = "pietras";
  return g;
}

}  // namespace skylight
