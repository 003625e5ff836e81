// The per-vertex sky network of Pietras (§III: the sky of the physical atmosphere, `nishita`, as
// small MLPs; nn/pietras.h) as a SkyModel, `pietras`, and the colour of a surface point seen
// through the air with it (§IV). docs/PIETRAS.md.
//
// rgb() is the network's output for the observer's altitude, the view and the sun, in the units of
// its source's rgb() (nishita: linear sRGB, Y in cd/m^2); tristimulus() is that rgb converted to
// XYZ (D65). Night is exactly dark by the shadow test of the view ray (nn::PietrasNetwork::lit).
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "skylight/io/image.h"
#include "skylight/models/nishita.h"
#include "skylight/models/sky_model.h"
#include "skylight/nn/pietras.h"
#include "skylight/nn/sky_network.h"

namespace skylight {

// The network used when none is given (data/nn/, embedded): log3 trained on Earth's nishita
// (data/nn/PROVENANCE.md).
inline constexpr const char* kEmbeddedPietrasNetwork = "nn/log3.json";

struct PietrasParameters {
  SunPosition sun;
  std::string weights;  // --weights FILE (skylight-nn-pietras); empty: kEmbeddedPietrasNetwork
  // --observer-altitude [m]: the network's density input rho0 = exp(-h / H0).
  double observer_altitude_m = 0.0;

  static const ParameterSchema<PietrasParameters>& schema();
};

// Reads and checks a Pietras weights file: IoError when it cannot be read, InvalidArgument
// (naming the file and the field) when its content is malformed, or when it is a sky network
// (models/neural_sky.h reads those).
nn::PietrasNetwork load_pietras_network_file(const std::filesystem::path& path);
// The embedded network (parsed once).
const nn::PietrasNetwork& embedded_pietras_network();

// A weights file of either kind, read once: a Pietras network (`pietras` set) or a sky network
// (models/neural_sky.h). IoError / InvalidArgument as the loaders.
struct NetworkFile {
  std::optional<nn::PietrasNetwork> pietras;
  nn::SkyNetwork sky;
};
NetworkFile read_network_file(const std::filesystem::path& path);
// The model of a network file for a sun: `pietras` (at the observer altitude) or `nn` (at the
// turbidity). The option the other kind does not read is refused (InvalidArgument naming it):
// --turbidity for a Pietras network, --observer-altitude for a sky network.
std::unique_ptr<SkyModel> network_model(const NetworkFile& file, const std::string& path,
                                        const SunPosition& sun, std::optional<double> turbidity,
                                        std::optional<double> observer_altitude_m);

// The planet of a Pietras network seen from orbit or from the ground (`skylight nn planet`, the
// vertex shader of gpu/planet.h; docs/PIETRAS.md): the view, the sun at the point below the
// camera, the camera's altitude, look elevation and field of view, the ground's albedo, the
// icosphere level and the image size.
struct PlanetViewOptions {
  bool orbit = true;  // --view orbit|ground
  double sun_zenith_deg = 30.0, sun_azimuth_deg = 0.0;
  std::optional<double> altitude_m;  // absent: 2 planet radii (orbit), 2 m (ground)
  double look_elevation_deg = 10.0;
  std::optional<double> fov_deg;  // absent: the atmosphere's disc fills 85 % (orbit); 60 (ground)
  double albedo = 0.3;
  int subdivisions = 6;
  int width = 640, height = 480;
  static const ParameterSchema<PlanetViewOptions>& schema();
  // The camera's altitude above a planet of radius r0 [m].
  double altitude(double r0) const;
  // The vertical field of view [deg]: the given one, 60 from the ground; absent from orbit (the
  // orbit view's own, the atmosphere's disc filling 85 %).
  std::optional<double> vertical_fov_deg() const;
};

// A planet drawn by a Pietras network (`nn planet`, gpu/planet.h: render_planet_view): the linear
// sRGB image and what it took.
struct PlanetFrame {
  io::ImageF rgb;
  double altitude_m = 0.0;  // the camera's, above the ground
  std::size_t vertices = 0, triangles = 0;
  double mesh_seconds = 0.0;  // the vertex terms (CPU)
  double gl_seconds = 0.0;    // GL draw and readback
  std::string renderer;       // the GL renderer's name
};

// The nishita parameters a network was trained with, from its provenance (its schema's names;
// InvalidArgument for a name nishita does not have).
NishitaParameters nishita_parameters_of(const nn::PietrasNetwork& net);

// The `pietras` model. Every view and any sun (twilight and night included); views meeting the
// ground see the air up to the ground (the source without --albedo). Batch path: PietrasBatch
// (float SIMD per sub-network; error against the scalar double path: kModelBatchRelativeTolerance
// in the tests).
class PietrasSkyModel final : public SkyModel {
 public:
  explicit PietrasSkyModel(const PietrasParameters& p);
  // A Pietras network given in code, e.g. one just trained or read (p.weights only names it).
  PietrasSkyModel(const PietrasParameters& p, nn::PietrasNetwork network);
  static constexpr std::string_view kName = "pietras";
  // The registry entry: documentation, schema, factory and policy (models/sky_model.h).
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  ParameterValues parameter_values() const override;
  Xyz tristimulus(Vec3 view) const override;
  Rgb rgb(Vec3 view) const override;
  void tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const override;
  Domain domain() const override;
  std::optional<GpuSky> gpu_sky() const override;

