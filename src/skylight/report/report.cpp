// The validation and comparison report (report.h; methods in docs/REPORT.md): configuration,
// helpers, the HTML page and report.json. The sections are in section_*.cpp.
#include "skylight/report/report.h"

#include "skylight/core/math.h"

#include <algorithm>
#include <optional>
#include <system_error>

#include "skylight/core/error.h"
#include "skylight/report/detail/writer.h"

namespace skylight::report {

const ParameterSchema<ReportOptions>& ReportOptions::schema() {
  static const ParameterSchema<ReportOptions> s = [] {
    using O = ReportOptions;
    ParameterSchema<O> s;
    s.custom(
         {.name = "measurements",
          .kind = ParameterKind::text,
          .default_value = Absent{"the shipped synthetic example"},
          .description = "sky-luminance scan CSV (azimuth_deg,elevation_deg,luminance_cd_m2)"},
         [](O& o, const ParameterValue& v) { o.measurements = std::get<std::string>(v); },
         [](const O& o) -> std::optional<ParameterValue> {
           if (!o.measurements) return std::nullopt;
           return o.measurements->string();
         })
        .custom(
            {.name = "epw",
             .kind = ParameterKind::text,
             .default_value = Absent{"the shipped synthetic year"},
             .description = "EnergyPlus weather file for section 9 (daylight from weather data)"},
            [](O& o, const ParameterValue& v) { o.epw = std::get<std::string>(v); },
            [](const O& o) -> std::optional<ParameterValue> {
              if (!o.epw) return std::nullopt;
              return o.epw->string();
            })
        .custom(
            {.name = "kider",
             .kind = ParameterKind::text,
             .default_value = Absent{"the shipped subset, data/measured/kider2014/"},
             .description = "Kider et al. 2014's captures for \"Against measured skies\" (the "
                            "data set, a date, its RADIANCE folder or one capture; "
                            "docs/MEASURED.md)"},
            [](O& o, const ParameterValue& v) { o.kider = std::get<std::string>(v); },
            [](const O& o) -> std::optional<ParameterValue> {
              if (!o.kider) return std::nullopt;
              return o.kider->string();
            })
        .custom(
            {.name = "sun-azimuth",
             .unit = "deg",
             .min = -360.0,
             .max = 360.0,
             .default_value = Absent{"the file's '# sun_azimuth_deg'"},
             .description = "sun azimuth of the scan from north towards east"},
            [](O& o, const ParameterValue& v) {
              o.measurement_sun_azimuth = wrap_azimuth(deg_to_rad(std::get<double>(v)));
            },
            [](const O& o) -> std::optional<ParameterValue> {
              if (!o.measurement_sun_azimuth) return std::nullopt;
              return rad_to_deg(*o.measurement_sun_azimuth);
            })
        .custom(
            {.name = "sun-elevation",
             .unit = "deg",
             .min = 0.0,
             .max = 90.0,
             .default_value = Absent{"the file's '# sun_elevation_deg'"},
             .description = "sun elevation of the scan"},
            [](O& o, const ParameterValue& v) {
              o.measurement_sun_elevation = deg_to_rad(std::get<double>(v));
            },
            [](const O& o) -> std::optional<ParameterValue> {
              if (!o.measurement_sun_elevation) return std::nullopt;
              return rad_to_deg(*o.measurement_sun_elevation);
            })
        .flag(&O::quick,
              {.name = "quick",
               .kind = ParameterKind::flag,
               .description = "reduced resolution and fewer sun positions (seconds; for tests)"});
    return s;
  }();
  return s;
}
namespace detail {

namespace {

// The full report's settings: its resolutions, steps and sun positions.
void set_full(Config& c) {
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
  c.fit_per_sun_zeniths_deg = {10, 20, 30, 40, 50, 60, 70, 80, 85};
  c.zone_sun_zeniths_deg = {60, 65, 70, 75, 80, 85};
  c.pair_sun_zeniths_deg = {20, 30, 40, 50, 60, 65};
  c.low_sun_zeniths_deg = {60, 70, 80};
  c.zone_n_theta = 36;
  c.zone_n_phi = 144;
  c.trust_bands = {{"low sun", 5, 15, {7, 12}},
                   {"mid sun", 15, 45, {20, 30, 40}},
                   {"high sun", 45, 80, {50, 65, 80}}};
  c.trust_n_theta = 24;
  c.trust_n_phi = 96;
  c.trust_axis_samples = 24;
  c.trust_map_sun_zeniths_deg = {10, 15, 20, 25, 30, 35, 40, 45, 50, 55, 60, 65, 70, 75, 80, 85};
  c.twilight_band = {"twilight", -6, 0, {-1, -3, -5}};
  c.colour_n_theta = 12;
  c.colour_n_phi = 48;
  c.weather_stride = 16;
  c.planes_hours = "";
  c.planes_costly = true;
  c.weather_n_theta = 90;
  c.weather_n_phi = 180;
  c.measured_costly_captures = 1;
}

// The quick (test) report's settings: reduced resolution and fewer sun positions.
void set_quick(Config& c) {
  c.trust_bands = {{"low sun", 5, 15, {10}}, {"mid sun", 15, 45, {30}}, {"high sun", 45, 80, {60}}};
  c.trust_n_theta = 12;
  c.trust_n_phi = 48;
  c.trust_axis_samples = 8;
  c.trust_map_sun_zeniths_deg = {30, 60, 80};
  c.twilight_band = {"twilight", -6, 0, {-3}};
  c.colour_n_theta = 6;
  c.colour_n_phi = 24;
  c.weather_stride = 60;
  c.planes_hours = "4000-4240";
  c.planes_costly = false;
  c.weather_n_theta = 45;
  c.weather_n_phi = 90;
  c.measured_costly_captures = 0;
  c.fit_per_sun_zeniths_deg = {30, 80};
  c.zone_sun_zeniths_deg = {60, 85};
  c.pair_sun_zeniths_deg = {30, 60};
  c.low_sun_zeniths_deg = {70};
  c.zone_n_theta = 12;
  c.zone_n_phi = 48;
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

}  // namespace

Config make_config(bool quick) {
  Config c;
  c.comparison.sun_exclusion = 5.0 * kDegree;
  c.comparison.sun_azimuth = kPi;
  c.fit_t_min = 1.7;
  c.fit_t_max = 10.0;
  c.antisolar_headline_sun_zenith_deg = 80.0;
  c.antisolar_headline_elevation_deg = 3.0;
  c.fig1_linear_t = {1.0, 12.0};  // Zotti's Fig. 1
  if (!quick) {
    set_full(c);
  } else {
    set_quick(c);
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

double snapped_log10(double v) {
  const double l = std::log10(v), r = std::round(l);
  return std::abs(l - r) < kDecadeSnap ? r : l;
}

// The y axis of a validity map with a single row (the model has no second parameter): no ticks
// (the one requested lies outside the range).
std::string degrees_list(const std::vector<double>& deg) {
  std::string s;
  for (double v : deg) s += (s.empty() ? "" : ", ") + fmt::format("{:g}", v);
  return s;
}

std::vector<double> sun_zeniths_deg(const ComparisonSettings& c) {
  std::vector<double> d;
  for (double z : c.sun_zeniths) d.push_back(rad_to_deg(z));
  return d;
}

HtmlTable::HtmlTable(const std::vector<std::string>& headers, std::vector<bool> left)
    : text_("<table><tr>"), left_(std::move(left)) {
  for (const auto& h : headers) text_ += "<th>" + h + "</th>";
  text_ += "</tr>\n";
}

void HtmlTable::row(const std::vector<std::string>& cells, std::string_view row_attributes) {
  text_ += fmt::format("<tr{}>", row_attributes);
  for (std::size_t i = 0; i < cells.size(); ++i)
    text_ += (i < left_.size() && left_[i] ? "<td style=\"text-align:left\">" : "<td>") + cells[i] +
             "</td>";
  text_ += "</tr>\n";
}

std::string esc_html(std::string_view s) {
  std::string o;
  for (char c : s) {
    if (c == '&')
      o += "&amp;";
    else if (c == '<')
      o += "&lt;";
    else if (c == '>')
      o += "&gt;";
    else
      o += c;
  }
  return o;
}

svg::Axis one_row_axis() {
  return {0.0, 1.0, false, "", {-1.0}};
}

std::string validity_name(Validity v) {
  return std::string(to_string(v));
}

double finite_or(double v, double fallback) {
  return std::isfinite(v) ? v : fallback;
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
.verdict-use { color: #1b5e20; font-weight: bold; } .verdict-care { color: #8a6d00; font-weight: bold; }
.verdict-avoid { color: #b71c1c; font-weight: bold; }
nav#contents { background: #f7f7f7; border: 1px solid #ddd; padding: 0.4em 1em; display: inline-block; }
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
  // In-page links (the contents): each must name an element of the page.
  var links = Array.prototype.slice.call(document.querySelectorAll('a[href^="#"]'));
  var linked = 0, dangling = [];
  links.forEach(function (a) {
    var id = a.getAttribute('href').slice(1);
    if (document.getElementById(id)) linked++; else dangling.push('#' + id);
  });
  function done() {
    out.textContent = 'images ok: ' + ok + ' of ' + total +
        (broken.length ? ' (broken: ' + broken.join(', ') + ')' : '') +
        '; links ok: ' + linked + ' of ' + links.length +
        (dangling.length ? ' (dangling: ' + dangling.join(', ') + ')' : '');
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
  std::string models;
  for (const auto& m : model_registry()) models += (models.empty() ? "" : ", ") + m.name;
  // The sections in page order: anchor, heading, body.
  const std::vector<std::array<std::string, 3>> sections = {
      {"trust", "Which model to trust where", html_trust_},
      {"zotti", "Zotti et al.'s findings in brief", findings_summary_html()},
      {"measured-skies", "Against measured skies", html_measured_},
      {"zenith", "1. Preetham's zenith luminance", html_zenith_},
      {"relative-maps", "2. Relative luminance maps (Zotti Figs. 4, 6)", html_rel_},
      {"absolute-maps", "3. Absolute luminance maps (Zotti Figs. 5, 7)", html_abs_},
      {"matching", "4. Preetham against the CIE general sky", html_match_},
      {"vertical", "5. The solar vertical (Zotti Fig. 3)", html_vertical_},
      {"illuminance", "6. Horizontal illuminance and irradiance", html_illum_},
      {"measurements", "7. Measurements", html_scan_},
      {"validity", "8. Where each model is valid",
       "<h3>Measured</h3>\n<p>From this report's own numbers: each cell judged by the rule of "
       "<a href=\"#trust\">the trust table</a> at one sun position and one value of the "
       "model's parameter. These maps can show a model failing where it declares itself "
       "valid.</p>\n" +
           html_validity_measured_ +
           "<h3>Declared</h3>\n<p>Each model's <code>domain().worst()</code> (valid &lt; "
           "extrapolated &lt; unphysical &lt; undefined) over the sun zenith angle and its main "
           "parameter, as the model declares it; sun azimuth 180°.</p>\n" +
           html_validity_},
      {"weather", "9. Daylight from weather data", html_weather_},
      {"planes", "10. Light on planes", html_planes_},
      {"closing", "Closing note: Zotti et al.'s findings, paper against ours",
       "<p>One row per finding (report.json <code>zotti_findings</code>; the summary above is "
       "generated from the same records).</p>\n" +
           html_findings_}};
  std::string toc =
      "<nav id=\"contents\"><b>Contents</b><ol>\n<li><a href=\"#summary\">Summary</a></li>\n";
  std::string body;
  for (const auto& [id, heading, html] : sections) {
    toc += fmt::format("<li><a href=\"#{}\">{}</a></li>\n", id, heading);
    body += fmt::format("<h2 id=\"{}\">{}</h2>\n{}", id, heading, html);
  }
  toc += "</ol></nav>\n";
  // The plain-language summary: one line per judged model, then the findings' count.
  std::string summary = "<ul>\n";
  for (const std::string& line : trust_summary_) summary += "<li>" + line + "</li>\n";
  int agree = 0;
  for (const Finding& f : summary_.findings) agree += f.agrees() ? 1 : 0;
  summary += "<li>" + measured_summary_line() + "</li>\n";
  summary += fmt::format(
      "<li>Distribution only (<a href=\"#trust\">table and rule</a>) but for the measured skies; "
      "of Zotti et al.'s {} "
      "findings on Preetham, {} agree with our numbers (<a href=\"#zotti\">in brief</a>).</li>\n"
      "</ul>\n",
      summary_.findings.size(), agree);
  std::string html = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n"
      "<title>skylight validation report</title>\n<style>{}</style>\n</head>\n<body>\n"
      "<h1>skylight validation report: which sky model to trust where</h1>\n"
      "<p>skylight {} · models in the registry: {} · {} report. Judges every registered model "
      "against the CIE standard general sky, reproduces the analyses of Zotti, Wilkie &amp; "
      "Purgathofer 2007, <i>A Critical Review of the Preetham Skylight Model</i> (WSCG), "
      "judges the models against measured clear skies (Kider et al. 2014) and compares them "
      "with a sky-luminance scan. Headline numbers: <a "
      "href=\"report.json\">report.json</a>; methods: docs/REPORT.md in the repository. Angles "
      "in degrees; θ<sub>s</sub> = sun zenith angle, T = turbidity.</p>\n"
      "<p id=\"image-check\">images: not checked (needs JavaScript)</p>\n{}"
      "<h2 id=\"summary\">Summary</h2>\n{}{}{}</body>\n</html>\n",
      kStyle, kVersion, models, opt_.quick ? "quick (reduced-resolution)" : "full", toc, summary,
      body, kImageCheck);
  write_text("index.html", html);

  Json j;
  j["generator"] = fmt::format("skylight {} report", kVersion);
  j["quick"] = opt_.quick;
  j["angles"] = "degrees";
  // The headline numbers first, then the details in the order they were computed.
  for (const char* key : {"which_model_to_trust_where", "against_measured_skies", "zotti_findings",
                          "preetham_negative_zenith", "best_preetham_turbidity_for_cie12",
                          "best_cie_type_per_preetham_turbidity"})
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
  // The weather file and the measured skies before anything is written: a bad file fails fast.
  load_weather();
  load_kider();
  step("weather file");
  weather_hours();
  step("weather hours");
  // All or nothing: every file goes to a temporary and is renamed into place only when the whole
  // report has been written; a directory this call created is removed again on failure.
  std::error_code ec;
  const bool existed = fs::exists(opt_.output_dir, ec);
  fs::create_directories(opt_.output_dir, ec);
  if (ec || !fs::is_directory(opt_.output_dir))
    throw IoError(fmt::format("cannot create directory '{}': {}", opt_.output_dir.string(),
                              ec ? ec.message() : "not a directory"));
  struct RemoveIfFailed {
    const fs::path& dir;
    bool armed;
    ~RemoveIfFailed() {
      std::error_code ignored;
      if (armed) fs::remove(dir, ignored);  // only if empty: never deletes the user's files
    }
  } cleanup{opt_.output_dir, !existed};
  std::optional<OutputTransaction> own;
  if (!OutputTransaction::current()) own.emplace();
  // The measurements first: a bad file fails fast, before any work.
  section_measurements();
  section_daylight();
  section_planes();
  step("measurements and weather file");
  measured_skies();
  step("against measured skies");
  section_trust();
  measured_table();
  physical_atmosphere_table();
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
  measured_validity_maps();
  step("validity maps");
  section_findings();
  write_html_and_json();
  step("index.html and report.json");
  if (own) own->commit();
  cleanup.armed = false;
  return summary_;
}

}  // namespace detail

ReportSummary write_report(const ReportOptions& options) {
  detail::ReportWriter w(options);
  return w.run();
}

}  // namespace skylight::report
