// The report's Fig. 1 (Preetham's zenith luminance) and hemisphere mosaics (Figs. 4-7).
#include <algorithm>
#include <functional>

#include "skylight/core/error.h"
#include "skylight/core/parallel.h"
#include "skylight/models/cie_sky.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/nishita.h"
#include "skylight/models/preetham.h"
#include "skylight/report/detail/writer.h"

namespace skylight::report::detail {

// ---- Fig. 1 ------------------------------------------------------------------------------------

namespace {

constexpr double kTMin = 1.0, kTMax = 64.0;  // the turbidity range `preetham` accepts

// Fig. 1 on the log-T axis: the PNG map behind it and the boundary Yz = 0.
svg::Plot fig1_plot(const std::vector<ZenithRoot>& roots) {
  svg::Plot p;
  p.id = "fig1";
  p.title = "Preetham zenith luminance Yz(θs, T) (Zotti et al. 2007, Fig. 1)";
  p.x = {0, 90, false, "sun zenith angle θs [deg]", {0, 10, 20, 30, 40, 50, 60, 70, 80, 90}};
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
  // The whole-sky band (Zotti's 1.6, finding negative_luminance_clear): between these T the
  // sky is negative somewhere at every sun position (preetham_negative_sky_range).
  const NegativeSkyRange band = preetham_negative_sky_range();
  p.series.push_back(svg::line_series(
      fmt::format("sky < 0 somewhere, every θs: T {}-{}", g3(band.t_low), g3(band.t_high)),
      {0.0, 90.0}, {band.t_low, band.t_low}, "#00bcd4", 1.8, "6 3"));
  p.series.push_back(
      svg::line_series("", {0.0, 90.0}, {band.t_high, band.t_high}, "#00bcd4", 1.8, "6 3"));
  p.swatches = {{"Yz < 0 (negative)", svg::hex_colour(kNegativeYzColour)}};
  return p;
}

// Zotti's view of Fig. 1: T lt0-lt1 on a linear axis, the boundary points inside it.
svg::Plot fig1_linear_plot(const svg::Plot& p, double lt0, double lt1) {
  svg::Plot q = p;
  q.id = "fig1lin";
  q.title =
      fmt::format("Preetham zenith luminance, T {:g}-{:g} linear (as Zotti's Fig. 1)", lt0, lt1);
  q.y = {lt0, lt1, false, "turbidity T", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}};
  q.background_image = "fig1_preetham_zenith_luminance_linear.png";
  for (auto& series : q.series) {
    svg::Series kept = series;
    kept.x.clear();
    kept.y.clear();
    for (std::size_t i = 0; i < series.x.size(); ++i)
      if (series.y[i] >= lt0 && series.y[i] <= lt1) {
        kept.x.push_back(series.x[i]);
        kept.y.push_back(series.y[i]);
      }
    series = kept;
  }
  return q;
}

}  // namespace

