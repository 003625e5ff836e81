// "Which model to trust where": the report's answer to its title, generated from the registry
// (docs/REPORT.md, "Which model to trust where"). For every registered model with a report policy,
// and each regime of sun elevation and sky class, its best luminance distribution within its own
// domain against the CIE standard skies of that class (CIE S 011/E:2003), with a verdict whose
// rule is printed beside the table and whose thresholds are measured in the same run.
#include <algorithm>
#include <map>

#include "skylight/core/error.h"
#include "skylight/models/cie_sky.h"
#include "skylight/models/nishita.h"
#include "skylight/report/detail/writer.h"

namespace skylight::report::detail {
namespace {

// The CIE standard skies by class (CIE S 011/E:2003 Table 1: types 1-5 overcast, 6-10
// intermediate, 11-15 clear); type 16, the traditional overcast sky, is not a class member.
struct SkyClass {
  const char* name;
  int first_type, last_type;
};
constexpr std::array<SkyClass, 3> kSkyClasses = {
    {{"overcast", 1, 5}, {"intermediate", 6, 10}, {"clear", 11, 15}}};

// One number of a cell as the table prints it.
std::string rms_text(double v) {
  return std::isfinite(v) ? fmt::format("{:.3f}", v) : "n/a";
}

// The factor a RMS of log10 ratios stands for, as the page explains it ("0.05 ≈ ×1.12").
std::string factor_text(double rms) {
  return fmt::format("×{:.2f}", std::pow(10.0, rms));
}

// The CSS class of a verdict's word (report.cpp's style sheet).
std::string verdict_class(TrustVerdict v) {
  return v == TrustVerdict::use ? "use" : v == TrustVerdict::care ? "care" : "avoid";
}

// The spec's domain() is valid or extrapolated at every sun zenith (a value the model refuses is
// outside).
bool within_domain(const ModelSpec& spec, const std::vector<double>& sun_zeniths,
                   double sun_azimuth) {
  for (double z : sun_zeniths) {
    try {
      const Validity w = make_model(spec, z, sun_azimuth)->domain().worst();
      if (w != Validity::valid && w != Validity::extrapolated) return false;
    } catch (const InvalidArgument&) {
      return false;
    }
  }
  return true;
}

// The standard skies of `settings` (types 1..count) and, per class, the median RMS between
// neighbouring types (4 steps per class: the upper middle), the rule's yardstick.
struct StandardSkies {
  std::vector<RelativeSamples> types;
  std::array<double, kSkyClasses.size()> neighbour{};
};
StandardSkies standard_skies(const ComparisonSettings& settings, const HemisphereGrid& grid,
                             int count) {
  StandardSkies r;
  for (int type = 1; type <= count; ++type)
    r.types.push_back(relative_samples(comparison_spec(CieSkyModel::kName, type), settings, grid));
  for (std::size_t k = 0; k < kSkyClasses.size(); ++k) {
    std::vector<double> steps;
    for (int t = kSkyClasses[k].first_type; t < kSkyClasses[k].last_type; ++t)
      steps.push_back(relative_log_rms(r.types[t - 1], r.types[t], grid));
    std::sort(steps.begin(), steps.end());
    r.neighbour[k] = steps[steps.size() / 2];
  }
  return r;
}

// The comparison settings with the sun elevations of a trust band (as sun zenith angles).
ComparisonSettings with_band_suns(const ComparisonSettings& comparison, const TrustBand& band) {
  ComparisonSettings s = comparison;
  s.sun_zeniths.clear();
  for (double e : band.sun_elevations_deg) s.sun_zeniths.push_back((90.0 - e) * kDegree);
  return s;
}

// The settings of the trust table in a band: its sun elevations on the trust grid.
ComparisonSettings trust_settings(const Config& cfg, const TrustBand& band) {
  ComparisonSettings s = with_band_suns(cfg.comparison, band);
  s.n_theta = cfg.trust_n_theta;
  s.n_phi = cfg.trust_n_phi;
  return s;
}

// The settings of the measured maps at one sun zenith [deg] on the trust grid.
ComparisonSettings one_sun_settings(const Config& cfg, double deg) {
  ComparisonSettings s = cfg.comparison;
  s.sun_zeniths = {deg * kDegree};
  s.n_theta = cfg.trust_n_theta;
  s.n_phi = cfg.trust_n_phi;
  return s;
}

// A band's column header: its name and its range of sun elevations.
std::string band_header(const TrustBand& band) {
  return fmt::format("{}<br/>{:g}–{:g}°", band.name, band.elevation_lo_deg, band.elevation_hi_deg);
}

// The CIE skies per trust band and type, and the measured step between neighbouring types per
// class.
struct BandStandards {
  std::vector<std::vector<RelativeSamples>> cie;
  std::vector<std::array<double, kSkyClasses.size()>> neighbour;
};
BandStandards band_standards(const Config& cfg, const HemisphereGrid& grid) {
  BandStandards r;
  r.cie.resize(cfg.trust_bands.size());
  r.neighbour.resize(cfg.trust_bands.size());
  for (std::size_t b = 0; b < cfg.trust_bands.size(); ++b) {
    StandardSkies sky =
        standard_skies(trust_settings(cfg, cfg.trust_bands[b]), grid, kCieTypeCount);
    r.cie[b] = std::move(sky.types);
    r.neighbour[b] = sky.neighbour;
  }
  return r;
}

// The list item of a model the trust table does not judge.
std::string not_judged_item(const std::string& model) {
  return fmt::format(
      "<li><code>{}</code>: not judged (it has no report policy, ReportPolicy in its registry "
      "entry)</li>\n",
      model);
}

// A model's sky in a band that lies within its domain, with its RMS against every standard type
// (1-15) and the class of its nearest type.
struct Sky {
  ModelSpec spec;
  std::array<double, 15> rms;
  std::size_t nearest_class;
};

// The model's skies in one band (settings s, the band's standard skies cie) that lie within its
// domain and, for a model with a source, its own samples and its source's (for the comparison
// with its source).
struct BandSkies {
  std::vector<Sky> skies;
  std::vector<RelativeSamples> own, source;
};
BandSkies band_skies(const ModelInfo& info, const std::vector<std::optional<double>>& values,
                     const ComparisonSettings& s, const HemisphereGrid& grid,
                     const std::vector<RelativeSamples>& cie) {
  BandSkies r;
  for (const auto& v : values) {
    const ModelSpec spec = comparison_spec(info.name, v);
    if (!within_domain(spec, s.sun_zeniths, s.sun_azimuth)) continue;
    RelativeSamples samples = relative_samples(spec, s, grid);
    if (!info.report.source.empty()) {  // its source at the same sun and axis value
      r.own.push_back(samples);
      r.source.push_back(relative_samples(comparison_spec(info.report.source, v), s, grid));
    }
    Sky sky{spec, {}, 0};
    int nearest = 1;
    for (int t = 1; t <= 15; ++t) {
      sky.rms[t - 1] = relative_log_rms(samples, cie[t - 1], grid);
      if (sky.rms[t - 1] < sky.rms[nearest - 1]) nearest = t;
    }
    for (std::size_t k = 0; k < kSkyClasses.size(); ++k)
      if (nearest >= kSkyClasses[k].first_type && nearest <= kSkyClasses[k].last_type)
        sky.nearest_class = k;
    r.skies.push_back(std::move(sky));
  }
  return r;
}

// A model's best sky for class k: the smallest RMS against a type of the class, its sky and that
// type, and how many skies stand for the class. Only the skies whose nearest standard sky is of
// this class stand for it: a clear sky is not judged as an overcast one because the overcast types
// differ widely.
struct ClassBest {
  double rms = kInf;
  std::string label;
  int type = 0;
  std::size_t members = 0;
};
ClassBest class_best(const std::vector<Sky>& skies, std::size_t k) {
  const SkyClass& c = kSkyClasses[k];
  ClassBest r;
  for (const Sky& sky : skies) {
    if (sky.nearest_class != k) continue;
    ++r.members;
    for (int t = c.first_type; t <= c.last_type; ++t)
      if (sky.rms[t - 1] < r.rms) {
        r.rms = sky.rms[t - 1];
        r.label = sky.spec.label;
        r.type = t;
      }
  }
  return r;
}

// The trust table's cell of class c: the verdict on the model's best sky of the class, or why it
// has none (in_domain: the number of its skies within its domain in the band).
std::string class_cell(TrustVerdict verdict, const ClassBest& best, std::size_t in_domain,
                       const SkyClass& c) {
  if (verdict == TrustVerdict::reference) return "reference";
  if (in_domain == 0)
    return "<span class=\"verdict-avoid\">avoid</span><br/><small>outside its domain</small>";
  if (best.members == 0)
    return fmt::format(
        "<span class=\"verdict-avoid\">avoid</span><br/><small>none of its "
        "{} skies is nearest to a {} type</small>",
        in_domain, c.name);
  return fmt::format(
      "<span class=\"verdict-{}\">{}</span><br/><small>{} ({}) · {} vs CIE {}</small>",
      verdict == TrustVerdict::use    ? "use"
      : verdict == TrustVerdict::care ? "care"
                                      : "avoid",
      trust_verdict_name(verdict), rms_text(best.rms), factor_text(best.rms), best.label,
      best.type);
}

// report.json's record of a model in one regime (band and class) of the trust table.
Json regime_json(const TrustBand& band, const SkyClass& c, const ClassBest& best, double neighbour,
                 std::size_t in_domain, TrustVerdict verdict) {
  return {{"sun_elevation_deg", {band.elevation_lo_deg, band.elevation_hi_deg}},
          {"sky_class", c.name},
          {"cie_types", {c.first_type, c.last_type}},
          {"best_rms_log10", num(best.rms)},
          {"best_sky", best.label},
          {"best_cie_type", best.type},
          {"neighbour_rms_log10", num(neighbour)},
          {"skies_in_domain", in_domain},
          {"skies_nearest_to_this_class", best.members},
          {"verdict", trust_verdict_name(verdict)}};
}

// A table cell and its record in report.json.
struct Cell {
  std::string html;
  Json json;
};

// A model against its source in a band: the error of its skies within its domain against its
// source's at the same sun and axis values, judged against the band's smallest neighbour step
// between CIE types.
Cell source_cell(const std::string& source_name, const TrustBand& band, const BandSkies& sk,
                 const std::array<double, kSkyClasses.size()>& neighbour,
                 const HemisphereGrid& grid) {
  std::vector<const RelativeSamples*> a, r;
  for (std::size_t i = 0; i < sk.own.size(); ++i) {
    a.push_back(&sk.own[i]);
    r.push_back(&sk.source[i]);
  }
  const SourceError e = source_error(a, r, grid);
  const double step = *std::min_element(neighbour.begin(), neighbour.end());
  const TrustVerdict verdict =
      sk.own.empty() ? TrustVerdict::avoid : trust_verdict(e.rms_log10, step);
  Cell cell;
  cell.html = sk.own.empty()
                  ? "<span class=\"verdict-avoid\">avoid</span><br/><small>outside its "
                    "domain</small>"
                  : fmt::format(
                        "<span class=\"verdict-{}\">{}</span><br/><small>median {:.1f} %, "
                        "p95 {:.1f} %, RMS log<sub>10</sub> {} [{}]</small>",
                        verdict_class(verdict), trust_verdict_name(verdict), 100.0 * e.median,
                        100.0 * e.p95, rms_text(e.rms_log10), rms_text(step));
  cell.json = {{"source", source_name},
               {"sun_elevation_deg", {band.elevation_lo_deg, band.elevation_hi_deg}},
               {"skies_in_domain", sk.own.size()},
               {"relative_error_median", num(e.median)},
               {"relative_error_p95", num(e.p95)},
               {"rms_log10", num(e.rms_log10)},
               {"smallest_neighbour_rms_log10", num(step)},
               {"verdict", trust_verdict_name(verdict)}};
  return cell;
}

// The plain-language summary's line of a judged model: the regimes of each verdict.
std::string summary_line(const std::string& model,
                         const std::map<TrustVerdict, std::vector<std::string>>& by_verdict) {
  auto list = [&](TrustVerdict v) {
    std::string t;
    if (const auto it = by_verdict.find(v); it != by_verdict.end())
      for (const auto& regime : it->second) t += (t.empty() ? "" : ", ") + regime;
    return t.empty() ? std::string("none") : t;
  };
  return fmt::format("<b>{}</b>: use for {}; with care for {}; avoid elsewhere.", model,
                     list(TrustVerdict::use), list(TrustVerdict::care));
}

// The neighbour steps of this run as the page lists them ("low sun overcast: 0.123; ...").
std::string neighbour_steps_text(
    const std::vector<TrustBand>& bands,
    const std::vector<std::array<double, kSkyClasses.size()>>& neighbour) {
  std::string neighbours;
  for (std::size_t b = 0; b < bands.size(); ++b)
    for (std::size_t k = 0; k < kSkyClasses.size(); ++k)
      neighbours += fmt::format("{}{} {}: {}", neighbours.empty() ? "" : "; ", bands[b].name,
                                kSkyClasses[k].name, rms_text(neighbour[b][k]));
  return neighbours;
}

// The trust table's part of the page: its rule with this run's neighbour steps, the table, the
// models not judged, and the approximations against their source with its rule.
std::string trust_tables_html(double sun_exclusion_deg, const std::string& bands,
                              const std::string& neighbours, const std::string& table,
                              const std::string& not_judged, const std::string& source_tables) {
  return fmt::format(
      "<p>Each cell: the model's sky closest to a CIE standard sky of the class (CIE S 011/E:2003: "
      "types 1–5 overcast, 6–10 intermediate, 11–15 clear), over the values of its report "
      "parameter that lie within its own domain (<code>domain()</code> valid or extrapolated at "
      "every sun elevation of the band) and whose nearest standard sky of all 15 is of that "
      "class (a model none of whose skies is nearest to a type of the class cannot make that "
      "sky: <i>avoid</i>), measured as the RMS of log<sub>10</sub> of the "
      "zenith-normalised luminance ratio (solid-angle weighted, {:g}° around the sun left out; "
      "sun elevations {}). <b>Rule</b>: <i>use</i> when that RMS is at most {:g} × the median RMS "
      "between neighbouring CIE types of the class in the same band (the model reproduces a "
      "standard sky more closely than the standard skies differ from each other); <i>use with "
      "care</i> up to {:g} ×; otherwise <i>avoid</i>. The neighbour steps of this run: {}. The "
      "distribution only, except the last column: the shape of the measured clear skies by the "
      "same rule against the clear class's step at their sun (<a href=\"#measured-skies\">Against "
      "measured skies</a>, where absolute level and spectrum are judged too); colour and twilight "
      "are judged in the tables below; absolute luminance and spectrum have no verdict elsewhere "
      "(<a href=\"#trust-not-judged\">why</a>).</p>\n{}{}"
      "<h3 id=\"trust-source\">Approximations against their source</h3>\n<p>A model that "
      "approximates another with its default data (its report policy's <code>source</code>: a "
      "trained network, a fitted table) against that model at the same sun and parameter "
      "values, within its domain: the solid-angle-weighted median and 95th percentile of the "
      "relative luminance error, and the RMS of log<sub>10</sub> of the ratio (not normalised; "
      "negative values count as 1000 times too dark). <b>Rule</b>: the same fractions ({:g} ×, "
      "{:g} ×) of the band's smallest neighbour step between CIE types [in brackets]: below "
      "them the approximation inherits its source's verdicts above.</p>\n{}",
      sun_exclusion_deg, bands, kTrustUseFraction, kTrustCareFraction, neighbours, table,
      not_judged.empty() ? "" : "<ul>\n" + not_judged + "</ul>\n", kTrustUseFraction,
      kTrustCareFraction, source_tables);
}

// The model's sky closest to the physical atmosphere `reference` over its axis values within its
// domain (in colour; at twilight in luminance) and its label (empty where none is).
struct Closest {
  ColourDifference best{kNaN, kNaN, kNaN, 0};
  std::string label;
};
Closest closest_to_reference(const std::string& model,
                             const std::vector<std::optional<double>>& values,
                             const std::string& reference, const ComparisonSettings& s,
                             const HemisphereGrid& grid, bool twilight) {
  Closest r;
  for (const auto& v : values) {
    const ModelSpec spec = comparison_spec(model, v);
    if (!within_domain(spec, s.sun_zeniths, s.sun_azimuth)) continue;
    const ColourDifference d = colour_difference(spec, comparison_spec(reference), s, grid);
    const double key = twilight ? d.rms_log10 : d.mean_duv;
    const double best_key = twilight ? r.best.rms_log10 : r.best.mean_duv;
    if (std::isfinite(key) && !(key >= best_key)) {
      r.best = d;
      r.label = spec.label;
    }
  }
  return r;
}

// A model's cell in a band of the table against the physical atmosphere `reference`: the
// reference itself, not judged (luminance only, or undefined at twilight), outside its domain, or
// the verdict on its closest sky (colour; at twilight the worse of luminance against `step`, the
// smallest CIE neighbour step, and colour).
Cell physical_band_cell(const ModelInfo& info, const std::string& reference, const TrustBand& band,
                        bool twilight, const std::vector<std::optional<double>>& values,
                        const ComparisonSettings& s, const HemisphereGrid& grid, double step) {
  if (info.name == reference)
    return {"reference", Json{{"band", band.name}, {"verdict", "reference"}}};
  if (!twilight && info.luminance_only)
    return {"n/a<br/><small>grey by design (luminance only)</small>",
            Json{{"band", band.name}, {"verdict", "not judged"}, {"reason", "luminance only"}}};
  // The model's sky closest to the reference (in colour; at twilight in luminance).
  const Closest closest = closest_to_reference(info.name, values, reference, s, grid, twilight);
  const ColourDifference& best = closest.best;
  const std::string& best_label = closest.label;
  if (best_label.empty())
    return {twilight ? "n/a<br/><small>undefined with the sun below the horizon</small>"
                     : "<span class=\"verdict-avoid\">avoid</span><br/><small>outside "
                       "its domain</small>",
            Json{{"band", band.name},
                 {"verdict", twilight ? "not judged" : "avoid"},
                 {"reason", twilight ? "undefined below the horizon" : "outside domain"}}};
  TrustVerdict verdict =
      twilight ? trust_verdict(best.rms_log10, step) : colour_verdict(best.mean_duv);
  if (twilight && !info.luminance_only)  // the worse of luminance and colour
    verdict = std::max(verdict, colour_verdict(best.mean_duv));
  return {fmt::format("<span class=\"verdict-{}\">{}</span><br/><small>Δu′v′ {} (p95 {}), RMS "
                      "log<sub>10</sub> Y {} · {}</small>",
                      verdict_class(verdict), trust_verdict_name(verdict),
                      info.luminance_only ? "n/a" : fmt::format("{:.4f}", best.mean_duv),
                      info.luminance_only ? "n/a" : fmt::format("{:.4f}", best.p95_duv),
                      rms_text(best.rms_log10), best_label),
          Json{{"band", band.name},
               {"sun_elevation_deg", {band.elevation_lo_deg, band.elevation_hi_deg}},
               {"best_sky", best_label},
               {"mean_duv", info.luminance_only ? Json(nullptr) : num(best.mean_duv)},
               {"p95_duv", info.luminance_only ? Json(nullptr) : num(best.p95_duv)},
               {"rms_log10_luminance", num(best.rms_log10)},
               {"verdict", trust_verdict_name(verdict)}}};
}

// The text of the table against the physical atmosphere `reference`: its measures and rules
// (twilight's with `step`, the smallest CIE neighbour step), then the table.
std::string physical_table_html(const Config& cfg, const std::string& reference, double step,
                                const std::string& table) {
  return fmt::format(
      "<h3 id=\"trust-physical\">Colour and twilight against the physical atmosphere</h3>\n<p>"
      "Each model's sky closest to <code>{}</code> (its report title: the physical atmosphere, "
      "multiple scattering with its default orders; its own error against a path tracer in "
      "docs/ATMOSPHERE.md) "
      "over its parameter values within its "
      "domain, on a {} × {} grid, {:g}° around the sun left out. Colour: the solid-angle-weighted "
      "mean CIE 1976 chromaticity distance Δu′v′; <b>rule</b>: <i>use</i> up to {:g} (about "
      "the size of MacAdam's just-noticeable ellipses in u′v′), <i>use with care</i> up to {:g}, "
      "else <i>avoid</i>; a model that gives luminance only is not judged on colour. Twilight "
      "(sun {} deg): the RMS of log<sub>10</sub> of the luminance, with the rule of the tables "
      "above against the smallest neighbour step between CIE types above the horizon ({}), and "
      "the worse of that and the colour verdict; a model undefined below the horizon says "
      "so.</p>\n{}",
      reference, cfg.colour_n_theta, cfg.colour_n_phi, cfg.comparison.sun_exclusion / kDegree,
      kColourUseDuv, kColourCareDuv, degrees_list(cfg.twilight_band.sun_elevations_deg),
      rms_text(step), table);
}

// What the tables cannot judge, and why (the physical atmosphere is `reference`): printed, and in
// report.json, so that a missing verdict is a statement and not a gap. Absolute level and
// spectrum are judged against the measured clear skies for the models with a fit (section
// "Against measured skies"); the rest has no verdict.
Cell quantities_without_verdict(const std::string& reference) {
  std::string unfitted;
  for (const ModelInfo& info : model_registry())
    if (!info.report.title.empty() && !info.estimation)
      unfitted += fmt::format("{}<code>{}</code>", unfitted.empty() ? "" : ", ", info.name);
  const std::string measured = fmt::format(
      "judged against the measured clear skies for the models fitted to them (<a "
      "href=\"#measured-skies\">Against measured skies</a>); no verdict for the models without a "
      "fit ({}) nor for overcast and intermediate skies, which were not measured",
      unfitted);
  const std::vector<std::pair<std::string, std::string>> without_verdict = {
      {"absolute illuminance",
       fmt::format(
           "{}: there the report has no reference it trusts for the levels: the CIE absolute "
           "level is the Kittler-Darula typical zenith luminance, whose own band spans a factor "
           "3-4 (section 3), and the physical atmosphere ({}) with its default aerosols is one "
           "clean atmosphere (its diffuse horizontal illuminance is about half the CIE clear "
           "sky's); section 6 compares the levels without a verdict",
           measured, reference)},
      {"spectrum",
       fmt::format("{}: there the CIE standard skies give luminance only, and the physical "
                   "atmosphere ({}) is spectral but one clean atmosphere; spectral irradiance is "
                   "compared in section 6 without a verdict, and colour (above) is the "
                   "spectrum's judged projection",
                   measured, reference)}};
  std::string items;
  Json json_items = Json::array();
  for (const auto& [quantity, reason] : without_verdict) {
    items += fmt::format("<li><b>{}</b>: {}.</li>\n", quantity, reason);
    json_items.push_back({{"quantity", quantity}, {"reason", reason}});
  }
  return {fmt::format("<h3 id=\"trust-not-judged\">Absolute level and spectrum: where they have "
                      "no verdict</h3>\n<ul>\n{}</ul>\n",
                      items),
          std::move(json_items)};
}

// Cell edges halfway between samples, from lo to hi.
std::vector<double> cell_edges(const std::vector<double>& v, double lo, double hi) {
  std::vector<double> e{lo};
  for (std::size_t i = 1; i < v.size(); ++i) e.push_back(0.5 * (v[i - 1] + v[i]));
  e.push_back(hi);
  return e;
}

// The row edges of a model's measured map: one row without an axis, else halfway between its
// values (in log10 on a log axis).
std::vector<double> row_edges(const std::vector<double>& rows, bool has_axis, bool log_axis) {
  std::vector<double> ye;
  if (!has_axis) {
    ye = {0.0, 1.0};
  } else if (log_axis) {
    std::vector<double> logs;
    for (double r : rows) logs.push_back(std::log10(r));
    const double step = logs.size() > 1 ? logs[1] - logs[0] : 1.0;
    for (double e : cell_edges(logs, logs.front() - step / 2, logs.back() + step / 2))
      ye.push_back(std::pow(10.0, e));
  } else {
    ye = cell_edges(rows, rows.front() - 0.5, rows.back() + 0.5);
  }
  return ye;
}

// A cell of a measured map (the sky of `spec` at the one sun of s): the trust rule's verdict
// against the nearest of the 15 standard skies `cie` at that sun (0 use, 1 care, 2 avoid), or 3
// outside its domain.
int measured_class(const ModelSpec& spec, const ComparisonSettings& s, const HemisphereGrid& grid,
                   const std::vector<RelativeSamples>& cie,
                   const std::array<double, kSkyClasses.size()>& neighbour) {
  int cls = 3;
  if (within_domain(spec, s.sun_zeniths, s.sun_azimuth)) {
    const RelativeSamples sky = relative_samples(spec, s, grid);
    int nearest = 1;
    double best = kInf;
    for (int t = 1; t <= 15; ++t) {
      const double rms = relative_log_rms(sky, cie[t - 1], grid);
      if (rms < best) {
        best = rms;
        nearest = t;
      }
    }
    std::size_t k = 0;
    while (nearest > kSkyClasses[k].last_type) ++k;
    cls = static_cast<int>(trust_verdict(best, neighbour[k]));  // use, care, avoid
  }
  return cls;
}

// The index of the clear class in kSkyClasses.
constexpr std::size_t kClearClass = 2;

// The trust band whose sun elevations hold `elevation` [deg] (the nearest when none does).
std::size_t measured_band_index(const std::vector<TrustBand>& bands, double elevation) {
  std::size_t best = 0;
  double distance = kInf;
  for (std::size_t b = 0; b < bands.size(); ++b) {
    const double d = std::max(
        {0.0, bands[b].elevation_lo_deg - elevation, elevation - bands[b].elevation_hi_deg});
    if (d < distance) {
      distance = d;
      best = b;
    }
  }
  return best;
}

// The shape verdict of a model against the measured skies.
TrustVerdict measured_verdict(const MeasuredModel* m, double step) {
  return trust_verdict(m->shape_log10, step);
}

// The measured column's cell (the clear row): the shape verdict against the measured skies, or
// why there is none.
Cell measured_cell(const MeasuredModel* m, double step) {
  if (!m)
    return {"n/a<br/><small>not fitted to measured skies (no estimation policy)</small>",
            Json{{"verdict", "not judged"}, {"reason", "no estimation policy"}}};
  if (m->captures.empty())
    return {"n/a<br/><small>not compared in the quick report</small>",
            Json{{"verdict", "not judged"}, {"reason", "quick report"}}};
  const TrustVerdict v = measured_verdict(m, step);
  return {verdict_html(v, fmt::format("shape {:.1f} %, RMS log<sub>10</sub> {} [{}] · {} "
                                      "captures",
                                      100.0 * m->shape, rms_text(m->shape_log10), rms_text(step),
                                      m->captures.size())),
          Json{{"verdict", trust_verdict_name(v)},
               {"median_luminance_rms_shape", num(m->shape)},
               {"median_rms_log10", num(m->shape_log10)},
               {"clear_neighbour_rms_log10", num(step)},
               {"captures", m->captures.size()}}};
}

}  // namespace

std::string trust_verdict_name(TrustVerdict v) {
  switch (v) {
    case TrustVerdict::use:
      return "use";
    case TrustVerdict::care:
      return "use with care";
    case TrustVerdict::avoid:
      return "avoid";
    case TrustVerdict::reference:
      return "reference";
    case TrustVerdict::not_judged:
      break;
  }
  return "not judged";
}

TrustVerdict colour_verdict(double mean_duv) {
  if (!std::isfinite(mean_duv)) return TrustVerdict::avoid;
  if (mean_duv <= kColourUseDuv) return TrustVerdict::use;
  return mean_duv <= kColourCareDuv ? TrustVerdict::care : TrustVerdict::avoid;
}

TrustVerdict trust_verdict(double best_rms, double neighbour_rms) {
  if (!std::isfinite(best_rms) || !std::isfinite(neighbour_rms)) return TrustVerdict::avoid;
  if (best_rms <= kTrustUseFraction * neighbour_rms) return TrustVerdict::use;
  if (best_rms <= kTrustCareFraction * neighbour_rms) return TrustVerdict::care;
  return TrustVerdict::avoid;
}

void ReportWriter::section_trust() {
  const HemisphereGrid grid = hemisphere_grid(cfg_.trust_n_theta, cfg_.trust_n_phi);
  const std::string reference(CieSkyModel::kName);

  // The CIE skies per band and type, and the measured step between neighbouring types per class.
  const BandStandards standards = band_standards(cfg_, grid);
  const auto& neighbour = standards.neighbour;

  trust_min_neighbour_step_ = kInf;
  for (const auto& n : neighbour)
    for (double v : n) trust_min_neighbour_step_ = std::min(trust_min_neighbour_step_, v);
  // The measured skies' yardstick: the clear-class step of the band of their median sun.
  const std::size_t measured_band =
      measured_band_index(cfg_.trust_bands, measured_sun_elevation_deg_);
  measured_neighbour_step_ = neighbour[measured_band][kClearClass];
  Json models = Json::array();
  std::vector<std::string> headers = {"model", "sky class"};
  for (const TrustBand& band : cfg_.trust_bands) headers.push_back(band_header(band));
  std::vector<std::string> source_headers = {"model", "against"};
  source_headers.insert(source_headers.end(), headers.begin() + 2, headers.end());
  HtmlTable source_table(source_headers, {true, true});
  headers.push_back(fmt::format("measured clear skies<br/>Kider 2014, sun ≈ {:.0f}°",
                                measured_sun_elevation_deg_));
  HtmlTable table_with_measured(headers, {true, true});
  std::string truncation_html;
  std::string not_judged;
  std::vector<std::string> summary;  // the plain-language summary: one line per judged model
  for (const ModelInfo& info : model_registry()) {
    if (info.report.title.empty()) {
      not_judged += not_judged_item(info.name);
      models.push_back({{"model", info.name}, {"judged", false}});
      continue;
    }
    const std::vector<std::optional<double>> values = trust_axis_values(info);
    Json model_json = {{"model", info.name}, {"judged", true}, {"regimes", Json::array()}};
    std::map<TrustVerdict, std::vector<std::string>> by_verdict;  // "clear sky, low sun"
    std::vector<std::vector<std::string>> rows(kSkyClasses.size());
    std::vector<std::string> source_row;  // against its source, if it has one
    if (!info.report.source.empty())
      source_row = {fmt::format("<code>{}</code>", info.name),
                    fmt::format("<code>{}</code>", info.report.source)};
    for (std::size_t k = 0; k < kSkyClasses.size(); ++k)
      rows[k] = {fmt::format("<code>{}</code>", info.name), kSkyClasses[k].name};
    for (std::size_t b = 0; b < cfg_.trust_bands.size(); ++b) {
      const TrustBand& band = cfg_.trust_bands[b];
      // The model's skies in this band that lie within its domain.
      const BandSkies sk =
          band_skies(info, values, trust_settings(cfg_, band), grid, standards.cie[b]);
      for (std::size_t k = 0; k < kSkyClasses.size(); ++k) {
        const SkyClass& c = kSkyClasses[k];
        const ClassBest best = class_best(sk.skies, k);
        TrustVerdict verdict = info.name == reference ? TrustVerdict::reference
                                                      : trust_verdict(best.rms, neighbour[b][k]);
        rows[k].push_back(class_cell(verdict, best, sk.skies.size(), c));
        by_verdict[verdict].push_back(fmt::format("{} at {}", c.name, band.name));
        model_json["regimes"].push_back(
            regime_json(band, c, best, neighbour[b][k], sk.skies.size(), verdict));
      }
      if (!info.report.source.empty()) {
        const Cell cell = source_cell(info.report.source, band, sk, neighbour[b], grid);
        source_row.push_back(cell.html);
        model_json["against_source"].push_back(cell.json);
      }
    }
    const Cell measured = measured_cell(measured_model(info.name), measured_neighbour_step_);
    for (std::size_t k = 0; k < kSkyClasses.size(); ++k)
      rows[k].push_back(k == kClearClass ? measured.html : "—");
    model_json["measured_clear_skies"] = measured.json;
    if (const auto v = measured.json.find("verdict");
        v != measured.json.end() && v->is_string() && measured.json.contains("median_rms_log10"))
      by_verdict[measured_verdict(measured_model(info.name), measured_neighbour_step_)].push_back(
          "measured clear skies");
    if (!source_row.empty()) source_table.row(source_row);
    if (!info.report.truncation.empty()) truncation_html += truncation_table(info);
    for (auto& r : rows) table_with_measured.row(r);
    models.push_back(model_json);
    if (by_verdict.count(TrustVerdict::reference) == 0)
      summary.push_back(summary_line(info.name, by_verdict));
  }
  step("which model to trust where");

  html_trust_ = trust_tables_html(cfg_.comparison.sun_exclusion / kDegree, trust_band_text(),
                                  neighbour_steps_text(cfg_.trust_bands, neighbour),
                                  table_with_measured.html(), not_judged,
                                  source_table.html() + truncation_html);
  trust_summary_ = summary;
  json_["which_model_to_trust_where"] = {
      {"rule",
       fmt::format("use: best RMS <= {:g} x neighbour RMS; use with care: <= {:g} x; else avoid",
                   kTrustUseFraction, kTrustCareFraction)},
      {"models", models}};
  if (!truncation_json_.empty())
    json_["which_model_to_trust_where"]["truncation"] = truncation_json_;
}

void ReportWriter::physical_atmosphere_table() {
  // The registry's physical atmosphere (its ReportPolicy says so).
  std::string reference;
  for (const ModelInfo& info : model_registry())
    if (info.report.physical_reference) reference = info.name;
  SKYLIGHT_CHECK(!reference.empty(), "no model is the report's physical reference");
  const HemisphereGrid grid = hemisphere_grid(cfg_.colour_n_theta, cfg_.colour_n_phi);
  std::vector<TrustBand> bands = cfg_.trust_bands;
  bands.insert(bands.begin(), cfg_.twilight_band);
  // The luminance rule of the twilight cells: the smallest neighbour step between CIE types at
  // the lowest band above the horizon (the CIE skies themselves end at the horizon).
  const double step = trust_min_neighbour_step_;
  std::vector<std::string> headers = {"model"};
  for (const TrustBand& band : bands) headers.push_back(band_header(band));
  HtmlTable table(headers, {true});
  Json out = Json::object();
  for (const ModelInfo& info : model_registry()) {
    if (info.report.title.empty()) continue;
    std::vector<std::string> row = {fmt::format("<code>{}</code>", info.name)};
    Json cells = Json::array();
    const std::vector<std::optional<double>> values = trust_axis_values(info);
    for (std::size_t b = 0; b < bands.size(); ++b) {
      const TrustBand& band = bands[b];
      const bool twilight = b == 0;
      const ComparisonSettings s = with_band_suns(cfg_.comparison, band);
      const Cell cell = physical_band_cell(info, reference, band, twilight, values, s, grid, step);
      row.push_back(cell.html);
      cells.push_back(cell.json);
    }
    table.row(row);
    out[info.name] = cells;
  }
  html_trust_ += physical_table_html(cfg_, reference, step, table.html());
  json_["which_model_to_trust_where"]["against_physical_atmosphere"] = {
      {"reference", reference},
      {"colour_rule", fmt::format("use: mean du'v' <= {:g}; use with care: <= {:g}; else avoid",
                                  kColourUseDuv, kColourCareDuv)},
      {"twilight_rule",
       fmt::format("luminance RMS log10 against {} x / {} x the smallest CIE neighbour step {}",
                   kTrustUseFraction, kTrustCareFraction, rms_text(step))},
      {"models", out}};
  // What the tables above cannot judge, and why: printed, and in report.json, so that a
  // missing verdict is a statement and not a gap.
  Cell without = quantities_without_verdict(reference);
  html_trust_ += without.html;
  json_["which_model_to_trust_where"]["quantities_without_verdict"] = std::move(without.json);
}

std::vector<std::optional<double>> ReportWriter::trust_axis_values(const ModelInfo& info) const {
  // Every integer, or trust_axis_samples log-spaced values over the range it accepts (or the
  // policy's axis_range); one sky (no value) for a model the report does not vary.
  std::vector<std::optional<double>> values;
  if (info.report.axis.empty()) {
    values.push_back(std::nullopt);
    return values;
  }
  const ParameterSpec& p = *info.find_parameter(info.report.axis);
  const auto [lo, hi] = info.report.axis_range.value_or(std::array<double, 2>{p.min, p.max});
  if (p.kind == ParameterKind::integer) {
    for (double v = lo; v <= hi; v += 1.0) values.push_back(v);
    return values;
  }
  const int n = cfg_.trust_axis_samples;
  for (int i = 0; i < n; ++i) {
    const double f = n == 1 ? 0.5 : static_cast<double>(i) / (n - 1);
    values.push_back(lo > 0.0 ? lo * std::pow(hi / lo, f) : lo + f * (hi - lo));
  }
  return values;
}

void ReportWriter::measured_validity_maps() {
  const HemisphereGrid grid = hemisphere_grid(cfg_.trust_n_theta, cfg_.trust_n_phi);
  const std::string reference(CieSkyModel::kName);
  const std::vector<double>& zen_deg = cfg_.trust_map_sun_zeniths_deg;
  // Per sun zenith: the 15 standard skies and the median neighbour step of each class.
  std::vector<std::vector<RelativeSamples>> cie(zen_deg.size());
  std::vector<std::array<double, kSkyClasses.size()>> neighbour(zen_deg.size());
  for (std::size_t z = 0; z < zen_deg.size(); ++z) {
    StandardSkies sky = standard_skies(one_sun_settings(cfg_, zen_deg[z]), grid, 15);
    cie[z] = std::move(sky.types);
    neighbour[z] = sky.neighbour;
  }
  // Cell edges halfway between samples.
  const std::vector<double> xe = cell_edges(zen_deg, 0.0, 90.0);
  Json counts_json = Json::object();
  for (const ModelInfo& info : model_registry()) {
    if (info.report.title.empty() || info.name == reference) continue;
    const std::vector<std::optional<double>> values = trust_axis_values(info);
    std::vector<double> rows;
    for (const auto& v : values) rows.push_back(v.value_or(0.0));
    const bool has_axis = !info.report.axis.empty();
    const bool log_axis = has_axis && rows.front() > 0.0 &&
                          info.find_parameter(info.report.axis)->kind != ParameterKind::integer;
    const std::vector<double> ye = row_edges(rows, has_axis, log_axis);
    svg::Plot p;
    p.id = "measured-" + info.name;
    p.title = fmt::format("{}: measured against the CIE standard skies", info.name);
    p.x = {0, 90, false, "sun zenith angle θs [deg]", {0, 10, 20, 30, 40, 50, 60, 70, 80, 90}};
    p.y = has_axis ? svg::Axis{ye.front(), ye.back(), log_axis, info.report.axis, {}}
                   : one_row_axis();
    p.width = 760;
    p.height = has_axis ? 300 : 200;
    p.legend_outside = true;
    std::array<int, 4> counts{};
    static constexpr std::array<const char*, 4> kNames = {"use (≤ 0.5 × neighbour step)",
                                                          "use with care (≤ 1 ×)", "avoid (> 1 ×)",
                                                          "outside its domain"};
    for (std::size_t r = 0; r < values.size(); ++r) {
      const ModelSpec spec = comparison_spec(info.name, values[r]);
      for (std::size_t z = 0; z < zen_deg.size(); ++z) {
        const int cls =
            measured_class(spec, one_sun_settings(cfg_, zen_deg[z]), grid, cie[z], neighbour[z]);
        ++counts[static_cast<std::size_t>(cls)];
        p.regions.push_back(
            {xe[z], xe[z + 1], ye[r], ye[r + 1], std::string(kValidityColours[cls])});
      }
    }
    for (std::size_t c = 0; c < counts.size(); ++c)
      if (counts[c] > 0) p.swatches.push_back({kNames[c], std::string(kValidityColours[c])});
    html_validity_measured_ += figure(
        "measured_" + info.name + ".svg", svg::draw(p),
        fmt::format("{}: at each sun zenith (columns) and value of its {} (rows), the RMS of "
                    "log<sub>10</sub> between its zenith-normalised sky and the nearest of the "
                    "15 CIE standard skies, against the median step between neighbouring types "
                    "of that sky's class at the same sun: the rule of the trust table, per cell. "
                    "Grey: outside its own domain().",
                    info.name, has_axis ? info.report.axis : std::string("single sky")));
    counts_json[info.name] = {{"use", counts[0]},
                              {"use_with_care", counts[1]},
                              {"avoid", counts[2]},
                              {"outside_domain", counts[3]}};
  }
  json_["validity_measured"] = counts_json;
}

std::string ReportWriter::truncation_table(const ModelInfo& info) {
  const HemisphereGrid grid = hemisphere_grid(cfg_.trust_n_theta, cfg_.trust_n_phi);
  HtmlTable t({info.report.truncation, "median", "p95", "RMS log<sub>10</sub>"});
  Json rows = Json::array();
  ComparisonSettings s = cfg_.comparison;
  s.sun_zeniths.clear();
  for (const TrustBand& band : cfg_.trust_bands)
    for (double e : band.sun_elevations_deg) s.sun_zeniths.push_back((90.0 - e) * kDegree);
  s.n_theta = cfg_.trust_n_theta;
  s.n_phi = cfg_.trust_n_phi;
  const auto [first, last] = info.report.truncation_range;
  for (int n = first; n <= last; ++n) {
    std::vector<RelativeSamples> own, source;
    for (const auto& v : trust_axis_values(info)) {
      ModelSpec spec = comparison_spec(info.name, v);
      spec.params.values.set(info.report.truncation, static_cast<double>(n));
      if (!within_domain(spec, s.sun_zeniths, s.sun_azimuth)) continue;
      own.push_back(relative_samples(spec, s, grid));
      source.push_back(relative_samples(comparison_spec(info.report.source, v), s, grid));
    }
    std::vector<const RelativeSamples*> a, b;
    for (std::size_t i = 0; i < own.size(); ++i) {
      a.push_back(&own[i]);
      b.push_back(&source[i]);
    }
    const SourceError e = source_error(a, b, grid);
    t.row({fmt::format("{}", n), fmt::format("{:.1f} %", 100.0 * e.median),
           fmt::format("{:.1f} %", 100.0 * e.p95), rms_text(e.rms_log10)});
    rows.push_back({{info.report.truncation, n},
                    {"skies", own.size()},
                    {"relative_error_median", num(e.median)},
                    {"relative_error_p95", num(e.p95)},
                    {"rms_log10", num(e.rms_log10)}});
  }
  truncation_json_[info.name] = rows;
  return fmt::format(
      "<p><code>{}</code> against <code>{}</code> by its {} (the sun elevations of all bands, its "
      "parameter values within its domain; the measures of the table above): how much of the "
      "error is the truncation.</p>\n{}",
      info.name, info.report.source, info.report.truncation, t.html());
}

std::string ReportWriter::trust_band_text() const {
  std::string t;
  for (const TrustBand& band : cfg_.trust_bands)
    t += fmt::format("{}{} {}", t.empty() ? "" : ", ", band.name,
                     degrees_list(band.sun_elevations_deg));
  return t;
}

}  // namespace skylight::report::detail