  const nn::PietrasNetwork& network() const { return network_; }
  double observer_altitude_m() const { return params_.observer_altitude_m; }

 private:
  PietrasParameters params_;
  nn::PietrasNetwork network_;
  std::unique_ptr<nn::PietrasBatch> batch_;
};

// ---- the surface colour of §IV --------------------------------------------------------------

// Colour of a surface point and of the air in front of it (Pietras §IV) for an observer at
// altitude h looking along `view` at the point q = P + distance view (an upward-facing Lambertian
// surface of grey albedo): two evaluations of the sky function, at the observer and at the probe
// q looking the same way, plus the reflected sunlight from the atmosphere model directly:
//   I = I_sky(P, view) - T(P, q) I_sky(q, view) + T(P, q) albedo/pi E_sun(q).
// The paper subtracts I_sky(q) without T(P, q); with it the split is exact for single scattering
// (I(P) = I(P -> q) + T(P, q) I(q)), up to T taken per channel at kSurfaceChannelNm. The sky
// function is the network (nn::PietrasNetwork::rgb_at) or, for checks, nishita.
using PietrasSkyFunction = std::function<Rgb(double altitude_m, double cos_view_zenith,
                                             double cos_view_sun, double cos_sun_zenith)>;
// The parts of that sum for one surface point: the sky function's arguments at the observer and
// at the probe, T(P, q) per channel and the reflected sunlight (what gpu/planet.h hands each
// vertex of a planet mesh).
struct PietrasSurfaceTerms {
  double observer_altitude_m = 0, probe_altitude_m = 0;
  double cos_view_sun = 1;  // the same at both points
  double observer_cos_view_zenith = 1, observer_cos_sun_zenith = 1;
  double probe_cos_view_zenith = 1, probe_cos_sun_zenith = 1;
  std::array<double, 3> transmittance{};  // T(P, q) at kSurfaceChannelNm
  Rgb reflected{};                        // T(P, q) albedo/pi E_sun(q)
};
PietrasSurfaceTerms pietras_surface_terms(const NishitaSampler& atmosphere, double altitude_m,
                                          Vec3 view, double distance_m, double albedo, Vec3 sun);
Rgb pietras_surface(const PietrasSkyFunction& sky, const NishitaSampler& atmosphere,
                    double altitude_m, Vec3 view, double distance_m, double albedo, Vec3 sun);
// The sky function of a network.
PietrasSkyFunction sky_function(const nn::PietrasNetwork& net);

}  // namespace skylight
