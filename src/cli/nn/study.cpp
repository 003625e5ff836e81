// `skylight nn study`: the hidden-layer study of Satilmis et al. 2016 §III-B (Fig. 5, eq. 8) on
// this implementation (docs/NN.md; fit/network_training.h, study_hidden_layers): per hidden-layer
// width the validation error, the evaluation time and the efficiency eps = 1 / (Var T).
#include <fmt/format.h>

#include "nn.h"
#include "skylight/fit/network_training.h"
#include "skylight/operations/operations.h"

namespace skylight::cli {
namespace {

int run_study(const SchemaFlags& flags) {
  const auto f = flags.bind(fit::HiddenLayerStudy::schema(), fit::HiddenLayerStudy{}, "nn study");
  Progress progress("nn study");
  const std::vector<fit::StudyRow> rows = fit::study_hidden_layers(
      f, [&](int k, int n, int h) { progress(k, n, fmt::format("hidden {}", h)); });
  progress(static_cast<int>(f.hidden.size()), static_cast<int>(f.hidden.size()), "done");
  std::size_t best = 0;
  for (std::size_t k = 1; k < rows.size(); ++k)
    if (rows[k].efficiency > rows[best].efficiency) best = k;
  std::string out = fmt::format(
      "nn study: source {}, default trainer (lm), seed {}, time limit {} s per network; T = "
      "batch evaluation of the 1024 x 512 equirect grid on one thread (best of {})\n",
      f.source_model(), f.seed, f.time_limit_s, f.repeats);
  out +=
      "hidden  weights  val_rmse  var=rmse^2  rel_median  rel_p95  train_s  stop        T_ms   "
      "eps=1/(var*T)  eps/eps_max\n";
  for (const fit::StudyRow& r : rows)
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
  auto flags = std::make_shared<SchemaFlags>();
  auto* cmd = nn.add_subcommand(
      "study",
      "error and speed per hidden-layer width\n"
      "The hidden-layer study (Satilmis et al. 2016 Fig. 5, eq. 8): error, evaluation time "
      "and efficiency per hidden-layer width.");
  flags->add(*cmd, operations::find("nn study").parameters);
  commands.push_back({cmd, [flags] { return run_study(*flags); }});
}

}  // namespace skylight::cli
