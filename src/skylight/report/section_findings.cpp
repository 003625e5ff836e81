// The report's Zotti findings: one record per finding of Zotti, Wilkie & Purgathofer 2007 (paper
// statement, our numbers, agreement, cause), measured with the analyses of analysis/comparison.h.
// The summary and the closing table of index.html and report.json's `zotti_findings` are all
// generated from these records (docs/REPORT.md, "Zotti's findings").
#include <algorithm>
#include <map>

#include "skylight/core/error.h"
#include "skylight/models/cie_sky.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/nishita.h"
#include "skylight/models/preetham.h"
#include "skylight/report/detail/writer.h"

namespace skylight::report {

std::string format_finding_value(double v) {
  return detail::g3(v);
}

std::string agreement_name(Agreement a) {
  switch (a) {
    case Agreement::agrees:
      return "agrees";
    case Agreement::partly:
      return "partly";
    case Agreement::disagrees:
      return "disagrees";
    case Agreement::not_tested:
      break;
  }
  return "not tested";
}

Agreement agreement_of(int holding, int tested) {
  if (tested <= 0) return Agreement::not_tested;
  if (holding >= tested) return Agreement::agrees;
  return holding > 0 ? Agreement::partly : Agreement::disagrees;
}

namespace detail {
namespace {

// Zotti's "about 2-5 times too high" (§6) for the antisolar hemisphere at low sun: the
// solid-angle-weighted geometric mean of Preetham / CIE 12 over the antisolar half must lie in
// this range at a sun position for the statement to hold there.
constexpr double kZottiAntisolarMin = 2.0, kZottiAntisolarMax = 5.0;
// Zotti's low-sun range "θs >~ 60" of the shape statements.
constexpr double kLowSunZenithDeg = 60.0;
// Zotti's T 5 <-> CIE 7 "≈ 1": taken as agreeing within this factor either way.
constexpr double kAboutOneFactor = 1.25;
// Zotti's negative-luminance limit of Fig. 1's text (T < 1.6) is reproduced by a boundary within
// this distance in T (the paper gives one decimal).
constexpr double kOneDecimal = 0.05;
// Circumsolar ring of the weak-brightening finding [deg from the sun]: outside the 5 deg left
// out everywhere, inside the CIE clear-sky corona.
constexpr double kRingInnerDeg = 5.0, kRingOuterDeg = 10.0;
// Horizon band of the "horizon unnaturally bright" finding: view elevations below this [deg],
// at least kHorizonSunDistanceDeg from the sun (the circumsolar peak is a separate finding).
constexpr double kHorizonBandDeg = 5.0, kHorizonSunDistanceDeg = 10.0;
// Zotti's horizon case: "even for T > 2.4".
constexpr double kHorizonTurbidity = 2.5;
// Zotti's Fig. 3 and his "T < 2 definitely wrong": the low-turbidity shape case.
constexpr double kLowTurbidity = 1.8;

struct Range {
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  double at_min = kNaN;  // where the minimum lies (elevation or sun zenith, per use) [deg]
  // One sample's min and max; `where` belongs to lo_v.
  void add(double lo_v, double hi_v, double where = kNaN) {
    if (std::isfinite(lo_v) && lo_v < min) {
      min = lo_v;
      at_min = where;
    }
    if (std::isfinite(hi_v)) max = std::max(max, hi_v);
  }
  double lo() const { return std::isfinite(min) ? min : kNaN; }
  double hi() const { return std::isfinite(max) ? max : kNaN; }
};

// Our numbers as text, exactly as the summary prints them.
std::string v3(double v) {
  return format_finding_value(v);
}

// The records hold plain text; the page escapes it.
std::string esc(const std::string& s) {
  return esc_html(s);
}

// One finding's record as report.json's `zotti_findings` holds it.
Json finding_json(const Finding& f) {
  Json vals = Json::array();
  for (const auto& v : f.our_values) vals.push_back({{"name", v.name}, {"value", num(v.value)}});
  return {{"id", f.id},
          {"title", f.title},
          {"paper_statement", f.paper_statement},
          {"paper_value", f.paper_value_text},
          {"our_values", vals},
          {"agrees", f.agrees()},
          {"agreement", agreement_name(f.agreement)},
          {"cause", f.cause}};
}

// A model's luminance over a region of the sky, Preetham at turbidity t against CIE 12.
RegionRatio preetham_against_cie12(double t, double sun_zenith_deg, const HemisphereGrid& grid,
                                   const SkyRegion& in_region) {
  return region_ratio(comparison_spec(PreethamModel::kName, t),
                      comparison_spec(CieSkyModel::kName, 12), sun_zenith_deg * kDegree, grid,
                      in_region);
}

}  // namespace

bool pair_reading_holds(const ZottiPair& pair, const LuminanceRatio& ratio) {
  auto holds = [&](double v) {
    return pair.about
               ? (v >= pair.threshold / kAboutOneFactor && v <= pair.threshold * kAboutOneFactor)
               : v > pair.threshold;
  };
  return holds(ratio.min) && holds(ratio.max);
}

bool antisolar_factor_holds(double geomean) {
  return geomean >= kZottiAntisolarMin && geomean <= kZottiAntisolarMax;
}

void ReportWriter::section_findings() {
  summary_.findings.clear();
  const HemisphereGrid zone_grid = hemisphere_grid(cfg_.zone_n_theta, cfg_.zone_n_phi);
  finding_negative_clear();
  finding_negative_turbid();
  step("Zotti findings: negative luminance");
  finding_best_turbidity();
  step("Zotti findings: best turbidity per sun position");
  finding_antisolar(zone_grid);
  step("Zotti findings: antisolar half");
  finding_pairs();
  step("Zotti findings: T-CIE pairs against the Kittler-Darula band");
  finding_low_sun(zone_grid);
  finding_fig3();
  finding_cie_classes();
  finding_pair_shapes();
  finding_fitted_range();
  finding_measurements();
  // report.json and the closing table.
  Json arr = Json::array();
  for (const Finding& f : summary_.findings) arr.push_back(finding_json(f));
  json_["zotti_findings"] = arr;
  html_findings_ = findings_table_html();
  step("Zotti findings: circumsolar ring, horizon band, measurements");
}

// 1. Negative luminance at low turbidity: the zenith formula and the whole sky.
void ReportWriter::finding_negative_clear() {
  const NegativeSkyRange neg = preetham_negative_sky_range();
  // The two numbers of the paper, each reproduced when a sign boundary of ours lies within one
  // decimal of it.
  auto boundary_near = [&](double t) {
    return std::abs(neg.t_high - t) <= kOneDecimal || std::abs(neg.t_low - t) <= kOneDecimal ||
           std::abs(low_branch_t_at_zenith_ - t) <= kOneDecimal;
  };
  const bool t16 = boundary_near(1.6), t19 = boundary_near(1.9);
  summary_.findings.push_back(
      {.id = "negative_luminance_clear",
       .title = "Negative luminance in very clear air (Fig. 1)",
       .paper_statement =
           "From Fig. 1 (zenith luminance) Preetham's model should not be used for exceptionally "
           "clear air (§3: \"T > 1.6\", meaning T below 1.6); §7: it \"breaks down numerically "
           "for T > 1.9\" (meaning T below 1.9).",
       .paper_value_text = "T < 1.6 (§3), T < 1.9 (§7)",
       .our_values = {{"zenith luminance Yz < 0 for T below (θs = 0)", low_branch_t_at_zenith_},
                      {"Yz < 0 region ends at θs [deg] (T = 1)",
                       rad_to_deg(low_branch_max_sun_zenith_)},
                      {"whole sky negative somewhere, every θs: T above (B(T) = 0)", neg.t_low},
                      {"whole sky negative somewhere, every θs: T below (1 + A e^B = 0)",
                       neg.t_high}},
       .agreement = agreement_of(int{t16} + int{t19}, 2),
       .cause = fmt::format(
           "Fig. 1's own quantity, the zenith luminance Yz, is negative only below T = {} and "
           "only with a high sun (up to θs = {} deg): Fig. 1 does not give 1.6. The whole sky "
           "has negative values somewhere at every sun position for {} < T < {} (the Perez "
           "gradation term 1 + A e^(B/cos θ) is 1 at the horizon and 1 + A e^B at the zenith; "
           "B = 0 at T = {}, 1 + A e^B = 0 at T = {}; the band is drawn in section 1's map): "
           "§3's 1.6 is {}. §7's 1.9 {}.",
           v3(low_branch_t_at_zenith_), v3(rad_to_deg(low_branch_max_sun_zenith_)), v3(neg.t_low),
           v3(neg.t_high), v3(neg.t_low), v3(neg.t_high),
           t16 ? "that band's upper end" : "not reproduced either",
           t19 ? "is reproduced by a sign boundary"
               : "is not reproduced: no sign boundary lies within 0.05 of it (it may be where "
                 "Zotti judges the shape wrong)")});
}

// 2. Negative zenith luminance for turbid air near the horizon.
void ReportWriter::finding_negative_turbid() {
  double t85 = kNaN;
  for (const auto& r : preetham_zenith_roots({85.0 * kDegree}, 1.0, 64.0))
    if (r.negative_above) t85 = r.turbidity;
  summary_.findings.push_back(
      {.id = "negative_luminance_turbid",
       .title = "Negative zenith luminance near sunrise/sunset (Fig. 1)",
       .paper_statement =
           "\"values near sunrise/sunset (θs > 85) are apparently problematic, and fail for "
           "turbidities T >~ 10\" (§3).",
       .paper_value_text = "θs > 85 deg, T >~ 10",
       .our_values = {{"Yz < 0 for T above (θs = 90 deg)", high_branch_t_at_horizon_},
                      {"Yz < 0 for T above (θs = 85 deg)", t85}},
       .agreement = high_branch_t_at_horizon_ < 12.0 ? Agreement::agrees : Agreement::disagrees,
       .cause = fmt::format(
           "Yz = 0 at T = 2.4192 / 0.2155 = {} with the sun at the horizon and at T = {} at "
           "θs = 85 deg: Zotti's T >~ 10 read from the map.",
           v3(high_branch_t_at_horizon_), v3(t85))});
}

// 3. Best turbidity for CIE 12 and its spread over the sun positions.
void ReportWriter::finding_best_turbidity() {
  const double fit_t = summary_.best_turbidity_for_cie12.turbidity;
  Range spread;
  std::vector<double> per_sun;
  for (double d : cfg_.fit_per_sun_zeniths_deg) {
    ComparisonSettings one = cfg_.comparison;
    one.sun_zeniths = {d * kDegree};
    const double t =
        best_preetham_turbidity_for_cie(12, cfg_.fit_t_min, cfg_.fit_t_max, cfg_.fit_t_step, one)
            .turbidity;
    per_sun.push_back(t);
    spread.add(t, t, d);
  }
  const std::string pooled = degrees_list(sun_zeniths_deg(cfg_.comparison));
  Finding f{
      .id = "best_turbidity_cie12",
      .title = "Preetham turbidity that best matches CIE 12",
      .paper_statement =
          "\"The CIE Clear Sky (Type 12) is best approximated with T ≈ 2.3...2.5\" (§6), found by "
          "comparing the maps of Figs. 4 and 6 by eye.",
      .paper_value_text = "T ≈ 2.3-2.5",
      .our_values = {{fmt::format("best T, pooled over θs {} deg", pooled), fit_t}},
      .agreement = fit_t >= 2.3 - kOneDecimal && fit_t <= 2.5 + kOneDecimal ? Agreement::agrees
                                                                            : Agreement::disagrees,
      .cause = fmt::format(
          "Zotti matched by eye over all sun positions; the RMS of the zenith-normalised log "
          "ratio pooled over θs {} deg is smallest at T = {}, but the best T depends on the "
          "sun position: {} to {} over θs {} deg, so a single T ≈ 2.3-2.5 is a compromise.",
          pooled, v3(fit_t), v3(spread.lo()), v3(spread.hi()),
          degrees_list(cfg_.fit_per_sun_zeniths_deg))};
  for (std::size_t i = 0; i < per_sun.size(); ++i)
    f.our_values.push_back(
        {fmt::format("best T at θs = {:g} deg", cfg_.fit_per_sun_zeniths_deg[i]), per_sun[i]});
  summary_.findings.push_back(f);
}

namespace {

// Preetham against CIE 12 over the antisolar half at each sun zenith of the zone: at the fitted
// turbidity and at kLowTurbidity, the ranges of the absolute and zenith-normalised ratios, the
// geometric means (and at how many low-sun positions Zotti's 2-5 holds), and report.json's rows.
struct AntisolarZone {
  Range abs_fit, rel_fit, rel_low, abs_low, geomean;
  int geomean_in_range = 0, geomean_tested = 0;
  Json rows = Json::array();
};
AntisolarZone antisolar_zone(double fit_t, const std::vector<double>& zone_sun_zeniths_deg,
                             const HemisphereGrid& zone_grid) {
  AntisolarZone z;
  for (double d : zone_sun_zeniths_deg) {
    const RegionRatio a = preetham_against_cie12(fit_t, d, zone_grid, in_antisolar_half);
    z.geomean.add(a.absolute_geomean, a.absolute_geomean);
    if (d >= kLowSunZenithDeg) {
      ++z.geomean_tested;
      z.geomean_in_range += antisolar_factor_holds(a.absolute_geomean);
    }
    const RegionRatio b = preetham_against_cie12(kLowTurbidity, d, zone_grid, in_antisolar_half);
    z.abs_fit.add(a.absolute_min, a.absolute_max, rad_to_deg(a.absolute_min_elevation));
    z.rel_fit.add(a.relative_min, a.relative_max, rad_to_deg(a.relative_min_elevation));
    z.abs_low.add(b.absolute_min, b.absolute_max);
    z.rel_low.add(b.relative_min, b.relative_max);
    for (const auto* r : {&a, &b})
      z.rows.push_back({{"turbidity", r == &a ? fit_t : kLowTurbidity},
                        {"sun_zenith_deg", d},
                        {"absolute_min", num(r->absolute_min)},
                        {"absolute_max", num(r->absolute_max)},
                        {"absolute_min_elevation_deg", num(rad_to_deg(r->absolute_min_elevation))},
                        {"relative_min", num(r->relative_min)},
                        {"relative_max", num(r->relative_max)},
                        {"directions", r->directions}});
  }
  return z;
}

// Finding 5: the antisolar dip in each model's own terms, the horizon-to-darkest contrast over
// the antisolar half at low sun, Preetham at the fitted turbidity against CIE 12 (rel_low_max:
// the largest zenith-normalised ratio at kLowTurbidity).
Finding antisolar_shape_finding(double fit_t, const std::vector<double>& zone_sun_zeniths_deg,
                                const HemisphereGrid& zone_grid, double rel_low_max) {
  Range pr_contrast, cie_contrast, pr_depth, cie_depth;
  int weaker = 0, tested = 0;
  for (double d : zone_sun_zeniths_deg) {
    if (d < kLowSunZenithDeg) continue;
    const AntisolarDip p = antisolar_dip(comparison_spec(PreethamModel::kName, fit_t), d * kDegree,
                                         zone_grid, kHorizonBandDeg * kDegree);
    const AntisolarDip c = antisolar_dip(comparison_spec(CieSkyModel::kName, 12), d * kDegree,
                                         zone_grid, kHorizonBandDeg * kDegree);
    pr_contrast.add(p.contrast(), p.contrast());
    cie_contrast.add(c.contrast(), c.contrast());
    pr_depth.add(p.depth(), p.depth());
    cie_depth.add(c.depth(), c.depth());
    ++tested;
    weaker += p.contrast() < c.contrast();
  }
  return {.id = "antisolar_shape",
          .title = "Antisolar darkening too weak in shape at T ≈ 2.3-2.5",
          .paper_statement =
              "\"The CIE Clear Sky (Type 12) is best approximated with T ≈ 2.3...2.5, however, "
              "differences remain, esp. the mentioned darkening is too weak when θs >~ 60\"; "
              "\"The results for low turbidities T < 2 are definitely wrong\" (§6).",
          .paper_value_text = "darkening too weak at T ≈ 2.3-2.5, θs >~ 60; T < 2 wrong",
          .our_values =
              {{fmt::format("horizon-to-darkest contrast over the antisolar half, Preetham T = "
                            "{:.3g}, θs {:g}-{:g} deg: min",
                            fit_t, kLowSunZenithDeg, zone_sun_zeniths_deg.back()),
                pr_contrast.lo()},
               {"the same: max", pr_contrast.hi()},
               {"the same for CIE 12: min", cie_contrast.lo()},
               {"the same for CIE 12: max", cie_contrast.hi()},
               {"darkest / zenith, Preetham: min", pr_depth.lo()},
               {"darkest / zenith, CIE 12: min", cie_depth.lo()},
               {fmt::format("zenith-normalised Preetham/CIE 12 at T = {:g}: max", kLowTurbidity),
                rel_low_max}},
          .agreement = agreement_of(weaker, tested),
          .cause = fmt::format(
              "Seen from the horizon, Preetham's dip opposite the sun is {}-{} times darker than "
              "its horizon against CIE 12's {}-{} times (θs {:g}-{:g} deg): weaker at {} of {} sun "
              "positions, {}: the shape fault is mild, not the 2-5x, which comes from the absolute "
              "level (antisolar_factor). Below T ≈ 2 the shape goes wrong: at T = {:g} the "
              "zenith-normalised factor reaches {}.",
              v3(pr_contrast.lo()), v3(pr_contrast.hi()), v3(cie_contrast.lo()),
              v3(cie_contrast.hi()), kLowSunZenithDeg, zone_sun_zeniths_deg.back(), weaker, tested,
              weaker == tested ? "so weaker, mildly" : "so not weaker everywhere", kLowTurbidity,
              v3(rel_low_max))};
}

}  // namespace

// 4-5. The antisolar half at low sun, absolute and zenith-normalised (shape).
void ReportWriter::finding_antisolar(const HemisphereGrid& zone_grid) {
  const double fit_t = summary_.best_turbidity_for_cie12.turbidity;
  const AntisolarZone zone = antisolar_zone(fit_t, cfg_.zone_sun_zeniths_deg, zone_grid);
  const Range &abs_fit = zone.abs_fit, &rel_fit = zone.rel_fit, &geomean = zone.geomean;
  json_["antisolar_zone"] = {
      {"region", "antisolar half: view azimuth at least 90 deg from the sun's, all elevations"},
      {"grid",
       fmt::format("{} zenith rings x {} azimuth sectors", cfg_.zone_n_theta, cfg_.zone_n_phi)},
      {"quantity",
       "Preetham / CIE 12 (Kittler-Darula typical): absolute, and zenith-normalised (shape)"},
      {"rows", zone.rows}};
  const std::string zs = degrees_list(cfg_.zone_sun_zeniths_deg);
  summary_.findings.push_back(
      {.id = "antisolar_factor",
       .title = "Antisolar darkening: Preetham too bright",
       .paper_statement =
           "\"The Preetham model does not properly reproduce the noticeable darkening of the sky "
           "in the antisolar hemisphere when the sun is low, with luminance values about 2-5 times "
           "too high\" (§6).",
       .paper_value_text = "2-5 times too high",
       .our_values = {{fmt::format("absolute Preetham/CIE 12 over the antisolar half, T = {:.3g}, "
                                   "θs {} deg: min",
                                   fit_t, zs),
                       abs_fit.lo()},
                      {"the same: max", abs_fit.hi()},
                      {"the same: elevation of the min [deg]", abs_fit.at_min},
                      {"solid-angle-weighted geometric mean over the half: min", geomean.lo()},
                      {"the same: max", geomean.hi()},
                      {"zenith-normalised (shape): min", rel_fit.lo()},
                      {"zenith-normalised (shape): max", rel_fit.hi()}},
       .agreement = agreement_of(zone.geomean_in_range, zone.geomean_tested),
       .cause = fmt::format(
           "In absolute luminance Preetham (T = {}) is {}-{} times CIE 12 over the antisolar half "
           "at θs {} deg (lowest at elevation {} deg); the solid-angle-weighted geometric mean "
           "over the half is {}-{}, within Zotti's 2-5 at {} of {} sun positions with θs >= {:g} "
           "deg (the range includes θs = 85 deg, outside the Kittler-Darula recommended 10-80 "
           "deg). Normalised to each model's zenith the factor is only {}-{}: the excess is "
           "mostly Preetham's higher zenith luminance (absolute level), not the shape.",
           v3(fit_t), v3(abs_fit.lo()), v3(abs_fit.hi()), zs, v3(abs_fit.at_min), v3(geomean.lo()),
           v3(geomean.hi()), zone.geomean_in_range, zone.geomean_tested, kLowSunZenithDeg,
           v3(rel_fit.lo()), v3(rel_fit.hi()))});
  // The dip in each model's own terms: horizon-to-darkest contrast over the antisolar half.
  summary_.findings.push_back(
      antisolar_shape_finding(fit_t, cfg_.zone_sun_zeniths_deg, zone_grid, zone.rel_low.hi()));
}

// 6. Zotti's T <-> CIE type pairs, 15 < θs < 70: four readings of "k times as bright", each
// tested against Zotti's bound; the Kittler-Darula band is shown, never used for a verdict.
void ReportWriter::finding_pairs() {
  const std::string zs = degrees_list(cfg_.pair_sun_zeniths_deg);
  ComparisonSettings cs = cfg_.comparison;
  cs.sun_zeniths.clear();
  for (double d : cfg_.pair_sun_zeniths_deg) cs.sun_zeniths.push_back(d * kDegree);
  const HemisphereGrid grid = hemisphere_grid(cs.n_theta, cs.n_phi);
  Json band_rows = Json::array();
  for (const ZottiPair& p : kZottiPairs) {
    const RatioBand r = pair_bands_.at(p.t);  // section_matching
    const LuminanceReadings k =
        luminance_readings(comparison_spec(PreethamModel::kName, p.t),
                           comparison_spec(CieSkyModel::kName, p.type), cs, grid);
    const std::array<std::pair<const char*, const LuminanceRatio*>, 4> readings = {
        {{"geometric mean over the sky", &k.geometric_mean},
         {"sky maxima (5 deg around the sun left out)", &k.peak},
         {"zenith", &k.zenith},
         {"diffuse horizontal illuminance", &k.diffuse}}};
    int holding = 0;
    std::string hold, fail;
    std::vector<FindingValue> values;
    for (const auto& [name, ratio] : readings) {
      const bool ok = pair_reading_holds(p, *ratio);
      holding += ok;
      (ok ? hold : fail) += fmt::format("{}{} {}-{}", (ok ? hold : fail).empty() ? "" : "; ", name,
                                        v3(ratio->min), v3(ratio->max));
      values.push_back({fmt::format("Y_Pr/Y_CIE, {}, Kittler-Darula typical Lz, θs {} deg: "
                                    "min over the sun positions",
                                    name, zs),
                        ratio->min});
      values.push_back({"the same: max", ratio->max});
    }
    values.push_back({"geometric mean with the CIE Lz at the band's low end", r.against_cie_low});
    values.push_back({"the same at the band's high end", r.against_cie_high});
    summary_.findings.push_back(
        {.id = fmt::format("pair_T{:g}_cie{}", p.t, p.type),
         .title = fmt::format("Preetham T {:g} against CIE type {}: absolute level", p.t, p.type),
         .paper_statement = fmt::format(
             "Preetham T = {:g} resembles CIE type {} \"but with different absolute luminances "
             "(with values from [KD06])\": Y_Pr / Y_CIE {} for 15 < θs < 70 (§6 table).",
             p.t, p.type, p.ratio),
         .paper_value_text = fmt::format("Y_Pr/Y_CIE {}", p.ratio),
         .our_values = values,
         .agreement = agreement_of(holding, static_cast<int>(readings.size())),
         .cause = fmt::format(
             "Zotti compared maps side by side, so which ratio he read is not stated; each "
             "reading is tested at every sun position (θs {} deg). Holds: {}. Does not hold: {}. "
             "With the CIE zenith luminance at the ends of the Kittler-Darula band (our own "
             "derivation, docs/REPORT.md) the geometric mean spans {}-{}: that the absolute "
             "level Zotti used lay elsewhere in this band is a hypothesis, not tested here.",
             zs, hold.empty() ? "none" : hold, fail.empty() ? "none" : fail, v3(r.against_cie_high),
             v3(r.against_cie_low))});
    band_rows.push_back({{"turbidity", p.t},
                         {"cie_type", p.type},
                         {"ratio_typical", num(r.typical)},
                         {"ratio_cie_low", num(r.against_cie_low)},
                         {"ratio_cie_high", num(r.against_cie_high)},
                         {"ratio_peak", num(k.peak.mean)},
                         {"ratio_zenith", num(k.zenith.mean)},
                         {"ratio_diffuse_illuminance", num(k.diffuse.mean)},
                         {"sun_zeniths_deg", cfg_.pair_sun_zeniths_deg},
                         {"zotti_2007", p.ratio}});
  }
  json_["zotti_pairs_band"] = band_rows;
}

// 7-8. Circumsolar brightening and the horizon at low sun (zenith-normalised shape).
void ReportWriter::finding_low_sun(const HemisphereGrid& zone_grid) {
  const double fit_t = summary_.best_turbidity_for_cie12.turbidity;
  const double inner = kRingInnerDeg * kDegree, outer = kRingOuterDeg * kDegree;
  const auto ring = [=](Vec3 v, Vec3 s) {
    const double a = angle_between(v, s);
    return a >= inner && a <= outer;
  };
  const double band = kHorizonBandDeg * kDegree, away = kHorizonSunDistanceDeg * kDegree;
  const auto horizon = [=](Vec3 v, Vec3 s) {
    return v.z <= std::sin(band) && angle_between(v, s) >= away;
  };
  Range cs_rel, hz_rel, hz_abs;
  for (double d : cfg_.low_sun_zeniths_deg) {
    const RegionRatio c = preetham_against_cie12(fit_t, d, zone_grid, ring);
    cs_rel.add(c.relative_min, c.relative_max);
    const RegionRatio h = preetham_against_cie12(kHorizonTurbidity, d, zone_grid, horizon);
    hz_rel.add(h.relative_min, h.relative_max);
    hz_abs.add(h.absolute_min, h.absolute_max);
  }
  const std::string zs = degrees_list(cfg_.low_sun_zeniths_deg);
  const bool weaker = cs_rel.hi() < 1.0;
  summary_.findings.push_back(
      {.id = "circumsolar_brightening",
       .title = "Brightening around the sun too weak",
       .paper_statement =
           "\"the brightening around the sun is too weak\"; \"the brightness peak towards the sun "
           "is not as steep as ... modelled by the CIE Clear-Sky models\" (§6).",
       .paper_value_text = "qualitative: weaker than CIE 12",
       .our_values = {{fmt::format("zenith-normalised Preetham/CIE 12, {:g}-{:g} deg from the "
                                   "sun, T = {:.3g}, θs {} deg: min",
                                   kRingInnerDeg, kRingOuterDeg, fit_t, zs),
                       cs_rel.lo()},
                      {"the same: max", cs_rel.hi()}},
       .agreement = weaker ? Agreement::agrees : Agreement::disagrees,
       .cause = fmt::format(
           "Relative to its zenith, Preetham's circumsolar ring is {}-{} of CIE 12's: {}.",
           v3(cs_rel.lo()), v3(cs_rel.hi()),
           weaker ? "weaker, as Zotti says" : "not weaker everywhere")});
  const bool shape_brighter = hz_rel.lo() > 1.0, level_brighter = hz_abs.lo() > 1.0;
  summary_.findings.push_back(
      {.id = "horizon_bright_t_above_2_4",
       .title = "Horizon unnaturally bright for T > 2.4 at low sun",
       .paper_statement =
           "\"Even for T > 2.4 the horizon is shown unnaturally bright when the sun is low "
           "(θs >~ 60)\" (§6).",
       .paper_value_text = "qualitative: horizon brighter than CIE 12",
       .our_values = {{fmt::format("zenith-normalised Preetham/CIE 12, view elevation below {:g} "
                                   "deg, more than {:g} deg from the sun, T = {:g}, θs {} "
                                   "deg: min",
                                   kHorizonBandDeg, kHorizonSunDistanceDeg, kHorizonTurbidity, zs),
                       hz_rel.lo()},
                      {"the same: max", hz_rel.hi()},
                      {"absolute: min", hz_abs.lo()},
                      {"absolute: max", hz_abs.hi()}},
       .agreement = agreement_of(int{shape_brighter} + int{level_brighter}, 2),
       .cause = fmt::format(
           "Two readings. Absolute luminance: Preetham's horizon band is {}-{} times CIE 12's "
           "(the typical Kittler-Darula level): {}. Shape (each normalised to its zenith): {}-{} "
           "times: {}. {}",
           v3(hz_abs.lo()), v3(hz_abs.hi()), level_brighter ? "brighter, agrees" : "not brighter",
           v3(hz_rel.lo()), v3(hz_rel.hi()),
           shape_brighter ? "brighter, agrees" : "not brighter, does not agree",
           level_brighter && !shape_brighter
               ? "The bright horizon is Preetham's absolute level, not a horizon glow."
               : "")});
}

// 10. Fig. 3: at low turbidity and a low sun the horizon under the sun outshines the sun's
// vicinity on the solar vertical.
void ReportWriter::finding_fig3() {
  constexpr double kFig3SunZenithDeg = 72.0;  // Zotti Fig. 3
  constexpr double kHorizonElevationDeg = 0.5;
  const auto model = make_model(comparison_spec(PreethamModel::kName, kLowTurbidity),
                                kFig3SunZenithDeg * kDegree, kPi);
  // The solar vertical: azimuth of the sun (south, 180 deg), elevation e.
  auto on_vertical = [&](double elevation_deg) {
    const double e = elevation_deg * kDegree;
    return model->tristimulus(Vec3{0.0, -std::cos(e), std::sin(e)}).Y;
  };
  const double sun_elevation = 90.0 - kFig3SunZenithDeg;
  const double horizon = on_vertical(kHorizonElevationDeg);
  const double vicinity = on_vertical(sun_elevation + kRingInnerDeg);
  summary_.findings.push_back(
      {.id = "fig3_horizon_outshines_sun_vicinity",
       .title = "Horizon brighter than the sun's vicinity at T 1.8 (Fig. 3)",
       .paper_statement = "Fig. 3 (T = 1.8, θs = 72): on the solar vertical Preetham's horizon "
                          "is brighter than the sky around the sun, unlike a clear sky.",
       .paper_value_text = "horizon brighter than the sun's vicinity",
       .our_values = {{fmt::format("Preetham T = {:g}, θs = {:g} deg: luminance at elevation "
                                   "{:g} deg under the sun [cd/m^2]",
                                   kLowTurbidity, kFig3SunZenithDeg, kHorizonElevationDeg),
                       horizon},
                      {fmt::format("the same {:g} deg above the sun [cd/m^2]", kRingInnerDeg),
                       vicinity}},
       .agreement = horizon > vicinity ? Agreement::agrees : Agreement::disagrees,
       .cause = fmt::format("The horizon under the sun has {} cd/m^2, {} deg above the sun {} "
                            "cd/m^2: the horizon is {}.",
                            v3(horizon), kRingInnerDeg, v3(vicinity),
                            horizon > vicinity ? "brighter, as Fig. 3 shows" : "not brighter")});
}

// 11. §4: only the clear CIE types (11-15) are comparable with Preetham.
void ReportWriter::finding_cie_classes() {
  std::vector<FindingValue> values;
  int clear = 0;
  std::string types;
  for (const CieTypeMatch& m : summary_.cie_matches) {
    values.push_back({fmt::format("best CIE type for Preetham T = {:g}", m.turbidity),
                      static_cast<double>(m.best_type)});
    clear += m.best_type >= 11 && m.best_type <= 15;
    types += fmt::format("{}T {:g}: {}", types.empty() ? "" : ", ", m.turbidity, m.best_type);
  }
  const int n = static_cast<int>(summary_.cie_matches.size());
  summary_.findings.push_back(
      {.id = "only_clear_types_comparable",
       .title = "Only CIE types 11-15 are comparable (§4)",
       .paper_statement = "§4: of the CIE standard skies, only the clear types 11-15 are "
                          "comparable with Preetham's model.",
       .paper_value_text = "best-matching types within 11-15",
       .our_values = values,
       .agreement = clear == n ? Agreement::agrees : Agreement::disagrees,
       .cause = fmt::format("The best CIE type by the zenith-normalised RMS (section 4's table): "
                            "{}; {} of {} lie in 11-15{}.",
                            types, clear, n,
                            clear == n ? "" : ": Preetham's skies also match intermediate types")});
}

// 12. The pairs' shapes: each pair's CIE type should rank first of the 16 at its turbidity.
void ReportWriter::finding_pair_shapes() {
  std::vector<FindingValue> values;
  int first = 0;
  std::string ranks;
  for (const ZottiPair& p : kZottiPairs) {
    const CieTypeMatch m =
        rank_cie_types(comparison_spec(PreethamModel::kName, p.t), cfg_.comparison);
    int rank = 1;
    for (int t = 0; t < kCieTypeCount; ++t)
      rank += m.rms_by_type[static_cast<std::size_t>(t)] <
              m.rms_by_type[static_cast<std::size_t>(p.type - 1)];
    values.push_back(
        {fmt::format("rank of CIE type {} among 16 for Preetham T = {:g}", p.type, p.t),
         static_cast<double>(rank)});
    first += rank == 1;
    ranks +=
        fmt::format("{}T {:g} -> type {}: rank {}", ranks.empty() ? "" : ", ", p.t, p.type, rank);
  }
  summary_.findings.push_back(
      {.id = "pair_shapes",
       .title = "Each pair's CIE type is the closest in shape (§6 table)",
       .paper_statement = "§6 table: Preetham T 10, 5, 2.9 resemble CIE types 6, 7, 10 in the "
                          "luminance distribution.",
       .paper_value_text = "T 10 ~ 6, T 5 ~ 7, T 2.9 ~ 10",
       .our_values = values,
       .agreement = agreement_of(first, static_cast<int>(kZottiPairs.size())),
       .cause = fmt::format("By the zenith-normalised RMS over θs {} deg: {}.",
                            degrees_list(sun_zeniths_deg(cfg_.comparison)), ranks)});
}

// 13. Preetham's fitted range: a declaration of the paper, carried into domain().
void ReportWriter::finding_fitted_range() {
  summary_.findings.push_back(
      {.id = "fitted_range_declared",
       .title = "Preetham fitted for T 2-6",
       .paper_statement = "Preetham's coefficients were fitted for turbidities 2-6; Zotti's "
                          "findings concern their use outside (§3, §6).",
       .paper_value_text = "T 2-6 (declared)",
       .our_values = {{"fitted range: lowest T", kPreethamFittedTurbidityMin},
                      {"fitted range: highest T", kPreethamFittedTurbidityMax}},
       .agreement = Agreement::not_tested,
       .cause = "A declaration, not a finding a number can test: the model's domain() reports T "
                "outside it as extrapolated (section 8)."});
}

// 9. The measurements.
void ReportWriter::finding_measurements() {
  summary_.findings.push_back(
      {.id = "measurements",
       .title = "Measured skies (Fig. 2)",
       .paper_statement =
           "Measured clear skies (Fig. 2, Minolta LS-110) show luminance patterns \"not "
           "reproducible by the Preetham model, but ... reasonably close to the CIE Clear Sky "
           "models\" (§7).",
       .paper_value_text = "measurements close to CIE clear skies, not Preetham",
       .our_values = {{"best CIE type for the scan (zenith-normalised RMS)",
                       static_cast<double>(scan_best_cie_type_)},
                      {"scan is synthetic (1) or a measurement (0)", scan_synthetic_ ? 1.0 : 0.0}},
       // A measured scan is judged by its nearest CIE type: a clear type (11-15) agrees.
       .agreement = scan_synthetic_                                          ? Agreement::not_tested
                    : scan_best_cie_type_ >= 11 && scan_best_cie_type_ <= 15 ? Agreement::agrees
                                                                             : Agreement::disagrees,
       .cause =
           scan_synthetic_
               ? fmt::format(
                     "Not reproduced: Zotti's measurements are not published. The shipped "
                     "scan is synthetic (CIE type 7 plus 5 % noise), so its best type, {}, is "
                     "a self-test of the comparison, not evidence.",
                     scan_best_cie_type_)
               : fmt::format("A user scan was given (best CIE type {}); Zotti's own measurements "
                             "(Fig. 2) are not published, so his statement is not tested here.",
                             scan_best_cie_type_)});
}

std::string ReportWriter::findings_summary_html() const {
  std::map<Agreement, int> count;
  std::string not_reproduced;
  for (const Finding& f : summary_.findings) {
    ++count[f.agreement];
    if (f.agreement != Agreement::agrees)
      not_reproduced +=
          fmt::format("<li>{} ({})</li>\n", esc(f.title), agreement_name(f.agreement));
  }
  std::string items;
  for (const Finding& f : summary_.findings) {
    std::string ours;
    for (const auto& v : f.our_values)
      ours += (ours.empty() ? "" : "; ") + fmt::format("{} = <b>{}</b>", esc(v.name), v3(v.value));
    items += fmt::format("<li><b>{}</b> — <i>{}</i>. Zotti: {}. Ours: {}. {}</li>\n", esc(f.title),
                         agreement_name(f.agreement), esc(f.paper_value_text), ours, esc(f.cause));
  }
  return fmt::format(
      "<div class=\"note\">\n<p>This report <b>partly reproduces</b> Zotti et al. 2007: of {} "
      "findings, {} agree with our numbers, {} partly (some of their readings), {} disagree and "
      "{} are not tested. Not fully reproduced:</p>\n<ul>\n{}"
      "<li>the lower halves of Figs. 6/7 (Preetham with the CIE function, eq. 5)</li>\n"
      "<li>Kittler &amp; Darula's published minimum/maximum zenith luminances (Fig. 5): not "
      "available to us; the band used here is our derivation from their typical parameters "
      "(docs/REPORT.md)</li>\n</ul>\n<ul>\n{}</ul>\n</div>\n",
      summary_.findings.size(), count[Agreement::agrees], count[Agreement::partly],
      count[Agreement::disagrees], count[Agreement::not_tested], not_reproduced, items);
}

std::string ReportWriter::findings_table_html() const {
  HtmlTable t({"finding", "Zotti 2007", "ours", "agrees", "cause"},
              {false, true, true, false, true});
  for (const Finding& f : summary_.findings) {
    std::string ours;
    for (const auto& v : f.our_values)
      ours += (ours.empty() ? "" : "<br/>") + fmt::format("{}: {}", esc(v.name), v3(v.value));
    t.row({esc(f.title), esc(f.paper_statement), ours, agreement_name(f.agreement), esc(f.cause)});
  }
  return t.html();
}

}  // namespace detail
}  // namespace skylight::report
