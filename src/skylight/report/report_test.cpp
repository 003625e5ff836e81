#include "skylight/report/report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "skylight/analysis/scan.h"
#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/models/cie_sky.h"
#include "skylight/models/preetham.h"
#include "skylight/report/detail/writer.h"
#include "support/xml_check.h"

namespace skylight::report {
namespace {

namespace fs = std::filesystem;

// report.json's boundary points are bisected to 1e-10 in T (analysis/comparison.cpp); |dYz/dT| <
// 2e5 cd/m^2 per unit T, so |Yz| there is below 2e-5 cd/m^2: 1e-4 leaves room for round-off.
constexpr double kYzAtRootTol = 1e-4;  // [cd/m^2]
// ---- the report files (quick mode, written once) --------------------------------------------

class ReportFiles : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("skylight_report_test_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    ReportOptions o;
    o.output_dir = *dir_;
    o.quick = true;
    o.progress = [](int done, int total, std::string_view) {
      ++steps_;
      total_ = total;
      last_ = done;
    };
    summary_ = new ReportSummary(write_report(o));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete summary_;
  }
  static std::string slurp(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  }
  static fs::path* dir_;
  static ReportSummary* summary_;
  static int steps_, total_, last_;
};
fs::path* ReportFiles::dir_ = nullptr;
ReportSummary* ReportFiles::summary_ = nullptr;
int ReportFiles::steps_ = 0;
int ReportFiles::total_ = 0;
int ReportFiles::last_ = 0;

TEST_F(ReportFiles, ProgressReachesTheEnd) {
  EXPECT_EQ(steps_, total_);
  EXPECT_EQ(last_, total_);
  EXPECT_GT(total_, 5);
}

// Section 9: each sampled hour's sky of the shipped (synthetic) weather year integrates to the
// diffuse horizontal illuminance of the efficacy model within 0.5 % (docs/DAYLIGHT.md's bound on
// the sky's integral); the synthetic year has no measured illuminance, and the page says so.
constexpr double kWeatherIntegralTol = 0.005;

TEST_F(ReportFiles, WeatherSectionComparesEachHoursSkyWithItsIlluminance) {
  const auto j = nlohmann::json::parse(slurp(*dir_ / "report.json"));
  const auto& w = j["daylight_from_weather"];
  EXPECT_TRUE(w["synthetic"].get<bool>());
  EXPECT_EQ(w["records"].get<int>(), 8760);
  EXPECT_GT(w["hours_sun_up"].get<int>(), 4000);
  EXPECT_TRUE(w["sky_vs_measured"].is_null());
  const auto& e = w["sky_vs_efficacy_model"];
  EXPECT_GT(e["hours"].get<int>(), 50);
  EXPECT_LE(e["median"].get<double>(), e["p95"].get<double>());
  EXPECT_LT(e["p95"].get<double>(), kWeatherIntegralTol);
  const std::string html = slurp(*dir_ / "index.html");
  EXPECT_NE(html.find("id=\"weather\""), std::string::npos);
  EXPECT_NE(html.find("weather_diffuse.svg"), std::string::npos);
  EXPECT_NE(html.find("<b>synthetic</b>"), std::string::npos);
}

// Section 10: the weather year on a façade and a roof, perez1990 and the sky method of the models
// with a ReportPolicy::planes (the quick report leaves out those with a costly set-up). Every
// method shares the direct and ground light (the record's DNI cos AOI and the ground of its global
// light): global - sky diffuse is the same for all, to the sums' round-off.
TEST_F(ReportFiles, PlanesSectionComparesTheSkyMethodWithPerez1990) {
  const auto j = nlohmann::json::parse(slurp(*dir_ / "report.json"));
  const auto& planes = j["light_on_planes"]["planes"];
  ASSERT_EQ(planes.size(), 2u);
  std::size_t with_planes = 0;
  for (const ModelInfo& info : model_registry())
    if (info.report.planes && !info.costly_setup) ++with_planes;
  for (const auto& p : planes) {
    const auto& m = p["methods"];
    ASSERT_EQ(m.size(), 1 + with_planes) << p["plane"];
    const double direct_and_ground =
        m[0]["global_kwh_m2"].get<double>() - m[0]["sky_diffuse_kwh_m2"].get<double>();
    EXPECT_GT(direct_and_ground, 0.0);
    for (const auto& r : m) {
      const double g = r["global_kwh_m2"].get<double>(), d = r["sky_diffuse_kwh_m2"].get<double>();
      EXPECT_NEAR(g - d, direct_and_ground, 1e-9 * g) << r["method"];
      EXPECT_NEAR(r["circumsolar_kwh_m2"].get<double>() + r["horizon_kwh_m2"].get<double>() +
                      r["rest_kwh_m2"].get<double>(),
                  d, 1e-9 * d)
          << r["method"];
    }
  }
  EXPECT_NE(slurp(*dir_ / "index.html").find("id=\"planes\""), std::string::npos);
}

TEST_F(ReportFiles, JsonHasTheHeadlineNumbers) {
  const auto j = nlohmann::json::parse(slurp(*dir_ / "report.json"));
  ASSERT_TRUE(j.contains("preetham_negative_zenith"));
  ASSERT_TRUE(j["preetham_negative_zenith"].is_array());
  ASSERT_FALSE(j["preetham_negative_zenith"].empty());
  for (const auto& p : j["preetham_negative_zenith"]) {
    ASSERT_TRUE(p["sun_zenith_deg"].is_number());
    ASSERT_TRUE(p["turbidity"].is_number());
    const double ts = p["sun_zenith_deg"], T = p["turbidity"];
    EXPECT_LT(std::abs(preetham_zenith_luminance(T, deg_to_rad(ts))), kYzAtRootTol);
  }
  // The single-point ratio is not a headline key: it stands under its details.
  EXPECT_FALSE(j.contains("antisolar_horizon_ratio_preetham_vs_cie12"));
  const auto& ad = j["antisolar_horizon_ratio_details"];
  ASSERT_TRUE(ad["ratio"].is_number());
  const double ratio = ad["ratio"];
  EXPECT_TRUE(std::isfinite(ratio));
  EXPECT_GT(ratio, 0.0);
  EXPECT_DOUBLE_EQ(ratio, summary_->antisolar_ratio);
  EXPECT_TRUE(ad["sun_zenith_deg"].is_number());
  EXPECT_TRUE(ad["view_elevation_deg"].is_number());
  EXPECT_TRUE(ad["preetham_turbidity"].is_number());
  ASSERT_TRUE(j["best_preetham_turbidity_for_cie12"].is_number());
  const double T = j["best_preetham_turbidity_for_cie12"];
  EXPECT_GE(T, 1.7);
  EXPECT_LE(T, 10.0);
  ASSERT_TRUE(j["best_cie_type_per_preetham_turbidity"].is_array());
  ASSERT_FALSE(j["best_cie_type_per_preetham_turbidity"].empty());
  for (const auto& m : j["best_cie_type_per_preetham_turbidity"]) {
    ASSERT_TRUE(m["turbidity"].is_number());
    ASSERT_TRUE(m["cie_type"].is_number_integer());
    EXPECT_GE(m["cie_type"].get<int>(), 1);
    EXPECT_LE(m["cie_type"].get<int>(), 16);
    ASSERT_TRUE(m["rms_log10"].is_number());
    ASSERT_TRUE(m["luminance_ratio_preetham_over_cie"].is_number());
    EXPECT_TRUE(std::isfinite(m["rms_log10"].get<double>()));
  }
  EXPECT_TRUE(j["measurements"]["synthetic"].get<bool>());
}

// "Which model to trust where" reads the registry: every model has an entry, each model with a
// report policy a verdict per regime that follows the printed rule from the printed numbers, and
// the page has its section and a row per model (the contents' links: HtmlIsWellFormed...).
TEST_F(ReportFiles, TrustTableJudgesEveryRegisteredModelByItsPrintedRule) {
  const auto j = nlohmann::json::parse(slurp(*dir_ / "report.json"));
  const std::string html = slurp(*dir_ / "index.html");
  ASSERT_TRUE(j.contains("which_model_to_trust_where"));
  const auto& models = j["which_model_to_trust_where"]["models"];
  ASSERT_EQ(models.size(), model_registry().size());
  std::size_t judged = 0;
  for (std::size_t i = 0; i < models.size(); ++i) {
    const ModelInfo& info = model_registry()[i];
    SCOPED_TRACE(info.name);
    const auto& m = models[i];
    EXPECT_EQ(m["model"], info.name);
    EXPECT_EQ(m["judged"].get<bool>(), !info.report.title.empty());
    EXPECT_NE(html.find("<code>" + info.name + "</code>"), std::string::npos);
    if (!m["judged"].get<bool>()) continue;
    ++judged;
    ASSERT_EQ(m["regimes"].size(), 9u);  // 3 sun-elevation bands x 3 sky classes (quick)
    // Against its source (same rule, the band's smallest neighbour step).
    ASSERT_EQ(m.contains("against_source"), !info.report.source.empty());
    if (!info.report.source.empty()) {
      ASSERT_EQ(m["against_source"].size(), 3u);
      for (const auto& r : m["against_source"]) {
        EXPECT_EQ(r["source"], info.report.source);
        ASSERT_GT(r["skies_in_domain"].get<int>(), 0);
        EXPECT_LE(r["relative_error_median"].get<double>(), r["relative_error_p95"].get<double>());
        EXPECT_EQ(r["verdict"], detail::trust_verdict_name(detail::trust_verdict(
                                    r["rms_log10"], r["smallest_neighbour_rms_log10"])));
      }
    }
    for (const auto& r : m["regimes"]) {
      const std::string verdict = r["verdict"];
      if (verdict == "reference") continue;
      if (r["skies_nearest_to_this_class"].get<int>() == 0) {
        EXPECT_EQ(verdict, "avoid");
        continue;
      }
      const double best = r["best_rms_log10"], step = r["neighbour_rms_log10"];
      EXPECT_EQ(verdict, detail::trust_verdict_name(detail::trust_verdict(best, step)));
      EXPECT_GE(r["best_cie_type"].get<int>(), r["cie_types"][0].get<int>());
      EXPECT_LE(r["best_cie_type"].get<int>(), r["cie_types"][1].get<int>());
    }
  }
  EXPECT_GE(judged, 5u);
  // A truncated approximation (SH bands) against its source per truncation value: more bands,
  // a closer sky (the RMS of the last below that of the first).
  for (const ModelInfo& info : model_registry()) {
    if (info.report.truncation.empty()) continue;
    const auto& rows = j["which_model_to_trust_where"]["truncation"][info.name];
    ASSERT_EQ(rows.size(), static_cast<std::size_t>(info.report.truncation_range[1] -
                                                    info.report.truncation_range[0] + 1));
    EXPECT_LT(rows.back()["rms_log10"].get<double>(), rows.front()["rms_log10"].get<double>());
  }
  // The quantities docs/REPORT.md lists that the report cannot judge say so, with a
  // reason, in report.json and on the page (a gap is a statement, not a silence).
  std::vector<std::string> without;
  for (const auto& q : j["which_model_to_trust_where"]["quantities_without_verdict"]) {
    without.push_back(q["quantity"]);
    EXPECT_FALSE(q["reason"].get<std::string>().empty());
  }
  EXPECT_EQ(without, (std::vector<std::string>{"absolute illuminance", "spectrum"}));
  EXPECT_NE(html.find("id=\"trust-not-judged\""), std::string::npos);
  // Colour and twilight against the physical atmosphere: every judged model a row of 4 bands
  // (twilight first); luminance-only models not judged on colour; verdicts by the colour rule.
  const auto& physical = j["which_model_to_trust_where"]["against_physical_atmosphere"];
  for (const ModelInfo& info : model_registry()) {
    if (info.report.title.empty()) continue;
    SCOPED_TRACE(info.name);
    const auto& cells = physical["models"][info.name];
    ASSERT_EQ(cells.size(), 4u);
    EXPECT_EQ(cells[0]["band"], "twilight");
    for (std::size_t b = 1; b < cells.size(); ++b) {
      const auto& c = cells[b];
      if (c["verdict"] == "reference") continue;
      if (info.luminance_only) {
        EXPECT_EQ(c["verdict"], "not judged");
        continue;
      }
      if (!c.contains("mean_duv")) continue;  // outside its domain
      EXPECT_EQ(c["verdict"],
                detail::trust_verdict_name(detail::colour_verdict(c["mean_duv"].get<double>())));
    }
  }
  // Section 8's measured maps: one per judged model but the reference, every cell counted.
  ASSERT_TRUE(j.contains("validity_measured"));
  for (const ModelInfo& info : model_registry()) {
    if (info.report.title.empty() || info.name == CieSkyModel::kName) continue;
    SCOPED_TRACE(info.name);
    ASSERT_TRUE(j["validity_measured"].contains(info.name));
    const auto& c = j["validity_measured"][info.name];
    const int cells = c["use"].get<int>() + c["use_with_care"].get<int>() + c["avoid"].get<int>() +
                      c["outside_domain"].get<int>();
    // quick: 3 sun zeniths x (8 values of a continuous axis, or 1 sky)
    EXPECT_EQ(cells, 3 * static_cast<int>(info.report.axis.empty() ? 1 : 8)) << c;
    EXPECT_TRUE(fs::is_regular_file(*dir_ / ("measured_" + info.name + ".svg")));
  }
  EXPECT_NE(html.find("<h2 id=\"trust\">Which model to trust where</h2>"), std::string::npos);
}

// The Zotti findings' pass rules on planted numbers: each fails on a counter-example.
TEST(ReportFindings, PassRulesFailOnPlantedCounterExamples) {
  EXPECT_EQ(agreement_of(2, 2), Agreement::agrees);
  EXPECT_EQ(agreement_of(1, 2), Agreement::partly);
  EXPECT_EQ(agreement_of(0, 2), Agreement::disagrees);
  EXPECT_EQ(agreement_of(0, 0), Agreement::not_tested);
  EXPECT_EQ(agreement_name(Agreement::not_tested), "not tested");
  const detail::ZottiPair t10 = detail::kZottiPairs[0], t5 = detail::kZottiPairs[1];
  ASSERT_EQ(t10.threshold, 2.0);
  EXPECT_TRUE(detail::pair_reading_holds(t10, {2.1, 2.07, 2.24}));
  // Above 2 on average but not at every sun position (T 10's zenith ratio, 1.83-2.13).
  EXPECT_FALSE(detail::pair_reading_holds(t10, {2.0, 1.83, 2.13}));
  EXPECT_TRUE(detail::pair_reading_holds(t5, {1.1, 0.86, 1.15}));
  EXPECT_FALSE(detail::pair_reading_holds(t5, {1.1, 0.79, 1.15}));  // below 1 / 1.25
  EXPECT_FALSE(detail::pair_reading_holds(t5, {1.1, 0.9, 1.26}));   // above 1.25
  EXPECT_TRUE(detail::antisolar_factor_holds(2.2));
  EXPECT_FALSE(detail::antisolar_factor_holds(1.99));
  EXPECT_FALSE(detail::antisolar_factor_holds(5.07));
}

// The rule's planted counter-examples: a model as far from the class as its neighbouring types
// are from each other is not "use"; no number is never "use".
TEST(ReportTrust, VerdictRuleFailsOnPlantedCounterExamples) {
  using detail::TrustVerdict;
  EXPECT_EQ(detail::trust_verdict(0.04, 0.1), TrustVerdict::use);
  EXPECT_EQ(detail::trust_verdict(0.05, 0.1), TrustVerdict::use);  // the bound itself
  EXPECT_EQ(detail::trust_verdict(0.051, 0.1), TrustVerdict::care);
  EXPECT_EQ(detail::trust_verdict(0.1, 0.1), TrustVerdict::care);
  EXPECT_EQ(detail::trust_verdict(0.101, 0.1), TrustVerdict::avoid);
  EXPECT_EQ(detail::trust_verdict(std::nan(""), 0.1), TrustVerdict::avoid);
  EXPECT_EQ(detail::trust_verdict(0.01, std::nan("")), TrustVerdict::avoid);
  EXPECT_EQ(detail::trust_verdict_name(TrustVerdict::care), "use with care");
  EXPECT_EQ(detail::colour_verdict(0.005), TrustVerdict::use);
  EXPECT_EQ(detail::colour_verdict(0.0051), TrustVerdict::care);
  EXPECT_EQ(detail::colour_verdict(0.02), TrustVerdict::care);
  EXPECT_EQ(detail::colour_verdict(0.0201), TrustVerdict::avoid);
  EXPECT_EQ(detail::colour_verdict(std::nan("")), TrustVerdict::avoid);
}

// Against measured skies: every model with a fit and a report policy, its medians those of the
// library's comparison (fit/measured_fit.h) on the same captures, its verdicts by the printed
// rules, the trust table's measured column the same verdict, the figures written.
TEST_F(ReportFiles, MeasuredSkiesJudgeEachFittedModelByThePrintedRules) {
  const auto j = nlohmann::json::parse(slurp(*dir_ / "report.json"));
  const std::string html = slurp(*dir_ / "index.html");
  const auto& m = j["against_measured_skies"];
  EXPECT_EQ(m["captures"], 15);
  const double step = m["clear_neighbour_rms_log10"].get<double>();
  std::map<std::string, nlohmann::json> by_model;
  for (const auto& x : m["models"]) by_model[x["model"].get<std::string>()] = x;
  std::map<std::string, nlohmann::json> trust;
  for (const auto& x : j["which_model_to_trust_where"]["models"])
    trust[x["model"].get<std::string>()] = x;
  for (const ModelInfo& info : model_registry()) {
    if (info.report.title.empty()) continue;
    SCOPED_TRACE(info.name);
    const auto& cell = trust[info.name]["measured_clear_skies"];
    if (!info.estimation) {
      EXPECT_EQ(by_model.count(info.name), 0u);
      EXPECT_EQ(cell["verdict"], "not judged");
      continue;
    }
    ASSERT_EQ(by_model.count(info.name), 1u);
    const auto& x = by_model[info.name];
    if (info.costly_setup) {  // the quick report leaves them out, and says so
      EXPECT_TRUE(x["captures"].empty());
      EXPECT_EQ(cell["reason"], "quick report");
      continue;
    }
    ASSERT_EQ(x["captures"].size(), 15u);
    fit::MeasuredSettings settings;
    settings.model = info.name;
    const auto direct = fit::compare_to_measured(io::shipped_kider_subset(), settings);
    std::vector<double> scales;
    for (const auto& r : direct) scales.push_back(r.scale);
    std::sort(scales.begin(), scales.end());
    EXPECT_EQ(x["median_scale"].get<double>(), scales[7]);
    const auto verdict = [](detail::TrustVerdict v) { return detail::trust_verdict_name(v); };
    EXPECT_EQ(x["verdict_shape"],
              verdict(detail::trust_verdict(x["median_rms_log10_shape"].get<double>(), step)));
    EXPECT_EQ(x["verdict_absolute"], verdict(detail::absolute_verdict(scales[7])));
    EXPECT_EQ(x["verdict_spectrum"],
              verdict(x["median_spectral_rms"].is_null()
                          ? detail::TrustVerdict::not_judged
                          : detail::spectrum_verdict(x["median_spectral_rms"].get<double>())));
    EXPECT_EQ(cell["verdict"], x["verdict_shape"]);
    EXPECT_TRUE(fs::exists(*dir_ / ("measured_error_" + info.name + ".svg")));
  }
  EXPECT_TRUE(fs::exists(*dir_ / "measured_solar_vertical.svg"));
  EXPECT_TRUE(fs::exists(*dir_ / "measured_almucantar.svg"));
  EXPECT_NE(html.find("id=\"measured-skies\""), std::string::npos);
  EXPECT_NE(html.find("<b>Against measured clear skies</b>"), std::string::npos);
}

// The rules of absolute level and spectrum at their bounds and beyond.
TEST(ReportTrust, MeasuredRulesFailOnPlantedCounterExamples) {
  using detail::TrustVerdict;
  EXPECT_EQ(detail::absolute_verdict(1.25), TrustVerdict::use);
  EXPECT_EQ(detail::absolute_verdict(0.8), TrustVerdict::use);  // 1 / 1.25
  EXPECT_EQ(detail::absolute_verdict(1.26), TrustVerdict::care);
  EXPECT_EQ(detail::absolute_verdict(0.5), TrustVerdict::care);
  EXPECT_EQ(detail::absolute_verdict(0.49), TrustVerdict::avoid);
  EXPECT_EQ(detail::absolute_verdict(0.0), TrustVerdict::avoid);
  EXPECT_EQ(detail::spectrum_verdict(0.1), TrustVerdict::use);
  EXPECT_EQ(detail::spectrum_verdict(0.15), TrustVerdict::care);
  EXPECT_EQ(detail::spectrum_verdict(0.21), TrustVerdict::avoid);
  EXPECT_EQ(detail::spectrum_verdict(std::nan("")), TrustVerdict::not_judged);
}

TEST_F(ReportFiles, ZottiFindingsInJsonMatchTheSummaryAndTheHtml) {
  const auto j = nlohmann::json::parse(slurp(*dir_ / "report.json"));
  const std::string html = slurp(*dir_ / "index.html");
  ASSERT_TRUE(j.contains("zotti_findings"));
  const auto& arr = j["zotti_findings"];
  ASSERT_TRUE(arr.is_array());
  ASSERT_EQ(arr.size(), summary_->findings.size());
  std::set<std::string> ids;
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const auto& f = arr[i];
    const Finding& s = summary_->findings[i];
    SCOPED_TRACE(s.id);
    ids.insert(f["id"].get<std::string>());
    EXPECT_EQ(f["id"], s.id);
    ASSERT_TRUE(f["agrees"].is_boolean());
    EXPECT_EQ(f["agrees"].get<bool>(), s.agrees());
    EXPECT_EQ(f["agreement"], agreement_name(s.agreement));
    EXPECT_FALSE(f["paper_statement"].get<std::string>().empty());
    EXPECT_FALSE(f["paper_value"].get<std::string>().empty());
    EXPECT_FALSE(f["cause"].get<std::string>().empty());
    ASSERT_FALSE(f["our_values"].empty());
    ASSERT_EQ(f["our_values"].size(), s.our_values.size());
    for (std::size_t k = 0; k < s.our_values.size(); ++k) {
      const auto& v = f["our_values"][k];
      ASSERT_TRUE(v["value"].is_number()) << v["name"];  // finite: null would fail
      EXPECT_DOUBLE_EQ(v["value"].get<double>(), s.our_values[k].value);
      // The summary prints the same number.
      EXPECT_NE(html.find("<b>" + format_finding_value(s.our_values[k].value) + "</b>"),
                std::string::npos)
          << s.our_values[k].name;
    }
    EXPECT_NE(html.find("<i>" + agreement_name(s.agreement) + "</i>"), std::string::npos);
  }
  for (const char* id :
       {"negative_luminance_clear", "negative_luminance_turbid", "best_turbidity_cie12",
        "antisolar_factor", "antisolar_shape", "pair_T10_cie6", "pair_T5_cie7", "pair_T2.9_cie10",
        "circumsolar_brightening", "horizon_bright_t_above_2_4", "measurements",
        "fig3_horizon_outshines_sun_vicinity", "only_clear_types_comparable", "pair_shapes",
        "fitted_range_declared"})
    EXPECT_EQ(ids.count(id), 1u) << id;
  EXPECT_NE(html.find("partly reproduces"), std::string::npos);
  // The synthetic scan is never read as evidence.
  for (const Finding& f : summary_->findings)
    if (f.id == "measurements") {
      EXPECT_EQ(f.agreement, Agreement::not_tested);
      EXPECT_NE(f.cause.find("synthetic"), std::string::npos);
    }
}

