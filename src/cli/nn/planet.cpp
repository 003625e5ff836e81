// `skylight nn planet`: a Pietras weights file shading an icosphere planet and its atmosphere
// shell in the GL vertex shader (gpu/planet.h, docs/PIETRAS.md), seen from orbit or from the
// ground (models/pietras.h, PlanetViewOptions), rendered headlessly and written like `render`.
#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "nn.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/io/file.h"
#include "skylight/models/pietras.h"
#include "skylight/operations/operations.h"
#include "skylight/render/sky_render.h"
#include "skylight/render/tonemap.h"
#ifdef SKYLIGHT_HAVE_GPU
#include "skylight/gpu/context.h"
#include "skylight/gpu/planet.h"
#endif

namespace skylight::cli {
namespace {

struct PlanetCommand {
  SchemaFlags flags;
  std::string weights, output;
};

#ifdef SKYLIGHT_HAVE_GPU
double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
#endif

int run_planet(const PlanetCommand& c) {
#ifndef SKYLIGHT_HAVE_GPU
  // Said before any input is read.
  (void)c;
  throw std::runtime_error(
      "nn planet: this skylight was built without the GPU module (SKYLIGHT_GPU=OFF: EGL and "
      "OpenGL were not found when configuring; docs/GPU.md)");
#else
  const auto f = c.flags.bind(PlanetViewOptions::schema(), PlanetViewOptions{}, "nn planet");
  (void)io::format_from_path(c.output);
  const std::string text = io::read_text_file(c.weights);
  if (!nn::is_pietras_json(text))
    throw InvalidArgument(
        fmt::format("--weights '{}': not a Pietras weights file (nn train "
                    "--network pietras|log3)",
                    excerpt(c.weights)));
  const nn::PietrasNetwork net = nn::pietras_from_json(text, c.weights);
  const NishitaParameters planet = nishita_parameters_of(net);
  const SunPosition sun = sun_from_degrees(f.sun_zenith_deg, f.sun_azimuth_deg);
  const bool orbit = f.orbit;
  const double altitude = f.altitude(planet.ground_radius_m);
  gpu::PlanetView view = orbit ? gpu::orbit_view(planet, altitude, sun.zenith)
                               : gpu::ground_view(planet, altitude, sun.zenith, sun.azimuth,
                                                  deg_to_rad(f.look_elevation_deg));
  if (const auto fov = f.vertical_fov_deg()) view.vertical_fov = deg_to_rad(*fov);
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
      c.output, rgb,
      {{"Software", "skylight nn planet"},
       {"skylight:weights", c.weights},
       {"skylight:view", orbit ? "orbit" : "ground"},
       {"skylight:altitude_m", fmt::format("{}", altitude)},
       {"skylight:sun_zenith_deg", fmt::format("{}", f.sun_zenith_deg)},
       {"skylight:sun_azimuth_deg", fmt::format("{}", f.sun_azimuth_deg)},
       {"skylight:subdivisions", fmt::format("{}", f.subdivisions)},
       {"Comment", "linear sRGB of the Pietras vertex shader (docs/PIETRAS.md)"}});
  write_stdout(fmt::format(
      "nn planet: {} network from {} at {:.0f} m, sun zenith {} deg; icosphere level {}: {} "
      "vertices, {} triangles; vertex terms {:.2f} s (CPU), GL draw + readback {:.3f} s on "
      "'{}'\n",
      nn::to_string(net.kind), orbit ? "orbit" : "ground", altitude, f.sun_zenith_deg,
      f.subdivisions, mesh.vertices.size(), mesh.indices.size() / 3, mesh_s, gl_s,
      context.renderer()));
  announce_after_commit(fmt::format("wrote {}", io::shown_path(c.output)));
  return kExitOk;
#endif
}

}  // namespace

void add_nn_planet_command(CLI::App& nn, Commands& commands) {
  auto c = std::make_shared<PlanetCommand>();
  auto* cmd = nn.add_subcommand(
      "planet",
      "a planet and its atmosphere shaded by a network, from orbit or ground\n"
      "A Pietras network shading an icosphere planet and its atmosphere in a GL vertex shader, "
      "from orbit or from the ground (docs/PIETRAS.md).");
  cmd->add_option("--weights", c->weights, "Pietras weights file (JSON)")->required();
  c->flags.add(*cmd, operations::find("nn planet").parameters);
  cmd->add_option("-o,--output", c->output,
                  "output: .exr (float + metadata), .hdr, .pfm or .png (tone-mapped preview)")
      ->required();
  commands.push_back({cmd, [c] { return run_planet(*c); }});
}

}  // namespace skylight::cli
