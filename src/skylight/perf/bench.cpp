#include "skylight/perf/bench.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <map>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/core/parallel.h"
#include "skylight/core/parameters.h"
#include "skylight/core/statistics.h"
#include "skylight/core/system.h"
#include "skylight/io/table_cache.h"
#include "skylight/models/sh.h"
#include "skylight/perf/workloads.h"

namespace skylight::perf {
namespace {

// The row of one model: (scalar, batch on one thread) [s].
std::pair<double, double> model_row(const ModelInfo& info, DirectionGrid& grid, int repeats,
                                    const Output& out) {
  const auto model = bench_model(info.name);
  volatile float sink = 0.0f;
  // In-run baseline: the plain scalar loop of the same model (double precision, one thread).
  const double scalar = median_seconds(repeats, [&] {
    grid.scalar(*model);
    sink = grid.Y[grid.size() / 2];
  });
  const double batch1 = median_seconds(repeats, [&] {
    grid.batch(*model);
    sink = grid.Y[grid.size() / 2];
  });
  const double batchN = median_seconds(repeats, [&] {
    grid.threads(*model);
    sink = grid.Y[grid.size() / 2];
  });
  (void)sink;
  out(fmt::format("{:<10} {:>12.2f} {:>12.2f} {:>12.2f} {:>10.2f} {:>10.2f}\n", info.name,
                  1e3 * scalar, 1e3 * batch1, 1e3 * batchN, scalar / batch1, batch1 / batchN));
  return {scalar, batch1};
}

// One `skylight estimate` on the 1-megapixel fisheye: wall time and this thread's CPU time (the
// estimate runs on the calling thread only; on a busy machine the CPU time is the cost).
void bench_estimate(int repeats, const Output& out) {
  const EstimatePhoto photo = estimate_photo();
  fit::PhotoFit e;
  std::vector<double> cpu;
  const double wall = median_seconds(repeats, [&] {
    const double c0 = thread_cpu_s();
    e = estimate_once(photo);
    cpu.push_back(thread_cpu_s() - c0);
  });
  out(fmt::format(
      "estimate: 1024x1024 fisheye (preetham T = 4, sun 40 deg / 150 deg), sun detection + mask + "
      "fit on one thread: {:.2f} ms CPU, {:.2f} ms wall (T = {:.4f}, sun found at {:.2f} deg / "
      "{:.2f} deg)\n",
      1e3 * median(cpu), 1e3 * wall, e.fit.parameters.front().value, rad_to_deg(e.fit.sun.zenith),
      rad_to_deg(e.fit.sun.azimuth)));
}

// Habel 2008 §4: one sky's SH from the table against projecting its model.
void bench_sh_table(int repeats, const std::string& table_path, const Output& out) {
  const sh::PolynomialTable table = load_sh_table(table_path);
  if (table.bands < 7)
    throw InvalidArgument(spelled("sh-table") + ": the table has fewer than 7 bands");
  constexpr int kCalls = 2000;
  volatile double sink = 0.0;
  // Wall and thread CPU time: on a loaded machine the wall time includes waiting for a core.
  std::vector<double> cpu;
  const double per_eval =
      median_seconds(repeats,
                     [&] {
                       const double c0 = thread_cpu_s();
                       double acc = 0.0;
                       for (int i = 0; i < kCalls; ++i)
                         acc += evaluate_sh_table(table, 0.1 + 1.3 * i / kCalls).c[4][1];
                       sink = acc;
                       cpu.push_back((thread_cpu_s() - c0) / kCalls);
                     }) /
      kCalls;
  const double project = median_seconds(
      std::min(repeats, 3), [&] { sink = project_sh_model(table).coefficients.c[4][1]; });
  (void)sink;
  out(
      fmt::format("sh: 7 bands x 3 channels from the '{}' ({}, {}) table incl. rotation and "
                  "filter {:.2f} us CPU, {:.2f} us wall (medians, one thread); "
                  "direct projection of {} {:.1f} ms ({} threads); ratio {:.0f}x\n",
                  table.model, table.degree_theta, table.degree_tau, 1e6 * median(cpu),
                  1e6 * per_eval, table.model, 1e3 * project, thread_count(), project / per_eval));
}

// Pietras §III: each network kind against its source's fast path on one thread.
void bench_network_kinds(const ModelInfo& info, int repeats, DirectionGrid& grid,
                         const Output& out) {
  volatile float sink = 0.0f;
  const auto time = [&](const SkyModel& m) {
    return median_seconds(repeats, [&] {
      grid.batch(m);
      sink = grid.Y[grid.size() / 2];
    });
  };
  const double base = time(*bench_model(info.bench.baseline));
  std::string text = fmt::format("{}: {} fast path {:.2f} ms per frame (one thread)\n", info.name,
                                 info.bench.baseline, 1e3 * base);
  for (nn::PietrasKind k : {nn::PietrasKind::pietras, nn::PietrasKind::log3}) {
    const double t = time(*pietras_bench_model(k));
    text +=
        fmt::format("{}: {} ({} weights) {:.2f} ms per frame: {:.1f}x faster than {}\n", info.name,
                    nn::to_string(k), nn::initial_pietras_network(k, 1).parameter_count(), 1e3 * t,
                    base / t, info.bench.baseline);
  }
  (void)sink;
  out(text);
}

// Morales 2017 eq. 26 on 1920 x 1080: the Gamma-table path on all threads against the exact
// per-pixel spectral integral (eq. 11 at 81 wavelengths) on one thread, timed on 1/20 of the frame
// and scaled; then with per-pixel airlight. Returns the table path's wall time per frame.
double bench_haze(int repeats, const Output& out) {
  HazeFrame full, strip(54);
  const auto& cam = haze_camera();
  haze::HazeReport report;
  // Wall time, and the CPU time of all threads per frame: on a busy machine the wall time includes
  // waiting for a core, the CPU time is the cost (frames/s on n idle cores = n / CPU time).
  std::vector<double> cpu;
  const double fast = median_seconds(repeats, [&] {
    const double c0 = process_cpu_s();
    haze::apply_haze_in_place(full.image, full.depth, cam, full.settings, &report);
    cpu.push_back(process_cpu_s() - c0);
  });
  const double fast_cpu = median(cpu);
  const double exact = 20.0 * median_seconds(std::max(1, repeats / 3), [&] {
                         const io::ImageF o =
                             haze::apply_haze_exact(strip.image, strip.depth, cam, strip.settings);
                         volatile float sink = o.data[o.data.size() / 2];
                         (void)sink;
                       });
  out(fmt::format(
      "haze retarget 1920x1080 + depth (eq. 26, T 1.9 -> 4.36): {:.2f} ms wall = {:.0f} frames/s "
      "on {} threads; CPU time {:.2f} ms per frame (= {:.0f} frames/s on 2 idle cores); Gamma "
      "tables {} entries, interpolation error <= {:.1g}; exact per-pixel spectral integral on one "
      "thread: {:.0f} ms per frame = {:.0f}x the wall time, {:.0f}x the CPU time\n",
      1e3 * fast, 1.0 / fast, thread_count(), 1e3 * fast_cpu, 2.0 / fast_cpu, report.table_entries,
      report.table_error_bound, 1e3 * exact, exact / fast, exact / fast_cpu));
  HazeFrame per_pixel;
  const double maps = median_seconds(1, [&] { add_per_pixel_airlight(per_pixel); });
  cpu.clear();
  const double fast_map = median_seconds(repeats, [&] {
    const double c0 = process_cpu_s();
    haze::apply_haze_in_place(per_pixel.image, per_pixel.depth, cam, per_pixel.settings);
    cpu.push_back(process_cpu_s() - c0);
  });
  const double map_cpu = median(cpu);
  out(fmt::format(
      "haze retarget 1920x1080, per-pixel airlight (60 deg pinhole, eqs. 12-13): {:.2f} ms wall = "
      "{:.0f} frames/s; CPU time {:.2f} ms per frame (= {:.0f} frames/s on 2 idle cores); the two "
      "airlight maps once per camera: {:.0f} ms\n",
      1e3 * fast_map, 1.0 / fast_map, 1e3 * map_cpu, 2.0 / map_cpu, 1e3 * maps));
  return fast;
}

// The model's first construction in the process (its tables, its sky-view LUT) and its first
// batch frame (the whole-sky LUT, then the frame): wall and CPU time of all threads. The
// frame after it is the row's batchN.
std::string bench_precomputation(const ModelInfo& info, DirectionGrid& grid, int width,
                                 int height) {
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = process_cpu_s();
  const auto model = bench_model(info.name);
  const double build_wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double build_cpu = process_cpu_s() - c0;
  const double first = median_seconds(1, [&] { grid.threads(*model); });
  const char* cache = std::getenv(io::kTableCacheVariable);
  return fmt::format(
      "{}: precomputation {:.2f} s wall, {:.2f} s CPU (tables and sky-view LUT{}); first "
      "{}x{} frame {:.0f} ms (with the whole-sky LUT); each frame after it: batchN above\n",
      info.name, build_wall, build_cpu,
      cache && *cache
          ? fmt::format(", {} set: tables read from it when there", io::kTableCacheVariable)
          : "",
      width, height, 1e3 * first);
}

std::vector<const ModelInfo*> bench_infos(const BenchSettings& s) {
  std::vector<const ModelInfo*> models;
  for (const auto& name : s.models.empty() ? default_bench_models() : s.models) {
    if (name == "gpu") continue;  // not a model: the GL frames (gpu/bench.h)
    models.push_back(&require_model(name, "models"));
  }
  return models;
}

}  // namespace

const ParameterSchema<BenchSettings>& BenchSettings::schema() {
  static const ParameterSchema<BenchSettings> s = [] {
    using B = BenchSettings;
    const B d;
    std::string defaults;
    for (const auto& m : default_bench_models()) defaults += (defaults.empty() ? "" : ",") + m;
    ParameterSchema<B> s;
    s.integer(&B::width, {.name = "width",
                          .unit = "px",
                          .kind = ParameterKind::integer,
                          .min = 1,
                          .max = kMaxImageSide,
                          .default_value = ParameterValue(static_cast<double>(d.width)),
                          .description = "grid width"})
        .integer(&B::height, {.name = "height",
                              .unit = "px",
                              .kind = ParameterKind::integer,
                              .min = 1,
                              .max = kMaxImageSide,
                              .default_value = ParameterValue(static_cast<double>(d.height)),
                              .description = "grid height"})
        .integer(&B::repeats, {.name = "repeats",
                               .unit = "1",
                               .kind = ParameterKind::integer,
                               .min = 1,
                               .max = 1000,
                               .default_value = ParameterValue(static_cast<double>(d.repeats)),
                               .description = "runs per measurement (the median is reported)"})
        .custom(
            {.name = "models",
             .kind = ParameterKind::text,
             .default_value = Absent{defaults},
             .description =
                 "models to time, comma-separated (each with its comparison and workload: sh its "
                 "table's evaluation, pietras each network kind); gpu: the GL frames"},
            [](B& b, const ParameterValue& v) {
              // An empty list, or an empty name in it, is refused: it would silently time the
              // defaults (or skip a model the user meant to type).
              b.models.clear();
              const std::string& t = std::get<std::string>(v);
              for (std::size_t a = 0, k = 1; a <= t.size(); ++k) {
                const std::size_t e = std::min(t.find(',', a), t.size());
                if (e == a)
                  throw InvalidArgument(
                      t.empty() ? fmt::format("{} = '' names no model", spelled("models"))
                                : fmt::format("{} = '{}': name {} is empty", spelled("models"),
                                              excerpt(t), k));
                b.models.push_back(t.substr(a, e - a));
                a = e + 1;
              }
            },
            [](const B& b) -> std::optional<ParameterValue> {
              if (b.models.empty()) return std::nullopt;
              std::string t;
              for (const auto& m : b.models) t += (t.empty() ? "" : ",") + m;
              return t;
            })
        .flag(&B::estimate,
              {.name = "estimate",
               .kind = ParameterKind::flag,
               .description = "also time one turbidity estimate on a 1-megapixel fisheye "
                              "(skylight estimate)"})
        .flag(&B::haze,
              {.name = "haze",
               .kind = ParameterKind::flag,
               .description =
                   "also time haze retarget on a 1920x1080 frame + depth against the exact "
                   "per-pixel spectral integral (skylight haze), and its GL frame when "
                   "built with the GPU module"})
        .text(&B::sh_table, {.name = "sh-table",
                             .kind = ParameterKind::text,
                             .default_value = Absent{"the embedded one"},
                             .description = "with sh in --models: the SH table timed"});
    return s;
  }();
  return s;
}

double run_bench(const BenchSettings& s, const Output& out) {
  const std::vector<const ModelInfo*> models = bench_infos(s);
  DirectionGrid grid(s.width, s.height);
  out(
      fmt::format("skylight bench: {}x{} equirect directions, median of {} runs, {} threads\n"
                  "{:<10} {:>12} {:>12} {:>12} {:>10} {:>10}\n",
                  s.width, s.height, s.repeats, thread_count(), "model", "scalar ms", "batch1 ms",
                  "batchN ms", "SIMD x", "threads x"));
  std::map<std::string, std::pair<double, double>> timed;  // name -> (scalar, batch1)
  std::string precomputations;
  for (const ModelInfo* info : models)
    if (info->bench.extra == BenchPolicy::Extra::precomputation)
      precomputations += bench_precomputation(*info, grid, s.width, s.height);
  for (const ModelInfo* info : models) timed[info->name] = model_row(*info, grid, s.repeats, out);
  out("SIMD x = scalar loop / batch on one thread; threads x = batch one thread / batch all "
      "threads\n");
  for (const ModelInfo* info : models) {
    const std::string& base = info->bench.baseline;
    if (!base.empty() && timed.count(base) && info->bench.extra == BenchPolicy::Extra::none)
      out(fmt::format(
          "{} batch on one thread: {:.2f}x faster than the {} batch, {:.1f}x faster than its own "
          "scalar loop\n",
          info->bench.label.empty() ? info->name : info->bench.label,
          timed[base].second / timed[info->name].second, base,
          timed[info->name].first / timed[info->name].second));
    if (info->bench.extra == BenchPolicy::Extra::network_kinds)
      bench_network_kinds(*info, s.repeats, grid, out);
  }
  out(precomputations);
  if (s.estimate) bench_estimate(s.repeats, out);
  for (const ModelInfo* info : models)
    if (info->bench.extra == BenchPolicy::Extra::sh_table)
      bench_sh_table(s.repeats, s.sh_table, out);
  return s.haze ? bench_haze(s.repeats, out) : 0.0;
}

}  // namespace skylight::perf
