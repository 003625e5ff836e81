// The report's illuminance/irradiance, measurement-scan and validity-map sections.
#include <algorithm>
#include <numeric>

#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/core/parallel.h"
#include "skylight/core/parameters.h"
#include "skylight/models/cie_sky.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/nishita.h"
#include "skylight/models/perez.h"
#include "skylight/models/preetham.h"
#include "skylight/report/detail/writer.h"

namespace skylight::report::detail {

// ---- illuminance / irradiance -----------------------------------------------------------------

namespace {

// One model of the illumination section, with its colour and whether it is spectral.
struct IlluminationModel {
  ModelSpec spec;
  std::string colour;
  bool spectral;
};
// Spectral: the irradiance comes from the model's spectral radiance (its registry entry).
IlluminationModel illumination_model(ModelSpec spec) {
  const std::string colour = comparison_colour(spec.name);
  const bool spectral = find_model(spec.name)->spectral;
  return {std::move(spec), colour, spectral};
}

// The section's two plots, its table and report.json's rows, filled one model at a time.
struct IlluminationFigures {
  svg::Plot lx, wm;
  double lx_max = 0.0, wm_max = 0.0;
  HtmlTable table{{"model", "sun elevation [deg]", "diffuse [lx]", "direct [lx]", "global [lx]",
                   "diffuse [W/m2]", "direct [W/m2]", "global [W/m2]"}};
  Json rows = Json::array();

