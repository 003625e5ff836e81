// The validation and comparison report (report.h; methods in docs/REPORT.md).
#include "skylight/report/report.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <system_error>

#include "skylight/analysis/comparison.h"
#include "skylight/analysis/illumination.h"
#include "skylight/analysis/scan.h"
#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/core/parallel.h"
#include "skylight/io/file.h"
#include "skylight/io/image.h"
#include "skylight/models/cie_sky.h"
#include "skylight/models/preetham.h"
#include "skylight/render/false_colour.h"
#include "skylight/render/sky_render.h"
#include "skylight/report/svg_plot.h"
#include "skylight/version.h"

namespace skylight::report {
namespace {

namespace fs = std::filesystem;
// The report arranges the numbers of analysis/ into files (io/) with figures (render/).
using namespace analysis;
using namespace io;
using namespace render;
using Json = nlohmann::ordered_json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

double finite_or(double v, double fallback) {
  return std::isfinite(v) ? v : fallback;
}

}  // namespace
namespace {

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
};

Config make_config(bool quick) {
  Config c;
  c.comparison.sun_exclusion = 5.0 * kDegree;
  c.comparison.sun_azimuth = kPi;
  c.fit_t_min = 1.7;
  c.fit_t_max = 10.0;
  c.antisolar_headline_sun_zenith_deg = 80.0;
  c.antisolar_headline_elevation_deg = 3.0;
  if (!quick) {
    c.yz_width = 540;
    c.yz_height = 320;
    c.root_step_deg = 1.0;
    c.tile_px = 96;
    c.tile_gap = 4;
    c.map_sun_zeniths_deg = {0, 10, 20, 30, 40, 50, 60, 70, 80, 90};
    c.map_preetham_t = {1.7, 1.9, 2.0, 2.2, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0, 15.0};
    c.map_hosek_t = {1.7, 1.9, 2.0, 2.2, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0};
    for (double z : {20, 30, 40, 50, 60, 70}) c.comparison.sun_zeniths.push_back(z * kDegree);
    c.comparison.n_theta = 36;
    c.comparison.n_phi = 144;
    c.match_turbidities = {1.7, 2.0, 2.5, 2.9, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0};
    c.fit_t_step = 0.05;
    c.antisolar_sun_zeniths_deg = {75, 80, 85};
    c.antisolar_elevations_deg = {2, 3, 5};
    c.vertical_step_deg = 0.5;
    c.vertical_cases = {{1.8, 72}, {-1, 72}, {3.0, 45}};
    c.illum_elevations_deg = {2, 5, 10, 15, 20, 30, 40, 50, 60, 70, 80, 90};
    c.scan_t_step = 0.1;
    c.validity_step_deg = 1.0;
    c.validity_preetham_rows = 100;
    c.validity_hosek_step = 0.1;
    c.validity_nishita_deg = {0, 10, 20, 30, 40, 50, 60, 70, 80, 89, 89.9, 90.1, 91, 100, 110};
  } else {
    c.yz_width = 180;
    c.yz_height = 100;
    c.root_step_deg = 10.0;
    c.tile_px = 24;
    c.tile_gap = 2;
    c.map_sun_zeniths_deg = {0, 45, 85};
    c.map_preetham_t = {2.0, 5.0};
    c.map_hosek_t = {2.0, 5.0};
    for (double z : {30, 60}) c.comparison.sun_zeniths.push_back(z * kDegree);
    c.comparison.n_theta = 12;
    c.comparison.n_phi = 48;
    c.match_turbidities = {2.5, 5.0};
    c.fit_t_step = 0.25;
    c.antisolar_sun_zeniths_deg = {80};
    c.antisolar_elevations_deg = {3};
    c.vertical_step_deg = 2.0;
    c.vertical_cases = {{-1, 72}};
    c.illum_elevations_deg = {10, 45};
    c.illum.n_theta = 30;
    c.illum.n_phi = 60;
    c.illum.n_theta_spectral = 8;
    c.illum.n_phi_spectral = 16;
    c.illum.nm_step = 20.0;
    c.scan_t_step = 0.5;
    c.validity_step_deg = 10.0;
    c.validity_preetham_rows = 10;
    c.validity_hosek_step = 1.0;
    c.validity_nishita_deg = {0, 45, 89.9, 90.1, 100};
  }
  return c;
}

std::string g3(double v) {
  if (!std::isfinite(v)) return "n/a";
  return fmt::format("{:.3g}", v);
}
std::string f2(double v) {
  if (!std::isfinite(v)) return "n/a";
  return fmt::format("{:.2f}", v);
}

// JSON numbers must be finite: non-finite values become null.
Json num(double v) {
  return std::isfinite(v) ? Json(v) : Json(nullptr);
}

// Colour of the validity classes (valid, extrapolated, unphysical, undefined).
constexpr std::array<std::string_view, 4> kValidityColours = {"#4caf50", "#ffc107", "#e53935",
                                                              "#9e9e9e"};
constexpr std::array<std::uint8_t, 3> kMaskColour = {255, 255, 255};    // outside the hemisphere
constexpr std::array<std::uint8_t, 3> kInvalidColour = {40, 40, 40};    // zero / negative
constexpr std::array<std::uint8_t, 3> kNegativeYzColour = {230, 0, 0};  // Yz < 0 in Fig. 1
// Colour scales (log10 decades) of the maps.
constexpr double kRelativeLog10Min = 0.0, kRelativeLog10Max = 4.0;  // % of zenith luminance
constexpr double kAbsoluteLog10Min = 2.0, kAbsoluteLog10Max = 6.0;  // cd/m^2

// Model colours in line plots.
constexpr std::string_view kPreethamColour = "#000000";
constexpr std::string_view kCieColour = "#d62728";
constexpr std::string_view kHosekColour = "#1f77b4";
constexpr std::string_view kNishitaColour = "#2ca02c";
constexpr std::string_view kCie16Colour = "#9467bd";

// Within this distance of an integer, a log10 value is taken as that integer: the float batch
// path (relative error ~1e-7, i.e. ~4e-8 in log10) must not flip a value that is exactly on a
// decade (the uniform sky, type 5, at 100 %) between the two hues of the false-colour scale.
constexpr double kDecadeSnap = 1e-6;
double snapped_log10(double v) {
  const double l = std::log10(v), r = std::round(l);
  return std::abs(l - r) < kDecadeSnap ? r : l;
}

// The y axis of a validity map with a single row (the model has no second parameter): no ticks
// (the one requested lies outside the range).
svg::Axis one_row_axis() {
  return {0.0, 1.0, false, "", {-1.0}};
}

std::string validity_name(Validity v) {
  return std::string(to_string(v));
}

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

  bool has_model(std::string_view name) const { return find_model(name) != nullptr; }

  void section_zenith();
  void section_maps();
  void section_matching();
  void section_vertical();
  void section_illumination();
  void section_measurements();
  void section_validity();
  void write_html_and_json();

  // Renders one family of tiles into a relative and an absolute mosaic.
  // relative_rows (optional): the specs whose L / L(zenith) the relative map shows.
  void mosaic(const std::string& key, const std::string& title, const std::string& what,
              const std::string& row_header, const std::vector<ModelSpec>& rows,
              const std::vector<std::string>& row_labels,
              const std::vector<ModelSpec>& relative_rows = {});

  static constexpr int kSteps = 12;
  const ReportOptions& opt_;
  Config cfg_;
  int done_ = 0;
  ReportSummary summary_;
  Json json_;
  // HTML fragments by section.
  std::string html_zenith_, html_rel_, html_abs_, html_match_, html_vertical_, html_illum_,
      html_scan_, html_validity_, html_notes_;
  // Numbers for the closing note.
  double low_branch_max_sun_zenith_ = kNaN, low_branch_t_at_zenith_ = kNaN;
  double high_branch_t_at_horizon_ = kNaN, high_branch_t_at_zenith_ = kNaN;
  std::vector<AntisolarRow> antisolar_;
  std::string scan_best_;
  std::string pairs_note_;                // Zotti's pairs, our numbers
  double antisolar_relative_ = kNaN;      // the headline ratio of zenith-normalised values
  double antisolar_zenith_ratio_ = kNaN;  // Preetham Yz / CIE 12 Lz at the headline theta_s
};

// ---- Fig. 1 ------------------------------------------------------------------------------------