TEST_F(ReportFiles, SvgFilesAreWellFormedAndTheirImagesExist) {
  int svgs = 0, images = 0;
  for (const auto& e : fs::directory_iterator(*dir_)) {
    if (e.path().extension() != ".svg") continue;
    ++svgs;
    SCOPED_TRACE(e.path().filename().string());
    const auto check = skylight::testing_support::check_xml(slurp(e.path()));
    EXPECT_TRUE(check.ok) << check.error;
    EXPECT_EQ(check.elements.front(), "svg");
    for (const auto& h : check.hrefs) {
      ++images;
      EXPECT_TRUE(fs::is_regular_file(*dir_ / h)) << h;
      EXPECT_GT(fs::file_size(*dir_ / h), 0u) << h;
    }
  }
  EXPECT_GT(svgs, 10);
  EXPECT_GT(images, 0);
}

TEST_F(ReportFiles, HtmlIsWellFormedAndReferencesOnlyExistingFiles) {
  const std::string html = slurp(*dir_ / "index.html");
  // The inline script has no markup characters inside, so the page also parses as XML.
  const auto check = skylight::testing_support::check_xml(html);
  EXPECT_TRUE(check.ok) << check.error;
  int images = 0;
  for (const auto& h : check.hrefs) {
    if (h.starts_with("#")) {  // in-page: an element of the page
      EXPECT_NE(html.find("id=\"" + h.substr(1) + "\""), std::string::npos) << h;
      continue;
    }
    EXPECT_TRUE(fs::is_regular_file(*dir_ / h)) << h;
    if (h.ends_with(".png")) ++images;
  }
  EXPECT_GT(images, 5);
  EXPECT_NE(html.find("id=\"image-check\""), std::string::npos);
  EXPECT_NE(html.find("Closing note"), std::string::npos);
  // Every file the summary lists was written, and nothing temporary is left.
  for (const auto& f : summary_->files) EXPECT_TRUE(fs::is_regular_file(*dir_ / f)) << f;
  for (const auto& e : fs::directory_iterator(*dir_))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos);
}

TEST(ReportOptionsCheck, BadOptionsAndFiles) {
  const fs::path dir =
      fs::temp_directory_path() / ("skylight_report_bad_" + std::to_string(::getpid()));
  ReportOptions o;
  o.output_dir = dir;
  o.quick = true;
  o.measurement_sun_azimuth = 1.0;  // without the elevation
  EXPECT_THROW(write_report(o), InvalidArgument);
  o.measurement_sun_azimuth.reset();
  o.measurements = dir / "missing.csv";
  EXPECT_THROW(write_report(o), IoError);
  o.measurements.reset();
  o.kider = dir / "missing";  // no such folder: before anything is written
  EXPECT_ANY_THROW(write_report(o));
  EXPECT_FALSE(fs::exists(dir));
  o.kider.reset();
  fs::create_directories(dir);
  { std::ofstream(dir / "nosun.csv") << "azimuth_deg,elevation_deg,luminance_cd_m2\n0,6,100\n"; }
  o.measurements = dir / "nosun.csv";
  try {
    write_report(o);
    ADD_FAILURE() << "no error for a scan without a sun position";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("no sun position"), std::string::npos);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace skylight::report