// Section 9 of the report: daylight from weather data. Each sampled hour of an EPW file with the
// sun up becomes the `perez` model's sky from that hour's direct and diffuse radiation (Perez et
// al. 1990, 1993; models/perez_allweather.h); its diffuse horizontal illuminance, integrated over
// the hemisphere, is set against the file's measured illuminance, or, where the file has none
// (the shipped synthetic year), against the efficacy model's value (a self-test).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/analysis/illumination.h"
#include "skylight/core/data.h"
#include "skylight/core/statistics.h"
#include "skylight/daylight/sky_matrix.h"
#include "skylight/io/epw.h"
#include "skylight/io/file.h"
#include "skylight/models/perez.h"
#include "skylight/report/detail/writer.h"

namespace skylight::report::detail {
namespace {

constexpr const char* kSampleEpw = "weather/synthetic_munich.epw";

struct Spread {
  double median = kNaN, p95 = kNaN;
  std::size_t n = 0;
};

Spread spread_of(std::vector<double> rel) {
  Spread s;
  s.n = rel.size();
  if (rel.empty()) return s;
  for (double& r : rel) r = std::abs(r);
  s.median = median(rel);
  s.p95 = nearest_rank_percentile(rel, 0.95);
  return s;
}

Json spread_json(const Spread& s) {
  if (s.n == 0) return nullptr;
  return {{"hours", s.n}, {"median", num(s.median)}, {"p95", num(s.p95)}};
}

// The sampled hours of section 9: each sky's diffuse horizontal illuminance against the efficacy
// model's (x) and, where the file measured it, against the file's, with the relative errors.
struct WeatherSamples {
  std::vector<double> efficacy_x, measured_x, sky_y_eff, sky_y_meas, rel_eff, rel_meas;
};
WeatherSamples weather_samples(const daylight::SkyMatrix& m, const Config& cfg) {
  WeatherSamples w;
  for (std::size_t k = 0; k < m.hours.size(); k += static_cast<std::size_t>(cfg.weather_stride)) {
    const daylight::MatrixHour& h = m.hours[k];
    if (!(h.dhi_w_m2 > 0.0) || !(h.diffuse_horizontal_lux > 0.0)) continue;
    PerezParameters p;
    p.sun = {deg_to_rad(h.sun_zenith_deg), deg_to_rad(h.sun_azimuth_deg)};
    p.dni = h.dni_w_m2;
    p.dhi = h.dhi_w_m2;
    p.day_of_year = h.day_of_year;
    p.dew_point = h.dew_point_c;
    const PerezModel sky(p);
    const double e =
        analysis::diffuse_horizontal_illuminance(sky, cfg.weather_n_theta, cfg.weather_n_phi);
    w.efficacy_x.push_back(h.diffuse_horizontal_lux);
    w.sky_y_eff.push_back(e);
    w.rel_eff.push_back(e / h.diffuse_horizontal_lux - 1.0);
    if (h.measured_diffuse_lux && *h.measured_diffuse_lux > 0.0) {
      w.measured_x.push_back(*h.measured_diffuse_lux);
      w.sky_y_meas.push_back(e);
      w.rel_meas.push_back(e / *h.measured_diffuse_lux - 1.0);
    }
  }
  return w;
}

// The plot of the sampled hours' skies against the file's and the efficacy model's illuminance,
// with the 1:1 line.
svg::Plot weather_plot(const WeatherSamples& w, bool measured) {
  svg::Plot plot;
  plot.id = "weather";
  plot.title = measured ? "Diffuse horizontal illuminance: each hour's sky against the file"
                        : "Each hour's sky against its efficacy-model illuminance (a self-test)";
  double hi = 1.0;
  for (double v : w.efficacy_x) hi = std::max(hi, v);
  for (double v : w.measured_x) hi = std::max(hi, v);
  for (double v : w.sky_y_eff) hi = std::max(hi, v);
  hi = std::ceil(hi / 10000.0) * 10000.0;
  plot.series.push_back(svg::line_series("1:1", {0.0, hi}, {0.0, hi}, "#888888", 1.0, "4 3"));
  if (measured)
    plot.series.push_back(
        svg::marker_series("measured (file)", w.measured_x, w.sky_y_meas, "#1f77b4"));
  plot.series.push_back(
      svg::marker_series("Perez 1990 efficacy x DHI", w.efficacy_x, w.sky_y_eff, "#ff7f0e", 2.0));
  plot.x = {0.0, hi, false, "diffuse horizontal illuminance of the hour [lx]", {}};
  plot.y = {0.0, hi, false, "the hour's sky integrated over the hemisphere [lx]", {}};
  plot.width = 720;
  plot.height = 480;
  return plot;
}

// The table of the spreads against the file's measured illuminance and the efficacy model's.
std::string spread_table(const Spread& meas, const Spread& eff) {
  HtmlTable t({"against", "hours", "median |sky / x - 1|", "p95"});
  auto row = [&](const std::string& what, const Spread& s) {
    if (s.n == 0) {
      t.row({what, "0", "n/a (the file has no measured diffuse illuminance)", ""});
      return;
    }
    t.row({what, fmt::format("{}", s.n), fmt::format("{:.2f} %", 100.0 * s.median),
           fmt::format("{:.2f} %", 100.0 * s.p95)});
  };
  row("the file's measured diffuse horizontal illuminance", meas);
  row("the efficacy model's (Perez 1990 eq. 7 x the file's DHI)", eff);
  return t.html();
}

}  // namespace

void ReportWriter::load_weather() {
  weather_name_ = opt_.epw ? io::shown_path(*opt_.epw) : "data/" + std::string(kSampleEpw);
  weather_ = opt_.epw ? io::read_epw(*opt_.epw)
                      : io::parse_epw(data::embedded_file(kSampleEpw), weather_name_);
}

void ReportWriter::weather_hours() {
  // The hours' skies: a record the sky cannot use fails here, before any file is written.
  daylight::MatrixSettings settings;
  settings.sun_patches = 0;
  weather_matrix_ = std::make_shared<daylight::SkyMatrix>(
      daylight::sky_matrix(weather_, settings, weather_name_));
}

void ReportWriter::section_daylight() {
  const bool shipped = !opt_.epw.has_value();
  const std::string& name = weather_name_;
  const io::EpwFile& epw = weather_;
  const daylight::SkyMatrix& m = *weather_matrix_;
  const WeatherSamples w = weather_samples(m, cfg_);
  const Spread eff = spread_of(w.rel_eff), meas = spread_of(w.rel_meas);
  const bool measured = meas.n > 0;

  const svg::Plot plot = weather_plot(w, measured);

  const std::string table = spread_table(meas, eff);
  html_weather_ =
      (shipped ? std::string(
                     "<p class=\"note\">The shipped weather year is <b>synthetic</b> (no station "
                     "measured it; data/weather/PROVENANCE.md) and has no measured illuminance: "
                     "this section is a <b>self-test</b> that each hour's sky integrates to the "
                     "illuminance the efficacy model gives. Pass a station's EPW with "
                     "<code>--epw FILE</code> to compare with measured illuminance.</p>\n")
               : std::string()) +
      fmt::format(
          "<p>{}: {} records, {} with the sun up at the hour's midpoint; every {}th of those "
          "with diffuse light becomes the <code>perez</code> sky of its direct normal and "
          "diffuse horizontal radiation (Perez et al. 1990 and 1993, the papers' mode; "
          "docs/DAYLIGHT.md), integrated over the hemisphere ({} x {} grid, weight cos "
          "theta).</p>\n",
          esc_html(name), epw.records.size(), m.hours.size(), cfg_.weather_stride,
          cfg_.weather_n_theta, cfg_.weather_n_phi) +
      table +
      figure("weather_diffuse.svg", svg::draw(plot),
             measured ? "Each sampled hour: the sky's diffuse horizontal illuminance against the "
                        "file's measured value (blue) and the efficacy model's (orange)."
                      : "Each sampled hour: the sky's diffuse horizontal illuminance against the "
                        "efficacy model's value; no measured illuminance in this file.");
  json_["daylight_from_weather"] = {{"file", name},
                                    {"synthetic", shipped},
                                    {"records", epw.records.size()},
                                    {"hours_sun_up", m.hours.size()},
                                    {"stride", cfg_.weather_stride},
                                    {"sky_vs_measured", spread_json(meas)},
                                    {"sky_vs_efficacy_model", spread_json(eff)}};
}

}  // namespace skylight::report::detail
