// `skylight report`: the validation and comparison report (report/report.h, docs/REPORT.md).
#include <fmt/format.h>

#include <filesystem>
#include <iostream>

#include "common.h"
#include "skylight/analysis/scan.h"
#include "skylight/core/error.h"
#include "skylight/io/file.h"
#include "skylight/operations/operations.h"
#include "skylight/report/report.h"

namespace skylight::cli {
namespace {

struct ReportCommand {
  SchemaFlags flags;
  std::string output, write_synthetic;
};

int run_report(const ReportCommand& f) {
  const ParameterValues given = f.flags.values();
  if (!f.write_synthetic.empty()) {
    if (!f.output.empty() || !given.empty())
      throw InvalidArgument("--write-synthetic-measurements takes no other report flag");
    io::write_text_file(f.write_synthetic,
                        analysis::format_sky_scan(analysis::synthetic_tregenza_scan(),
                                                  analysis::synthetic_scan_comments()));
    announce_after_commit(fmt::format("skylight report: wrote the synthetic scan to {}",
                                      io::shown_path(f.write_synthetic)),
                          true);
    return kExitOk;
  }
  if (f.output.empty()) throw InvalidArgument("report: -o/--output DIR is required");
  if (given.has("sun-azimuth") != given.has("sun-elevation"))
    throw InvalidArgument("--sun-azimuth and --sun-elevation must be given together");
  report::ReportOptions o = f.flags.bind(report::ReportOptions::schema(), {}, "report");
  o.output_dir = f.output;
  Progress progress("report");
  o.progress = [&](int done, int total, std::string_view step) { progress(done, total, step); };
  const report::ReportSummary s = report::write_report(o);
  announce_after_commit(fmt::format("skylight report: wrote {} files to {} in {:.1f} s",
                                    s.files.size(), io::shown_path(f.output), progress.elapsed_s()),
                        true);
  write_stdout(fmt::format("{}\n", (std::filesystem::path(f.output) / "index.html").string()));
  return kExitOk;
}

}  // namespace

void add_report_command(CLI::App& app, Commands& commands) {
  auto f = std::make_shared<ReportCommand>();
  auto* cmd = app.add_subcommand(
      "report",
      "write the validation and comparison report (HTML, figures, JSON)\n"
      "The validation and comparison report: index.html, SVG/PNG figures and report.json "
      "(docs/REPORT.md).");
  cmd->add_option("-o,--output", f->output,
                  "output directory (created if needed): index.html, report.json, figures");
  f->flags.add(*cmd, operations::find("report").parameters);
  cmd->add_option("--write-synthetic-measurements", f->write_synthetic,
                  "only write the synthetic example scan (CIE type 7 at the 145 Tregenza "
                  "patches, 5 % noise, fixed seed) to this CSV file");
  commands.push_back({cmd, [f] { return run_report(*f); }});
}

}  // namespace skylight::cli