  void add(const IlluminationModel& m, const std::vector<double>& el,
           const IlluminationSettings& settings) {
    std::vector<double> d, g, dw, gw;
    bool has_sun = false, spectral = false;
    for (double e : el) {
      const auto model = make_model(m.spec, (90.0 - e) * kDegree, kPi);
      const auto h = horizontal_illumination(*model, settings, m.spectral);
      has_sun = h.has_sun;
      d.push_back(h.diffuse_lx);
      g.push_back(h.global_lx());
      const double dwv = h.diffuse_w_m2.value_or(kNaN);
      const double direct_w = h.direct_w_m2.value_or(kNaN);
      const double gwv = dwv + (h.has_sun ? direct_w : 0.0);
      spectral = spectral || h.diffuse_w_m2.has_value();
      dw.push_back(dwv);
      gw.push_back(gwv);
      lx_max = std::max(lx_max, h.global_lx());
      if (std::isfinite(gwv)) wm_max = std::max(wm_max, gwv);
      // A model without a direct sun has no direct and no global value: "n/a", null.
      table.row({m.spec.label, fmt::format("{:g}", e), fmt::format("{:.0f}", h.diffuse_lx),
                 h.has_sun ? fmt::format("{:.0f}", h.direct_lx) : "n/a",
                 h.has_sun ? fmt::format("{:.0f}", h.global_lx()) : "n/a", g3(dwv),
                 h.has_sun ? g3(direct_w) : "n/a", h.has_sun ? g3(gwv) : "n/a"});
      rows.push_back({{"model", m.spec.label},
                      {"sun_elevation_deg", e},
                      {"diffuse_lx", num(h.diffuse_lx)},
                      {"direct_lx", h.has_sun ? num(h.direct_lx) : Json(nullptr)},
                      {"global_lx", h.has_sun ? num(h.global_lx()) : Json(nullptr)},
                      {"diffuse_w_m2", num(dwv)},
                      {"direct_w_m2", h.has_sun ? num(direct_w) : Json(nullptr)},
                      {"global_w_m2", h.has_sun ? num(gwv) : Json(nullptr)}});
    }
    lx.series.push_back(svg::line_series(m.spec.label + " diffuse", el, d, m.colour, 1.6));
    if (has_sun)
      lx.series.push_back(svg::line_series(m.spec.label + " global", el, g, m.colour, 1.6, "6 3"));
    if (!spectral) return;
    wm.series.push_back(svg::line_series(m.spec.label + " diffuse", el, dw, m.colour, 1.6));
    if (has_sun)
      wm.series.push_back(svg::line_series(m.spec.label + " global", el, gw, m.colour, 1.6, "6 3"));
  }
};

}  // namespace

void ReportWriter::section_illumination() {
  std::vector<IlluminationModel> models = {
      illumination_model(comparison_spec(PreethamModel::kName, 3.0)),
      illumination_model(comparison_spec(CieSkyModel::kName, 12)),
      illumination_model(comparison_spec(CieSkyModel::kName, 16)),
      illumination_model(comparison_spec(HosekWilkieModel::kName, 3.0)),
      illumination_model(comparison_spec(NishitaModel::kName))};
  models[2].spec.label = "CIE type 16 (traditional overcast)";
  models[2].colour = kCie16Colour;
  IlluminationFigures f;
  for (const auto& m : models) f.add(m, cfg_.illum_elevations_deg, cfg_.illum);
  svg::Plot &lx = f.lx, &wm = f.wm;
  lx.id = "illum";
  wm.id = "irrad";
  lx.title = "Horizontal illuminance against sun elevation";
  wm.title = fmt::format("Horizontal irradiance {:g}-{:g} nm against sun elevation",
                         cfg_.illum.nm_min, cfg_.illum.nm_max);
  lx.x = wm.x = {0, 90, false, "sun elevation [deg]", {0, 10, 20, 30, 40, 50, 60, 70, 80, 90}};
  lx.y = {0, std::max(1.0, f.lx_max * 1.05), false, "horizontal illuminance [lx]", {}};
  wm.y = {0, std::max(1.0, f.wm_max * 1.05), false, "horizontal irradiance [W/m2]", {}};
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
      f.table.html();
  json_["horizontal_illumination"] = {
      {"irradiance_wavelength_range_nm", {cfg_.illum.nm_min, cfg_.illum.nm_max}},
      {"note",
       "CIE and nishita have no solar disc: diffuse only; irradiance only for spectral "
       "models"},
      {"rows", f.rows}};
}

// ---- measurements ------------------------------------------------------------------------------

namespace {

// The scan of the report: the user's or the shipped synthetic one, with the sun position the
// options give; origin: how the page names it.
SkyScan report_scan(const ReportOptions& opt, std::string& origin) {
  SkyScan scan;
  if (opt.measurements) {
    scan = read_sky_scan(*opt.measurements);
    origin = fmt::format("the scan <code>{}</code>", svg::escape(opt.measurements->string()));
  } else {
    scan = parse_sky_scan(data::embedded_file(kSyntheticScanDataPath),
                          std::string("data/") + std::string(kSyntheticScanDataPath));
    origin = fmt::format(
        "the shipped <b>synthetic</b> example <code>data/{}</code> (no public measurement set is "
        "shipped; it is CIE type 7 at the 145 Tregenza patches with ±5 % noise, so CIE 7 "
        "should win)",
        kSyntheticScanDataPath);
  }
  if (opt.measurement_sun_azimuth) scan.sun_azimuth = *opt.measurement_sun_azimuth;
  if (opt.measurement_sun_elevation) scan.sun_elevation = *opt.measurement_sun_elevation;
  if (!scan.sun_azimuth || !scan.sun_elevation)
    throw InvalidArgument(fmt::format(
        "{}: no sun position: add '# sun_azimuth_deg = A' and '# sun_elevation_deg = E' lines or "
        "pass {} and {}",
        scan.source, spelled("sun-azimuth"), spelled("sun-elevation")));
  return scan;
}

// One model compared with the scan.
struct ScanEntry {
  std::string label, colour;
  ScanErrors e;
  std::unique_ptr<SkyModel> model;
};

// The 16 CIE types (entries 0-15), the best-turbidity Preetham and Hosek-Wilkie skies, Nishita.
std::vector<ScanEntry> scan_entries(const Config& cfg, const SkyScan& scan) {
  const double ts = kPi / 2 - *scan.sun_elevation, az = *scan.sun_azimuth;
  const double excl = cfg.comparison.sun_exclusion;
  std::vector<ScanEntry> entries;
  // The value of the model's report axis with the lowest zenith-normalised RMS over [t0, t1].
  auto best_t = [&](std::string_view name, double t0, double t1) {
    double best = t0, best_rms = kInf;
    for (double T = t0; T <= t1 + 1e-9; T += cfg.scan_t_step) {
      const auto m = make_model(comparison_spec(name, T), ts, az);
      const double r = compare_to_scan(*m, scan, excl).rms_log10_relative;
      if (r < best_rms) {
        best_rms = r;
        best = T;
      }
    }
    return best;
  };
  auto add = [&](std::string label, const ModelSpec& spec, std::unique_ptr<SkyModel> m) {
    entries.push_back({std::move(label), comparison_colour(spec.name),
                       compare_to_scan(*m, scan, excl), std::move(m)});
  };
  // With the sun at the horizon the Kittler-Darula typical zenith luminance is 0 for most types:
  // those types are then scaled to the scan's highest sample (their absolute errors are labelled).
  const LuminanceSample* top = &scan.samples.front();
  for (const auto& smp : scan.samples)
    if (smp.elevation > top->elevation) top = &smp;
  for (int t = 1; t <= kCieTypeCount; ++t) {
    ModelSpec spec = comparison_spec(CieSkyModel::kName, t);
    auto m = make_model(spec, ts, az);
    if (!(m->tristimulus({0.0, 0.0, 1.0}).Y > 0.0)) {
      spec.params.values.set("zenith-luminance", top->luminance);
      spec.label += " (Lz from the scan: Kittler-Darula gives 0)";
      m = make_model(spec, ts, az);
    }
    add(spec.label, spec, std::move(m));
  }
  // Preetham over the report's fit range; Hosek-Wilkie over the turbidities it accepts.
  const ParameterSpec& hosek_t = *find_model(HosekWilkieModel::kName)->find_parameter("turbidity");
  for (const auto& [name, range] :
       {std::pair{PreethamModel::kName, std::array{cfg.fit_t_min, cfg.fit_t_max}},
        std::pair{HosekWilkieModel::kName, std::array{hosek_t.min, hosek_t.max}}}) {
    const double T = best_t(name, range[0], range[1]);
    const ModelSpec spec = comparison_spec(name, T);
    add(fmt::format("{} T = {:.2f} (best)", find_model(name)->report.title, T), spec,
        make_model(spec, ts, az));
  }
  const ModelSpec nishita = comparison_spec(NishitaModel::kName);
  add(nishita.label, nishita, make_model(nishita, ts, az));
  return entries;
}

// The most samples the scatter plot draws per model: a scan of a million rows made a page of
// gigabytes (5 markers per sample); beyond it every k-th sample is drawn (the statistics use all).
constexpr std::size_t kMaxScatterSamples = 5000;

// Every how many samples the scatter plot draws one.
std::size_t scatter_stride(const SkyScan& scan) {
  return (scan.samples.size() + kMaxScatterSamples - 1) / kMaxScatterSamples;
}

// Measured against modelled luminance: the best CIE type, CIE 12 and the other families.
svg::Plot scan_plot(const SkyScan& scan, const std::vector<ScanEntry>& entries,
                    std::size_t best_cie, double excl, bool synthetic) {
  const std::size_t stride = scatter_stride(scan);
  svg::Plot p;
  p.id = "scan";
  p.title = synthetic ? "Synthetic scan (CIE 7 + noise, a self-test) against modelled luminance"
                      : "Measured against modelled luminance";
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
    const Vec3 sun = entries[i].model->sun().direction();
    for (std::size_t k = 0; k < scan.samples.size(); k += stride) {
      const LuminanceSample& m = scan.samples[k];
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
  return p;
}

}  // namespace

void ReportWriter::section_measurements() {
  std::string origin;
  const SkyScan scan = report_scan(opt_, origin);
  const double az = *scan.sun_azimuth;
  const double excl = cfg_.comparison.sun_exclusion;
  const std::vector<ScanEntry> entries = scan_entries(cfg_, scan);
  // The best CIE type by relative RMS goes into the plot with the other families.
  std::size_t best_cie = 0;
  for (std::size_t i = 1; i < static_cast<std::size_t>(kCieTypeCount); ++i)
    if (entries[i].e.rms_log10_relative < entries[best_cie].e.rms_log10_relative) best_cie = i;
  std::size_t best_all = 0;
  for (std::size_t i = 1; i < entries.size(); ++i)
    if (entries[i].e.rms_log10_relative < entries[best_all].e.rms_log10_relative) best_all = i;
  scan_best_ = entries[best_all].label;
  scan_best_cie_type_ = static_cast<int>(best_cie) + 1;
  scan_synthetic_ = !opt_.measurements.has_value();
  const svg::Plot p = scan_plot(scan, entries, best_cie, excl, scan_synthetic_);

  HtmlTable t({"model", "samples", "RMS log10, absolute", "bias log10, absolute",
               "RMS log10, zenith-normalised", "bias log10, zenith-normalised"});
  Json rows = Json::array();
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const auto& e = entries[i].e;
    t.row(
        {entries[i].label, fmt::format("{}", e.samples_used),
         fmt::format("{:.3f}", e.rms_log10_absolute), fmt::format("{:+.3f}", e.bias_log10_absolute),
         fmt::format("{:.3f}", e.rms_log10_relative),
         fmt::format("{:+.3f}", e.bias_log10_relative)},
        i == best_all ? " class=\"best\"" : "");
    rows.push_back({{"model", entries[i].label},
                    {"samples", e.samples_used},
                    {"rms_log10_absolute", num(e.rms_log10_absolute)},
                    {"bias_log10_absolute", num(e.bias_log10_absolute)},
                    {"rms_log10_zenith_normalised", num(e.rms_log10_relative)},
                    {"bias_log10_zenith_normalised", num(e.bias_log10_relative)}});
  }
  html_scan_ =
      (scan_synthetic_
           ? std::string(
                 "<p class=\"note\">No measured scan is included: we found no public sky-luminance "
                 "scan whose licence lets us ship it. The shipped scan is <b>synthetic</b>, made "
                 "from CIE type 7, so this section is a <b>self-test</b> of the comparison (CIE 7 "
                 "must come first); it does <b>not rank the models</b>. Pass a measured scan with "
                 "<code>--measurements FILE</code> (docs/REPORT.md, \"Sky-luminance "
                 "scans\").</p>\n")
           : std::string()) +
      fmt::format(
          "<p>Compared with {}: {} samples, sun azimuth {:.4g} deg, elevation {:.4g} deg; "
          "samples within {:g} deg of the sun are left out. For each sample d = log10(L_model / "
          "L_measured); RMS = sqrt(mean d^2), bias = mean d (10^bias - 1 is the mean relative "
          "bias). <i>Absolute</i>: each model's own absolute luminance (CIE: Kittler-Darula "
          "typical zenith luminance). <i>Zenith-normalised</i>: the model scaled to the "
          "measurement at the highest sample (the zenith patch of a Tregenza scan). Preetham and "
          "Hosek-Wilkie: the turbidity with the lowest zenith-normalised RMS on a {:g} grid. "
          "{} (zenith-normalised): <b>{}</b>.</p>\n",
          origin, scan.samples.size(), rad_to_deg(az), rad_to_deg(*scan.sun_elevation),
          rad_to_deg(excl), cfg_.scan_t_step,
          scan_synthetic_ ? "Closest to the synthetic scan (the self-test's expected answer: CIE 7)"
                          : "Best overall",
          entries[best_all].label) +
      figure("measurements.svg", svg::draw(p),
             fmt::format("{} {} luminance (x) against the models' (y): the best CIE "
                         "type, CIE 12, the best-turbidity Preetham and Hosek-Wilkie skies and "
                         "Nishita; the dashed line is 1:1.",
                         scatter_stride(scan) == 1
                             ? std::string("Each sample's")
                             : fmt::format("Every {}th sample's (of {}; the table uses all)",
                                           scatter_stride(scan), scan.samples.size()),
                         scan_synthetic_ ? "synthetic" : "measured")) +
      t.html();
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

namespace {

// Cells span halfway to the neighbouring samples.
std::vector<double> cell_edges(const std::vector<double>& v, double lo, double hi) {
  std::vector<double> e{lo};
  for (std::size_t i = 1; i < v.size(); ++i) e.push_back(0.5 * (v[i - 1] + v[i]));
  e.push_back(hi);
  return e;
}

}  // namespace

void ReportWriter::validity_map(const ValidityMap& map, const std::vector<double>& zen_deg) {
  const std::string& key = map.spec.name;
  const std::string& row_parameter = find_model(key)->report.axis;
  std::vector<double> zen_rad;
  for (double v : zen_deg) zen_rad.push_back(v * kDegree);
  const auto grid =
      validity_grid(map.spec, zen_rad, map.rows, map.rows.empty() ? "" : row_parameter);
  const auto xe = cell_edges(zen_deg, 0.0, 110.0);
  const auto ye = map.rows.empty() ? std::vector<double>{map.row_lo, map.row_hi}
                                   : cell_edges(map.rows, map.row_lo, map.row_hi);
  svg::Plot p;
  p.id = "valid-" + key;
  p.title = fmt::format("{}: domain() over {}", key, map.over);
  p.x = {0,
         110,
         false,
         "sun zenith angle θs [deg] (> 90: sun below the horizon)",
         {0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110}};
  p.y = map.rows.empty() ? one_row_axis() : map.y;
  p.width = 760;
  p.height = map.rows.empty() ? 200 : 340;
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
  html_validity_ += figure("validity_" + key + ".svg", svg::draw(p), map.caption);
  json_["validity"][key] = counts;
}

void ReportWriter::section_validity() {
  std::vector<double> zen_deg;
  for (double d = 0.0; d <= 110.0 + 1e-9; d += cfg_.validity_step_deg) zen_deg.push_back(d);
  // Preetham: T on a log grid over every value `preetham` accepts.
  const ParameterSpec& pt = *find_model(PreethamModel::kName)->find_parameter("turbidity");
  std::vector<double> preetham_t;
  const int n = cfg_.validity_preetham_rows;
  for (int i = 0; i < n; ++i)
    preetham_t.push_back(pt.min * std::pow(pt.max / pt.min, (i + 0.5) / n));
  validity_map({comparison_spec(PreethamModel::kName, 3),
                "(θs, T)",
                preetham_t,
                {pt.min, pt.max, true, "turbidity T", {1, 1.5, 2, 3, 5, 7, 10, 15, 20, 30, 50, 64}},
                pt.min,
                pt.max,
                "Preetham: valid for the fitted T 2-6; extrapolated 1.9-2 and 6-10; unphysical "
                "outside 1.9-10 (Zotti) and wherever Yz &lt; 0; undefined with the sun below the "
                "horizon."},
               zen_deg);
  // Hosek-Wilkie: every turbidity it accepts.
  const ParameterSpec& ht = *find_model(HosekWilkieModel::kName)->find_parameter("turbidity");
  std::vector<double> hosek_t;
  const double step = cfg_.validity_hosek_step;
  for (double T = ht.min; T <= ht.max + 1e-9; T += step) hosek_t.push_back(T);
  validity_map({comparison_spec(HosekWilkieModel::kName, 3),
                "(θs, T)",
                hosek_t,
                {ht.min, ht.max, false, "turbidity T", {}},
                ht.min - 0.5 * step,
                ht.max + 0.5 * step,
                fmt::format("Hosek-Wilkie (albedo 0.3): T {:g}-{:g} (larger values are rejected "
                            "by the model).",
                            ht.min, ht.max)},
               zen_deg);
  std::vector<double> types;
  for (int t = 1; t <= kCieTypeCount; ++t) types.push_back(t);
  validity_map(
      {comparison_spec(CieSkyModel::kName, 12),
       "(θs, type)",
       types,
       {0.5, 16.5, false, "CIE type", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16}},
       0.5,
       16.5,
       "CIE general sky with the Kittler-Darula typical zenith luminance (recommended for "
       "sun elevations 10-80 deg)."},
      zen_deg);
  validity_map({comparison_spec(NishitaModel::kName),
                "θs (Earth defaults)",
                {},
                {},
                0.0,
                1.0,
                "Nishita single scattering: domain() depends on the sun zenith only; sampled at "
                "the marked sun zenith angles (each cell spans halfway to its neighbours)."},
               cfg_.validity_nishita_deg);
  validity_map({comparison_spec(PerezModel::kName),
                "θs (coefficients -1,-0.32,10,-3,0.45)",
                {},
                {},
                0.0,
                1.0,
                "Perez with the main job's clear-sky coefficients (A..E = -1, -0.32, 10, -3, "
                "0.45); its domain depends on the coefficients and the sun zenith only."},
               zen_deg);
}

}  // namespace skylight::report::detail
