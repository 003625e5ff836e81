// `skylight bench`: the batch path of each model timed against an in-run baseline (the plain
// scalar loop of the same model), medians of repeated runs, printed as ratios; the neural sky
// (`nn`, the embedded 6-12-3 network) also against the Hosek-Wilkie batch path (docs/NN.md);
// `--models gpu` times the same network's fragment-shader frame (gpu/, docs/GPU.md), and a log3
// Pietras network's per-pixel frame, each against its CPU batch path, and the Pietras planet's
// vertex-shader frame; `--models pietras` the Pietras networks against nishita's fast path
// (docs/PIETRAS.md).
#include <fmt/format.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>

#include "../../bench/estimate_fixture.h"  // the fixture of bench/bench_models.cpp
#include "common.h"
#include "skylight/core/error.h"
#include "skylight/core/parallel.h"
#include "skylight/core/statistics.h"
#include "skylight/fit/luminance_fit.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/haze/airlight_field.h"
#include "skylight/haze/image_haze.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/pietras.h"
#include "skylight/models/preetham.h"
#include "skylight/models/sh.h"
#include "skylight/render/sky_render.h"
#include "skylight/sh/polynomial.h"
#ifdef SKYLIGHT_HAVE_GPU
#include "skylight/gpu/haze.h"
#include "skylight/gpu/planet.h"
#include "skylight/gpu/sky_render.h"
#endif

namespace skylight::cli {
namespace {

struct BenchFlags {
  int width = 1024, height = 512, repeats = 7;
  std::vector<std::string> models{"preetham", "cie", "hosek", "nn"};
  // The model flags of render/eval, accepted here only to be refused with a clear message.
  std::vector<std::string> model_flags;
  std::string model_flag_text;
  bool estimate = false;
  bool haze = false;
  std::string sh_table;  // empty: the embedded default
};

// This thread's CPU time [s].
double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

template <class F>
double median_seconds(int repeats, F&& f) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
  }
  return median(std::move(t));
}

// One `skylight estimate` (estimate_from_photo: sun detection, automatic mask, 100 samples, RANSAC,
// bootstrap) on a 1024 x 1024 fisheye Preetham sky with the solar disc, on the calling thread.
void bench_estimate(int repeats) {
  const bench::EstimateFixture f = bench::estimate_fixture();
  fit::PhotoFit e;
  // Wall time and this thread's CPU time (the estimate runs on the calling thread only; on a busy
  // machine the CPU time is the cost, the wall time includes waiting for a core).
  std::vector<double> cpu;
  const double wall = median_seconds(repeats, [&] {
    const double c0 = thread_cpu_s();
    e = fit::estimate_from_photo(PreethamModel::kName, f.photo, f.camera, std::nullopt, {}, {});
    cpu.push_back(thread_cpu_s() - c0);
  });
  write_stdout(fmt::format(
      "estimate: 1024x1024 fisheye (preetham T = 4, sun 40 deg / 150 deg), sun detection + mask + "
      "fit on one thread: {:.2f} ms CPU, {:.2f} ms wall (T = {:.4f}, sun found at {:.2f} deg / "
      "{:.2f} deg)\n",
      1e3 * median(cpu), 1e3 * wall, e.fit.parameter("turbidity").value,
      rad_to_deg(e.fit.sun.zenith), rad_to_deg(e.fit.sun.azimuth)));
}

