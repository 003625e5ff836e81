#include "skylight/gpu/bench.h"

#include <fmt/format.h>

#include <optional>

#include "skylight/core/parallel.h"
#include "skylight/gpu/context.h"
#include "skylight/gpu/haze.h"
#include "skylight/gpu/planet.h"
#include "skylight/gpu/sky_render.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/pietras.h"
#include "skylight/perf/workloads.h"

namespace skylight::gpu {

void bench_frames(int width, int height, int repeats, const perf::Output& out) {
  Context context;
  render::RenderSettings s;
  s.width = width;
  s.height = height;
  const auto dirs = render::pixel_directions(s);
  const std::size_t n = dirs.x.size();
  std::vector<float> X(n), Y(n), Z(n);
  // One network's fragment-shader frame against its CPU batch path.
  const auto frame_vs_cpu = [&](const SkyModel& model, const std::string& what) {
    SkyRenderer r(model, s);
    r.draw();  // compile and first-use costs outside the timing
    context.finish();
    const double draw = perf::median_seconds(repeats, [&] {
      r.draw();
      context.finish();
    });
    const double readback = perf::median_seconds(repeats, [&] {
      r.draw();
      (void)r.read();
    });
    const double cpu = perf::median_seconds(repeats, [&] {
      tristimulus_parallel(model, {dirs.x, dirs.y, dirs.z}, {X, Y, Z});
    });
    out(fmt::format(
        "gpu: {} {}x{} equirect on '{}': frame {:.2f} ms (draw + glFinish), {:.2f} ms with the "
        "float readback; CPU batch path ({} threads) {:.2f} ms; GL frame / CPU {:.1f}x, with the "
        "readback {:.1f}x\n",
        what, width, height, context.renderer(), 1e3 * draw, 1e3 * readback, thread_count(),
        1e3 * cpu, draw / cpu, readback / cpu));
  };
  const auto model = perf::bench_model(NeuralSkyModel::kName);
  const auto& nn = dynamic_cast<const NeuralSkyModel&>(*model);
  frame_vs_cpu(nn,
               fmt::format("{} ({})", NeuralSkyModel::kName, nn.network().net.layout().describe()));
  // A Pietras network per pixel (log3: the network and its exact shadow test of the view ray;
  // untrained weights, the same cost as data/nn/log3.json) from 1 km with the sun at 60 degrees.
  PietrasParameters pp;
  pp.sun = sun_from_degrees(60.0, 180.0);
  pp.observer_altitude_m = 1000.0;
  const PietrasSkyModel log3(pp, nn::initial_pietras_network(nn::PietrasKind::log3, 1));
  frame_vs_cpu(log3, "Pietras log3 network (untrained weights, the same cost) per pixel from 1 km");
  // The Pietras vertex shader's planet from orbit (gpu/planet.h) at the `nn planet` default mesh:
  // the paper's network (untrained weights: the same cost): the vertex terms on the CPU, the
  // shader's compile with the first frame, then per frame the upload + draw (glFinish), and with
  // the readback.
  const nn::PietrasNetwork pietras = nn::initial_pietras_network(nn::PietrasKind::pietras, 1);
  const NishitaParameters earth;
  PlanetView view = orbit_view(earth, 2.0 * earth.ground_radius_m, 0.5);
  view.width = width;
  view.height = height;
  const NishitaSampler atmosphere(earth);
  PlanetMesh mesh;
  const double terms =
      perf::median_seconds(1, [&] { mesh = planet_mesh(pietras, atmosphere, view); });
  std::optional<PlanetRenderer> renderer;
  const double first = perf::median_seconds(1, [&] {
    renderer.emplace(pietras, width, height);
    renderer->draw(mesh);
    context.finish();
  });
  const double frame = perf::median_seconds(repeats, [&] {
    renderer->draw(mesh);
    context.finish();
  });
  const double with_read = perf::median_seconds(repeats, [&] {
    renderer->draw(mesh);
    (void)renderer->read();
  });
  out(fmt::format(
      "gpu: Pietras planet from orbit, icosphere level {} ({} vertices, {} triangles) {}x{} on "
      "'{}': {:.2f} ms per frame (upload + draw + glFinish), {:.2f} ms with the float readback; "
      "the first frame with the shader's compile {:.1f} ms; vertex terms on the CPU ({} threads) "
      "{:.1f} ms\n",
      view.subdivisions, mesh.vertices.size(), mesh.indices.size() / 3, width, height,
      context.renderer(), 1e3 * frame, 1e3 * with_read, 1e3 * first, thread_count(), 1e3 * terms));
}

void bench_haze(int repeats, double fast, const perf::Output& out) {
  const perf::HazeFrame full;
  const auto& cam = perf::haze_camera();
  // The same frame through the fragment shader (gpu/haze.h): the kernel's tables, upload of image,
  // depth and tables, draw and float readback.
  try {
    Context context;
    HazeRenderer r(1920, 1080, full.settings.operation, {});
    (void)r.apply(full.image, full.depth, cam,
                  full.settings);  // compile and first-use costs outside
    const double gl = perf::median_seconds(
        repeats, [&] { (void)r.apply(full.image, full.depth, cam, full.settings); });
    out(fmt::format(
        "haze retarget 1920x1080 on GL '{}' (gpu/haze.h): {:.2f} ms per frame (tables + upload + "
        "draw + float readback) = {:.0f} frames/s = {:.2f}x the CPU path's wall time\n",
        context.renderer(), 1e3 * gl, 1.0 / gl, gl / fast));
  } catch (const GpuError& e) {
    out(fmt::format("haze on GL: not timed, no headless GL here ({})\n", e.what()));
  }
}

}  // namespace skylight::gpu
