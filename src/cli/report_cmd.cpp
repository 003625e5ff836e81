// `skylight report`: the validation and comparison report (report/report.h, docs/REPORT.md).
#include <fmt/format.h>

#include <filesystem>
#include <iostream>

#include "common.h"
#include "skylight/analysis/scan.h"
#include "skylight/core/error.h"
#include "skylight/io/file.h"
#include "skylight/report/report.h"

namespace skylight::cli {
namespace {

struct ReportFlags {
  std::string output, measurements, write_synthetic;
  std::optional<double> sun_azimuth_deg, sun_elevation_deg;
  bool quick = false;
};

int run_report(const ReportFlags& f) {
  if (!f.write_synthetic.empty()) {
    if (!f.output.empty() || !f.measurements.empty() || f.sun_azimuth_deg || f.sun_elevation_deg ||
        f.quick)
      throw InvalidArgument("--write-synthetic-measurements takes no other report flag");
    io::write_text_file(f.write_synthetic,
                        analysis::format_sky_scan(analysis::synthetic_tregenza_scan(),
                                                  analysis::synthetic_scan_comments()));
    std::cerr << fmt::format("skylight report: wrote the synthetic scan to {}\n",
                             f.write_synthetic);
    return kExitOk;
  }
  if (f.output.empty()) throw InvalidArgument("report: -o/--output DIR is required");
  if (f.sun_azimuth_deg.has_value() != f.sun_elevation_deg.has_value())
    throw InvalidArgument("--sun-azimuth and --sun-elevation must be given together");
  report::ReportOptions o;
  o.output_dir = f.output;
  if (!f.measurements.empty()) o.measurements = f.measurements;
  if (f.sun_azimuth_deg) o.measurement_sun_azimuth = wrap_azimuth(deg_to_rad(*f.sun_azimuth_deg));
  if (f.sun_elevation_deg) o.measurement_sun_elevation = deg_to_rad(*f.sun_elevation_deg);
  o.quick = f.quick;
  Progress progress("report");
  o.progress = [&](int done, int total, std::string_view step) { progress(done, total, step); };
  const report::ReportSummary s = report::write_report(o);
  std::cerr << fmt::format("skylight report: wrote {} files to {} in {:.1f} s\n", s.files.size(),
                           f.output, progress.elapsed_s());
  write_stdout(fmt::format("{}\n", (std::filesystem::path(f.output) / "index.html").string()));
  return kExitOk;
}

}  // namespace

void add_report_command(CLI::App& app, Commands& commands) {
  auto f = std::make_shared<ReportFlags>();
  auto* cmd = app.add_subcommand(
      "report", "write the validation and comparison report (HTML + SVG/PNG + report.json)");
  cmd->add_option("-o,--output", f->output,
                  "output directory (created if needed): index.html, report.json, figures");
  cmd->add_option("--measurements", f->measurements,
                  "sky-luminance scan CSV (azimuth_deg,elevation_deg,luminance_cd_m2); default: "
                  "the shipped synthetic example");
  add_number(
      *cmd,
      {"sun-azimuth", "deg", ParameterKind::number, -360.0, 360.0, 1,
       Absent{"the file's '# sun_azimuth_deg'"}, "sun azimuth of the scan from north towards east"},
      f->sun_azimuth_deg);
  add_number(*cmd,
             {"sun-elevation", "deg", ParameterKind::number, 0.0, 90.0, 1,
              Absent{"the file's '# sun_elevation_deg'"}, "sun elevation of the scan"},
             f->sun_elevation_deg);
  cmd->add_flag("--quick", f->quick,
                "reduced resolution and fewer sun positions (seconds; for tests)");
  cmd->add_option("--write-synthetic-measurements", f->write_synthetic,
                  "only write the synthetic example scan (CIE type 7 at the 145 Tregenza "
                  "patches, 5 % noise, fixed seed) to this CSV file");
  commands.push_back({cmd, [f] { return run_report(*f); }});
}

}  // namespace skylight::cli