// Habel 2008 §4: the SH coefficients of one sky (7 bands x 3 channels) from the embedded table,
// eq. 1 + rotation (eq. 4) + ringing filter (eq. 5), against projecting the model it was fitted
// to (Preetham, converged quadrature, all threads).
void bench_sh(int repeats, const std::string& table_path) {
  const sh::PolynomialTable table = load_sh_table(table_path);
  if (table.bands < 7) throw InvalidArgument("--sh-table: the table has fewer than 7 bands");
  constexpr int kCalls = 2000;
  volatile double sink = 0.0;
  // Wall and thread CPU time: on a loaded machine the wall time includes waiting for a core.
  std::vector<double> cpu;
  const double per_eval =
      median_seconds(repeats,
                     [&] {
                       const double c0 = thread_cpu_s();
                       double acc = 0.0;
                       for (int i = 0; i < kCalls; ++i) {
                         const double theta = 0.1 + 1.3 * i / kCalls;
                         acc += sh::evaluate_table(table, theta, 3.0, 0.5 + theta, 7, true).c[4][1];
                       }
                       sink = acc;
                       cpu.push_back((thread_cpu_s() - c0) / kCalls);
                     }) /
      kCalls;
  SkyParameters p;
  p.sun = {0.8, 0.5};
  p.values.set("turbidity", 3.0);
  const auto preetham = make_sky_model("preetham", p);
  const double project = median_seconds(std::min(repeats, 3), [&] {
    sink = fit::project_model(*preetham, sh::Channels::xyz, 7).coefficients.c[4][1];
  });
  (void)sink;
  write_stdout(
      fmt::format("sh: 7 bands x 3 channels from the '{}' ({}, {}) table incl. rotation and "
                  "filter {:.2f} us CPU, {:.2f} us wall (medians, one thread); "
                  "direct projection of preetham {:.1f} ms ({} threads); ratio {:.0f}x\n",
                  table.model, table.degree_theta, table.degree_tau, 1e6 * median(cpu),
                  1e6 * per_eval, 1e3 * project, thread_count(), project / per_eval));
}

// The embedded network (`nn` at the bench's defaults) and a log3 Pietras network as fragment
// shaders on the headless GL context, one width x height equirect frame each: draw (glFinish) and
// draw + float readback, against the CPU batch path over the same directions on all threads; then
// the Pietras planet by vertex shader.
void bench_gpu(int width, int height, int repeats) {
#ifdef SKYLIGHT_HAVE_GPU
  gpu::Context context;
  render::RenderSettings s;
  s.width = width;
  s.height = height;
  const auto dirs = render::pixel_directions(s);
  const std::size_t n = dirs.x.size();
  std::vector<float> X(n), Y(n), Z(n);
  // One network's fragment-shader frame against its CPU batch path.
  const auto frame_vs_cpu = [&](const SkyModel& model, const std::string& what) {
    gpu::SkyRenderer r(model, s);
    r.draw();  // compile and first-use costs outside the timing
    context.finish();
    const double draw = median_seconds(repeats, [&] {
      r.draw();
      context.finish();
    });
    const double readback = median_seconds(repeats, [&] {
      r.draw();
      (void)r.read();
    });
    const double cpu = median_seconds(repeats, [&] {
      tristimulus_parallel(model, {dirs.x, dirs.y, dirs.z}, {X, Y, Z});
    });
    write_stdout(fmt::format(
        "gpu: {} {}x{} equirect on '{}': frame {:.2f} ms (draw + glFinish), {:.2f} ms with the "
        "float readback; CPU batch path ({} threads) {:.2f} ms; GL frame / CPU {:.1f}x, with the "
        "readback {:.1f}x\n",
        what, width, height, context.renderer(), 1e3 * draw, 1e3 * readback, thread_count(),
        1e3 * cpu, draw / cpu, readback / cpu));
  };
  SkyParameters p;
  p.values = find_model("nn")->example;
  const auto model = find_model("nn")->make(p);
  const auto& nn = dynamic_cast<const NeuralSkyModel&>(*model);
  frame_vs_cpu(nn, fmt::format("nn ({})", nn.network().net.layout().describe()));
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
  gpu::PlanetView view = gpu::orbit_view(earth, 2.0 * earth.ground_radius_m, 0.5);
  view.width = width;
  view.height = height;
  const NishitaSampler atmosphere(earth);
  gpu::PlanetMesh mesh;
  const double terms =
      median_seconds(1, [&] { mesh = gpu::planet_mesh(pietras, atmosphere, view); });
  std::optional<gpu::PlanetRenderer> renderer;
  const double first = median_seconds(1, [&] {
    renderer.emplace(pietras, width, height);
    renderer->draw(mesh);
    context.finish();
  });
  const double frame = median_seconds(repeats, [&] {
    renderer->draw(mesh);
    context.finish();
  });
  const double with_read = median_seconds(repeats, [&] {
    renderer->draw(mesh);
    (void)renderer->read();
  });
  write_stdout(fmt::format(
      "gpu: Pietras planet from orbit, icosphere level {} ({} vertices, {} triangles) {}x{} on "
      "'{}': {:.2f} ms per frame (upload + draw + glFinish), {:.2f} ms with the float readback; "
      "the first frame with the shader's compile {:.1f} ms; vertex terms on the CPU ({} threads) "
      "{:.1f} ms\n",
      view.subdivisions, mesh.vertices.size(), mesh.indices.size() / 3, width, height,
      context.renderer(), 1e3 * frame, 1e3 * with_read, 1e3 * first, thread_count(), 1e3 * terms));
#else
  (void)width, (void)height, (void)repeats;
  throw std::runtime_error(
      "--models gpu: this skylight was built without the GPU module (SKYLIGHT_GPU=OFF; "
      "docs/GPU.md)");
#endif
}