void ReportWriter::section_zenith() {
  constexpr double kTMin = 1.0, kTMax = 64.0;  // the turbidity range `preetham` accepts
  std::vector<double> zeniths;
  for (double d = 0.0; d <= 90.0 + 1e-9; d += cfg_.root_step_deg) zeniths.push_back(d * kDegree);
  summary_.negative_zenith_boundary = preetham_zenith_roots(zeniths, kTMin, kTMax);
  const auto& roots = summary_.negative_zenith_boundary;

  // The map: theta_s across, T (log) up; Yz on the absolute false-colour scale, Yz < 0 red.
  const int W = cfg_.yz_width, H = cfg_.yz_height;
  Image8 img(W, H);
  const FalseColourOptions fo{kAbsoluteLog10Min, kAbsoluteLog10Max, "cd/m2", false};
  for (int y = 0; y < H; ++y) {
    const double T = std::pow(10.0, std::log10(kTMax) * (1.0 - (y + 0.5) / H));
    for (int x = 0; x < W; ++x) {
      const double ts = (x + 0.5) / W * (kPi / 2);
      const double yz = preetham_zenith_luminance(T, ts);
      const auto c = yz < 0.0   ? kNegativeYzColour
                     : yz > 0.0 ? false_colour_of(std::log10(yz), fo)
                                : kInvalidColour;
      std::copy(c.begin(), c.end(), img.pixel(x, y));
    }
  }
  write_png_file("fig1_preetham_zenith_luminance.png", img);

  svg::Plot p;
  p.id = "fig1";
  p.title = "Preetham zenith luminance Yz(theta_s, T) (Zotti et al. 2007, Fig. 1)";
  p.x = {0, 90, false, "sun zenith angle theta_s [deg]", {0, 10, 20, 30, 40, 50, 60, 70, 80, 90}};
  p.y = {kTMin, kTMax, true, "turbidity T", {1, 1.5, 2, 3, 5, 7, 10, 15, 20, 30, 50, 64}};
  p.background_image = "fig1_preetham_zenith_luminance.png";
  p.width = 900;
  p.height = 460;
  p.has_colour_bar = true;
  p.colour_bar = {kAbsoluteLog10Min, kAbsoluteLog10Max, "Yz [cd/m2]", ""};
  p.legend_outside = true;
  svg::Series lo = svg::marker_series("Yz = 0 (T below: Yz < 0)", {}, {}, "#ffffff", 2.2);
  lo.marker_stroke = "#000000";
  svg::Series hi = svg::marker_series("Yz = 0 (T above: Yz < 0)", {}, {}, "#000000", 2.2);
  for (const auto& r : roots) {
    auto& s = r.negative_above ? hi : lo;
    s.x.push_back(rad_to_deg(r.sun_zenith));
    s.y.push_back(r.turbidity);
  }
  p.series = {lo, hi};
  p.swatches = {{"Yz < 0 (negative)", svg::hex_colour(kNegativeYzColour)}};

  // Branch summaries.
  for (const auto& r : roots) {
    if (!r.negative_above) {
      low_branch_max_sun_zenith_ = std::isnan(low_branch_max_sun_zenith_)
                                       ? r.sun_zenith
                                       : std::max(low_branch_max_sun_zenith_, r.sun_zenith);
      if (r.sun_zenith == 0.0) low_branch_t_at_zenith_ = r.turbidity;
    } else {
      if (r.sun_zenith == 0.0) high_branch_t_at_zenith_ = r.turbidity;
      if (std::abs(r.sun_zenith - kPi / 2) < 1e-9) high_branch_t_at_horizon_ = r.turbidity;
    }
  }
  // The low-T branch ends where Yz(T = 1) = 0: refine that sun zenith by bisection.
  double end_lo = 0.0, end_hi = kPi / 2;
  if (preetham_zenith_luminance(1.0, 0.0) < 0.0) {
    while (end_hi - end_lo > 1e-10) {
      const double m = 0.5 * (end_lo + end_hi);
      (preetham_zenith_luminance(1.0, m) < 0.0 ? end_lo : end_hi) = m;
    }
    low_branch_max_sun_zenith_ = 0.5 * (end_lo + end_hi);
  }

  std::string table =
      "<table><tr><th>theta_s [deg]</th><th>T where Yz = 0</th><th>Yz &lt; 0 for</th></tr>\n";
  for (const auto& r : roots) {
    const double d = rad_to_deg(r.sun_zenith);
    if (std::abs(std::remainder(d, 10.0)) > 1e-6 && std::abs(d - 85.0) > 1e-6) continue;
    table += fmt::format("<tr><td>{:g}</td><td>{:.4f}</td><td>T {} {:.4f}</td></tr>\n", d,
                         r.turbidity, r.negative_above ? "&gt;" : "&lt;", r.turbidity);
  }
  table += "</table>\n";
  html_zenith_ =
      figure("fig1_preetham_zenith_luminance.svg", svg::draw(p),
             "Preetham's zenith luminance Yz (Preetham 1999 A.2; Zotti eq. 1) over the sun zenith "
             "angle and the turbidity range the model accepts (1-64, log scale; Zotti shows 1-12). "
             "Red: Yz &lt; 0. Dots: the boundary Yz = 0 found by bisection (report.json "
             "<code>preetham_negative_zenith</code>).") +
      "<p>Boundary points every 10 deg (and 85 deg); all points at " +
      fmt::format("{:g}", cfg_.root_step_deg) + " deg steps are in report.json.</p>\n" + table;

  Json pts = Json::array();
  for (const auto& r : roots)
    pts.push_back({{"sun_zenith_deg", rad_to_deg(r.sun_zenith)},
                   {"turbidity", r.turbidity},
                   {"negative_for", r.negative_above ? "turbidity above" : "turbidity below"}});
  json_["preetham_negative_zenith"] = pts;
  json_["preetham_negative_zenith_details"] = {
      {"formula",
       "Yz = 1000 [(4.0453 T - 4.9710) tan chi - 0.2155 T + 2.4192] cd/m^2, chi = "
       "(4/9 - T/120)(pi - 2 theta_s) (Preetham 1999 A.2)"},
      {"turbidity_range", {kTMin, kTMax}},
      {"sun_zenith_step_deg", cfg_.root_step_deg},
      {"low_turbidity_branch",
       {{"description", "Yz < 0 for T below the boundary, high sun"},
        {"turbidity_at_sun_zenith_0", num(low_branch_t_at_zenith_)},
        {"ends_at_sun_zenith_deg_for_T_1", num(rad_to_deg(low_branch_max_sun_zenith_))}}},
      {"high_turbidity_branch",
       {{"description", "Yz < 0 for T above the boundary"},
        {"turbidity_at_sun_zenith_0", num(high_branch_t_at_zenith_)},
        {"turbidity_at_sun_zenith_90", num(high_branch_t_at_horizon_)}}}};
}

// ---- Figs. 4-7 ---------------------------------------------------------------------------------

void ReportWriter::mosaic(const std::string& key, const std::string& title, const std::string& what,
                          const std::string& row_header, const std::vector<ModelSpec>& rows,
                          const std::vector<std::string>& row_labels,
                          const std::vector<ModelSpec>& relative_rows) {
  SKYLIGHT_CHECK(relative_rows.empty() || relative_rows.size() == rows.size(),
                 "one relative spec per row");
  RenderSettings rs;
  rs.projection = Projection::fisheye;
  rs.width = rs.height = cfg_.tile_px;
  rs.fisheye.lens = FisheyeLens::stereographic;
  rs.fisheye.fov = kPi;
  const PixelDirections dirs = pixel_directions(rs);
  const std::size_t n = dirs.x.size();
  const int tile = cfg_.tile_px, gap = cfg_.tile_gap;
  const int cols = static_cast<int>(cfg_.map_sun_zeniths_deg.size());
  const int nrows = static_cast<int>(rows.size());
  const int W = cols * (tile + gap) - gap, H = nrows * (tile + gap) - gap;
  Image8 rel(W, H), abs(W, H);
  std::fill(rel.data.begin(), rel.data.end(), 255);
  std::fill(abs.data.begin(), abs.data.end(), 255);
  const FalseColourOptions fr{kRelativeLog10Min, kRelativeLog10Max, "%", false};
  const FalseColourOptions fa{kAbsoluteLog10Min, kAbsoluteLog10Max, "cd/m2", false};
  std::vector<float> X(n), Y(n), Z(n), R(n);
  for (int r = 0; r < nrows; ++r) {
    for (int k = 0; k < cols; ++k) {
      // Sun in the west (azimuth 270 deg): on the right of the upward-looking image (Zotti:
      // "with increasing theta_s, the sun sinks towards the right horizon").
      const double ts = cfg_.map_sun_zeniths_deg[k] * kDegree;
      const auto model = make_model(rows[r], ts, 1.5 * kPi);
      tristimulus_parallel(*model, {dirs.x, dirs.y, dirs.z}, {X, Y, Z});
      double yz = model->tristimulus({0, 0, 1}).Y;
      if (!relative_rows.empty()) {
        const auto rm = make_model(relative_rows[r], ts, 1.5 * kPi);
        tristimulus_parallel(*rm, {dirs.x, dirs.y, dirs.z}, {X, R, Z});
        yz = rm->tristimulus({0, 0, 1}).Y;
      } else {
        R = Y;
      }
      for (int py = 0; py < tile; ++py) {
        for (int px = 0; px < tile; ++px) {
          const std::size_t i = static_cast<std::size_t>(py) * tile + px;
          const int ox = k * (tile + gap) + px, oy = r * (tile + gap) + py;
          std::array<std::uint8_t, 3> cr = kMaskColour, ca = kMaskColour;
          if (dirs.valid[i]) {
            const double L = Y[i], Lr = R[i];
            ca = L > 0.0 ? false_colour_of(snapped_log10(L), fa) : kInvalidColour;
            cr = (Lr > 0.0 && yz > 0.0) ? false_colour_of(snapped_log10(100.0 * Lr / yz), fr)
                                        : kInvalidColour;
          }
          std::copy(cr.begin(), cr.end(), rel.pixel(ox, oy));
          std::copy(ca.begin(), ca.end(), abs.pixel(ox, oy));
        }
      }
    }
  }
  std::vector<std::string> col_labels;
  for (double d : cfg_.map_sun_zeniths_deg) col_labels.push_back(fmt::format("{:g}", d));
  const std::string rel_png = "relative_" + key + ".png", abs_png = "absolute_" + key + ".png";
  write_png_file(rel_png, rel);
  write_png_file(abs_png, abs);
  for (int which = 0; which < 2; ++which) {
    svg::Mosaic m;
    m.id = (which == 0 ? "rel-" : "abs-") + key;
    m.title = title + (which == 0 ? ": relative luminance" : ": absolute luminance");
    m.image = which == 0 ? rel_png : abs_png;
    m.rows = nrows;
    m.columns = cols;
    m.tile_px = tile;
    m.gap_px = gap;
    m.scale = cfg_.tile_px < 48 ? 2.0 : 0.75;
    m.row_header = row_header;
    m.column_header = "sun zenith angle theta_s [deg]";
    m.row_labels = row_labels;
    m.column_labels = col_labels;
    m.colour_bar = which == 0
                       ? svg::ColourBar{kRelativeLog10Min, kRelativeLog10Max, "% of zenith", "%"}
                       : svg::ColourBar{kAbsoluteLog10Min, kAbsoluteLog10Max, "cd/m2", ""};
    const std::string caption =
        which == 0 ? fmt::format(
                         "{}: sky luminance in percent of the zenith luminance, each "
                         "circle the upper hemisphere in stereographic projection "
                         "(zenith at the centre, north up, east left, sun in the west, "
                         "i.e. on the right). Dark grey: zero or negative luminance.",
                         what)
                   : fmt::format("{}: absolute sky luminance [cd/m2], same layout.", what);
    (which == 0 ? html_rel_ : html_abs_) +=
        figure((which == 0 ? "relative_" : "absolute_") + key + ".svg", svg::draw(m), caption);
  }
}

