// Google Benchmark: sky evaluation over a 1024x512 equirect direction grid.
//   *_Scalar:  the plain per-direction loop (double, virtual call) - the in-run baseline;
//   *_Batch:   the SIMD float batch on one thread;
//   *_Threads: the batch over all threads (parallel_for chunks).
// Ratios are printed by `skylight bench`; here compare the reported times of the three.
// EstimateFisheye1Mpx: one `skylight estimate` on a 1024 x 1024 fisheye Preetham sky with the solar
// disc (sun detection, automatic mask, 100 samples, RANSAC, bootstrap), on the calling thread.
// GpuNnFrame* (with SKYLIGHT_GPU): the `nn` model's fragment-shader frame, 1024x512 equirect, on
// the headless GL context (Mesa llvmpipe without a GPU; docs/GPU.md), with glFinish, without and
// with the float readback. GpuPlanetFrame* / PlanetTerms: the Pietras planet (gpu/planet.h).
// HazeRetarget1080p: re-target a 1920 x 1080 image + depth in place (Morales 2017 eq. 26, Gamma
// tables, all threads); HazeRetargetExact: the exact per-pixel spectral integral (eq. 11) on 1920 x
// 54, one thread (x 20 for a frame). HazeRetarget1080pPerPixel: the same with a per-pixel airlight
// at both turbidities (eqs. 12-13 through a 60 deg pinhole, haze/airlight_field.h; built once).
// `skylight bench --haze` prints frames/s and the ratio.
// RowsBaseline/*, Rows/*: 2^20 directions as float SoA and as float64 rows (the Python layout).
// SkyMatrixYear/*: `skylight daylight --epw`'s matrix of the sample year (Tregenza, Reinhart 2305).
// PlaneYear/*: `skylight irradiance --epw`'s hourly light on a south façade for the sample year:
// the Perez sky of each hour by the `sky` method, and Perez 1990's transposition (the baseline).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "skylight/core/parallel.h"
#include "skylight/daylight/plane_series.h"
#include "skylight/daylight/sky_matrix.h"
#include "skylight/haze/image_haze.h"
#include "skylight/models/evaluation.h"
#include "skylight/models/nishita.h"
#include "skylight/models/sh.h"
#include "skylight/perf/workloads.h"
#ifdef SKYLIGHT_HAVE_GPU
#include "skylight/gpu/planet.h"
#include "skylight/gpu/sky_render.h"
#endif