// Morales 2017 eq. 26 on a 1920 x 1080 frame + depth (100 m .. 20 km, T 1.9 -> 4.36, Canon EOS
// 5D): the Gamma-table path on all threads against the exact per-pixel spectral integral (eq. 11
// at 81 wavelengths) on one thread, timed on 1/20 of the frame and scaled.
void bench_haze(int repeats) {
  const auto frame = [](int height) {
    std::pair<io::ImageF, io::ImageF> f{io::ImageF(1920, height, 3), io::ImageF(1920, height, 1)};
    for (std::size_t i = 0; i < f.second.data.size(); ++i) {
      f.second.data[i] =
          100.0f + 19900.0f * static_cast<float>(i / 1920) / static_cast<float>(height);
      for (std::size_t c = 0; c < 3; ++c)
        f.first.data[3 * i + c] = 0.2f + 0.6f * static_cast<float>((i * (c + 3)) % 97) / 97.0f;
    }
    return f;
  };
  haze::HazeSettings s;
  s.operation = haze::HazeOperation::retarget;
  s.source = {1.9, 40.0};
  s.target_turbidity = 4.36;
  const auto& cam = haze::find_camera("canon-eos-5d");
  const auto full = frame(1080), strip = frame(54);
  haze::HazeReport report;
  // Wall time, and the CPU time of all threads per frame: on a busy machine the wall time includes
  // waiting for a core, the CPU time is the cost (frames/s on n idle cores = n / CPU time).
  const auto process_cpu_s = [] {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  };
  io::ImageF frame_buffer = full.first;
  std::vector<double> cpu;
  const double fast = median_seconds(repeats, [&] {
    const double c0 = process_cpu_s();
    haze::apply_haze_in_place(frame_buffer, full.second, cam, s, &report);  // repeated in place
    cpu.push_back(process_cpu_s() - c0);
  });
  const double fast_cpu = median(cpu);
  const double exact = 20.0 * median_seconds(std::max(1, repeats / 3), [&] {
                         const io::ImageF out =
                             haze::apply_haze_exact(strip.first, strip.second, cam, s);
                         volatile float sink = out.data[out.data.size() / 2];
                         (void)sink;
                       });
  write_stdout(fmt::format(
      "haze retarget 1920x1080 + depth (eq. 26, T 1.9 -> 4.36): {:.2f} ms wall = {:.0f} frames/s "
      "on {} threads; CPU time {:.2f} ms per frame (= {:.0f} frames/s on 2 idle cores); Gamma "
      "tables {} entries, interpolation error <= {:.1g}; exact per-pixel spectral integral on one "
      "thread: {:.0f} ms per frame = {:.0f}x the wall time, {:.0f}x the CPU time\n",
      1e3 * fast, 1.0 / fast, thread_count(), 1e3 * fast_cpu, 2.0 / fast_cpu, report.table_entries,
      report.table_error_bound, 1e3 * exact, exact / fast, exact / fast_cpu));
  // Per-pixel airlight at both turbidities (eqs. 12-13 through a 60 deg pinhole, Morales 2017
  // §6.2; haze/airlight_field.h): the maps once per camera, then every frame reads them.
  const haze::ImagePositioning pinhole(
      haze::view_matrix(3.0, 0.05, 0.0),
      haze::perspective_matrix(60.0 * kDegree, 1920.0 / 1080.0, 1.0, 1e4), 1920, 1080);
  haze::PhotoAirlight horizon;
  horizon.horizon = {0.7, 0.8, 0.95};
  horizon.theta_prime = 80.0 * kDegree;
  const auto t0 = std::chrono::steady_clock::now();
  haze::HazeSettings per_pixel = s;
  per_pixel.airlight_source_map = haze::photo_airlight_map(pinhole, horizon, 1.9);
  per_pixel.airlight_target_map = haze::photo_airlight_map(pinhole, horizon, 4.36);
  const double maps = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  cpu.clear();
  const double fast_map = median_seconds(repeats, [&] {
    const double c0 = process_cpu_s();
    haze::apply_haze_in_place(frame_buffer, full.second, cam, per_pixel);
    cpu.push_back(process_cpu_s() - c0);
  });
  const double map_cpu = median(cpu);
  write_stdout(fmt::format(
      "haze retarget 1920x1080, per-pixel airlight (60 deg pinhole, eqs. 12-13): {:.2f} ms wall = "
      "{:.0f} frames/s; CPU time {:.2f} ms per frame (= {:.0f} frames/s on 2 idle cores); the two "
      "airlight maps once per camera: {:.0f} ms\n",
      1e3 * fast_map, 1.0 / fast_map, 1e3 * map_cpu, 2.0 / map_cpu, 1e3 * maps));
#ifdef SKYLIGHT_HAVE_GPU
  // The same frame through the fragment shader (gpu/haze.h): the kernel's tables, upload of image,
  // depth and tables, draw and float readback.
  try {
    gpu::Context context;
    gpu::HazeRenderer r(1920, 1080, s.operation, {});
    (void)r.apply(full.first, full.second, cam, s);  // compile and first-use costs outside
    const double gl =
        median_seconds(repeats, [&] { (void)r.apply(full.first, full.second, cam, s); });
    write_stdout(fmt::format(
        "haze retarget 1920x1080 on GL '{}' (gpu/haze.h): {:.2f} ms per frame (tables + upload + "
        "draw + float readback) = {:.0f} frames/s = {:.2f}x the CPU path's wall time\n",
        context.renderer(), 1e3 * gl, 1.0 / gl, gl / fast));
  } catch (const gpu::GpuError& e) {
    write_stdout(fmt::format("haze on GL: not timed, no headless GL here ({})\n", e.what()));
  }
#endif
}

