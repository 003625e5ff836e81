// `bench` (each model's batch path timed against its scalar loop, perf/bench.h; the GL frames by
// the installed backend) and `report` (the validation and comparison report, report/report.h).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "skylight/analysis/scan.h"
#include "skylight/io/file.h"
#include "skylight/operations/detail/families.h"
#include "skylight/operations/gpu_backend.h"
#include "skylight/operations/operations.h"
#include "skylight/perf/bench.h"
#include "skylight/report/report.h"

namespace skylight::operations::detail {
namespace {

// ---- bench --------------------------------------------------------------------------------------

struct BenchResult {
  std::vector<std::string> lines{};
};

const ResultSchema<BenchResult>& bench_result() {
  static const ResultSchema<BenchResult> s = [] {
    ResultSchema<BenchResult> s;
    s.lines("lines",
            "the measurements, one line each: medians of the repeats, wall and CPU time, ratios "
            "against the in-run baselines",
            &BenchResult::lines);
    return s;
  }();
  return s;
}

Result run_bench(const Request& r) {
  const auto s = r.bind(perf::BenchSettings::schema());
  const bool gpu = std::find(s.models.begin(), s.models.end(), "gpu") != s.models.end();
  BenchResult b;
  // Each measured line goes to the progress as it comes (the run takes minutes).
  const perf::Output out = [&](std::string_view text) {
    for (std::size_t at = 0; at < text.size();) {
      const std::size_t nl = std::min(text.find('\n', at), text.size());
      if (nl > at) {
        b.lines.emplace_back(text.substr(at, nl - at));
        r.progress(static_cast<int>(b.lines.size()), 0, b.lines.back());
      }
      at = nl + 1;
    }
  };
  const double haze_wall = perf::run_bench(s, out);
  if (s.haze && has_gpu_backend()) gpu_backend("--haze").bench_haze(s.repeats, haze_wall, out);
  if (gpu) gpu_backend("--models gpu").bench_frames(s.width, s.height, s.repeats, out);
  Result res;
  res.record = bench_result().record(b);
  return res;
}

OperationInfo bench_operation() {
  OperationInfo op{.name = "bench",
                   .summary = "time the batch path against an in-run scalar loop (ratios, medians)",
                   .description =
                       "each model's batch path timed against its scalar loop, with "
                       "the comparisons and workloads its registry entry declares; "
                       "--estimate, --haze",
                   .parameters = perf::BenchSettings::schema().specs(),
                   .result = bench_result().fields(),
                   .result_type = "text: medians and ratios"};
  for (ParameterSpec& s : op.parameters)
    if (s.name == "sh-table") s.file = FileRole::input;
  op.check = [](Request& r) {
    const auto s = r.bind(perf::BenchSettings::schema());
    for (const std::string& m : s.models)
      if (m == "gpu")
        (void)gpu_backend("--models gpu");
      else
        (void)require_model(m, "models");
  };
  op.run = [](const Request& r, const ProgressSink&) { return run_bench(r); };
  return op;
}

// ---- report -------------------------------------------------------------------------------------

struct ReportResult {
  std::optional<std::string> index{}, synthetic_measurements{};
  long long files = 0;
};

const ResultSchema<ReportResult>& report_result() {
  using R = ReportResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("index", "the report's page (open it in a browser)", &R::index)
        .integer("files", "1", "files written into the report's directory", &R::files)
        .text("synthetic_measurements",
              "the synthetic scan written (--write-synthetic-measurements)",
              &R::synthetic_measurements);
    return s;
  }();
  return s;
}

Result run_report(const Request& r, const ProgressSink& progress) {
  Result out;
  ReportResult rr;
  if (r.output_wanted("write-synthetic-measurements")) {
    r.write_text(out, "write-synthetic-measurements",
                 analysis::format_sky_scan(analysis::synthetic_tregenza_scan(),
                                           analysis::synthetic_scan_comments()));
    rr.synthetic_measurements = r.output_path("write-synthetic-measurements");
  } else {
    report::ReportOptions o = r.bind(report::ReportOptions::schema());
    o.output_dir = r.output_path("output");
    o.progress = [&](int done, int total, std::string_view step) {
      if (progress) progress(done, total, step);
    };
    const report::ReportSummary s = report::write_report(o);
    rr.files = static_cast<long long>(s.files.size());
    rr.index = (std::filesystem::path(o.output_dir) / "index.html").string();
    out.notices.push_back(
        fmt::format("wrote {} files to {}", s.files.size(), io::shown_path(o.output_dir)));
  }
  out.record = report_result().record(rr);
  return out;
}

OperationInfo report_operation() {
  ParameterSpec dir = output_file("output",
                                  "the report's directory (created if needed): index.html, "
                                  "report.json, figures");
  dir.file = FileRole::output_directory;
  dir.default_value = Absent{"--write-synthetic-measurements only"};
  OperationInfo op{
      .name = "report",
      .summary = "write the validation and comparison report (HTML, figures, JSON)",
      .description =
          "the validation and comparison report: Zotti et al. 2007's analyses for "
          "every model, a sky-luminance scan, index.html, SVG/PNG figures and "
          "report.json (docs/REPORT.md)",
      .parameters =
          concat({{dir},
                  report::ReportOptions::schema().specs(),
                  {output_file("write-synthetic-measurements",
                               "only write the synthetic example scan (CIE type 7 at the 145 "
                               "Tregenza patches, 5 % noise, fixed seed) to this CSV file",
                               {}, "the report")}}),
      .relations = {needs("sun-azimuth", "sun-elevation", "the scan's sun: both or neither"),
                    needs("sun-elevation", "sun-azimuth", "the scan's sun: both or neither")},
      .result = report_result().fields(),
      .result_type = "report::ReportSummary"};
  for (ParameterSpec& s : op.parameters)
    if (s.name == "measurements" || s.name == "epw") s.file = FileRole::input;
  for (const ParameterSpec& s : op.parameters)
    if (s.name != "write-synthetic-measurements")
      op.relations.push_back(
          excludes("write-synthetic-measurements", s.name, "it takes no other report parameter"));
  op.check = [](Request& r) {
    if (!r.output_wanted("output") && !r.output_wanted("write-synthetic-measurements"))
      throw InvalidArgument(fmt::format("report needs {} DIR (or {} FILE)", spelled("output"),
                                        spelled("write-synthetic-measurements")));
    (void)r.bind(report::ReportOptions::schema());
    check_input_folder(r, "kider");
  };
  op.run = run_report;
  return op;
}

}  // namespace

std::vector<OperationInfo> report_operations() {
  return {bench_operation(), report_operation()};
}

}  // namespace skylight::operations::detail
