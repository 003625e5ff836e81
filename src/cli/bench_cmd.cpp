// `skylight bench`: the library's benchmark report (perf/bench.h: each model's batch path
// against its scalar loop, its comparison and workload, --estimate, --haze) and the GL frames of
// the gpu module (gpu/bench.h: --models gpu, the haze frame), medians of repeated runs.
#include <fmt/format.h>

#include <algorithm>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/operations/operations.h"
#include "skylight/perf/bench.h"
#ifdef SKYLIGHT_HAVE_GPU
#include "skylight/gpu/bench.h"
#endif

namespace skylight::cli {
namespace {

struct BenchCommand {
  SchemaFlags flags;
  // The model flags of render/eval, accepted here only to be refused with a clear message.
  std::vector<std::string> model_flags;
  std::string model_flag_text;
};

int run_bench(const BenchCommand& f, const CLI::App& cmd) {
  std::string given;
  for (const auto& name : f.model_flags)
    if (cmd.count(name) > 0) given += (given.empty() ? "" : ", ") + name;
  if (!given.empty())
    throw InvalidArgument(fmt::format(
        "bench takes no model flags ({}): every model runs at its defaults (sun zenith 45 deg, "
        "azimuth 180 deg, T = 3, albedo 0.3, CIE type 12); choose the models with --models",
        given));
  const auto s = f.flags.bind(perf::BenchSettings::schema(), {}, "bench");
  const bool gpu = std::find(s.models.begin(), s.models.end(), "gpu") != s.models.end();
#ifndef SKYLIGHT_HAVE_GPU
  if (gpu)
    throw std::runtime_error(
        "--models gpu: this skylight was built without the GPU module (SKYLIGHT_GPU=OFF; "
        "docs/GPU.md)");
#endif
  const perf::Output out = [](std::string_view text) { write_stdout(text); };
  const double haze_wall = perf::run_bench(s, out);
#ifdef SKYLIGHT_HAVE_GPU
  if (s.haze) gpu::bench_haze(s.repeats, haze_wall, out);
  if (gpu) gpu::bench_frames(s.width, s.height, s.repeats, out);
#else
  (void)haze_wall;
#endif
  return kExitOk;
}

}  // namespace

void add_bench_command(CLI::App& app, Commands& commands) {
  auto f = std::make_shared<BenchCommand>();
  auto* cmd = app.add_subcommand(
      "bench", "time the batch path against an in-run scalar loop (ratios, medians)");
  f->flags.add(*cmd, operations::find("bench").parameters);
  // Hidden: the model flags of render/eval, so that giving one names the problem.
  const auto hidden = [&](const std::string& name, bool is_flag) {
    f->model_flags.push_back("--" + name);
    if (is_flag)
      cmd->add_flag("--" + name)->group("");
    else
      cmd->add_option("--" + name, f->model_flag_text)->group("");
  };
  for (const auto& spec : operations::model_specs())
    hidden(spec.name, spec.kind == ParameterKind::flag);
  for (const auto& [name, specs] : model_parameter_names())
    if (std::find(f->model_flags.begin(), f->model_flags.end(), "--" + name) ==
        f->model_flags.end())
      hidden(name, std::all_of(specs.begin(), specs.end(),
                               [](const auto& s) { return s.second.kind == ParameterKind::flag; }));
  commands.push_back({cmd, [f, cmd] { return run_bench(*f, *cmd); }});
}

}  // namespace skylight::cli