void ReportWriter::section_maps() {
  {
    std::vector<ModelSpec> rows;
    std::vector<std::string> labels;
    for (int t = 1; t <= kCieTypeCount; ++t) {
      rows.push_back(cie_spec(t));
      labels.push_back(t == 16 ? "16 (trad.)" : fmt::format("{}", t));
    }
    // The relative map does not depend on the zenith luminance; an explicit one keeps it
    // defined where the Kittler-Darula value is 0 (overcast types with the sun at the horizon).
    std::vector<ModelSpec> relative = rows;
    for (auto& r : relative) r.params.zenith_luminance = 1e4;
    mosaic("cie", "CIE general sky, types 1-16",
           "CIE standard general sky, types 1-15 and 16 = traditional overcast (Zotti Figs. 4, 5); "
           "absolute: the Kittler-Darula typical zenith luminance (0 for the overcast types 1-6 "
           "with the sun at the horizon, hence the dark tiles)",
           "type", rows, labels, relative);
  }
  step("CIE luminance maps");
  {
    std::vector<ModelSpec> rows;
    std::vector<std::string> labels;
    for (double T : cfg_.map_preetham_t) {
      rows.push_back(preetham_spec(T));
      labels.push_back(fmt::format("{:.1f}", T));
    }
    mosaic("preetham", "Preetham", "Preetham (Zotti Figs. 6, 7, upper halves)", "T", rows, labels);
  }
  step("Preetham luminance maps");
  if (has_model("hosek")) {
    std::vector<ModelSpec> rows;
    std::vector<std::string> labels;
    for (double T : cfg_.map_hosek_t) {
      rows.push_back(hosek_spec(T));
      labels.push_back(fmt::format("{:.1f}", T));
    }
    mosaic("hosek", "Hosek-Wilkie", "Hosek-Wilkie (ground albedo 0.3)", "T", rows, labels);
  }
  if (has_model("nishita"))
    mosaic("nishita", "Nishita",
           "Nishita single scattering (Earth defaults, no ground reflection, ASTM G-173 sun)", "",
           {nishita_spec()}, {"Earth"});
  step("Hosek-Wilkie and Nishita luminance maps");
}

// ---- matching tables ---------------------------------------------------------------------------