void ReportWriter::section_zenith() {
  std::vector<double> zeniths;
  for (double d = 0.0; d <= 90.0 + 1e-9; d += cfg_.root_step_deg) zeniths.push_back(d * kDegree);
  summary_.negative_zenith_boundary = preetham_zenith_roots(zeniths, kTMin, kTMax);
  const auto& roots = summary_.negative_zenith_boundary;
  fig1_maps();
  zenith_branches();
  const double lt0 = cfg_.fig1_linear_t.front(), lt1 = cfg_.fig1_linear_t.back();
  const svg::Plot p = fig1_plot(roots);
  const svg::Plot q = fig1_linear_plot(p, lt0, lt1);
  HtmlTable table({"θs [deg]", "T where Yz = 0", "Yz &lt; 0 for"});
  for (const auto& r : roots) {
    const double d = rad_to_deg(r.sun_zenith);
    if (std::abs(std::remainder(d, 10.0)) > 1e-6 && std::abs(d - 85.0) > 1e-6) continue;
    table.row({fmt::format("{:g}", d), fmt::format("{:.4f}", r.turbidity),
               fmt::format("T {} {:.4f}", r.negative_above ? "&gt;" : "&lt;", r.turbidity)});
  }
  html_zenith_ =
      figure("fig1_preetham_zenith_luminance.svg", svg::draw(p),
             "Preetham's zenith luminance Yz (Preetham 1999 A.2; Zotti eq. 1) over the sun zenith "
             "angle and the turbidity range the model accepts (1-64, log scale; Zotti shows 1-12). "
             "Red: Yz &lt; 0. Dots: the boundary Yz = 0 found by bisection (report.json "
             "<code>preetham_negative_zenith</code>).");
  html_zenith_ +=
      figure(
          "fig1_preetham_zenith_luminance_linear.svg", svg::draw(q),
          fmt::format("The same on Zotti's axes: T {:g}-{:g}, linear. Yz alone is negative "
                      "only in the corners (T &lt; {:.3g} with a high sun, T &gt; {:.3g} with "
                      "the sun at the horizon); the whole sky is negative somewhere for {:.3g} "
                      "&lt; T &lt; {:.4g} at every sun position (summary, first finding).",
                      lt0, lt1, low_branch_t_at_zenith_, high_branch_t_at_horizon_,
                      preetham_negative_sky_range().t_low, preetham_negative_sky_range().t_high)) +
      "<p>Boundary points every 10 deg (and 85 deg); all points at " +
      fmt::format("{:g}", cfg_.root_step_deg) + " deg steps are in report.json.</p>\n" +
      table.html();
  Json pts = Json::array();
  for (const auto& r : roots)
    pts.push_back({{"sun_zenith_deg", rad_to_deg(r.sun_zenith)},
                   {"turbidity", r.turbidity},
                   {"negative_for", r.negative_above ? "turbidity above" : "turbidity below"}});
  json_["preetham_negative_zenith"] = pts;
  json_["preetham_negative_zenith_details"] = {
      {"formula",
       "Yz = 1000 [(4.0453 T - 4.9710) tan chi - 0.2155 T + 2.4192] cd/m^2, chi = "
       "(4/9 - T/120)(pi - 2 θs) (Preetham 1999 A.2)"},
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

void ReportWriter::fig1_maps() {
  // The map: theta_s across, T (log) up; Yz on the absolute false-colour scale, Yz < 0 red.
  const int W = cfg_.yz_width, H = cfg_.yz_height;
  const FalseColourOptions fo{kAbsoluteLog10Min, kAbsoluteLog10Max, "cd/m2", false};
  // Row y (0 at the top) shows turbidity t_of_row(y).
  const auto yz_map = [&](const std::string& name, const std::function<double(int)>& t_of_row) {
    Image8 img(W, H);
    for (int y = 0; y < H; ++y) {
      const double T = t_of_row(y);
      for (int x = 0; x < W; ++x) {
        const double ts = (x + 0.5) / W * (kPi / 2);
        const double yz = preetham_zenith_luminance(T, ts);
        const auto c = yz < 0.0   ? kNegativeYzColour
                       : yz > 0.0 ? false_colour_of(std::log10(yz), fo)
                                  : kInvalidColour;
        std::copy(c.begin(), c.end(), img.pixel(x, y));
      }
    }
    write_png_file(name, img);
  };
  yz_map("fig1_preetham_zenith_luminance.png",
         [&](int y) { return std::pow(10.0, std::log10(kTMax) * (1.0 - (y + 0.5) / H)); });
  const double lt0 = cfg_.fig1_linear_t.front(), lt1 = cfg_.fig1_linear_t.back();
  yz_map("fig1_preetham_zenith_luminance_linear.png",
         [&](int y) { return lt1 - (y + 0.5) / H * (lt1 - lt0); });
}

void ReportWriter::zenith_branches() {
  for (const auto& r : summary_.negative_zenith_boundary) {
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
}

// ---- Figs. 4-7 ---------------------------------------------------------------------------------

void ReportWriter::mosaic(const std::string& title, const std::string& what,
                          const std::string& row_header, const std::vector<ModelSpec>& rows,
                          const std::vector<std::string>& row_labels,
                          const std::vector<ModelSpec>& relative_rows) {
  SKYLIGHT_CHECK(!rows.empty() && row_labels.size() == rows.size() &&
                     (relative_rows.empty() || relative_rows.size() == rows.size()),
                 "rows, one label and (relative maps) one relative spec per row");
  const std::string& key = rows.front().name;  // the files' and plots' names
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
  const std::string rel_png = "relative_" + key + ".png", abs_png = "absolute_" + key + ".png";
  write_png_file(rel_png, rel);
  write_png_file(abs_png, abs);
  mosaic_figures(title, what, row_header, key, row_labels);
}

void ReportWriter::mosaic_figures(const std::string& title, const std::string& what,
                                  const std::string& row_header, const std::string& key,
                                  const std::vector<std::string>& row_labels) {
  std::vector<std::string> col_labels;
  for (double d : cfg_.map_sun_zeniths_deg) col_labels.push_back(fmt::format("{:g}", d));
  for (int which = 0; which < 2; ++which) {
    svg::Mosaic m;
    m.id = (which == 0 ? "rel-" : "abs-") + key;
    m.title = title + (which == 0 ? ": relative luminance" : ": absolute luminance");
    m.image = (which == 0 ? "relative_" : "absolute_") + key + ".png";
    m.rows = static_cast<int>(row_labels.size());
    m.columns = static_cast<int>(col_labels.size());
    m.tile_px = cfg_.tile_px;
    m.gap_px = cfg_.tile_gap;
    m.scale = cfg_.tile_px < 48 ? 2.0 : 0.75;
    m.row_header = row_header;
    m.column_header = "sun zenith angle θs [deg]";
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

namespace {

// The table of the Kittler-Darula zenith luminance band (cie_sky.h) of each CIE type at the sun
// zenith angles [deg]; its numbers also go to `band` (report.json's rows).
std::string zenith_band_table(const std::vector<double>& sun_zeniths_deg, Json& band) {
  std::string t = "<table><tr><th>type</th>";
  for (double d : sun_zeniths_deg) t += fmt::format("<th>θs {:g}</th>", d);
  t += "</tr>\n";
  for (int type = 1; type <= kCieTypeCount; ++type) {
    t += fmt::format("<tr><td>{}</td>", type);
    Json row = Json::array();
    for (double d : sun_zeniths_deg) {
      const ZenithLuminanceBand b =
          kittler_darula_zenith_luminance_band(type, (90.0 - d) * kDegree);
      t += fmt::format("<td>{} [{}, {}]</td>", g3(b.typical), g3(b.low), g3(b.high));
      row.push_back({{"sun_zenith_deg", d},
                     {"typical", num(b.typical)},
                     {"low", num(b.low)},
                     {"high", num(b.high)}});
    }
    t += "</tr>\n";
    band.push_back({{"cie_type", type}, {"zenith_luminance_cd_m2", row}});
  }
  t += "</table>\n";
  return t;
}

}  // namespace

void ReportWriter::section_maps() {
  {
    std::vector<ModelSpec> rows;
    std::vector<std::string> labels;
    for (int t = 1; t <= kCieTypeCount; ++t) {
      rows.push_back(comparison_spec(CieSkyModel::kName, t));
      labels.push_back(t == 16 ? "16 (trad.)" : fmt::format("{}", t));
    }
    // The relative map does not depend on the zenith luminance; an explicit one keeps it
    // defined where the Kittler-Darula value is 0 (overcast types with the sun at the horizon).
    std::vector<ModelSpec> relative = rows;
    for (auto& r : relative) r.params.values.set("zenith-luminance", 1e4);
    mosaic("CIE general sky, types 1-16",
           "CIE standard general sky, types 1-15 and 16 = traditional overcast (Zotti Figs. 4, 5); "
           "absolute: the Kittler-Darula typical zenith luminance (0 for the overcast types 1-6 "
           "with the sun at the horizon, hence the dark tiles)",
           "type", rows, labels, relative);
  }
  {
    // The Kittler-Darula zenith luminance band (cie_sky.h) at the maps' sun positions.
    Json band = Json::array();
    const std::string t = zenith_band_table(cfg_.map_sun_zeniths_deg, band);
    json_["kittler_darula_zenith_luminance_band"] = band;
    html_abs_ += fmt::format(
        "<p>CIE zenith luminance Lz [cd/m2] used above (Kittler-Darula typical) and, in brackets, "
        "the band [low, high] against which Zotti's pairs are also compared: types 7-15 the "
        "Kittler-Darula formula with A = A1 Tv + A2 over Linke turbidity Tv {:g}-{:g}; types 1-6 "
        "and 16 Dv/Ev over the range of the typical values of types 1-15. This band is our "
        "derivation from the published typical parameters (Kittler &amp; Darula's minimum and "
        "maximum values, drawn in Zotti's Fig. 5, are not available to us; docs/REPORT.md). "
        "Kittler &amp; Darula recommend the formula for sun elevations 10-80 deg (θs "
        "10-80 deg); other columns are extrapolated.</p>\n{}",
        kKittlerDarulaBandTvMin, kKittlerDarulaBandTvMax, t);
  }
  step("CIE luminance maps");
  // A model with a turbidity, one row per value.
  const auto turbidity_rows = [&](std::string_view model, const std::vector<double>& turbidities,
                                  const std::string& title, const std::string& what) {
    std::vector<ModelSpec> rows;
    std::vector<std::string> labels;
    for (double T : turbidities) {
      rows.push_back(comparison_spec(model, T));
      labels.push_back(fmt::format("{:.1f}", T));
    }
    mosaic(title, what, "T", rows, labels);
  };
  turbidity_rows(PreethamModel::kName, cfg_.map_preetham_t, "Preetham",
                 "Preetham (Zotti Figs. 6, 7, upper halves)");
  step("Preetham luminance maps");
  turbidity_rows(HosekWilkieModel::kName, cfg_.map_hosek_t, "Hosek-Wilkie",
                 "Hosek-Wilkie (ground albedo 0.3)");
  {
    // The physical atmospheres, one row each: single scattering, then multiple scattering.
    std::vector<ModelSpec> rows;
    std::vector<std::string> labels;
    for (const ModelInfo& info : model_registry())
      if (info.report.physical_atmosphere) {
        rows.push_back(comparison_spec(info.name));
        labels.push_back(info.name);
      }
    mosaic("Physical atmospheres",
           "The physically based atmospheres, each with its Earth defaults (no ground reflection, "
           "ASTM G-173 sun): the single scattering first, then the models that add multiple "
           "scattering and ozone (docs/ATMOSPHERE.md)",
           "model", rows, labels);
  }
  step("Hosek-Wilkie and physical atmospheres' luminance maps");
}

}  // namespace skylight::report::detail
