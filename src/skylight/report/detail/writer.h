// Internal to the report (report/*.cpp): its configuration, helpers and the writer class whose
// sections live in section_*.cpp. Not installed.
#pragma once

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/analysis/comparison.h"
#include "skylight/analysis/illumination.h"
#include "skylight/analysis/scan.h"
#include "skylight/daylight/sky_matrix.h"
#include "skylight/fit/measured_fit.h"
#include "skylight/io/epw.h"
#include "skylight/io/file.h"
#include "skylight/io/image.h"
#include "skylight/render/false_colour.h"
#include "skylight/render/sky_render.h"
#include "skylight/report/report.h"
#include "skylight/report/svg_plot.h"
#include "skylight/version.h"

namespace skylight::report::detail {

namespace fs = std::filesystem;
// The report arranges the numbers of analysis/ into files (io/) with figures (render/).
using namespace analysis;
using namespace io;
using namespace render;
using Json = nlohmann::ordered_json;

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

// Colour of the validity classes (valid, extrapolated, unphysical, undefined).
inline constexpr std::array<std::string_view, 4> kValidityColours = {"#4caf50", "#ffc107",
                                                                     "#e53935", "#9e9e9e"};
inline constexpr std::array<std::uint8_t, 3> kMaskColour = {255, 255,
                                                            255};  // outside the hemisphere
inline constexpr std::array<std::uint8_t, 3> kInvalidColour = {40, 40, 40};    // zero / negative
inline constexpr std::array<std::uint8_t, 3> kNegativeYzColour = {230, 0, 0};  // Yz < 0 in Fig. 1
// Colour scales (log10 decades) of the maps.
inline constexpr double kRelativeLog10Min = 0.0, kRelativeLog10Max = 4.0;  // % of zenith luminance
inline constexpr double kAbsoluteLog10Min = 2.0, kAbsoluteLog10Max = 6.0;  // cd/m^2
// Model colours in line plots.
inline constexpr std::string_view kCie16Colour = "#9467bd";
// Within this distance of an integer, a log10 value is taken as that integer: the float batch
// path (relative error ~1e-7, i.e. ~4e-8 in log10) must not flip a value that is exactly on a
// decade (the uniform sky, type 5, at 100 %) between the two hues of the false-colour scale.
inline constexpr double kDecadeSnap = 1e-6;

// A band of sun elevations of "Which model to trust where" (section_trust.cpp).
struct TrustBand {
  std::string name;  // "low sun"
  double elevation_lo_deg, elevation_hi_deg;
  std::vector<double> sun_elevations_deg;  // where it is sampled
};

// The verdicts of "Which model to trust where" and their rule: a model's best RMS of log10 ratios
// against a CIE class, as a fraction of the median RMS between neighbouring CIE types of the class
// in the same band: at most kTrustUseFraction (closer to a standard sky than halfway to the next
// one) is "use", at most kTrustCareFraction (no further than the next standard sky) "use with
// care", beyond "avoid".
enum class TrustVerdict { use, care, avoid, reference, not_judged };
inline constexpr double kTrustUseFraction = 0.5, kTrustCareFraction = 1.0;
TrustVerdict trust_verdict(double best_rms, double neighbour_rms);
// Colour against the physical atmosphere: the mean CIE 1976 chromaticity distance du'v' up to
// kColourUseDuv (about the size of MacAdam's just-noticeable ellipses in u'v') is "use", up to
// kColourCareDuv "use with care", beyond "avoid".
inline constexpr double kColourUseDuv = 0.005, kColourCareDuv = 0.02;
TrustVerdict colour_verdict(double mean_duv);
std::string trust_verdict_name(TrustVerdict v);
// Against the measured skies (section_measured.cpp): the absolute level by the median scale
// (measured / model) within a factor kAbsoluteUseFactor either way "use", kAbsoluteCareFactor "use
// with care" (chosen: the multiple-scattering atmospheres from the solar spectrum meet the scans
// within 11-13 %, docs/MEASURED.md); the spectrum by the median relative spectral RMS, 380-780 nm
// (chosen: twice the best luminance shape error, 5 %, and twice that); a model without spectra is
// not judged on it.
inline constexpr double kAbsoluteUseFactor = 1.25, kAbsoluteCareFactor = 2.0;
inline constexpr double kSpectrumUseRms = 0.10, kSpectrumCareRms = 0.20;
TrustVerdict absolute_verdict(double scale);
TrustVerdict spectrum_verdict(double spectral_rms);
// A verdict's cell: the word in its colour, the detail below.
std::string verdict_html(TrustVerdict v, std::string_view detail);

// Everything that the quick (test) report reduces.
struct Config {
  int yz_width, yz_height;
  double root_step_deg;
  int tile_px, tile_gap;
  std::vector<double> map_sun_zeniths_deg;
  std::vector<double> map_preetham_t, map_hosek_t;
  ComparisonSettings comparison;
  std::vector<double> match_turbidities;
  double fit_t_min, fit_t_max, fit_t_step;
  std::vector<double> antisolar_sun_zeniths_deg, antisolar_elevations_deg;
  double antisolar_headline_sun_zenith_deg, antisolar_headline_elevation_deg;
  double vertical_step_deg;
  std::vector<std::array<double, 2>> vertical_cases;  // (T, theta_s deg); T < 0: best T for CIE 12
  std::vector<double> illum_elevations_deg;
  IlluminationSettings illum;
  double scan_t_step;
  double validity_step_deg;
  int validity_preetham_rows;
  double validity_hosek_step;
  std::vector<double> validity_nishita_deg;
  // Zotti's findings (section_findings.cpp).
  std::vector<double> fit_per_sun_zeniths_deg;  // best T for CIE 12 at each sun position
  std::vector<double> zone_sun_zeniths_deg;     // antisolar half, low sun
  std::vector<double> pair_sun_zeniths_deg;     // Zotti's pairs: 15 < theta_s < 70
  std::vector<double> low_sun_zeniths_deg;      // circumsolar ring and horizon band
  int zone_n_theta, zone_n_phi;                 // hemisphere_grid for the regions
  std::vector<double> fig1_linear_t;            // T range of the linear Fig. 1 view
  // Which model to trust where (section_trust.cpp).
  std::vector<TrustBand> trust_bands;
  int trust_n_theta, trust_n_phi;                 // hemisphere_grid of the comparisons
  int trust_axis_samples;                         // values of a continuous report axis
  std::vector<double> trust_map_sun_zeniths_deg;  // columns of the measured validity maps
  TrustBand twilight_band;                        // the sun below the horizon
  int colour_n_theta, colour_n_phi;               // grid of the colour comparison
  // Daylight from weather data (section_daylight.cpp): every weather_stride-th hour with the sun
  // up, each sky integrated on a weather_n_theta x weather_n_phi hemisphere grid.
  int weather_stride, weather_n_theta, weather_n_phi;
  // Against measured skies (section_measured.cpp): models whose ModelInfo::costly_setup is set
  // (a table per parameter set) are compared on measured_costly_captures captures (the middle,
  // then the first and the last), or not at all (0, the quick report). The full report takes 1:
  // each capture costs bruneton a table (12 s of CPU); `skylight measured` compares them all.
  int measured_costly_captures;
  // Light on planes (section_planes.cpp): the weather records of the series (FIRST-LAST, when the
  // file has that many; empty: the year), and whether models with costly_setup take part.
  std::string planes_hours;
  bool planes_costly;
};
Config make_config(bool quick);

std::string g3(double v);  // 3 significant digits, "n/a" if not finite
// Text for HTML: &, < and > as entities.
std::string esc_html(std::string_view s);
std::string f2(double v);  // 2 decimals, "n/a" if not finite
// JSON numbers must be finite: non-finite values become null.
Json num(double v);
double finite_or(double v, double fallback);
// log10, snapped to the nearest integer within kDecadeSnap (see report.cpp).
double snapped_log10(double v);
// The y axis of a validity map with a single row (the model has no second parameter).
svg::Axis one_row_axis();
std::string validity_name(Validity v);
// Degrees as the page lists them: "15, 45, 75" ({:g}, comma-separated).
std::string degrees_list(const std::vector<double>& deg);
// The sun zenith angles of comparison settings [deg].
std::vector<double> sun_zeniths_deg(const ComparisonSettings& c);

// Zotti's Preetham T <-> CIE type pairs (§6 table) and his Y_Pr / Y_CIE for 15 < theta_s < 70:
// the bound `threshold`, or with `about` the centre of "≈ 1" (section_matching's tables and the
// pairs' findings).
struct ZottiPair {
  double t;
  int type;
  const char* ratio;  // as the paper writes it, e.g. "> 2"
  double threshold;
  bool about;
};
inline constexpr std::array<ZottiPair, 3> kZottiPairs = {
    {{10.0, 6, "> 2", 2.0, false}, {5.0, 7, "≈ 1", 1.0, true}, {2.9, 10, "> 1.25", 1.25, false}}};
// A reading of a pair holds when Zotti's bound holds at every sun position (its min and max over
// them; "≈ 1" within kAboutOneFactor either way).
bool pair_reading_holds(const ZottiPair& pair, const LuminanceRatio& ratio);
// Zotti's "about 2-5 times too high" at one sun position: the geometric mean over the antisolar
// half lies in [2, 5].
bool antisolar_factor_holds(double geomean);

// One table of index.html: a header row, then rows of cells already formatted as text or HTML.
class HtmlTable {
 public:
  // left: the columns whose cells are left-aligned (the style sheet right-aligns all but the
  // first).
  explicit HtmlTable(const std::vector<std::string>& headers, std::vector<bool> left = {});
  // row_attributes: e.g. " class=\"best\"" (with its leading space).
  void row(const std::vector<std::string>& cells, std::string_view row_attributes = "");
  std::string html() const { return text_ + "</table>\n"; }