void ReportWriter::section_matching() {
  const auto& cs = cfg_.comparison;
  summary_.cie_matches = best_cie_type_per_turbidity(cfg_.match_turbidities, cs);
  step("best CIE type per Preetham turbidity");
  summary_.best_turbidity_for_cie12 =
      best_preetham_turbidity_for_cie(12, cfg_.fit_t_min, cfg_.fit_t_max, cfg_.fit_t_step, cs);
  const TurbidityFit& fit = summary_.best_turbidity_for_cie12;
  step("best Preetham turbidity for CIE 12");

  std::string zs;
  for (double z : cs.sun_zeniths)
    zs += (zs.empty() ? "" : ", ") + fmt::format("{:g}", rad_to_deg(z));
  const std::string method = fmt::format(
      "Relative distributions L/L(zenith) of both models on a {}x{} midpoint grid over the "
      "hemisphere (zenith-angle rings x azimuth sectors), directions within {:g} deg of the sun "
      "left out, at sun zenith angles {} deg (sun azimuth 180 deg); RMS of log10(L_Preetham / "
      "L_CIE) weighted by solid angle and pooled over the sun positions.",
      cs.n_theta, cs.n_phi, rad_to_deg(cs.sun_exclusion), zs);

  // Zotti's pairs (T 10 / 5 / 2.9 <-> CIE 6 / 7 / 10).
  const std::map<double, int> zotti = {{10.0, 6}, {5.0, 7}, {2.9, 10}};
  const std::map<int, std::string> zotti_ratio = {{6, "&gt; 2"}, {7, "≈ 1"}, {10, "&gt; 1.25"}};
  std::string t =
      "<table><tr><th>Preetham T</th><th>best CIE type</th><th>RMS log10</th>"
      "<th>2nd best</th><th>RMS log10</th><th>Y_Pr / Y_CIE (best type): mean "
      "[min, max over theta_s]</th><th>Zotti 2007</th></tr>\n";
  Json matches = Json::array();
  const HemisphereGrid grid = hemisphere_grid(cs.n_theta, cs.n_phi);
  std::string pairs_html;
  Json pairs = Json::array();
  for (const auto& m : summary_.cie_matches) {
    std::string z;
    const auto it = zotti.find(m.turbidity);
    if (it != zotti.end()) {
      z = fmt::format("CIE {}, Y_Pr/Y_CIE {}", it->second, zotti_ratio.at(it->second));
      // Our numbers for Zotti's pairing.
      const auto pr = relative_samples(preetham_spec(m.turbidity), cs, grid);
      const auto ci = relative_samples(cie_spec(it->second), cs, grid);
      const LuminanceRatio r = absolute_luminance_ratio(pr, ci, grid);
      int rank = 1;
      for (int k = 0; k < kCieTypeCount; ++k)
        if (m.rms_by_type[k] < m.rms_by_type[it->second - 1]) ++rank;
      pairs_html += fmt::format(
          "<tr><td>{:g}</td><td>{}</td><td>{}</td><td>{} of 16</td><td>{} [{}, "
          "{}]</td><td>{}</td></tr>\n",
          m.turbidity, it->second, f2(m.rms_by_type[it->second - 1]), rank, g3(r.mean), g3(r.min),
          g3(r.max), zotti_ratio.at(it->second));
      pairs_note_ += fmt::format("{}T {:g} ↔ CIE {}: rank {} of 16, Y_Pr/Y_CIE {} (Zotti {})",
                                 pairs_note_.empty() ? "" : "; ", m.turbidity, it->second, rank,
                                 g3(r.mean), zotti_ratio.at(it->second));
      pairs.push_back({{"turbidity", m.turbidity},
                       {"cie_type", it->second},
                       {"rms_log10", num(m.rms_by_type[it->second - 1])},
                       {"rank_of_16", rank},
                       {"luminance_ratio_preetham_over_cie", num(r.mean)},
                       {"luminance_ratio_min", num(r.min)},
                       {"luminance_ratio_max", num(r.max)}});
    }
    t += fmt::format(
        "<tr><td>{:g}</td><td><b>{}</b></td><td>{}</td><td>{}</td><td>{}</td><td>{} [{}, "
        "{}]</td><td>{}</td></tr>\n",
        m.turbidity, m.best_type, f2(m.best_rms), m.second_type, f2(m.second_rms),
        g3(m.ratio_best.mean), g3(m.ratio_best.min), g3(m.ratio_best.max), z);
    Json rms = Json::object();
    for (int k = 0; k < kCieTypeCount; ++k) rms[fmt::format("{}", k + 1)] = num(m.rms_by_type[k]);
    matches.push_back({{"turbidity", m.turbidity},
                       {"cie_type", m.best_type},
                       {"rms_log10", num(m.best_rms)},
                       {"second_cie_type", m.second_type},
                       {"second_rms_log10", num(m.second_rms)},
                       {"luminance_ratio_preetham_over_cie", num(m.ratio_best.mean)},
                       {"luminance_ratio_min", num(m.ratio_best.min)},
                       {"luminance_ratio_max", num(m.ratio_best.max)},
                       {"rms_log10_by_cie_type", rms}});
  }
  t += "</table>\n";
  json_["best_cie_type_per_preetham_turbidity"] = matches;
  json_["zotti_pairs"] = pairs;

  // RMS(T) curve for CIE 12.
  svg::Plot p;
  p.id = "cie12fit";
  p.title = "Preetham vs CIE type 12: RMS of log10 relative luminance over T";
  p.x = {fit.curve_t.front(), fit.curve_t.back(), false, "Preetham turbidity T", {}};
  double ymax = 0.0;
  for (double v : fit.curve_rms)
    if (std::isfinite(v)) ymax = std::max(ymax, v);
  p.y = {
      0.0, std::max(0.05, 1.1 * ymax), false, "RMS log10(L_Pr / L_CIE12) (zenith-normalised)", {}};
  p.series.push_back(
      svg::line_series("RMS(T)", fit.curve_t, fit.curve_rms, std::string(kPreethamColour)));
  p.series.push_back(svg::marker_series(fmt::format("best T = {:.3f}", fit.turbidity),
                                        {fit.turbidity}, {fit.rms}, std::string(kCieColour), 4));
  p.series.push_back(svg::line_series("Zotti: T = 2.3-2.5", {2.3, 2.3, 2.5, 2.5},
                                      {0, p.y.max, p.y.max, 0}, "#888888", 1.0, "4 3"));
  p.width = 640;
  p.height = 360;

  html_match_ =
      "<p>" + method + "</p>\n<h3>Best-matching CIE type for each Preetham turbidity</h3>\n" + t +
      "<p>Y_Pr / Y_CIE: ratio of absolute luminances, Preetham over the CIE type with "
      "the Kittler-Darula typical zenith luminance: per sun position the solid-angle "
      "weighted geometric mean over the same directions, then the geometric mean over "
      "the sun positions (min and max over the sun positions in brackets).</p>\n"
      "<h3>Zotti's pairs</h3>\n<table><tr><th>Preetham T</th><th>CIE type</th><th>RMS "
      "log10</th><th>rank of this type</th><th>Y_Pr / Y_CIE mean [min, "
      "max]</th><th>Zotti: Y_Pr/Y_CIE for 15 &lt; theta_s &lt; 70</th></tr>\n" +
      pairs_html + "</table>\n" + "<h3>Preetham turbidity that best matches CIE 12</h3>\n" +
      fmt::format(
          "<p>Best T = <b>{:.3f}</b> (RMS log10 = {:.3f}), searched over T "
          "{:g}-{:g} on a {:g} grid refined by golden-section search; Zotti "
          "et al. 2007: T ≈ 2.3-2.5.</p>\n",
          fit.turbidity, fit.rms, cfg_.fit_t_min, cfg_.fit_t_max, cfg_.fit_t_step) +
      figure("cie12_fit.svg", svg::draw(p),
             "RMS of the log10 ratio of zenith-normalised luminance, Preetham(T) vs CIE "
             "type 12, over the grid and sun positions above.");
  json_["best_preetham_turbidity_for_cie12"] = fit.turbidity;
  json_["best_preetham_turbidity_for_cie12_details"] = {
      {"rms_log10", num(fit.rms)},
      {"search_range", {cfg_.fit_t_min, cfg_.fit_t_max}},
      {"grid_step", cfg_.fit_t_step},
      {"normalisation", "luminance relative to the zenith (Zotti 2007)"},
      {"sun_zeniths_deg",
       [&] {
         Json a = Json::array();
         for (double z : cs.sun_zeniths) a.push_back(rad_to_deg(z));
         return a;
       }()},
      {"sun_exclusion_deg", rad_to_deg(cs.sun_exclusion)},
      {"grid", fmt::format("{} zenith rings x {} azimuth sectors", cs.n_theta, cs.n_phi)},
      {"zotti_2007", {2.3, 2.5}}};

  // Antisolar horizon.
  const double T = fit.turbidity;
  std::vector<double> tz, el;
  for (double d : cfg_.antisolar_sun_zeniths_deg) tz.push_back(d * kDegree);
  for (double d : cfg_.antisolar_elevations_deg) el.push_back(d * kDegree);
  antisolar_ = antisolar_horizon_ratios(T, tz, el);
  summary_.antisolar_sun_zenith = cfg_.antisolar_headline_sun_zenith_deg * kDegree;
  summary_.antisolar_view_elevation = cfg_.antisolar_headline_elevation_deg * kDegree;
  summary_.antisolar_turbidity = T;
  const auto head = antisolar_horizon_ratios(T, {summary_.antisolar_sun_zenith},
                                             {summary_.antisolar_view_elevation});
  summary_.antisolar_ratio = head.front().ratio;
  antisolar_relative_ = head.front().relative_ratio;
  antisolar_zenith_ratio_ = head.front().ratio / head.front().relative_ratio;
  std::string at =
      "<table><tr><th>theta_s [deg]</th><th>view elevation [deg]</th><th>Preetham "
      "[cd/m2]</th><th>CIE 12 [cd/m2]</th><th>ratio</th><th>ratio of "
      "zenith-normalised values</th></tr>\n";
  Json rows = Json::array();
  for (const auto& r : antisolar_) {
    at += fmt::format(
        "<tr><td>{:g}</td><td>{:g}</td><td>{}</td><td>{}</td><td><b>{}</b></td><td>{}</td></tr>\n",
        rad_to_deg(r.sun_zenith), rad_to_deg(r.view_elevation), g3(r.preetham), g3(r.cie),
        g3(r.ratio), g3(r.relative_ratio));
    rows.push_back({{"sun_zenith_deg", rad_to_deg(r.sun_zenith)},
                    {"view_elevation_deg", rad_to_deg(r.view_elevation)},
                    {"preetham_cd_m2", num(r.preetham)},
                    {"cie12_cd_m2", num(r.cie)},
                    {"ratio", num(r.ratio)},
                    {"ratio_zenith_normalised", num(r.relative_ratio)}});
  }
  at += "</table>\n";
  html_match_ +=
      fmt::format(
          "<h3>Antisolar horizon: Preetham / CIE 12 at low sun</h3>\n<p>Luminance at the azimuth "
          "opposite the sun, near the horizon, Preetham at T = {:.3f} (the best match to CIE 12 "
          "above) over CIE type 12 with the Kittler-Darula typical zenith luminance. Headline "
          "(report.json "
          "<code>antisolar_horizon_ratio_preetham_vs_cie12</code>): theta_s = {:g} deg (sun "
          "elevation "
          "{:g} deg, the lowest the Kittler-Darula formula is recommended for), view elevation "
          "{:g} "
          "deg: <b>{:.3g}</b>. Zotti et al. 2007: 2-5 times too high.</p>\n",
          T, cfg_.antisolar_headline_sun_zenith_deg, 90 - cfg_.antisolar_headline_sun_zenith_deg,
          cfg_.antisolar_headline_elevation_deg, summary_.antisolar_ratio) +
      at;
  json_["antisolar_horizon_ratio_preetham_vs_cie12"] = num(summary_.antisolar_ratio);
  json_["antisolar_horizon_ratio_details"] = {
      {"sun_zenith_deg", cfg_.antisolar_headline_sun_zenith_deg},
      {"view_elevation_deg", cfg_.antisolar_headline_elevation_deg},
      {"view_azimuth", "opposite the sun (180 deg from the solar azimuth)"},
      {"preetham_turbidity", T},
      {"turbidity_source", "best_preetham_turbidity_for_cie12"},
      {"cie_zenith_luminance", "Kittler-Darula typical value for type 12"},
      {"quantity", "ratio of absolute luminances Preetham / CIE 12"},
      {"zotti_2007", "2-5 times too high"},
      {"table", rows}};
}

// ---- Fig. 3 ------------------------------------------------------------------------------------

