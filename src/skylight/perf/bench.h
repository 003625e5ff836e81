// `skylight bench`: each model's batch path timed against an in-run baseline (the plain scalar
// loop of the same model), medians of repeated runs, printed as ratios; each model's BenchPolicy
// (models/sky_model.h) adds its comparison (e.g. nn against hosek, pietras against nishita) and
// its workload (the SH table, the network kinds); --estimate and --haze time those operations.
// The GL frames (`--models gpu`) are the gpu module's (gpu/bench.h).
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/parameters.h"

namespace skylight::perf {

struct BenchSettings {
  int width = 1024, height = 512, repeats = 7;
  std::vector<std::string> models;  // empty: default_bench_models(); "gpu": the GL frames
  bool estimate = false, haze = false;
  std::string sh_table;  // the SH table timed (empty: the embedded one)
  static const ParameterSchema<BenchSettings>& schema();
};

using Output = std::function<void(std::string_view)>;

// The models' table, their comparisons and workloads (every name of settings.models but "gpu";
// InvalidArgument naming an unknown model), then --estimate and --haze. Returns the CPU path's
// wall time per haze frame [s] (0 without --haze), for the GL comparison.
double run_bench(const BenchSettings& settings, const Output& out);

}  // namespace skylight::perf