 private:
  std::string text_;
  std::vector<bool> left_;
};

// A model against the measured skies (section_measured.cpp): its comparisons and their medians.
struct MeasuredModel {
  std::string model;
  std::vector<fit::MeasuredCaptureResult> captures;  // those compared (all, or cfg_'s subset)
  double shape = kNaN, shape_log10 = kNaN, abs = kNaN, scale = kNaN;  // medians
  double spectral = kNaN, duv = kNaN;  // medians (spectral NaN: no spectra)
};

class ReportWriter {
 public:
  ReportWriter(const ReportOptions& o) : opt_(o), cfg_(make_config(o.quick)) {}

  ReportSummary run();

 private:
  void step(std::string_view what) {
    ++done_;
    if (opt_.progress) opt_.progress(done_, kSteps, what);
  }
  void write_text(const std::string& name, std::string_view content) {
    write_text_file(opt_.output_dir / name, content);
    summary_.files.push_back(name);
  }
  void write_png_file(const std::string& name, const Image8& img) {
    write_png(opt_.output_dir / name, img, {{"skylight:version", kVersion}});
    summary_.files.push_back(name);
  }
  // Writes the SVG file and returns the inline <svg> element for the HTML.
  std::string figure(const std::string& name, const svg::Canvas& c, const std::string& caption) {
    write_text(name, c.document());
    return fmt::format(
        "<figure>\n{}<figcaption>{} <a href=\"{}\">[SVG]</a></figcaption>\n</figure>\n", c.svg(),
        caption, name);
  }