void ReportWriter::section_vertical() {
  int index = 0;
  for (auto [T, tsd] : cfg_.vertical_cases) {
    if (T < 0) T = summary_.best_turbidity_for_cie12.turbidity;
    ++index;
    const double ts = tsd * kDegree;
    std::vector<ModelSpec> specs = {preetham_spec(T), cie_spec(12)};
    std::vector<std::string> colours = {std::string(kPreethamColour), std::string(kCieColour)};
    if (has_model("hosek") && T <= 10.0) {
      specs.push_back(hosek_spec(T));
      colours.emplace_back(kHosekColour);
    }
    if (has_model("nishita")) {
      specs.push_back(nishita_spec());
      colours.emplace_back(kNishitaColour);
    }
    std::vector<double> xs;
    std::vector<Vec3> dirs;
    const int n = static_cast<int>(std::lround(180.0 / cfg_.vertical_step_deg));
    for (int i = 0; i <= n; ++i) {
      const double x = -90.0 + i * cfg_.vertical_step_deg;
      xs.push_back(x);
      // Positive x: towards the sun (sun azimuth pi); negative: the antisolar side.
      dirs.push_back(direction_from_angles(std::abs(x) * kDegree, x >= 0 ? kPi : 0.0));
    }
    svg::Plot lum, ratio;
    lum.id = fmt::format("vert{}", index);
    ratio.id = fmt::format("vertratio{}", index);
    lum.title = fmt::format("Solar vertical, theta_s = {:g} deg, T = {:.3g}", tsd, T);
    ratio.title = fmt::format("Ratio to CIE type 12, theta_s = {:g} deg, T = {:.3g}", tsd, T);
    std::vector<std::vector<double>> values;
    double lo = kInf, hi = 0.0;
    for (std::size_t m = 0; m < specs.size(); ++m) {
      const auto model = make_model(specs[m], ts, kPi);
      values.push_back(sky_luminance(*model, dirs));
      for (double v : values.back())
        if (v > 0.0) {
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
      std::string label = specs[m].label;
      if (specs[m].name == "cie") label = "CIE type 12 (Kittler-Darula typical Lz)";
      lum.series.push_back(svg::line_series(label, xs, values.back(), colours[m], 1.6));
    }
    lum.x = {-90,
             90,
             false,
             "view zenith angle in the solar vertical [deg] (negative: antisolar side)",
             {-90, -75, -60, -45, -30, -15, 0, 15, 30, 45, 60, 75, 90}};
    lum.y = {std::pow(10.0, std::floor(std::log10(lo))),
             std::pow(10.0, std::ceil(std::log10(hi))),
             true,
             "luminance [cd/m2]",
             {}};
    lum.series.push_back(
        svg::marker_series("sun", {tsd}, {std::sqrt(lum.y.min * lum.y.max)}, "#ff9800", 5));
    ratio.x = lum.x;
    ratio.y = {0.1, 10.0, true, "model / CIE type 12", {0.1, 0.2, 0.5, 1, 2, 5, 10}};
    for (std::size_t m = 0; m < specs.size(); ++m) {
      if (specs[m].name == "cie") continue;
      std::vector<double> r(xs.size(), kNaN);
      for (std::size_t i = 0; i < xs.size(); ++i)
        if (values[1][i] > 0.0 && values[m][i] > 0.0) r[i] = values[m][i] / values[1][i];
      ratio.series.push_back(
          svg::line_series(specs[m].label + " / CIE 12", xs, r, colours[m], 1.6));
    }
    ratio.series.push_back(svg::line_series("2x and 5x", {-90, 90}, {2, 2}, "#888888", 1.0, "4 3"));
    ratio.series.push_back(svg::line_series("", {-90, 90}, {5, 5}, "#888888", 1.0, "4 3"));
    ratio.series.push_back(svg::line_series("", {-90, 90}, {1, 1}, "#444444", 0.8));
    lum.width = ratio.width = 900;
    lum.height = 400;
    ratio.height = 300;
    lum.legend_outside = ratio.legend_outside = true;
    html_vertical_ +=
        figure(fmt::format("solar_vertical_{}.svg", index), svg::draw(lum),
               fmt::format("Sky luminance along the solar vertical (sky only, no solar disc) for "
                           "theta_s = {:g} deg, T = {:.3g} (Zotti Fig. 3: theta_s = 72 deg, T = "
                           "1.8). CIE 12 uses the Kittler-Darula typical zenith luminance (the "
                           "report has no recommended min/max band).",
                           tsd, T)) +
        figure(fmt::format("solar_vertical_{}_ratio.svg", index), svg::draw(ratio),
               "The same, each model divided by CIE type 12 (Zotti: Preetham is 2-5x too "
               "bright on the antisolar side at low sun).");
  }
}

// ---- illuminance / irradiance -----------------------------------------------------------------

void ReportWriter::section_illumination() {
  struct Row {
    ModelSpec spec;
    std::string colour;
    bool spectral;
  };
  std::vector<Row> models = {{preetham_spec(3.0), std::string(kPreethamColour), true},
                             {cie_spec(12), std::string(kCieColour), false},
                             {cie_spec(16), std::string(kCie16Colour), false}};
  models[2].spec.label = "CIE type 16 (traditional overcast)";
  if (has_model("hosek")) models.push_back({hosek_spec(3.0), std::string(kHosekColour), true});
  if (has_model("nishita")) models.push_back({nishita_spec(), std::string(kNishitaColour), true});
  const auto& el = cfg_.illum_elevations_deg;
  svg::Plot lx, wm;
  lx.id = "illum";
  wm.id = "irrad";
  lx.title = "Horizontal illuminance against sun elevation";
  wm.title = fmt::format("Horizontal irradiance {:g}-{:g} nm against sun elevation",
                         cfg_.illum.nm_min, cfg_.illum.nm_max);
  double lx_max = 0.0, wm_max = 0.0;
  std::string table =
      "<table><tr><th>model</th><th>sun elevation [deg]</th><th>diffuse "
      "[lx]</th><th>direct [lx]</th><th>global [lx]</th><th>diffuse "
      "[W/m2]</th><th>direct [W/m2]</th><th>global [W/m2]</th></tr>\n";
  Json out = Json::array();
  for (const auto& m : models) {
    std::vector<double> d, g, dw, gw;
    bool has_sun = false, spectral = false;
    for (double e : el) {
      const auto model = make_model(m.spec, (90.0 - e) * kDegree, kPi);
      const auto h = horizontal_illumination(*model, cfg_.illum, m.spectral);
      has_sun = h.has_sun;
      d.push_back(h.diffuse_lx);
      g.push_back(h.global_lx());
      const double dwv = h.diffuse_w_m2.value_or(kNaN);
      const double gwv = dwv + (h.has_sun ? h.direct_w_m2.value_or(kNaN) : 0.0);
      spectral = spectral || h.diffuse_w_m2.has_value();
      dw.push_back(dwv);
      gw.push_back(gwv);
      lx_max = std::max(lx_max, h.global_lx());
      if (std::isfinite(gwv)) wm_max = std::max(wm_max, gwv);
      table += fmt::format(
          "<tr><td>{}</td><td>{:g}</td><td>{:.0f}</td><td>{}</td><td>{:.0f}</td>"
          "<td>{}</td><td>{}</td><td>{}</td></tr>\n",
          m.spec.label, e, h.diffuse_lx, h.has_sun ? fmt::format("{:.0f}", h.direct_lx) : "no sun",
          h.global_lx(), g3(dwv), h.has_sun ? g3(h.direct_w_m2.value_or(kNaN)) : "no sun", g3(gwv));
      out.push_back({{"model", m.spec.label},
                     {"sun_elevation_deg", e},
                     {"diffuse_lx", num(h.diffuse_lx)},
                     {"direct_lx", h.has_sun ? num(h.direct_lx) : Json(nullptr)},
                     {"global_lx", num(h.global_lx())},
                     {"diffuse_w_m2", num(dwv)},
                     {"direct_w_m2", h.has_sun ? num(h.direct_w_m2.value_or(kNaN)) : Json(nullptr)},
                     {"global_w_m2", num(gwv)}});
    }
    lx.series.push_back(svg::line_series(m.spec.label + " diffuse", el, d, m.colour, 1.6));
    if (has_sun)
      lx.series.push_back(svg::line_series(m.spec.label + " global", el, g, m.colour, 1.6, "6 3"));
    if (spectral) {
      wm.series.push_back(svg::line_series(m.spec.label + " diffuse", el, dw, m.colour, 1.6));
      if (has_sun)
        wm.series.push_back(
            svg::line_series(m.spec.label + " global", el, gw, m.colour, 1.6, "6 3"));
    }
  }
  table += "</table>\n";
  lx.x = wm.x = {0, 90, false, "sun elevation [deg]", {0, 10, 20, 30, 40, 50, 60, 70, 80, 90}};
  lx.y = {0, std::max(1.0, lx_max * 1.05), false, "horizontal illuminance [lx]", {}};
  wm.y = {0, std::max(1.0, wm_max * 1.05), false, "horizontal irradiance [W/m2]", {}};
  lx.width = wm.width = 900;
  lx.height = wm.height = 420;
  lx.legend_outside = wm.legend_outside = true;
  html_illum_ =
      fmt::format(
          "<p>Diffuse: the sky's luminance integrated over the upper hemisphere with weight cos "
          "theta on a {}x{} midpoint grid (lx). Direct: the solar disc integrated over a {}x{} "
          "polar grid with weight max(cos theta, 0), for models with a sun (Preetham, "
          "Hosek-Wilkie); the CIE and Nishita models have no sun here, so their curves are "
          "diffuse only. Irradiance: spectral radiance integrated over {:g}-{:g} nm (trapezoid, "
          "{:g} nm steps; the range every spectral model covers) on a {}x{} grid: a partial "
          "(visible) irradiance, not the broadband solar total. Preetham and Hosek-Wilkie at T "
          "= 3 (Hosek albedo 0.3), CIE with the Kittler-Darula typical zenith luminance.</p>\n",
          cfg_.illum.n_theta, cfg_.illum.n_phi, cfg_.illum.sun_rings, cfg_.illum.sun_sectors,
          cfg_.illum.nm_min, cfg_.illum.nm_max, cfg_.illum.nm_step, cfg_.illum.n_theta_spectral,
          cfg_.illum.n_phi_spectral) +
      figure(
          "illuminance.svg", svg::draw(lx),
          "Horizontal illuminance: diffuse (solid) and global = diffuse + direct sun (dashed).") +
      figure("irradiance.svg", svg::draw(wm),
             fmt::format("Horizontal irradiance {:g}-{:g} nm of the spectral models: diffuse "
                         "(solid) and global (dashed).",
                         cfg_.illum.nm_min, cfg_.illum.nm_max)) +
      table;
  json_["horizontal_illumination"] = {
      {"irradiance_wavelength_range_nm", {cfg_.illum.nm_min, cfg_.illum.nm_max}},
      {"note",
       "CIE and nishita have no solar disc: diffuse only; irradiance only for spectral "
       "models"},
      {"rows", out}};
}

// ---- measurements ------------------------------------------------------------------------------

void ReportWriter::section_measurements() {
  SkyScan scan;
  std::string origin;
  if (opt_.measurements) {
    scan = read_sky_scan(*opt_.measurements);
    origin = fmt::format("the scan <code>{}</code>", svg::escape(opt_.measurements->string()));
  } else {
    scan = parse_sky_scan(data::embedded_file(kSyntheticScanDataPath),
                          std::string("data/") + std::string(kSyntheticScanDataPath));
    origin = fmt::format(
        "the shipped <b>synthetic</b> example <code>data/{}</code> (no public measurement set is "
        "shipped; it is CIE type 7 at the 145 Tregenza patches with ±5 % noise, so CIE 7 "
        "should win)",
        kSyntheticScanDataPath);
  }
  if (opt_.measurement_sun_azimuth) scan.sun_azimuth = *opt_.measurement_sun_azimuth;
  if (opt_.measurement_sun_elevation) scan.sun_elevation = *opt_.measurement_sun_elevation;
  if (!scan.sun_azimuth || !scan.sun_elevation)
    throw InvalidArgument(fmt::format(
        "{}: no sun position: add '# sun_azimuth_deg = A' and '# sun_elevation_deg = E' lines or "
        "pass --sun-azimuth and --sun-elevation",
        scan.source));
  const double ts = kPi / 2 - *scan.sun_elevation, az = *scan.sun_azimuth;
  const double excl = cfg_.comparison.sun_exclusion;

  struct Entry {
    std::string label, colour;
    ScanErrors e;
    std::unique_ptr<SkyModel> model;
  };
  std::vector<Entry> entries;
  auto best_t = [&](const std::string& name, double t0, double t1) {
    double best = t0, best_rms = kInf;
    for (double T = t0; T <= t1 + 1e-9; T += cfg_.scan_t_step) {
      ModelSpec s{name, {}, ""};
      s.params.turbidity = T;
      const auto m = make_model(s, ts, az);
      const double r = compare_to_scan(*m, scan, excl).rms_log10_relative;
      if (r < best_rms) {
        best_rms = r;
        best = T;
      }
    }
    return best;
  };
  for (int t = 1; t <= kCieTypeCount; ++t) {
    auto m = make_model(cie_spec(t), ts, az);
    entries.push_back({cie_spec(t).label, std::string(kCieColour), compare_to_scan(*m, scan, excl),
                       std::move(m)});
  }
  {
    const double T = best_t("preetham", cfg_.fit_t_min, cfg_.fit_t_max);
    auto m = make_model(preetham_spec(T), ts, az);
    entries.push_back({fmt::format("Preetham T = {:.2f} (best)", T), std::string(kPreethamColour),
                       compare_to_scan(*m, scan, excl), std::move(m)});
  }
  if (has_model("hosek")) {
    const double T = best_t("hosek", 1.0, 10.0);
    auto m = make_model(hosek_spec(T), ts, az);
    entries.push_back({fmt::format("Hosek-Wilkie T = {:.2f} (best)", T), std::string(kHosekColour),
                       compare_to_scan(*m, scan, excl), std::move(m)});
  }
  if (has_model("nishita")) {
    auto m = make_model(nishita_spec(), ts, az);
    entries.push_back({nishita_spec().label, std::string(kNishitaColour),
                       compare_to_scan(*m, scan, excl), std::move(m)});
  }
  // The best CIE type by relative RMS goes into the plot with the other families.
  std::size_t best_cie = 0;
  for (std::size_t i = 1; i < static_cast<std::size_t>(kCieTypeCount); ++i)
    if (entries[i].e.rms_log10_relative < entries[best_cie].e.rms_log10_relative) best_cie = i;
  std::size_t best_all = 0;
  for (std::size_t i = 1; i < entries.size(); ++i)
    if (entries[i].e.rms_log10_relative < entries[best_all].e.rms_log10_relative) best_all = i;
  scan_best_ = entries[best_all].label;

  svg::Plot p;
  p.id = "scan";
  p.title = "Measured against modelled luminance";
  double lo = kInf, hi = 0.0;
  for (const auto& s : scan.samples) {
    lo = std::min(lo, s.luminance);
    hi = std::max(hi, s.luminance);
  }
  std::vector<std::size_t> shown = {best_cie};
  for (std::size_t i = kCieTypeCount; i < entries.size(); ++i) shown.push_back(i);
  if (best_cie != 11) shown.insert(shown.begin() + 1, 11);  // CIE 12 for reference
  for (std::size_t i : shown) {
    svg::Series s = svg::marker_series(entries[i].label, {}, {}, entries[i].colour, 2.2);
    if (i == 11 && best_cie != 11) s.colour = "#ff9896";
    const Vec3 sun = entries[i].model->parameters().sun.direction();
    for (const auto& m : scan.samples) {
      const Vec3 v = direction_from_angles(kPi / 2 - m.elevation, m.azimuth);
      if (angle_between(v, sun) < excl) continue;
      const double L = entries[i].model->tristimulus(v).Y;
      if (!(L > 0.0)) continue;
      s.x.push_back(m.luminance);
      s.y.push_back(L);
      lo = std::min(lo, L);
      hi = std::max(hi, L);
    }
    p.series.push_back(s);
  }
  lo = std::pow(10.0, std::floor(std::log10(lo)));
  hi = std::pow(10.0, std::ceil(std::log10(hi)));
  p.series.insert(p.series.begin(),
                  svg::line_series("1:1", {lo, hi}, {lo, hi}, "#888888", 1.0, "4 3"));
  p.x = {lo, hi, true, "measured luminance [cd/m2]", {}};
  p.y = {lo, hi, true, "model luminance [cd/m2]", {}};
  p.width = 900;
  p.height = 480;
  p.legend_outside = true;

  std::string t =
      "<table><tr><th>model</th><th>samples</th><th>RMS log10, absolute</th><th>bias "
      "log10, absolute</th><th>RMS log10, zenith-normalised</th><th>bias log10, "
      "zenith-normalised</th></tr>\n";
  Json rows = Json::array();
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const auto& e = entries[i].e;
    t += fmt::format(
        "<tr{}><td>{}</td><td>{}</td><td>{:.3f}</td><td>{:+.3f}</td><td>{:.3f}</td>"
        "<td>{:+.3f}</td></tr>\n",
        i == best_all ? " class=\"best\"" : "", entries[i].label, e.samples_used,
        e.rms_log10_absolute, e.bias_log10_absolute, e.rms_log10_relative, e.bias_log10_relative);
    rows.push_back({{"model", entries[i].label},
                    {"samples", e.samples_used},
                    {"rms_log10_absolute", num(e.rms_log10_absolute)},
                    {"bias_log10_absolute", num(e.bias_log10_absolute)},
                    {"rms_log10_zenith_normalised", num(e.rms_log10_relative)},
                    {"bias_log10_zenith_normalised", num(e.bias_log10_relative)}});
  }
  t += "</table>\n";
  html_scan_ =
      fmt::format(
          "<p>Compared with {}: {} samples, sun azimuth {:.4g} deg, elevation {:.4g} deg; "
          "samples within {:g} deg of the sun are left out. For each sample d = log10(L_model / "
          "L_measured); RMS = sqrt(mean d^2), bias = mean d (10^bias - 1 is the mean relative "
          "bias). <i>Absolute</i>: each model's own absolute luminance (CIE: Kittler-Darula "
          "typical zenith luminance). <i>Zenith-normalised</i>: the model scaled to the "
          "measurement at the highest sample (the zenith patch of a Tregenza scan). Preetham and "
          "Hosek-Wilkie: the turbidity with the lowest zenith-normalised RMS on a {:g} grid. "
          "Best overall (zenith-normalised): <b>{}</b>.</p>\n",
          origin, scan.samples.size(), rad_to_deg(az), rad_to_deg(*scan.sun_elevation),
          rad_to_deg(excl), cfg_.scan_t_step, entries[best_all].label) +
      figure("measurements.svg", svg::draw(p),
             "Each sample's measured luminance against the models' (best CIE type, CIE 12, and the "
             "best-turbidity Preetham and Hosek-Wilkie skies, Nishita).") +
      t;
  json_["measurements"] = {{"source", scan.source},
                           {"synthetic", !opt_.measurements.has_value()},
                           {"samples", scan.samples.size()},
                           {"sun_azimuth_deg", rad_to_deg(az)},
                           {"sun_elevation_deg", rad_to_deg(*scan.sun_elevation)},
                           {"sun_exclusion_deg", rad_to_deg(excl)},
                           {"best_model_zenith_normalised", entries[best_all].label},
                           {"models", rows}};
}

