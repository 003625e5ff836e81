// The report's model-matching tables and solar-vertical profiles (Fig. 3).
#include <algorithm>
#include <map>

#include "skylight/core/error.h"
#include "skylight/core/parallel.h"
#include "skylight/models/cie_sky.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/nishita.h"
#include "skylight/models/preetham.h"
#include "skylight/report/detail/writer.h"

namespace skylight::report::detail {

// ---- matching tables ---------------------------------------------------------------------------

namespace {

// The RMS(T) curve of the best Preetham turbidity for CIE 12.
svg::Plot cie12_fit_plot(const TurbidityFit& fit) {
  svg::Plot p;
  p.id = "cie12fit";
  p.title = "Preetham vs CIE type 12: RMS of log10 relative luminance over T";
  p.x = {fit.curve_t.front(), fit.curve_t.back(), false, "Preetham turbidity T", {}};
  double ymax = 0.0;
  for (double v : fit.curve_rms)
    if (std::isfinite(v)) ymax = std::max(ymax, v);
  p.y = {
      0.0, std::max(0.05, 1.1 * ymax), false, "RMS log10(L_Pr / L_CIE12) (zenith-normalised)", {}};
  p.series.push_back(svg::line_series("RMS(T)", fit.curve_t, fit.curve_rms,
                                      comparison_colour(PreethamModel::kName)));
  p.series.push_back(svg::marker_series(fmt::format("best T = {:.3f}", fit.turbidity),
                                        {fit.turbidity}, {fit.rms},
                                        comparison_colour(CieSkyModel::kName), 4));
  p.series.push_back(svg::line_series("Zotti: T = 2.3-2.5", {2.3, 2.3, 2.5, 2.5},
                                      {0, p.y.max, p.y.max, 0}, "#888888", 1.0, "4 3"));
  p.width = 640;
  p.height = 360;
  return p;
}

// For a Preetham turbidity of Zotti's pairs: our numbers for his pairing, as a row of the
// pairs' table `pt` and a record in `pairs`; returns the pair as the matches' table cites it (empty
// for any other turbidity).
std::string zotti_pair_row(const CieTypeMatch& m, const ComparisonSettings& cs,
                           const HemisphereGrid& grid, const std::map<double, RatioBand>& bands,
                           HtmlTable& pt, Json& pairs) {
  std::string z;
  const auto it = std::find_if(kZottiPairs.begin(), kZottiPairs.end(),
                               [&](const ZottiPair& p) { return p.t == m.turbidity; });
  if (it != kZottiPairs.end()) {
    const int type = it->type;
    const std::string ratio = svg::escape(it->ratio);
    z = fmt::format("CIE {}, Y_Pr/Y_CIE {}", type, ratio);
    // Our numbers for Zotti's pairing.
    const auto pr = relative_samples(comparison_spec(PreethamModel::kName, m.turbidity), cs, grid);
    const auto ci = relative_samples(comparison_spec(CieSkyModel::kName, type), cs, grid);
    const LuminanceRatio r = absolute_luminance_ratio(pr, ci, grid);
    int rank = 1;
    for (int k = 0; k < kCieTypeCount; ++k)
      if (m.rms_by_type[k] < m.rms_by_type[type - 1]) ++rank;
    const RatioBand& band = bands.at(m.turbidity);
    pt.row({fmt::format("{:g}", m.turbidity), fmt::format("{}", type), f2(m.rms_by_type[type - 1]),
            fmt::format("{} of 16", rank),
            fmt::format("{} [{}, {}]", g3(r.mean), g3(r.min), g3(r.max)),
            fmt::format("{} [{}, {}]", g3(band.typical), g3(band.against_cie_high),
                        g3(band.against_cie_low)),
            ratio});
    pairs.push_back({{"turbidity", m.turbidity},
                     {"cie_type", type},
                     {"rms_log10", num(m.rms_by_type[type - 1])},
                     {"rank_of_16", rank},
                     {"luminance_ratio_preetham_over_cie", num(r.mean)},
                     {"luminance_ratio_min", num(r.min)},
                     {"luminance_ratio_max", num(r.max)}});
  }
  return z;
}

// report.json's record of the best-matching CIE types for a Preetham turbidity.
Json match_json(const CieTypeMatch& m) {
  Json rms = Json::object();
  for (int k = 0; k < kCieTypeCount; ++k) rms[fmt::format("{}", k + 1)] = num(m.rms_by_type[k]);
  return {{"turbidity", m.turbidity},
          {"cie_type", m.best_type},
          {"rms_log10", num(m.best_rms)},
          {"second_cie_type", m.second_type},
          {"second_rms_log10", num(m.second_rms)},
          {"luminance_ratio_preetham_over_cie", num(m.ratio_best.mean)},
          {"luminance_ratio_min", num(m.ratio_best.min)},
          {"luminance_ratio_max", num(m.ratio_best.max)},
          {"rms_log10_by_cie_type", rms}};
}

}  // namespace

void ReportWriter::section_matching() {
  const auto& cs = cfg_.comparison;
  summary_.cie_matches = best_cie_type_per_turbidity(cfg_.match_turbidities, cs);
  step("best CIE type per Preetham turbidity");
  summary_.best_turbidity_for_cie12 =
      best_preetham_turbidity_for_cie(12, cfg_.fit_t_min, cfg_.fit_t_max, cfg_.fit_t_step, cs);
  step("best Preetham turbidity for CIE 12");
  // Zotti's sun range (15 < theta_s < 70) and the Kittler-Darula band, for every pair.
  ComparisonSettings ps = cs;
  ps.sun_zeniths.clear();
  for (double d : cfg_.pair_sun_zeniths_deg) ps.sun_zeniths.push_back(d * kDegree);
  pair_bands_.clear();
  for (const ZottiPair& p : kZottiPairs)
    pair_bands_[p.t] = preetham_cie_ratio_band(p.t, p.type, ps);
  // In this order: each part adds to report.json and the list of files.
  html_match_ = matching_tables();
  html_match_ += cie12_fit_html();
  html_match_ += antisolar_horizon_html();
}

std::string ReportWriter::matching_tables() {
  const auto& cs = cfg_.comparison;
  HtmlTable t({"Preetham T", "best CIE type", "RMS log10", "2nd best", "RMS log10",
               "Y_Pr / Y_CIE (best type): mean [min, max over θs]", "Zotti 2007"});
  HtmlTable pt({"Preetham T", "CIE type", "RMS log10", "rank of this type",
                "Y_Pr / Y_CIE mean [min, max]",
                fmt::format("Y_Pr / Y_CIE at θs {} deg: Kittler-Darula typical [CIE at the "
                            "band's high, low end]",
                            degrees_list(cfg_.pair_sun_zeniths_deg)),
                "Zotti: Y_Pr/Y_CIE for 15 &lt; θs &lt; 70"});
  Json matches = Json::array(), pairs = Json::array();
  const HemisphereGrid grid = hemisphere_grid(cs.n_theta, cs.n_phi);
  for (const auto& m : summary_.cie_matches) {
    const std::string z = zotti_pair_row(m, cs, grid, pair_bands_, pt, pairs);
    t.row({fmt::format("{:g}", m.turbidity), fmt::format("<b>{}</b>", m.best_type), f2(m.best_rms),
           fmt::format("{}", m.second_type), f2(m.second_rms),
           fmt::format("{} [{}, {}]", g3(m.ratio_best.mean), g3(m.ratio_best.min),
                       g3(m.ratio_best.max)),
           z});
    matches.push_back(match_json(m));
  }
  json_["best_cie_type_per_preetham_turbidity"] = matches;
  json_["zotti_pairs"] = pairs;
  const std::string method = fmt::format(
      "Relative distributions L/L(zenith) of both models on a {}x{} midpoint grid over the "
      "hemisphere (zenith-angle rings x azimuth sectors), directions within {:g} deg of the sun "
      "left out, at sun zenith angles {} deg (sun azimuth 180 deg); RMS of log10(L_Preetham / "
      "L_CIE) weighted by solid angle and pooled over the sun positions.",
      cs.n_theta, cs.n_phi, rad_to_deg(cs.sun_exclusion), degrees_list(sun_zeniths_deg(cs)));
  return "<p>" + method + "</p>\n<h3>Best-matching CIE type for each Preetham turbidity</h3>\n" +
         t.html() +
         "<p>Y_Pr / Y_CIE: ratio of absolute luminances, Preetham over the CIE type with "
         "the Kittler-Darula typical zenith luminance: per sun position the solid-angle "
         "weighted geometric mean over the same directions, then the geometric mean over "
         "the sun positions (min and max over the sun positions in brackets).</p>\n"
         "<h3>Zotti's pairs</h3>\n" +
         pt.html() +
         fmt::format(
             "<p>Two ratios per pair, both the geometric mean over the sky: the first over "
             "the sun positions of this section's fits (θs {} deg), the second over Zotti's "
             "range 15 &lt; θs &lt; 70 (θs {} deg), which his table states and the findings "
             "use, with the CIE zenith luminance also at the ends of the Kittler–Darula band "
             "(tabulated with the absolute CIE maps; our derivation from Kittler &amp; Darula's "
             "typical parameters, docs/REPORT.md). The findings read three more ratios per pair "
             "(sky maxima, zenith, diffuse illuminance): see <a href=\"#zotti\">Zotti et al.'s "
             "findings in brief</a>.</p>\n",
             degrees_list(sun_zeniths_deg(cs)), degrees_list(cfg_.pair_sun_zeniths_deg));
}

std::string ReportWriter::cie12_fit_html() {
  const auto& cs = cfg_.comparison;
  const TurbidityFit& fit = summary_.best_turbidity_for_cie12;
  json_["best_preetham_turbidity_for_cie12"] = fit.turbidity;
  json_["best_preetham_turbidity_for_cie12_details"] = {
      {"rms_log10", num(fit.rms)},
      {"search_range", {cfg_.fit_t_min, cfg_.fit_t_max}},
      {"grid_step", cfg_.fit_t_step},
      {"normalisation", "luminance relative to the zenith (Zotti 2007)"},
      {"sun_zeniths_deg", sun_zeniths_deg(cs)},
      {"sun_exclusion_deg", rad_to_deg(cs.sun_exclusion)},
      {"grid", fmt::format("{} zenith rings x {} azimuth sectors", cs.n_theta, cs.n_phi)},
      {"zotti_2007", {2.3, 2.5}}};
  return "<h3>Preetham turbidity that best matches CIE 12</h3>\n" +
         fmt::format(
             "<p>Best T = <b>{:.3f}</b> (RMS log10 = {:.3f}), searched over T "
             "{:g}-{:g} on a {:g} grid refined by golden-section search; Zotti "
             "et al. 2007: T ≈ 2.3-2.5.</p>\n",
             fit.turbidity, fit.rms, cfg_.fit_t_min, cfg_.fit_t_max, cfg_.fit_t_step) +
         figure("cie12_fit.svg", svg::draw(cie12_fit_plot(fit)),
                "RMS of the log10 ratio of zenith-normalised luminance, Preetham(T) vs CIE "
                "type 12, over the grid and sun positions above.");
}

std::string ReportWriter::antisolar_horizon_html() {
  const double T = summary_.best_turbidity_for_cie12.turbidity;
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
  HtmlTable at({"θs [deg]", "view elevation [deg]", "Preetham [cd/m2]", "CIE 12 [cd/m2]", "ratio",
                "ratio of zenith-normalised values"});
  Json rows = Json::array();
  for (const auto& r : antisolar_) {
    at.row({fmt::format("{:g}", rad_to_deg(r.sun_zenith)),
            fmt::format("{:g}", rad_to_deg(r.view_elevation)), g3(r.preetham), g3(r.cie),
            fmt::format("<b>{}</b>", g3(r.ratio)), g3(r.relative_ratio)});
    rows.push_back({{"sun_zenith_deg", rad_to_deg(r.sun_zenith)},
                    {"view_elevation_deg", rad_to_deg(r.view_elevation)},
                    {"preetham_cd_m2", num(r.preetham)},
                    {"cie12_cd_m2", num(r.cie)},
                    {"ratio", num(r.ratio)},
                    {"ratio_zenith_normalised", num(r.relative_ratio)}});
  }
  const std::string html =
      fmt::format(
          "<h3>Antisolar horizon: Preetham / CIE 12 at low sun</h3>\n<p>Luminance at the azimuth "
          "opposite the sun, near the horizon, Preetham at T = {:.3f} (the best match to CIE 12 "
          "above) over CIE type 12 with the Kittler-Darula typical zenith luminance. One point "
          "(report.json "
          "<code>antisolar_horizon_ratio_details.ratio</code>): θs = {:g} deg (sun "
          "elevation "
          "{:g} deg, the lowest the Kittler-Darula formula is recommended for), view elevation "
          "{:g} "
          "deg: <b>{:.3g}</b>. Zotti et al. 2007: 2-5 times too high. These are single points; "
          "the finding is measured over the whole antisolar half in the summary.</p>\n",
          T, cfg_.antisolar_headline_sun_zenith_deg, 90 - cfg_.antisolar_headline_sun_zenith_deg,
          cfg_.antisolar_headline_elevation_deg, summary_.antisolar_ratio) +
      at.html();
  // A single point, not a headline: under its details, with the sun and view it holds for.
  json_["antisolar_horizon_ratio_details"] = {
      {"ratio", num(summary_.antisolar_ratio)},
      {"sun_zenith_deg", cfg_.antisolar_headline_sun_zenith_deg},
      {"view_elevation_deg", cfg_.antisolar_headline_elevation_deg},
      {"view_azimuth", "opposite the sun (180 deg from the solar azimuth)"},
      {"preetham_turbidity", T},
      {"turbidity_source", "best_preetham_turbidity_for_cie12"},
      {"cie_zenith_luminance", "Kittler-Darula typical value for type 12"},
      {"quantity", "ratio of absolute luminances Preetham / CIE 12"},
      {"zotti_2007", "2-5 times too high"},
      {"table", rows}};
  return html;
}

// ---- Fig. 3 ------------------------------------------------------------------------------------

namespace {

// specs[kVerticalReference] is CIE type 12, the ratio plot's denominator.
constexpr std::size_t kVerticalReference = 1;

// Each model's luminance along the solar vertical divided by CIE 12's, on the x axis of lum.
svg::Plot vertical_ratio_plot(const svg::Plot& lum, const std::vector<ModelSpec>& specs,
                              const std::vector<double>& xs,
                              const std::vector<std::vector<double>>& values) {
  svg::Plot ratio;
  ratio.x = lum.x;
  ratio.y = {0.1, 10.0, true, "model / CIE type 12", {0.1, 0.2, 0.5, 1, 2, 5, 10}};
  const auto& reference = values[kVerticalReference];
  for (std::size_t m = 0; m < specs.size(); ++m) {
    if (m == kVerticalReference) continue;
    std::vector<double> r(xs.size(), kNaN);
    for (std::size_t i = 0; i < xs.size(); ++i)
      if (reference[i] > 0.0 && values[m][i] > 0.0) r[i] = values[m][i] / reference[i];
    ratio.series.push_back(svg::line_series(specs[m].label + " / CIE 12", xs, r,
                                            comparison_colour(specs[m].name), 1.6));
  }
  ratio.series.push_back(svg::line_series("2x and 5x", {-90, 90}, {2, 2}, "#888888", 1.0, "4 3"));
  ratio.series.push_back(svg::line_series("", {-90, 90}, {5, 5}, "#888888", 1.0, "4 3"));
  ratio.series.push_back(svg::line_series("", {-90, 90}, {1, 1}, "#444444", 0.8));
  ratio.width = 900;
  ratio.height = 300;
  ratio.legend_outside = true;
  return ratio;
}

}  // namespace

void ReportWriter::section_vertical() {
  int index = 0;
  for (auto [T, tsd] : cfg_.vertical_cases) {
    if (T < 0) T = summary_.best_turbidity_for_cie12.turbidity;
    vertical_case(++index, T, tsd);
  }
}

void ReportWriter::vertical_case(int index, double T, double tsd) {
  const double ts = tsd * kDegree;
  // Hosek-Wilkie joins where it accepts the turbidity.
  std::vector<ModelSpec> specs = {comparison_spec(PreethamModel::kName, T),
                                  comparison_spec(CieSkyModel::kName, 12)};
  specs[kVerticalReference].label = "CIE type 12 (Kittler-Darula typical Lz)";
  if (T <= find_model(HosekWilkieModel::kName)->find_parameter("turbidity")->max)
    specs.push_back(comparison_spec(HosekWilkieModel::kName, T));
  specs.push_back(comparison_spec(NishitaModel::kName));
  std::vector<double> xs;
  std::vector<Vec3> dirs;
  const int n = static_cast<int>(std::lround(180.0 / cfg_.vertical_step_deg));
  for (int i = 0; i <= n; ++i) {
    const double x = -90.0 + i * cfg_.vertical_step_deg;
    xs.push_back(x);
    // Positive x: towards the sun (sun azimuth pi); negative: the antisolar side.
    dirs.push_back(direction_from_angles(std::abs(x) * kDegree, x >= 0 ? kPi : 0.0));
  }
  svg::Plot lum;
  lum.id = fmt::format("vert{}", index);
  lum.title = fmt::format("Solar vertical, θs = {:g} deg, T = {:.3g}", tsd, T);
  std::vector<std::vector<double>> values;
  double lo = kInf, hi = 0.0;
  for (const auto& spec : specs) {
    const auto model = make_model(spec, ts, kPi);
    values.push_back(sky_luminance(*model, dirs));
    for (double v : values.back())
      if (v > 0.0) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    lum.series.push_back(
        svg::line_series(spec.label, xs, values.back(), comparison_colour(spec.name), 1.6));
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
  // The sun's direction: a vertical line across the plot (its luminance is not on this scale).
  lum.series.push_back(svg::line_series(fmt::format("sun (view zenith {:g} deg)", tsd), {tsd, tsd},
                                        {lum.y.min, lum.y.max}, "#ff9800", 1.5, "5 3"));
  lum.width = 900;
  lum.height = 400;
  lum.legend_outside = true;
  svg::Plot ratio = vertical_ratio_plot(lum, specs, xs, values);
  ratio.id = fmt::format("vertratio{}", index);
  ratio.series.push_back(
      svg::line_series("", {tsd, tsd}, {ratio.y.min, ratio.y.max}, "#ff9800", 1.5, "5 3"));
  ratio.title = fmt::format("Ratio to CIE type 12, θs = {:g} deg, T = {:.3g}", tsd, T);
  html_vertical_ +=
      figure(fmt::format("solar_vertical_{}.svg", index), svg::draw(lum),
             fmt::format("Sky luminance along the solar vertical (sky only, no solar disc) for "
                         "θs = {:g} deg, T = {:.3g} (Zotti Fig. 3: θs = 72 deg, T = "
                         "1.8); view zenith angle across, negative on the side opposite the sun; "
                         "the dashed orange line is the sun's direction. CIE 12 uses the "
                         "Kittler-Darula typical zenith luminance.",
                         tsd, T));
  html_vertical_ +=
      figure(fmt::format("solar_vertical_{}_ratio.svg", index), svg::draw(ratio),
             "The curves of the figure above, each divided by CIE type 12 (its Kittler-Darula "
             "typical zenith luminance): 1 means equal, above 1 brighter than CIE 12; the dashed "
             "orange line is the sun's direction.");
}

}  // namespace skylight::report::detail