  // Which model to trust where: the table, its rule and report.json's
  // which_model_to_trust_where (section_trust.cpp).
  void section_trust();
  std::string trust_band_text() const;  // "low sun 7, 12, mid ..." (the sampled elevations)
  // The values of a model's report axis the trust table and the measured maps sample.
  std::vector<std::optional<double>> trust_axis_values(const ModelInfo& info) const;
  // Section 8's measured maps: the trust rule per (sun zenith, axis value) cell.
  void measured_validity_maps();
  // The trust table's second part: colour and twilight against the physical atmosphere.
  void physical_atmosphere_table();
  // A model's error against its source for each value of its truncation parameter (SH bands).
  std::string truncation_table(const ModelInfo& info);
  void section_zenith();
  void fig1_maps();        // the two PNG maps behind Fig. 1
  void zenith_branches();  // the branch summaries of the boundary Yz = 0 (closing note)
  void section_maps();
  void section_matching();
  // The parts of section_matching's HTML (each also fills its part of report.json).
  std::string matching_tables();
  std::string cie12_fit_html();
  std::string antisolar_horizon_html();
  void section_vertical();
  void vertical_case(int index, double turbidity, double sun_zenith_deg);  // one pair of plots
  void section_illumination();
  void section_measurements();
  // Section 9: each hour's sky from a weather file against the file's illuminance
  // (section_daylight.cpp); load_weather reads the file first (weather_, weather_name_),
  // weather_hours makes its hours' skies (weather_matrix_), both before anything is written.
  void load_weather();
  void weather_hours();
  void section_daylight();
  // Section 10: the weather year's light on a façade and a roof (section_planes.cpp).
  void section_planes();
  // Against measured skies (section_measured.cpp): load_kider reads the captures (kider_) before
  // anything is written; measured_skies fits every model with an estimation policy and a report
  // policy to them (measured_) and writes the section; measured_cell gives the trust table's
  // measured column and verdicts (section_trust.cpp).
  void load_kider();
  void measured_skies();
  const MeasuredModel* measured_model(std::string_view name) const;
  void measured_figures();                    // the chosen capture's plots and the error maps
  void measured_table();                      // the section's table and text (after section_trust)
  std::string kider_opt_text() const;         // report.json's source of the captures
  std::string measured_summary_line() const;  // the summary's line on the measured skies
  void section_validity();
  // A validity map of one model over the sun zenith (columns) and, with rows, the values of its
  // report axis (ReportPolicy::axis): its rows' y axis and the range the cells span.
  struct ValidityMap {
    ModelSpec spec;
    std::string over;  // the title's "over ...", e.g. "(theta_s, T)"
    std::vector<double> rows;
    svg::Axis y;
    double row_lo = 0.0, row_hi = 1.0;
    std::string caption;
  };
  void validity_map(const ValidityMap& map, const std::vector<double>& zen_deg);
  void section_findings();
  // Zotti's findings, one builder each (section_findings.cpp): each appends its records to
  // summary_.findings and, where the page has a table of them, its rows to json_.
  void finding_negative_clear();
  void finding_negative_turbid();
  void finding_best_turbidity();
  void finding_antisolar(const HemisphereGrid& zone_grid);
  void finding_pairs();
  void finding_low_sun(const HemisphereGrid& zone_grid);
  void finding_fig3();
  void finding_cie_classes();
  void finding_pair_shapes();
  void finding_fitted_range();
  void finding_measurements();
  // The summary (generated from summary_.findings) and the findings table.
  std::string findings_summary_html() const;
  std::string findings_table_html() const;
  void write_html_and_json();

