// The validation and comparison report (`skylight report`): which sky model to trust where.
// Reproduces the analyses of Zotti, Wilkie & Purgathofer 2007 ("A Critical Review of the Preetham
// Skylight Model", WSCG) for the models of the registry, and writes a self-contained HTML page with
// SVG/PNG figures and a report.json of the headline numbers. Methods: docs/REPORT.md.
//
// Every analysis is a library function in analysis/ returning numbers (tested there); write_report
// only arranges them into files. Angles are radians here; the files use degrees.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/analysis/comparison.h"
#include "skylight/core/parameters.h"

namespace skylight::report {

using analysis::CieTypeMatch;
using analysis::TurbidityFit;
using analysis::ZenithRoot;

// ---- the report --------------------------------------------------------------------------------

struct ReportOptions {
  std::filesystem::path output_dir;
  // A sky-luminance scan (analysis/scan.h); nullopt: the shipped synthetic example.
  std::optional<std::filesystem::path> measurements;
  // Override the scan's sun position (both or neither), [rad].
  std::optional<double> measurement_sun_azimuth, measurement_sun_elevation;
  // An EnergyPlus weather file for the daylight section; nullopt: the shipped synthetic year.
  std::optional<std::filesystem::path> epw;
  // Kider et al. 2014's captures for "Against measured skies" (a folder as io::read_kider takes);
  // nullopt: the shipped subset (docs/MEASURED.md).
  std::optional<std::filesystem::path> kider;
  // Reduced resolution and fewer sun positions: for tests (a few seconds instead of ~20 s).
  bool quick = false;
  // Progress: step `done` of `total` finished (called on the calling thread).
  std::function<void(int done, int total, std::string_view step)> progress;

  // --measurements, --sun-azimuth, --sun-elevation (degrees; both or neither), --epw, --kider,
  // --quick.
  static const ParameterSchema<ReportOptions>& schema();
};

// One finding of Zotti et al. 2007 set against our numbers (report.json `zotti_findings`; the
// summary of index.html is generated from these records).
struct FindingValue {
  std::string name;  // what the number is, with its conditions
  double value = 0.0;
};
// How our numbers stand to a finding: all of its readings reproduced, some of them, none, or
// a statement that is a declaration rather than something a number can test.
enum class Agreement { agrees, partly, disagrees, not_tested };
// "agrees", "partly", "disagrees", "not tested" (report.json's `agreement`).
std::string agreement_name(Agreement a);
// From the readings that hold and those tested: all -> agrees, some -> partly, none -> disagrees.
Agreement agreement_of(int holding, int tested);

struct Finding {
  std::string id;                // stable key, e.g. "negative_luminance_clear"
  std::string title;             // short heading
  std::string paper_statement;   // what Zotti et al. say (quoted or paraphrased, with the place)
  std::string paper_value_text;  // the paper's number(s) as text, e.g. "T < 1.6"
  std::vector<FindingValue> our_values;
  Agreement agreement = Agreement::disagrees;  // whether our numbers reproduce the statement
  std::string cause;  // why (dis)agreement, generated from our_values where it cites numbers
  bool agrees() const { return agreement == Agreement::agrees; }
};
// How a finding's number is written in index.html (3 significant digits; "n/a" if not finite).
std::string format_finding_value(double v);

// The headline numbers (also in report.json).
struct ReportSummary {
  std::vector<Finding> findings;  // Zotti's findings, paper against ours
  std::vector<ZenithRoot> negative_zenith_boundary;
  double antisolar_ratio = 0.0;  // Preetham / CIE 12 at the conditions below
  double antisolar_sun_zenith = 0.0, antisolar_view_elevation = 0.0, antisolar_turbidity = 0.0;
  TurbidityFit best_turbidity_for_cie12;
  std::vector<CieTypeMatch> cie_matches;
  std::vector<std::string> files;  // written, relative to output_dir
};

// Writes DIR/index.html, DIR/report.json and the figures (DIR/*.svg, DIR/*.png), each atomically
// (temporary file + rename); creates DIR if needed. Throws InvalidArgument for bad options or a bad
// measurement file, IoError when a file cannot be read or written.
ReportSummary write_report(const ReportOptions& options);

}  // namespace skylight::report