// Pietras §III against its source: the `nn` model with Pietras networks (the trainer's initial
// weights: the cost of a trained network) and `nishita`'s fast path (its batch is the scalar loop
// over the table-driven path) on the same grid, one thread, observer on the ground, sun at zenith
// 45 deg.
void bench_pietras(int repeats, const render::PixelDirections& dirs) {
  const std::size_t n = dirs.x.size();
  std::vector<float> X(n), Y(n), Z(n);
  volatile float sink = 0.0f;
  auto time = [&](const SkyModel& m) {
    return median_seconds(repeats, [&] {
      m.tristimulus_batch({dirs.x, dirs.y, dirs.z}, {X, Y, Z});
      sink = Y[n / 2];
    });
  };
  SkyParameters p;
  p.sun = {deg_to_rad(45.0), kPi};
  const double nishita = time(*make_sky_model("nishita", p));
  std::string out =
      fmt::format("pietras: nishita fast path {:.2f} ms per frame (one thread)\n", 1e3 * nishita);
  for (nn::PietrasKind k : {nn::PietrasKind::pietras, nn::PietrasKind::log3}) {
    PietrasParameters np;
    np.sun = p.sun;
    const PietrasSkyModel m(np, nn::initial_pietras_network(k, 1));
    const double t = time(m);
    out +=
        fmt::format("pietras: {} ({} weights) {:.2f} ms per frame: {:.1f}x faster than nishita\n",
                    nn::to_string(k), m.network().parameter_count(), 1e3 * t, nishita / t);
  }
  (void)sink;
  write_stdout(out);
}