  // Renders one family of tiles into a relative and an absolute mosaic (files named after the
  // rows' model). relative_rows (optional): the specs whose L / L(zenith) the relative map shows.
  void mosaic(const std::string& title, const std::string& what, const std::string& row_header,
              const std::vector<ModelSpec>& rows, const std::vector<std::string>& row_labels,
              const std::vector<ModelSpec>& relative_rows = {});
  // The relative and absolute SVG mosaics of the PNGs mosaic() wrote.
  void mosaic_figures(const std::string& title, const std::string& what,
                      const std::string& row_header, const std::string& key,
                      const std::vector<std::string>& row_labels);

  static constexpr int kSteps = 21;  // the step() calls of run()
  const ReportOptions& opt_;
  Config cfg_;
  int done_ = 0;
  ReportSummary summary_;
  Json json_;
  // HTML fragments by section.
  std::string html_trust_, html_zenith_, html_rel_, html_abs_, html_match_, html_vertical_,
      html_illum_, html_scan_, html_validity_, html_validity_measured_, html_findings_,
      html_weather_, html_planes_;
  std::string html_measured_;
  std::vector<io::KiderCapture> kider_;       // the captures (load_kider)
  std::string kider_source_;                  // where they came from, as the page says
  std::vector<MeasuredModel> measured_;       // per fitted model (measured_skies)
  double measured_sun_elevation_deg_ = kNaN;  // the captures' median sun elevation
  // The median step between neighbouring clear CIE types in the trust band of that elevation
  // (section_trust.cpp): the measured shape's yardstick.
  double measured_neighbour_step_ = kNaN;
  std::string html_measured_figures_;
  // Numbers for the closing note.
  double low_branch_max_sun_zenith_ = kNaN, low_branch_t_at_zenith_ = kNaN;
  double high_branch_t_at_horizon_ = kNaN, high_branch_t_at_zenith_ = kNaN;
  std::vector<AntisolarRow> antisolar_;
  std::string scan_best_;
  std::vector<std::string> trust_summary_;  // one line per judged model (section_trust.cpp)
  double trust_min_neighbour_step_ = kNaN;
  Json truncation_json_ = Json::object();  // report.json's which_model_to_trust_where.truncation //
                                           // the smallest CIE neighbour step of any band
  std::map<double, RatioBand> pair_bands_;  // Zotti's pairs by Preetham T (section_matching)
  int scan_best_cie_type_ = 0;              // best CIE type for the scan (0: none)
  io::EpwFile weather_;                     // section 9's weather file (load_weather)
  std::string weather_name_;
  std::shared_ptr<const daylight::SkyMatrix> weather_matrix_;  // its hours' skies
  bool scan_synthetic_ = true;
  double antisolar_relative_ = kNaN;      // the headline ratio of zenith-normalised values
  double antisolar_zenith_ratio_ = kNaN;  // Preetham Yz / CIE 12 Lz at the headline theta_s
};

}  // namespace skylight::report::detail
