// `skylight nn study`: the hidden-layer study of Satilmis et al. 2016 §III-B (Fig. 5, eq. 8) on
// this implementation (docs/NN.md): for each hidden-layer width, a network trained with the
// paper's protocol (or the given reduced sampling), its validation error, its evaluation time on
// the 1024 x 512 equirect grid (batch path, one thread, best of --repeats) and the efficiency
// eps = 1 / (Var T), Var = the validation MSE of the normalised outputs (RMSE^2, metrics.h).
#include <fmt/format.h>

#include <chrono>
#include <limits>

#include "common.h"
#include "nn_parts.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/fit/neural_training.h"
#include "skylight/nn/sky_network.h"
#include "skylight/render/sky_render.h"

namespace skylight::cli {
namespace {

struct StudyFlags {
  std::string source = "hosek";
  std::vector<double> hidden{4, 8, 12, 16, 24, 32};
  int seed = 1, iterations = 500, repeats = 5;
  double time_limit_s = 60.0;
  int suns = 0, view_zeniths = 0, view_azimuths = 0;
};

// Best-of-repeats wall time [s] of the batch path over the grid on the calling thread.
double grid_seconds(const nn::SkyNetwork& sky, const render::PixelDirections& d, int repeats) {
  nn::SkyState state;
  state.turbidity = 3.0;
  state.sun_zenith = deg_to_rad(40.0);
  state.sun_azimuth = deg_to_rad(150.0);
  const nn::SkyNetworkBatch batch(sky, state);
  const std::size_t n = d.x.size();
  std::vector<float> r(n), g(n), b(n);
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    batch.rgb(d.x.data(), d.y.data(), d.z.data(), r.data(), g.data(), b.data(), n);
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count());
  }
  return best;
}

int run_study(const StudyFlags& f) {
  render::RenderSettings grid;  // 1024 x 512 equirect
  const render::PixelDirections dirs = render::pixel_directions(grid);
  Progress progress("nn study");
  struct Row {
    int hidden;
    std::size_t weights;
    double rmse, median, p95, train_s, grid_s, efficiency;
    std::string stop;
  };
  std::vector<Row> rows;
  for (std::size_t k = 0; k < f.hidden.size(); ++k) {
    const int h = static_cast<int>(f.hidden[k]);
    progress(static_cast<int>(k), static_cast<int>(f.hidden.size()), fmt::format("hidden {}", h));
    fit::NeuralTraining t;
    t.source = f.source;
    t.hidden = {h};
    t.sun_count = f.suns;
    t.view_zeniths = f.view_zeniths;
    t.view_azimuths = f.view_azimuths;
    t.options.seed = static_cast<std::uint64_t>(f.seed);
    t.options.time_limit_s = f.time_limit_s;
    t.options.max_iterations = f.iterations;
    const fit::NeuralTrainingResult r = fit::train_neural_sky(t);
    const nn::ErrorStats& e = r.validation->errors;
    Row row;
    row.hidden = h;
    row.weights = r.network.net.layout().parameter_count();
    row.rmse = e.rmse;
    row.median = e.relative_median;
    row.p95 = e.relative_p95;
    row.train_s = r.train.seconds;
    row.stop = r.train.stop;
    row.grid_s = grid_seconds(r.network, dirs, f.repeats);
    row.efficiency = 1.0 / (e.rmse * e.rmse * row.grid_s);
    rows.push_back(row);
  }
  progress(static_cast<int>(f.hidden.size()), static_cast<int>(f.hidden.size()), "done");
  std::size_t best = 0;
  for (std::size_t k = 1; k < rows.size(); ++k)
    if (rows[k].efficiency > rows[best].efficiency) best = k;
  std::string out = fmt::format(
      "nn study: source {}, default trainer (lm), seed {}, time limit {} s per network; T = "
      "batch evaluation of the 1024 x 512 equirect grid on one thread (best of {})\n",
      f.source, f.seed, f.time_limit_s, f.repeats);
  out +=
      "hidden  weights  val_rmse  var=rmse^2  rel_median  rel_p95  train_s  stop        T_ms   "
      "eps=1/(var*T)  eps/eps_max\n";
  for (const Row& r : rows)
    out += fmt::format(
        "{:6}  {:7}  {:8.5f}  {:10.3e}  {:9.2f}%  {:6.2f}%  {:7.1f}  {:10}  {:5.2f}  "
        "{:13.4g}  {:11.3f}\n",
        r.hidden, r.weights, r.rmse, r.rmse * r.rmse, 100.0 * r.median, 100.0 * r.p95, r.train_s,
        r.stop, 1e3 * r.grid_s, r.efficiency, r.efficiency / rows[best].efficiency);
  out += fmt::format("most efficient: {} hidden neurons\n", rows[best].hidden);
  write_stdout(out);
  return kExitOk;
}

}  // namespace

void add_nn_study_command(CLI::App& nn, Commands& commands) {
  auto f = std::make_shared<StudyFlags>();
  auto* cmd = nn.add_subcommand(
      "study",
      "hidden-layer study (Satilmis et al. 2016 Fig. 5, eq. 8): error, evaluation time "
      "and efficiency per hidden-layer width");
  cmd->add_option("--source", f->source, "sky model to learn; default hosek (the paper's)");
  add_numbers(*cmd,
              {"hidden", "1", ParameterKind::numbers, 1.0, 256.0, 0, ParameterValue(f->hidden),
               "hidden-layer widths to compare (integers)"},
              f->hidden);
  add_integer(*cmd,
              {"seed", "1", ParameterKind::integer, 0, 2147483647, 1,
               ParameterValue(static_cast<double>(f->seed)), "seed of the initial weights"},
              f->seed);
  add_number(*cmd,
             {"time-limit", "s", ParameterKind::number, 0.01, 1e6, 1,
              ParameterValue(f->time_limit_s), "training wall time per network"},
             f->time_limit_s);
  add_integer(*cmd,
              {"iterations", "1", ParameterKind::integer, 1, 100000000, 1,
               ParameterValue(static_cast<double>(f->iterations)),
               "at most this many LM iterations per network"},
              f->iterations);
  add_integer(*cmd,
              {"repeats", "1", ParameterKind::integer, 1, 1000, 1,
               ParameterValue(static_cast<double>(f->repeats)), "timing repeats (the best counts)"},
              f->repeats);
  add_integer(*cmd,
              {"suns", "1", ParameterKind::integer, 0, 1000, 1, ParameterValue(0.0),
               "sun zenith angles per turbidity (0: the protocol's)"},
              f->suns);
  add_integer(*cmd,
              {"view-zeniths", "1", ParameterKind::integer, 0, 1000, 1, ParameterValue(0.0),
               "view zenith strata per sky (0: the protocol's)"},
              f->view_zeniths);
  add_integer(*cmd,
              {"view-azimuths", "1", ParameterKind::integer, 0, 1000, 1, ParameterValue(0.0),
               "view azimuth strata per sky (0: the protocol's)"},
              f->view_azimuths);
  commands.push_back({cmd, [f] { return run_study(*f); }});
}

}  // namespace skylight::cli