int run_bench(const BenchFlags& f, const CLI::App& cmd) {
  std::string given;
  for (const auto& name : f.model_flags)
    if (cmd.count(name) > 0) given += (given.empty() ? "" : ", ") + name;
  if (!given.empty())
    throw InvalidArgument(fmt::format(
        "bench takes no model flags ({}): every model runs at its defaults (sun zenith 45 deg, "
        "azimuth 180 deg, T = 3, albedo 0.3, CIE type 12); choose the models with --models",
        given));
  std::vector<const ModelInfo*> models;
  for (const auto& name : f.models) {
    if (name == "gpu") continue;      // not a model: the GL frame, timed last (bench_gpu)
    if (name == "pietras") continue;  // not a model: timed last (bench_pietras)
    const ModelInfo* m = find_model(name);
    if (!m) {
      std::string known;
      for (const auto& r : model_registry()) known += (known.empty() ? "" : ", ") + r.name;
      throw InvalidArgument(fmt::format("--models: unknown model '{}' (known: {})", name, known));
    }
    models.push_back(m);
  }
  render::RenderSettings s;
  s.width = f.width;
  s.height = f.height;
  const auto dirs = render::pixel_directions(s);
  const std::size_t n = dirs.x.size();
  std::vector<float> X(n), Y(n), Z(n);
  write_stdout(
      fmt::format("skylight bench: {}x{} equirect directions, median of {} runs, {} threads\n"
                  "{:<10} {:>12} {:>12} {:>12} {:>10} {:>10}\n",
                  f.width, f.height, f.repeats, thread_count(), "model", "scalar ms", "batch1 ms",
                  "batchN ms", "SIMD x", "threads x"));
  std::map<std::string, std::pair<double, double>> timed;  // name -> (scalar, batch1)
  for (const ModelInfo* info : models) {
    // Each model at its defaults (plus the registry's example values for required parameters).
    SkyParameters p;
    p.values = info->example;
    const auto model = info->make(p);
    volatile float sink = 0.0f;
    // In-run baseline: the plain scalar loop of the same model (double precision, one thread).
    const double scalar = median_seconds(f.repeats, [&] {
      float acc = 0.0f;
      for (std::size_t i = 0; i < n; ++i)
        acc += static_cast<float>(model->tristimulus({dirs.x[i], dirs.y[i], dirs.z[i]}).Y);
      sink = acc;
    });
    const double batch1 = median_seconds(f.repeats, [&] {
      model->tristimulus_batch({dirs.x, dirs.y, dirs.z}, {X, Y, Z});
      sink = Y[n / 2];
    });
    const double batchN = median_seconds(f.repeats, [&] {
      tristimulus_parallel(*model, {dirs.x, dirs.y, dirs.z}, {X, Y, Z});
      sink = Y[n / 2];
    });
    (void)sink;
    timed[info->name] = {scalar, batch1};
    write_stdout(fmt::format("{:<10} {:>12.2f} {:>12.2f} {:>12.2f} {:>10.2f} {:>10.2f}\n",
                             info->name, 1e3 * scalar, 1e3 * batch1, 1e3 * batchN, scalar / batch1,
                             batch1 / batchN));
  }
  write_stdout(
      "SIMD x = scalar loop / batch on one thread; threads x = batch one thread / batch all "
      "threads\n");
  if (timed.count("nn") && timed.count("hosek")) {
    write_stdout(fmt::format(
        "nn (6-12-3) batch on one thread: {:.2f}x faster than the hosek batch, {:.1f}x faster "
        "than its own scalar loop\n",
        timed["hosek"].second / timed["nn"].second, timed["nn"].first / timed["nn"].second));
  }
  if (std::find(f.models.begin(), f.models.end(), "pietras") != f.models.end())
    bench_pietras(f.repeats, dirs);
  if (f.estimate) bench_estimate(f.repeats);
  if (f.haze) bench_haze(f.repeats);
  if (std::find(f.models.begin(), f.models.end(), "sh") != f.models.end())
    bench_sh(f.repeats, f.sh_table);
  if (std::find(f.models.begin(), f.models.end(), "gpu") != f.models.end())
    bench_gpu(f.width, f.height, f.repeats);
  return kExitOk;
}

}  // namespace

