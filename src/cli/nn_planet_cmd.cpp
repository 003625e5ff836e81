// `skylight nn planet`: a Pietras weights file shading an icosphere planet and its atmosphere
// shell in the GL vertex shader (gpu/planet.h, docs/PIETRAS.md), seen from orbit or from the
// ground, rendered headlessly and written like `render` (float formats, or the tone-mapped PNG).
#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "common.h"
#include "nn_parts.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/io/file.h"
#include "skylight/models/pietras.h"
#include "skylight/models/sky_model.h"
#include "skylight/render/icosphere.h"
#include "skylight/render/sky_render.h"
#include "skylight/render/tonemap.h"
#ifdef SKYLIGHT_HAVE_GPU
#include "skylight/gpu/context.h"
#include "skylight/gpu/planet.h"
#endif

namespace skylight::cli {
namespace {

// From orbit, the default camera altitude in planet radii.
constexpr double kOrbitAltitudeRadii = 2.0;
// From the ground: the camera's default altitude [m] and field of view [deg].
constexpr double kGroundAltitudeM = 2.0;
constexpr double kGroundFovDeg = 60.0;

struct PlanetFlags {
  std::string weights, view = "orbit", output;
  double sun_zenith_deg = 30.0, sun_azimuth_deg = 0.0, look_elevation_deg = 10.0;
  std::optional<double> altitude_m, fov_deg;
  double albedo = 0.3;
  int subdivisions = 6;
  int width = 640, height = 480;
};

#ifdef SKYLIGHT_HAVE_GPU
double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
#endif

int run_planet(const PlanetFlags& f) {
#ifndef SKYLIGHT_HAVE_GPU
  // Said before any input is read.
  (void)f;
  throw std::runtime_error(
      "nn planet: this skylight was built without the GPU module (SKYLIGHT_GPU=OFF: EGL and "
      "OpenGL were not found when configuring; docs/GPU.md)");
#else
  (void)io::format_from_path(f.output);
  const std::string text = io::read_text_file(f.weights);
  if (!nn::is_pietras_json(text))
    throw InvalidArgument(
        fmt::format("--weights '{}': not a Pietras weights file (nn train "
                    "--network pietras|log3)",
                    excerpt(f.weights)));
  const nn::PietrasNetwork net = nn::pietras_from_json(text, f.weights);
  const NishitaParameters planet = nishita_parameters_of(net);
  const SunPosition sun = sun_from_degrees(f.sun_zenith_deg, f.sun_azimuth_deg);
  const bool orbit = f.view == "orbit";
  const double altitude = f.altitude_m.value_or(orbit ? kOrbitAltitudeRadii * planet.ground_radius_m
                                                      : kGroundAltitudeM);
  gpu::PlanetView view = orbit ? gpu::orbit_view(planet, altitude, sun.zenith)
                               : gpu::ground_view(planet, altitude, sun.zenith, sun.azimuth,
                                                  deg_to_rad(f.look_elevation_deg));
  if (f.fov_deg)
    view.vertical_fov = deg_to_rad(*f.fov_deg);
  else if (!orbit)
    view.vertical_fov = deg_to_rad(kGroundFovDeg);
  view.albedo = f.albedo;
  view.subdivisions = f.subdivisions;
  view.width = f.width;
  view.height = f.height;
  const auto t0 = std::chrono::steady_clock::now();
  const NishitaSampler atmosphere(planet);
  const gpu::PlanetMesh mesh = gpu::planet_mesh(net, atmosphere, view);
  const double mesh_s = seconds_since(t0);
  gpu::Context context;
  const auto t1 = std::chrono::steady_clock::now();
  const io::ImageF rgba = gpu::render_planet(net, mesh, f.width, f.height);
  const double gl_s = seconds_since(t1);
  io::ImageF rgb(f.width, f.height, 3);
  for (std::size_t i = 0; i < rgb.data.size() / 3; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const float v = rgba.data[4 * i + k];
      rgb.data[3 * i + k] = std::isfinite(v) ? v : 0.0f;
    }
  render::write_image_or_preview(
      f.output, rgb,
      {{"Software", "skylight nn planet"},
       {"skylight:weights", f.weights},
       {"skylight:view", f.view},
       {"skylight:altitude_m", fmt::format("{}", altitude)},
       {"skylight:sun_zenith_deg", fmt::format("{}", f.sun_zenith_deg)},
       {"skylight:sun_azimuth_deg", fmt::format("{}", f.sun_azimuth_deg)},
       {"skylight:subdivisions", fmt::format("{}", f.subdivisions)},
       {"Comment", "linear sRGB of the Pietras vertex shader (docs/PIETRAS.md)"}});
  write_stdout(fmt::format(
      "nn planet: {} network from {} at {:.0f} m, sun zenith {} deg; icosphere level {}: {} "
      "vertices, {} triangles; vertex terms {:.2f} s (CPU), GL draw + readback {:.3f} s on "
      "'{}'\nwrote {}\n",
      nn::to_string(net.kind), f.view, altitude, f.sun_zenith_deg, f.subdivisions,
      mesh.vertices.size(), mesh.indices.size() / 3, mesh_s, gl_s, context.renderer(), f.output));
  return kExitOk;
#endif
}

}  // namespace

void add_nn_planet_command(CLI::App& nn, Commands& commands) {
  auto f = std::make_shared<PlanetFlags>();
  auto* cmd = nn.add_subcommand(
      "planet",
      "a Pietras network shading an icosphere planet and its atmosphere in a GL vertex shader, "
      "from orbit or from the ground (docs/PIETRAS.md)");
  cmd->add_option("--weights", f->weights, "Pietras weights file (JSON)")->required();
  cmd->add_option("--view", f->view, "orbit|ground; default orbit")
      ->check(CLI::IsMember({"orbit", "ground"}));
  ParameterSpec zenith = sun_parameter_specs()[0];
  zenith.default_value = ParameterValue(f->sun_zenith_deg);
  zenith.description = "solar zenith angle at the point below the camera";
  add_number(*cmd, zenith, f->sun_zenith_deg);
  ParameterSpec azimuth = sun_parameter_specs()[1];
  azimuth.default_value = ParameterValue(f->sun_azimuth_deg);
  azimuth.description = "solar azimuth from north towards east (the ground view looks north)";
  add_number(*cmd, azimuth, f->sun_azimuth_deg);
  add_number(*cmd,
             {"altitude", "m", ParameterKind::number, 0.0, 1e10, 1,
              Absent{"orbit: 2 planet radii; ground: 2 m"}, "camera above the ground"},
             f->altitude_m);
  add_number(*cmd,
             {"look-elevation", "deg", ParameterKind::number, -90.0, 90.0, 1,
              ParameterValue(f->look_elevation_deg),
              "ground view: the view's elevation above the horizon"},
             f->look_elevation_deg);
  add_number(
      *cmd,
      {"fov", "deg", ParameterKind::number, 1.0, 170.0, 1,
       Absent{"orbit: the atmosphere's disc fills 85 %; ground: 60"}, "vertical field of view"},
      f->fov_deg);
  add_number(*cmd,
             {"albedo", "1", ParameterKind::number, 0.0, 1.0, 1, ParameterValue(f->albedo),
              "grey Lambertian albedo of the ground (Pietras §IV)"},
             f->albedo);
  add_integer(*cmd,
              {"subdivisions", "1", ParameterKind::integer, 0,
               static_cast<double>(render::kMaxIcosphereSubdivisions), 1,
               ParameterValue(static_cast<double>(f->subdivisions)),
               "icosphere level of the ground and the shell (10 * 4^n + 2 vertices each)"},
              f->subdivisions);
  add_integer(*cmd,
              {"width", "px", ParameterKind::integer, 1, kMaxImageSide, 1,
               ParameterValue(static_cast<double>(f->width)), "image width"},
              f->width);
  add_integer(*cmd,
              {"height", "px", ParameterKind::integer, 1, kMaxImageSide, 1,
               ParameterValue(static_cast<double>(f->height)), "image height"},
              f->height);
  cmd->add_option("-o,--output", f->output,
                  "output: .exr (float + metadata), .hdr, .pfm or .png (tone-mapped preview)")
      ->required();
  commands.push_back({cmd, [f] { return run_planet(*f); }});
}

}  // namespace skylight::cli