// ---- validity ----------------------------------------------------------------------------------

void ReportWriter::section_validity() {
  std::vector<double> zen_deg;
  for (double d = 0.0; d <= 110.0 + 1e-9; d += cfg_.validity_step_deg) zen_deg.push_back(d);
  auto to_rad = [](const std::vector<double>& d) {
    std::vector<double> r;
    for (double v : d) r.push_back(v * kDegree);
    return r;
  };
  // Cells span halfway to the neighbouring samples.
  auto edges = [](const std::vector<double>& v, double lo, double hi) {
    std::vector<double> e;
    e.push_back(lo);
    for (std::size_t i = 1; i < v.size(); ++i) e.push_back(0.5 * (v[i - 1] + v[i]));
    e.push_back(hi);
    return e;
  };
  auto draw_map = [&](const std::string& key, const std::string& title, const ModelSpec& spec,
                      const std::vector<double>& cols_deg, const std::vector<double>& rows,
                      const std::function<void(SkyParameters&, double)>& setter,
                      const svg::Axis& yaxis, double row_lo, double row_hi,
                      const std::string& caption) {
    const auto grid = validity_grid(spec, to_rad(cols_deg), rows, setter);
    const auto xe = edges(cols_deg, 0.0, 110.0);
    const auto ye =
        rows.empty() ? std::vector<double>{row_lo, row_hi} : edges(rows, row_lo, row_hi);
    svg::Plot p;
    p.id = "valid-" + key;
    p.title = title;
    p.x = {0,
           110,
           false,
           "sun zenith angle theta_s [deg] (> 90: sun below the horizon)",
           {0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110}};
    p.y = yaxis;
    p.width = 760;
    p.height = rows.empty() ? 200 : 340;
    p.legend_outside = true;
    std::array<int, 4> hist{};
    for (const auto& row : grid)
      for (auto v : row) ++hist[static_cast<int>(v)];
    Json counts = Json::object();
    for (int v = 0; v < 4; ++v) {
      counts[validity_name(static_cast<Validity>(v))] = hist[v];
      if (hist[v] > 0)
        p.swatches.push_back(
            {validity_name(static_cast<Validity>(v)), std::string(kValidityColours[v])});
    }
    // One rectangle per run of equal cells in a row.
    for (std::size_t r = 0; r < grid.size(); ++r) {
      std::size_t k = 0;
      while (k < grid[r].size()) {
        std::size_t e = k;
        while (e + 1 < grid[r].size() && grid[r][e + 1] == grid[r][k]) ++e;
        p.regions.push_back({xe[k], xe[e + 1], ye[r], ye[r + 1],
                             std::string(kValidityColours[static_cast<int>(grid[r][k])])});
        k = e + 1;
      }
    }
    html_validity_ += figure("validity_" + key + ".svg", svg::draw(p), caption);
    json_["validity"][key] = counts;
  };

  {
    // T on a log grid 1-64 (what `preetham` accepts).
    std::vector<double> ts;
    const int n = cfg_.validity_preetham_rows;
    for (int i = 0; i < n; ++i) ts.push_back(std::pow(64.0, (i + 0.5) / n));
    draw_map(
        "preetham", "preetham: domain() over (theta_s, T)", preetham_spec(3), zen_deg, ts,
        [](SkyParameters& p, double v) { p.turbidity = v; },
        {1, 64, true, "turbidity T", {1, 1.5, 2, 3, 5, 7, 10, 15, 20, 30, 50, 64}}, 1.0, 64.0,
        "Preetham: valid for the fitted T 2-6; extrapolated 1.9-2 and 6-10; unphysical "
        "outside 1.9-10 (Zotti) and wherever Yz &lt; 0; undefined with the sun below the "
        "horizon.");
  }
  if (has_model("hosek")) {
    std::vector<double> ts;
    for (double T = 1.0; T <= 10.0 + 1e-9; T += cfg_.validity_hosek_step) ts.push_back(T);
    draw_map(
        "hosek", "hosek: domain() over (theta_s, T)", hosek_spec(3), zen_deg, ts,
        [](SkyParameters& p, double v) { p.turbidity = v; }, {1, 10, false, "turbidity T", {}},
        1.0 - 0.5 * cfg_.validity_hosek_step, 10.0 + 0.5 * cfg_.validity_hosek_step,
        "Hosek-Wilkie (albedo 0.3): T 1-10 (larger values are rejected by the model).");
  }
  {
    std::vector<double> types;
    for (int t = 1; t <= kCieTypeCount; ++t) types.push_back(t);
    draw_map(
        "cie", "cie: domain() over (theta_s, type)", cie_spec(12), zen_deg, types,
        [](SkyParameters& p, double v) { p.cie_type = static_cast<int>(v); },
        {0.5, 16.5, false, "CIE type", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16}},
        0.5, 16.5,
        "CIE general sky with the Kittler-Darula typical zenith luminance (recommended for "
        "sun elevations 10-80 deg).");
  }
  if (has_model("nishita"))
    draw_map("nishita", "nishita: domain() over theta_s (Earth defaults)", nishita_spec(),
             cfg_.validity_nishita_deg, {}, nullptr, one_row_axis(), 0.0, 1.0,
             "Nishita single scattering: domain() depends on the sun zenith only; sampled at the "
             "marked sun zenith angles (each cell spans halfway to its neighbours).");
  {
    ModelSpec perez{"perez", {}, "perez"};
    perez.params.perez_coefficients = std::array<double, 5>{-1.0, -0.32, 10.0, -3.0, 0.45};
    perez.params.zenith_luminance = 5000.0;
    draw_map("perez", "perez: domain() over theta_s (coefficients -1,-0.32,10,-3,0.45)", perez,
             zen_deg, {}, nullptr, one_row_axis(), 0.0, 1.0,
             "Perez with the main job's clear-sky coefficients (A..E = -1, -0.32, 10, -3, 0.45); "
             "its domain depends on the coefficients and the sun zenith only.");
  }
}