namespace {

using namespace skylight;

// The workloads are perf/workloads.h's, shared with `skylight bench`: each model at its defaults
// plus the registry's example values, the sun at zenith 45 deg, azimuth 180 deg.
perf::DirectionGrid& grid() {
  static perf::DirectionGrid g;
  return g;
}

void Scalar(benchmark::State& state, const char* name) {
  const auto m = perf::bench_model(name);
  perf::DirectionGrid& g = grid();
  for (auto _ : state) {
    g.scalar(*m);
    benchmark::DoNotOptimize(g.Y.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(g.size()));
}

void Batch(benchmark::State& state, const char* name) {
  const auto m = perf::bench_model(name);
  perf::DirectionGrid& g = grid();
  for (auto _ : state) {
    g.batch(*m);
    benchmark::DoNotOptimize(g.Y.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(g.size()));
}

void Threads(benchmark::State& state, const char* name) {
  const auto m = perf::bench_model(name);
  perf::DirectionGrid& g = grid();
  for (auto _ : state) {
    g.threads(*m);
    benchmark::DoNotOptimize(g.Y.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(g.size()));
  state.counters["threads"] = thread_count();
}

// nishita's brute-force reference path on a 64 x 32 grid (the full frame would take minutes),
// all threads; the counter scales the time to one 1024 x 512 frame for comparison with Threads.
void NishitaReference(benchmark::State& state) {
  NishitaParameters p;
  p.sun = {deg_to_rad(45.0), deg_to_rad(180.0)};
  const NishitaModel m(p);
  const perf::DirectionGrid g(64, 32);
  std::vector<float> Y(g.size());
  double seconds = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    parallel_for(g.size(), 16, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i)
        Y[i] = static_cast<float>(m.tristimulus_reference({g.d.x[i], g.d.y[i], g.d.z[i]}).Y);
    });
    benchmark::DoNotOptimize(Y.data());
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  state.counters["s_per_1024x512_frame"] = seconds / static_cast<double>(state.iterations()) *
                                           (1024.0 * 512.0) / static_cast<double>(g.size());
}

void EstimateFisheye1Mpx(benchmark::State& state) {
  const perf::EstimatePhoto photo = perf::estimate_photo();
  for (auto _ : state) {
    const auto e = perf::estimate_once(photo);
    benchmark::DoNotOptimize(e.fit.log_scale);
  }
}

// 2^20 directions (a 2048 x 512 equirect grid) as the SIMD float batch takes them (RowsBaseline,
// one thread, directions already float SoA) and as float64 rows in and out (Rows: evaluate_rows,
// models/evaluation.h, one thread: the Python package's Sky.evaluate_directions without the
// binding). Their ratio is the cost of the float64 row layout (docs/PYTHON.md).
perf::DirectionGrid& grid_2m() {
  static perf::DirectionGrid g(2048, 512);
  return g;
}

void RowsBaseline(benchmark::State& state, const char* name) {
  const auto m = perf::bench_model(name);
  perf::DirectionGrid& g = grid_2m();
  for (auto _ : state) {
    g.batch(*m);
    benchmark::DoNotOptimize(g.Y.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(g.size()));
}

void Rows(benchmark::State& state, const char* name) {
  const auto m = perf::bench_model(name);
  const perf::DirectionGrid& g = grid_2m();
  std::vector<double> rows(3 * g.size()), out(3 * g.size());
  // Unit vectors in float64 (as numpy normalises them: no scaling pass).
  for (std::size_t i = 0; i < g.size(); ++i) {
    const Vec3 v = normalize(Vec3{g.d.x[i], g.d.y[i], g.d.z[i]});
    rows[3 * i] = v.x;
    rows[3 * i + 1] = v.y;
    rows[3 * i + 2] = v.z;
  }
  EvaluationOptions o;
  o.quantity = Quantity::xyz;
  set_thread_count(1);
  for (auto _ : state) {
    evaluate_rows(*m, rows, o, out);
    benchmark::DoNotOptimize(out.data());
  }
  set_thread_count(0);
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(g.size()));
}

void SetUp(benchmark::State& state, const char* name) {
  for (auto _ : state) benchmark::DoNotOptimize(perf::bench_model(name));
}

}  // namespace

// Every model the registry's bench policies name, as `skylight bench` does: those timed by default
// (preetham, cie, hosek, nn: the embedded 6-12-3 network, docs/NN.md) and the models others are
// compared with (nishita, pietras' baseline: the scalar loop over its table-driven fast path, no
// SIMD batch): scalar loop, batch, batch on all threads and set-up; the float64 rows of the Python
// layout for those timed by default. `nishita`'s set-up: the optical-length tables (2 components x
// 256 x 256 quadratures); `hosek`'s: XYZ, RGB and 11 spectral band states and the solar disc's XYZ
// polynomial, the embedded tables parsed once on first use (outside the steady state).
const bool kModelBenchmarksRegistered = [] {
  std::vector<std::string> names;
  for (const ModelInfo& m : model_registry())
    if (m.bench.by_default) names.push_back(m.name);
  for (const ModelInfo& m : model_registry())
    if (!m.bench.baseline.empty() &&
        std::find(names.begin(), names.end(), m.bench.baseline) == names.end())
      names.push_back(m.bench.baseline);
  // The benchmarks keep a pointer to their model's name: the names live as long as the process.
  static const std::vector<std::string> kept = names;
  for (const std::string& name : kept) {
    const char* n = name.c_str();
    const ModelInfo& m = *find_model(name);
    if (m.bench.by_default) {
      benchmark::RegisterBenchmark(("RowsBaseline/" + name).c_str(), RowsBaseline, n)
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("Rows/" + name).c_str(), Rows, n)
          ->Unit(benchmark::kMillisecond);
    }
    benchmark::RegisterBenchmark(("Scalar/" + name).c_str(), Scalar, n)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Batch/" + name).c_str(), Batch, n)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Threads/" + name).c_str(), Threads, n)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("SetUp/" + name).c_str(), SetUp, n)
        ->Unit(m.bench.by_default ? benchmark::kMicrosecond : benchmark::kMillisecond);
  }
  return true;
}();
// Pietras §III: the pietras model with a Pietras network (trainer's initial weights, the cost of a
// trained one), observer on the ground, sun at zenith 45 deg; compare with Batch/nishita.
void PietrasBatch(benchmark::State& state, nn::PietrasKind kind) {
  const auto m = perf::pietras_bench_model(kind);
  perf::DirectionGrid& g = grid();
  for (auto _ : state) {
    g.batch(*m);
    benchmark::DoNotOptimize(g.Y.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(g.size()));
}
BENCHMARK_CAPTURE(PietrasBatch, pietras, nn::PietrasKind::pietras)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(PietrasBatch, log3, nn::PietrasKind::log3)->Unit(benchmark::kMillisecond);
BENCHMARK(NishitaReference)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// Habel 2008 §4: one sky's 7 bands x 3 channels from the embedded (17, 12) table, eq. 1 + rotation
// (eq. 4) + ringing filter (eq. 5); against the direct projection of the table's model
// (ShProjectModel).
void ShEvaluateTable(benchmark::State& state) {
  const sh::PolynomialTable table = load_sh_table({});
  double theta = 0.1;
  for (auto _ : state) {
    theta = theta > 1.4 ? 0.1 : theta + 1e-3;
    benchmark::DoNotOptimize(perf::evaluate_sh_table(table, theta));
  }
}

void ShProjectModel(benchmark::State& state) {
  const sh::PolynomialTable table = load_sh_table({});
  for (auto _ : state) benchmark::DoNotOptimize(perf::project_sh_model(table));
}

BENCHMARK(ShEvaluateTable)->Unit(benchmark::kMicrosecond);
BENCHMARK(ShProjectModel)->Unit(benchmark::kMillisecond)->UseRealTime();

#ifdef SKYLIGHT_HAVE_GPU
void GpuNnFrame(benchmark::State& state, bool readback) {
  gpu::Context context;
  const auto m = perf::bench_model("nn");
  render::RenderSettings s;  // 1024 x 512 equirect
  gpu::SkyRenderer r(*m, s);
  for (auto _ : state) {
    r.draw();
    if (readback)
      benchmark::DoNotOptimize(r.read().data.data());
    else
      context.finish();
  }
}
BENCHMARK_CAPTURE(GpuNnFrame, draw, false)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(GpuNnFrame, draw_and_readback, true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The Pietras vertex shader's planet from orbit at the `nn planet` defaults (paper network,
// trainer's initial weights: the same cost), the program compiled once: per frame the vertex
// attributes' upload and the draw, with glFinish or the float readback. PlanetTerms: the vertex
// terms on the CPU (all threads), which a moving camera needs per frame as well.
struct PlanetScene {
  nn::PietrasNetwork net = nn::initial_pietras_network(nn::PietrasKind::pietras, 1);
  NishitaParameters earth;
  NishitaSampler atmosphere{earth};
  gpu::PlanetView view = gpu::orbit_view(earth, 2.0 * earth.ground_radius_m, 0.5);
};
void GpuPlanetFrame(benchmark::State& state, bool readback) {
  gpu::Context context;
  const PlanetScene scene;
  const gpu::PlanetMesh mesh = gpu::planet_mesh(scene.net, scene.atmosphere, scene.view);
  gpu::PlanetRenderer r(scene.net, scene.view.width, scene.view.height);
  for (auto _ : state) {
    r.draw(mesh);
    if (readback)
      benchmark::DoNotOptimize(r.read().data.data());
    else
      context.finish();
  }
}
BENCHMARK_CAPTURE(GpuPlanetFrame, draw, false)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(GpuPlanetFrame, draw_and_readback, true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
void PlanetTerms(benchmark::State& state) {
  const PlanetScene scene;
  for (auto _ : state)
    benchmark::DoNotOptimize(gpu::planet_mesh(scene.net, scene.atmosphere, scene.view));
}
BENCHMARK(PlanetTerms)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif

void HazeRetarget1080p(benchmark::State& state) {
  perf::HazeFrame f;
  for (auto _ : state) {
    haze::apply_haze_in_place(f.image, f.depth, perf::haze_camera(), f.settings);  // one buffer
    benchmark::DoNotOptimize(f.image.data.data());
  }
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void HazeRetargetExact(benchmark::State& state) {
  const perf::HazeFrame f(54);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        haze::apply_haze_exact(f.image, f.depth, perf::haze_camera(), f.settings));
}

void HazeRetarget1080pPerPixel(benchmark::State& state) {
  perf::HazeFrame f;
  perf::add_per_pixel_airlight(f);
  for (auto _ : state) {
    haze::apply_haze_in_place(f.image, f.depth, perf::haze_camera(), f.settings);
    benchmark::DoNotOptimize(f.image.data.data());
  }
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// The annual sky matrix of the sample EPW year (4440 hours with the sun up; daylight/), one
// thread, file reading and writing left out.
void SkyMatrixYear(benchmark::State& state, const char* patches) {
  static const io::EpwFile epw =
      io::read_epw(std::string(SKYLIGHT_SOURCE_DATA_DIR) + "/weather/synthetic_munich.epw");
  daylight::MatrixSettings s;
  s.patches = patches;
  for (auto _ : state) benchmark::DoNotOptimize(daylight::sky_matrix(epw, s, "sample"));
  state.counters["hours"] =
      static_cast<double>(daylight::sky_matrix(epw, s, "sample").hours.size());
}

// The year's hourly light on a south façade (4440 hours; all threads, as the command runs it).
void PlaneYear(benchmark::State& state, daylight::Transposition method) {
  static const io::EpwFile epw =
      io::read_epw(std::string(SKYLIGHT_SOURCE_DATA_DIR) + "/weather/synthetic_munich.epw");
  static const io::HorizonProfile flat;
  const daylight::PlaneContext plane = daylight::plane_context({0.5 * kPi, kPi}, method, flat);
  daylight::SeriesSettings s;
  s.weather_sky = true;
  for (auto _ : state) benchmark::DoNotOptimize(daylight::plane_series(epw, plane, s, "sample"));
}

BENCHMARK_CAPTURE(PlaneYear, Sky, daylight::Transposition::sky)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(PlaneYear, Perez1990, daylight::Transposition::perez1990)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(SkyMatrixYear, Tregenza, "tregenza")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(SkyMatrixYear, Reinhart2305, "reinhart4")->Unit(benchmark::kMillisecond);
BENCHMARK(HazeRetarget1080p)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(HazeRetargetExact)->Unit(benchmark::kMillisecond);
BENCHMARK(HazeRetarget1080pPerPixel)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(EstimateFisheye1Mpx)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