void add_bench_command(CLI::App& app, Commands& commands) {
  auto f = std::make_shared<BenchFlags>();
  auto* cmd = app.add_subcommand(
      "bench", "time the batch path against an in-run scalar loop (ratios, medians)");
  add_integer(*cmd,
              {"width", "px", ParameterKind::integer, 1, kMaxImageSide, 1,
               ParameterValue(static_cast<double>(f->width)), "grid width"},
              f->width);
  add_integer(*cmd,
              {"height", "px", ParameterKind::integer, 1, kMaxImageSide, 1,
               ParameterValue(static_cast<double>(f->height)), "grid height"},
              f->height);
  add_integer(*cmd,
              {"repeats", "1", ParameterKind::integer, 1, 1000, 1,
               ParameterValue(static_cast<double>(f->repeats)),
               "runs per measurement (the median is reported)"},
              f->repeats);
  cmd->add_option("--models", f->models,
                  "models to time; default preetham,cie,hosek,nn; with sh also the SH table's "
                  "evaluation against direct projection; with gpu the nn network's GL frame "
                  "against its CPU batch path; with pietras the Pietras networks against nishita")
      ->delimiter(',');
  cmd->add_option("--sh-table", f->sh_table,
                  "with sh in --models: the SH table timed (default: the embedded one)");
  // Hidden: the model flags of render/eval, so that giving one names the problem.
  const auto hidden = [&](const std::string& name, bool is_flag) {
    f->model_flags.push_back("--" + name);
    if (is_flag)
      cmd->add_flag("--" + name)->group("");
    else
      cmd->add_option("--" + name, f->model_flag_text)->group("");
  };
  for (const char* name : {"model", "sun-zenith", "sun-elevation", "sun-azimuth", "time", "lat",
                           "lon", "elevation", "pressure", "temperature", "delta-t"})
    hidden(name, false);
  for (const char* name : {"include-sun", "sun-only"}) hidden(name, true);
  for (const auto& [name, specs] : model_parameter_names())
    if (std::find(f->model_flags.begin(), f->model_flags.end(), "--" + name) ==
        f->model_flags.end())
      hidden(name, std::all_of(specs.begin(), specs.end(),
                               [](const auto& s) { return s.second.kind == ParameterKind::flag; }));
  cmd->add_flag("--estimate", f->estimate,
                "also time one turbidity estimate on a 1-megapixel fisheye (skylight estimate)");
  cmd->add_flag("--haze", f->haze,
                "also time haze retarget on a 1920x1080 frame + depth against the exact "
                "per-pixel spectral integral (skylight haze), and its GL frame when built with "
                "the GPU module");
  commands.push_back({cmd, [f, cmd] { return run_bench(*f, *cmd); }});
}

}  // namespace skylight::cli