// ---- HTML and JSON -----------------------------------------------------------------------------

constexpr std::string_view kStyle = R"css(
body { font-family: "DejaVu Sans", Arial, Helvetica, sans-serif; max-width: 1100px; margin: 2em auto; padding: 0 1em; color: #222; line-height: 1.45; }
h1 { font-size: 1.6em; } h2 { margin-top: 2em; border-bottom: 1px solid #ccc; } h3 { margin-top: 1.4em; }
table { border-collapse: collapse; margin: 0.8em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: right; }
th { background: #f3f3f3; } td:first-child { text-align: left; }
tr.best td { background: #e8f5e9; }
figure { margin: 1.2em 0; } figure svg { max-width: 100%; height: auto; }
figcaption { font-size: 0.9em; color: #444; max-width: 900px; }
code { background: #f5f5f5; padding: 0 0.2em; }
#image-check { font-size: 0.85em; color: #666; }
.note { background: #fffbe6; border: 1px solid #f0e0a0; padding: 0.6em 1em; }
)css";

// Checks that every <img> and every SVG <image> loaded, and writes the result into the page.
constexpr std::string_view kImageCheck = R"js(
<script>
window.addEventListener('load', function () {
  var out = document.getElementById('image-check');
  var imgs = Array.prototype.slice.call(document.images);
  var refs = Array.prototype.slice.call(document.querySelectorAll('svg image'));
  var total = imgs.length + refs.length, ok = 0, pending = refs.length, broken = [];
  // (No ampersand or less-than sign in this script: the page stays well-formed XML.)
  imgs.forEach(function (im) {
    if (!im.complete || im.naturalWidth === 0) broken.push(im.getAttribute('src'));
    else ok++;
  });
  function done() {
    out.textContent = 'images ok: ' + ok + ' of ' + total +
        (broken.length ? ' (broken: ' + broken.join(', ') + ')' : '');
  }
  if (pending === 0) { done(); return; }
  refs.forEach(function (el) {
    var href = el.getAttribute('href') ||
        el.getAttributeNS('http://www.w3.org/1999/xlink', 'href');
    var probe = new Image();
    probe.onload = function () {
      if (probe.naturalWidth > 0) ok++; else broken.push(href);
      if (--pending === 0) done();
    };
    probe.onerror = function () { broken.push(href); if (--pending === 0) done(); };
    probe.src = href;
  });
});
</script>
)js";

void ReportWriter::write_html_and_json() {
  const auto& fit = summary_.best_turbidity_for_cie12;
  // Closing note: Zotti's findings as numbers.
  std::string type_list;
  for (const auto& m : summary_.cie_matches)
    type_list += (type_list.empty() ? "" : "; ") + fmt::format("T {:g} → CIE {} (Y_Pr/Y_CIE {})",
                                                               m.turbidity, m.best_type,
                                                               g3(m.ratio_best.mean));
  double amin = kInf, amax = 0.0;
  for (const auto& r : antisolar_)
    if (std::isfinite(r.ratio)) {
      amin = std::min(amin, r.ratio);
      amax = std::max(amax, r.ratio);
    }
  html_notes_ = fmt::format(
      "<div class=\"note\">\n<ul>\n"
      "<li><b>Negative zenith luminance (Zotti Fig. 1).</b> Preetham's Yz is negative for T below "
      "{:.3f} with the sun at the zenith, a region that closes at theta_s = {:.2f} deg for T = 1 "
      "(Zotti: 'exceptionally clear air'); and for T above {:.2f} with the sun at the horizon "
      "(theta_s = 90 deg), rising to T = {:.1f} at theta_s = 0 (Zotti: 'fails for T &gt;~ 10' at "
      "sunrise/sunset). The boundary is listed in report.json.</li>\n"
      "<li><b>Antisolar horizon at low sun.</b> At theta_s = {:g} deg, {:g} deg above the "
      "horizon opposite the sun, Preetham (T = {:.2f}) is <b>{:.2f}</b> times CIE 12 "
      "(Kittler-Darula typical); over theta_s {} deg and elevations {} deg the factor is "
      "{:.2f}-{:.2f}. Zotti: 'about 2-5 times too high'. The excess is in the absolute level: "
      "Preetham's zenith luminance is {:.2f} times the Kittler-Darula value there, and relative "
      "to its own zenith Preetham's antisolar horizon is {:.2f} times CIE 12's.</li>\n"
      "<li><b>Best Preetham turbidity for CIE 12.</b> T = <b>{:.2f}</b> (RMS log10 {:.3f}, "
      "zenith-normalised, theta_s {} deg). Zotti: T ≈ 2.3-2.5.</li>\n"
      "<li><b>Best CIE type per Preetham turbidity.</b> {}. Zotti's pairs (T 10 / 5 / 2.9 ↔ "
      "CIE 6 / 7 / 10) here: {}.</li>\n"
      "<li><b>Measurements.</b> Best model for the scan (zenith-normalised RMS): {}.</li>\n"
      "</ul>\n</div>\n",
      low_branch_t_at_zenith_, rad_to_deg(low_branch_max_sun_zenith_), high_branch_t_at_horizon_,
      high_branch_t_at_zenith_, cfg_.antisolar_headline_sun_zenith_deg,
      cfg_.antisolar_headline_elevation_deg, summary_.antisolar_turbidity, summary_.antisolar_ratio,
      [&] {
        std::string s;
        for (double d : cfg_.antisolar_sun_zeniths_deg)
          s += (s.empty() ? "" : ", ") + fmt::format("{:g}", d);
        return s;
      }(),
      [&] {
        std::string s;
        for (double d : cfg_.antisolar_elevations_deg)
          s += (s.empty() ? "" : ", ") + fmt::format("{:g}", d);
        return s;
      }(),
      finite_or(amin, kNaN), finite_or(amax, kNaN), antisolar_zenith_ratio_, antisolar_relative_,
      fit.turbidity, fit.rms,
      [&] {
        std::string s;
        for (double z : cfg_.comparison.sun_zeniths)
          s += (s.empty() ? "" : ", ") + fmt::format("{:g}", rad_to_deg(z));
        return s;
      }(),
      type_list, pairs_note_, scan_best_);

  std::string models;
  for (const auto& m : model_registry()) models += (models.empty() ? "" : ", ") + m.name;
  std::string html = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n"
      "<title>skylight validation report</title>\n<style>{}</style>\n</head>\n<body>\n"
      "<h1>skylight validation report: which sky model to trust where</h1>\n"
      "<p>skylight {} · models in the registry: {} · {} report. Reproduces the "
      "analyses of Zotti, Wilkie &amp; Purgathofer 2007, <i>A Critical Review of the Preetham "
      "Skylight Model</i> (WSCG), for every model, and compares them with the CIE standard "
      "general sky and a sky-luminance scan. Headline numbers: <a "
      "href=\"report.json\">report.json</a>; methods: docs/REPORT.md in the repository. Angles "
      "in degrees; theta_s = sun zenith angle, T = turbidity.</p>\n"
      "<p id=\"image-check\">images: not checked (needs JavaScript)</p>\n"
      "<h2>Summary</h2>\n{}"
      "<h2>1. Preetham's zenith luminance</h2>\n{}"
      "<h2>2. Relative luminance maps (Zotti Figs. 4, 6)</h2>\n{}"
      "<h2>3. Absolute luminance maps (Zotti Figs. 5, 7)</h2>\n{}"
      "<h2>4. Preetham against the CIE general sky</h2>\n{}"
      "<h2>5. The solar vertical (Zotti Fig. 3)</h2>\n{}"
      "<h2>6. Horizontal illuminance and irradiance</h2>\n{}"
      "<h2>7. Measurements</h2>\n{}"
      "<h2>8. Where each model is valid</h2>\n<p>Each model's <code>domain().worst()</code> "
      "(valid &lt; extrapolated &lt; unphysical &lt; undefined) over the sun zenith angle and "
      "its main parameter; sun azimuth 180 deg.</p>\n{}"
      "<h2>Closing note: Zotti et al.'s findings, as numbers</h2>\n{}"
      "{}</body>\n</html>\n",
      kStyle, kVersion, models, opt_.quick ? "quick (reduced-resolution)" : "full", html_notes_,
      html_zenith_, html_rel_, html_abs_, html_match_, html_vertical_, html_illum_, html_scan_,
      html_validity_, html_notes_, kImageCheck);
  write_text("index.html", html);

  Json j;
  j["generator"] = fmt::format("skylight {} report", kVersion);
  j["quick"] = opt_.quick;
  j["angles"] = "degrees";
  // The headline numbers first, then the details in the order they were computed.
  for (const char* key :
       {"preetham_negative_zenith", "antisolar_horizon_ratio_preetham_vs_cie12",
        "best_preetham_turbidity_for_cie12", "best_cie_type_per_preetham_turbidity"})
    if (json_.contains(key)) j[key] = json_[key];
  for (auto it = json_.begin(); it != json_.end(); ++it)
    if (!j.contains(it.key())) j[it.key()] = it.value();
  write_text("report.json", j.dump(2) + "\n");
}

ReportSummary ReportWriter::run() {
  if (opt_.output_dir.empty()) throw InvalidArgument("report: output directory is empty");
  if (opt_.measurement_sun_azimuth.has_value() != opt_.measurement_sun_elevation.has_value())
    throw InvalidArgument(
        "report: give both the sun azimuth and elevation of the scan, or neither");
  std::error_code ec;
  fs::create_directories(opt_.output_dir, ec);
  if (ec || !fs::is_directory(opt_.output_dir))
    throw IoError(fmt::format("cannot create directory '{}': {}", opt_.output_dir.string(),
                              ec ? ec.message() : "not a directory"));
  // The measurements first: a bad file fails fast, before any work.
  section_measurements();
  step("measurements");
  section_zenith();
  step("Preetham zenith luminance (Fig. 1)");
  section_maps();
  section_matching();
  step("antisolar horizon ratio");
  section_vertical();
  step("solar vertical (Fig. 3)");
  section_illumination();
  step("illuminance and irradiance");
  section_validity();
  step("validity maps");
  write_html_and_json();
  step("index.html and report.json");
  return summary_;
}

}  // namespace

ReportSummary write_report(const ReportOptions& options) {
  ReportWriter w(options);
  return w.run();
}

}  // namespace skylight::report
