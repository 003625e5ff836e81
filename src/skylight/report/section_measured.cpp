// "Against measured skies": every model with an estimation policy and a report policy fitted to
// Kider et al. 2014's clear skies by `skylight measured`'s library code (fit/measured_fit.h), its
// errors in shape, absolute level, spectrum and colour, the solar vertical and almucantar of one
// capture and each model's error over the scan (docs/MEASURED.md, docs/REPORT.md).
#include <algorithm>

#include "skylight/core/error.h"
#include "skylight/core/statistics.h"
#include "skylight/report/detail/writer.h"

namespace skylight::report::detail {
namespace {

// The error classes of the maps over the scan: scale x model / measured - 1 [%], each a colour
// from "model too dark" (blue) to "too bright" (red).
constexpr std::array<double, 6> kErrorEdgesPercent = {-30, -15, -5, 5, 15, 30};
constexpr std::array<std::string_view, 7> kErrorColours = {
    "#2166ac", "#67a9cf", "#d1e5f0", "#e0e0e0", "#fddbc7", "#ef8a62", "#b2182b"};
// Model curves along the solar vertical and the almucantar: one value per degree.
constexpr double kCurveStepDeg = 1.0;

// The median of the finite values (NaN: none).
double median_of(std::vector<double> v) {
  std::erase_if(v, [](double x) { return !std::isfinite(x); });
  return v.empty() ? kNaN : median(std::move(v));
}

// RMS of log10(scale M / m) over the samples used: the shape error in the trust table's measure.
double shape_log10(const fit::MeasuredCaptureResult& r) {
  double s = 0.0;
  int n = 0;
  for (const auto& m : r.samples)
    if (m.used) {
      const double d = std::log10(r.scale * m.model_luminance / m.measured_luminance);
      s += d * d;
      ++n;
    }
  return n ? std::sqrt(s / n) : kNaN;
}

// "min–max" of each fitted parameter over the captures, joined by `separator`.
std::string parameters_text(const std::vector<fit::MeasuredCaptureResult>& captures,
                            std::string_view separator = "<br/>") {
  if (captures.empty()) return "—";
  std::string out;
  for (std::size_t a = 0; a < captures.front().fit.parameters.size(); ++a) {
    double lo = kInf, hi = -kInf;
    for (const auto& r : captures) {
      lo = std::min(lo, r.fit.parameters[a].value);
      hi = std::max(hi, r.fit.parameters[a].value);
    }
    out += fmt::format("{}{} {}", out.empty() ? "" : separator,
                       captures.front().fit.parameters[a].name,
                       lo == hi ? g3(lo) : g3(lo) + "–" + g3(hi));
  }
  return out;
}

// "median [min, max]" of a per-capture number, in per cent or plain.
template <class F>
std::string spread_text(const std::vector<fit::MeasuredCaptureResult>& captures, F value,
                        bool percent) {
  std::vector<double> v;
  for (const auto& r : captures)
    if (const double x = value(r); std::isfinite(x)) v.push_back(x);
  if (v.empty()) return "—";
  const double k = percent ? 100.0 : 1.0;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  if (percent)
    return fmt::format("{:.1f} % <small>[{:.1f}, {:.1f}]</small>", k * median_of(v), k * *lo,
                       k * *hi);
  return fmt::format("{:.2f} <small>[{:.2f}, {:.2f}]</small>", median_of(v), *lo, *hi);
}

// The captures a model is compared on: all, or for a model with costly set-up the middle, first
// and last (as many as `costly` allows).
std::vector<io::KiderCapture> captures_for(const ModelInfo& info,
                                           const std::vector<io::KiderCapture>& all, int costly) {
  if (!info.costly_setup) return all;
  std::vector<std::size_t> idx;
  for (std::size_t i : {all.size() / 2, std::size_t{0}, all.size() - 1})
    if (static_cast<int>(idx.size()) < costly && std::find(idx.begin(), idx.end(), i) == idx.end())
      idx.push_back(i);
  std::sort(idx.begin(), idx.end());
  std::vector<io::KiderCapture> out;
  for (std::size_t i : idx) out.push_back(all[i]);
  return out;
}

// The fisheye position of a direction (upward view, north up, east right; the horizon at 1).
std::array<double, 2> fisheye(double zenith_deg, double azimuth_deg) {
  const double r = zenith_deg / 90.0, a = azimuth_deg * kDegree;
  return {r * std::sin(a), r * std::cos(a)};
}

// The scan's samples along the solar vertical (per ring, the one nearest the vertical on each
// side) and the almucantar (every sample of the ring nearest the sun's zenith angle), with the
// samples near the sun (not fitted) apart: v the vertical, a the almucantar, n near the sun.
struct ScanProfiles {
  double almucantar_zenith = 0.0;
  std::vector<double> vx, vy, ax, ay, vnx, vny, anx, any;
};
ScanProfiles scan_profiles(const fit::MeasuredCaptureResult& r, double sun_zenith,
                           double sun_azimuth) {
  ScanProfiles p;
  auto& [almucantar_zenith, vx, vy, ax, ay, vnx, vny, anx, any] = p;
  std::map<double, std::vector<const fit::MeasuredSampleResult*>> rings;
  for (const auto& s : r.samples) rings[std::round(s.zenith_deg * 100.0) / 100.0].push_back(&s);
  const auto relative_azimuth = [&](double az) {
    return std::remainder(az - sun_azimuth, 360.0);  // -180..180, 0 at the sun
  };
  double nearest = kInf;
  for (const auto& [zenith, samples] : rings)
    if (zenith > 0.0 && std::abs(zenith - sun_zenith) < nearest) {
      nearest = std::abs(zenith - sun_zenith);
      almucantar_zenith = zenith;
    }
  for (const auto& [zenith, samples] : rings) {
    const fit::MeasuredSampleResult *toward = nullptr, *away = nullptr;
    for (const auto* s : samples) {
      const double d = std::abs(relative_azimuth(s->azimuth_deg));
      if (!toward || d < std::abs(relative_azimuth(toward->azimuth_deg))) toward = s;
      if (!away || d > std::abs(relative_azimuth(away->azimuth_deg))) away = s;
      if (zenith == almucantar_zenith) {
        (s->used ? ax : anx).push_back(relative_azimuth(s->azimuth_deg));
        (s->used ? ay : any).push_back(s->measured_luminance);
      }
    }
    (toward->used ? vx : vnx).push_back(zenith);
    (toward->used ? vy : vny).push_back(toward->measured_luminance);
    if (zenith > 0.0) {
      vx.push_back(-zenith);
      vy.push_back(away->measured_luminance);
    }
  }
  return p;
}

// A fitted model times its scale along the exact solar vertical and the almucantar at
// `almucantar_zenith` [deg], into the two plots; lo, hi: the range of its positive values.
void add_model_curves(const std::string& model, const fit::MeasuredCaptureResult& r,
                      double sun_azimuth, double almucantar_zenith, svg::Plot& vertical,
                      svg::Plot& almucantar, double& lo, double& hi) {
  const auto sky = fit::fitted_model(r.fit, r.sun.sun);
  std::vector<double> xs, ys, as, bs;
  for (double x = -90.0; x <= 90.0 + 1e-9; x += kCurveStepDeg) {
    const double az = x >= 0.0 ? sun_azimuth : sun_azimuth + 180.0;
    xs.push_back(x);
    ys.push_back(r.scale *
                 sky->tristimulus(direction_from_angles(std::abs(x) * kDegree, az * kDegree)).Y);
  }
  for (double a = -180.0; a <= 180.0 + 1e-9; a += kCurveStepDeg) {
    as.push_back(a);
    bs.push_back(r.scale * sky->tristimulus(direction_from_angles(almucantar_zenith * kDegree,
                                                                  (sun_azimuth + a) * kDegree))
                               .Y);
  }
  for (double y : ys)
    if (y > 0.0) lo = std::min(lo, y), hi = std::max(hi, y);
  const std::string label = fmt::format("{} × {:.2f}", model, r.scale);
  vertical.series.push_back(svg::line_series(label, xs, ys, comparison_colour(model), 1.4));
  almucantar.series.push_back(svg::line_series(label, as, bs, comparison_colour(model), 1.4));
}

// A model's error over the scan (scale x model / measured - 1 in kErrorColours' classes) on an
// upward fisheye, the samples near the sun hollow, the sun marked.
svg::Plot error_map(const std::string& model, const fit::MeasuredCaptureResult& r,
                    double sun_zenith, double sun_azimuth) {
  svg::Plot p;
  p.id = "measured-map-" + model;
  p.title = fmt::format("{}: scale × model / measured − 1", model);
  p.x = {-1.08, 1.08, false, "", {-5}};
  p.y = {-1.08, 1.08, false, "", {-5}};
  for (double ring : {30.0, 60.0, 90.0}) {
    std::vector<double> cx, cy;
    for (int k = 0; k <= 72; ++k) {
      const auto q = fisheye(ring, 5.0 * k);
      cx.push_back(q[0]);
      cy.push_back(q[1]);
    }
    p.series.push_back(svg::line_series("", cx, cy, "#bbbbbb", 0.8));
  }
  std::array<std::vector<double>, kErrorColours.size()> bx, by;
  std::vector<double> ux, uy;
  for (const auto& s : r.samples) {
    const auto q = fisheye(s.zenith_deg, s.azimuth_deg);
    if (!s.used) {
      ux.push_back(q[0]);
      uy.push_back(q[1]);
      continue;
    }
    const double e = 100.0 * (r.scale * s.model_luminance / s.measured_luminance - 1.0);
    const std::size_t bin = static_cast<std::size_t>(
        std::upper_bound(kErrorEdgesPercent.begin(), kErrorEdgesPercent.end(), e) -
        kErrorEdgesPercent.begin());
    bx[bin].push_back(q[0]);
    by[bin].push_back(q[1]);
  }
  for (std::size_t b = 0; b < kErrorColours.size(); ++b) {
    const std::string name =
        b == 0 ? fmt::format("< {:g} %", kErrorEdgesPercent[0])
        : b == kErrorEdgesPercent.size()
            ? fmt::format("> {:g} %", kErrorEdgesPercent.back())
            : fmt::format("{:g} to {:g} %", kErrorEdgesPercent[b - 1], kErrorEdgesPercent[b]);
    svg::Series s = svg::marker_series(name, bx[b], by[b], std::string(kErrorColours[b]), 5.0);
    s.marker_stroke = "#555555";
    p.series.push_back(std::move(s));
  }
  svg::Series unused = svg::marker_series("not used (near the sun)", ux, uy, "#ffffff", 4.0);
  unused.marker_stroke = "#999999";
  p.series.push_back(std::move(unused));
  const auto sun = fisheye(sun_zenith, sun_azimuth);
  p.series.push_back(svg::marker_series("sun", {sun[0]}, {sun[1]}, "#ff9800", 6.0));
  p.width = 615;  // a square plot area beside the legend
  p.height = 420;
  p.legend_outside = true;
  return p;
}

// The profiles' axes: one log luminance axis over [lo, hi] and the near-sun points, the view
// zenith and the azimuth from the sun, the sun's line on the vertical, and the figures' size.
void set_profile_axes(const ScanProfiles& pr, double sun_zenith, double lo, double hi,
                      svg::Plot& vertical, svg::Plot& almucantar) {
  for (double v : pr.vny) lo = std::min(lo, v), hi = std::max(hi, v);
  for (double v : pr.any) lo = std::min(lo, v), hi = std::max(hi, v);
  for (double v : pr.ay) lo = std::min(lo, v), hi = std::max(hi, v);
  const svg::Axis y{std::pow(10.0, std::floor(std::log10(lo))),
                    std::pow(10.0, std::ceil(std::log10(hi))),
                    true,
                    "luminance [cd/m2]",
                    {}};
  vertical.x = {-90,
                90,
                false,
                "view zenith angle [deg] (negative: away from the sun)",
                {-90, -60, -30, 0, 30, 60, 90}};
  vertical.y = y;
  vertical.series.push_back(
      svg::line_series("sun", {sun_zenith, sun_zenith}, {y.min, y.max}, "#ff9800", 1.5, "5 3"));
  almucantar.x = {
      -180, 180, false, "azimuth from the sun [deg]", {-180, -135, -90, -45, 0, 45, 90, 135, 180}};
  almucantar.y = y;
  for (svg::Plot* p : {&vertical, &almucantar}) {
    p->width = 900;
    p->height = 380;
    p->legend_outside = true;
  }
}

}  // namespace

void ReportWriter::load_kider() {
  if (opt_.kider) {
    kider_ = io::read_kider(*opt_.kider);
    kider_source_ = fmt::format("<code>{}</code>", esc_html(io::shown_path(*opt_.kider)));
  } else {
    kider_ = io::shipped_kider_subset();
    kider_source_ =
        fmt::format("the shipped subset (<code>data/{}</code>)", io::kKiderSubsetDataDir);
  }
  if (kider_.empty()) throw InvalidArgument("report: the measured skies hold no capture");
}

const MeasuredModel* ReportWriter::measured_model(std::string_view name) const {
  for (const MeasuredModel& m : measured_)
    if (m.model == name) return &m;
  return nullptr;
}

void ReportWriter::measured_skies() {
  for (const ModelInfo& info : model_registry()) {
    if (!info.estimation || info.report.title.empty()) continue;
    MeasuredModel m;
    m.model = info.name;
    fit::MeasuredSettings s;
    s.model = info.name;
    const std::vector<io::KiderCapture> captures =
        captures_for(info, kider_, cfg_.measured_costly_captures);
    if (!captures.empty()) m.captures = fit::compare_to_measured(captures, s);
    std::vector<double> shape, log10s, abs, scale, spectral, duv;
    for (const auto& r : m.captures) {
      shape.push_back(r.luminance_rms_shape);
      log10s.push_back(shape_log10(r));
      abs.push_back(r.luminance_rms_abs);
      scale.push_back(r.scale);
      spectral.push_back(r.spectral_rms.value_or(kNaN));
      duv.push_back(r.mean_delta_uv);
    }
    m.shape = median_of(shape);
    m.shape_log10 = median_of(log10s);
    m.abs = median_of(abs);
    m.scale = median_of(scale);
    m.spectral = median_of(spectral);
    m.duv = median_of(duv);
    measured_.push_back(std::move(m));
  }
  std::vector<double> elevations;
  for (const MeasuredModel& m : measured_)
    if (m.captures.size() == kider_.size()) {
      for (const auto& r : m.captures) elevations.push_back(90.0 - rad_to_deg(r.sun.sun.zenith));
      break;
    }
  measured_sun_elevation_deg_ = median_of(elevations);
  measured_figures();
}

std::string ReportWriter::measured_summary_line() const {
  std::vector<const MeasuredModel*> ranked;
  for (const MeasuredModel& m : measured_)
    if (!m.captures.empty()) ranked.push_back(&m);
  std::sort(ranked.begin(), ranked.end(),
            [](const MeasuredModel* a, const MeasuredModel* b) { return a->shape < b->shape; });
  std::string shapes, levels;
  for (const MeasuredModel* m : ranked) {
    shapes += fmt::format("{}<code>{}</code> {:.1f} %", shapes.empty() ? "" : ", ", m->model,
                          100.0 * m->shape);
    levels +=
        fmt::format("{}<code>{}</code> ×{:.2f}", levels.empty() ? "" : ", ", m->model, m->scale);
  }
  return fmt::format(
      "<b>Against measured clear skies</b> (<a href=\"#measured-skies\">{} captures</a>, "
      "parameters fitted per capture): luminance shape RMS {}; measured / model level {}.",
      kider_.size(), shapes, levels);
}

std::string ReportWriter::kider_opt_text() const {
  return opt_.kider ? io::shown_path(*opt_.kider)
                    : fmt::format("data/{} (shipped)", io::kKiderSubsetDataDir);
}

// The chosen capture (the middle one: every model is compared on it): its solar vertical and
// almucantar, measured points against each model's fitted sky times its scale, and each model's
// error over the scan.
void ReportWriter::measured_figures() {
  const io::KiderCapture& chosen = kider_[kider_.size() / 2];
  std::vector<std::pair<const MeasuredModel*, const fit::MeasuredCaptureResult*>> on_chosen;
  for (const MeasuredModel& m : measured_)
    for (const auto& r : m.captures)
      if (r.name == chosen.name) on_chosen.emplace_back(&m, &r);
  if (on_chosen.empty()) return;
  const fit::MeasuredCaptureResult& first = *on_chosen.front().second;
  const double sun_zenith = rad_to_deg(first.sun.sun.zenith);
  const double sun_azimuth = rad_to_deg(first.sun.sun.azimuth);
  const ScanProfiles pr = scan_profiles(first, sun_zenith, sun_azimuth);
  const double almucantar_zenith = pr.almucantar_zenith;
  svg::Plot vertical, almucantar;
  vertical.id = "measured-vertical";
  vertical.title = fmt::format("Solar vertical, {} (sun zenith {:.1f}°)", chosen.name, sun_zenith);
  almucantar.id = "measured-almucantar";
  almucantar.title =
      fmt::format("Almucantar at view zenith {:.1f}°, {}", almucantar_zenith, chosen.name);
  double lo = kInf, hi = 0.0;
  for (double y : pr.vy) lo = std::min(lo, y), hi = std::max(hi, y);
  for (const auto& [m, r] : on_chosen)
    add_model_curves(m->model, *r, sun_azimuth, almucantar_zenith, vertical, almucantar, lo, hi);
  vertical.series.push_back(svg::marker_series("measured", pr.vx, pr.vy, "#000000", 3.0));
  almucantar.series.push_back(svg::marker_series("measured", pr.ax, pr.ay, "#000000", 3.0));
  const auto near_sun = [](std::vector<double> x, std::vector<double> y) {
    svg::Series s = svg::marker_series("measured, near the sun (not fitted)", std::move(x),
                                       std::move(y), "#ffffff", 3.5);
    s.marker_stroke = "#000000";
    return s;
  };
  almucantar.series.push_back(near_sun(pr.anx, pr.any));
  vertical.series.push_back(near_sun(pr.vnx, pr.vny));
  set_profile_axes(pr, sun_zenith, lo, hi, vertical, almucantar);
  std::string html = figure(
      "measured_solar_vertical.svg", svg::draw(vertical),
      fmt::format("Capture {} ({} EDT): the measured luminance of the scan's samples nearest the "
                  "solar vertical (one per ring on each side; a ring of 8 samples is up to "
                  "22.5° off the vertical) and each model fitted to this capture times its "
                  "scale, along the exact vertical. The sun's azimuth from the sky's symmetry.",
                  chosen.name, chosen.local_time));
  html +=
      figure("measured_almucantar.svg", svg::draw(almucantar),
             fmt::format("The same capture around the ring of the scan nearest the sun's "
                         "zenith angle ({:.1f}° against the sun's {:.1f}°): every sample of the "
                         "ring, and the models along the same ring.",
                         almucantar_zenith, sun_zenith));
  // Each model's error over the scan.
  for (const auto& [m, r] : on_chosen) {
    const svg::Plot p = error_map(m->model, *r, sun_zenith, sun_azimuth);
    html += figure(fmt::format("measured_error_{}.svg", m->model), svg::draw(p),
                   fmt::format("<code>{}</code> fitted to {} ({}): each sample's error after the "
                               "scale, on an upward fisheye (north up, east right; circles at "
                               "view zenith 30°, 60°, 90°); shape RMS {:.1f} %.",
                               m->model, chosen.name, parameters_text({*r}, ", "),
                               100.0 * r->luminance_rms_shape));
  }
  html_measured_figures_ = html;
}

TrustVerdict absolute_verdict(double scale) {
  if (!(scale > 0.0) || !std::isfinite(scale)) return TrustVerdict::avoid;
  const double factor = std::max(scale, 1.0 / scale);
  if (factor <= kAbsoluteUseFactor) return TrustVerdict::use;
  return factor <= kAbsoluteCareFactor ? TrustVerdict::care : TrustVerdict::avoid;
}

TrustVerdict spectrum_verdict(double spectral_rms) {
  if (!std::isfinite(spectral_rms)) return TrustVerdict::not_judged;
  if (spectral_rms <= kSpectrumUseRms) return TrustVerdict::use;
  return spectral_rms <= kSpectrumCareRms ? TrustVerdict::care : TrustVerdict::avoid;
}

std::string verdict_html(TrustVerdict v, std::string_view detail) {
  const char* cls = v == TrustVerdict::use ? "use" : v == TrustVerdict::care ? "care" : "avoid";
  if (v == TrustVerdict::not_judged || v == TrustVerdict::reference)
    return fmt::format("{}<br/><small>{}</small>", trust_verdict_name(v), detail);
  return fmt::format("<span class=\"verdict-{}\">{}</span><br/><small>{}</small>", cls,
                     trust_verdict_name(v), detail);
}

// A model's row of the section's table and its record in report.json (step: the clear CIE
// types' neighbour step of the shape rule).
std::pair<std::vector<std::string>, Json> measured_row(const MeasuredModel& m, double step) {
  if (m.captures.empty())
    return {{fmt::format("<code>{}</code>", m.model), "0",
             "not compared in the quick report (a table per parameter set)", "", "", "", "", "", "",
             "not judged", "not judged", "not judged"},
            Json{{"model", m.model}, {"captures", Json::array()}, {"verdict", "not judged"}}};
  const TrustVerdict shape = trust_verdict(m.shape_log10, step);
  const TrustVerdict absolute = absolute_verdict(m.scale);
  const TrustVerdict spectrum = spectrum_verdict(m.spectral);
  const auto& c = m.captures;
  std::vector<std::string> cells = {
      fmt::format("<code>{}</code>", m.model),
      fmt::format("{}", c.size()),
      parameters_text(c),
      spread_text(
          c, [](const auto& r) { return r.luminance_rms_shape; }, true),
      g3(m.shape_log10),
      spread_text(
          c, [](const auto& r) { return r.luminance_rms_abs; }, true),
      spread_text(
          c, [](const auto& r) { return r.scale; }, false),
      spread_text(
          c, [](const auto& r) { return r.spectral_rms.value_or(kNaN); }, true),
      std::isfinite(m.duv) ? fmt::format("{:.4f}", m.duv) : "—",
      verdict_html(shape, fmt::format("{} vs step {}", g3(m.shape_log10), g3(step))),
      verdict_html(absolute, fmt::format("×{:.2f}", m.scale)),
      verdict_html(spectrum, std::isfinite(m.spectral) ? fmt::format("{:.1f} %", 100.0 * m.spectral)
                                                       : std::string("luminance only"))};
  Json names = Json::array();
  for (const auto& r : c) names.push_back(r.name);
  return {std::move(cells), Json{{"model", m.model},
                                 {"captures", names},
                                 {"median_luminance_rms_shape", num(m.shape)},
                                 {"median_rms_log10_shape", num(m.shape_log10)},
                                 {"median_luminance_rms_abs", num(m.abs)},
                                 {"median_scale", num(m.scale)},
                                 {"median_spectral_rms", num(m.spectral)},
                                 {"median_mean_delta_uv", num(m.duv)},
                                 {"verdict_shape", trust_verdict_name(shape)},
                                 {"verdict_absolute", trust_verdict_name(absolute)},
                                 {"verdict_spectrum", trust_verdict_name(spectrum)}}};
}

void ReportWriter::measured_table() {
  const fit::MeasuredSettings defaults;
  HtmlTable table({"model", "captures", "fitted", "shape RMS", "RMS log<sub>10</sub> (shape)",
                   "absolute RMS", "scale (measured / model)", "spectral RMS 380–780 nm",
                   "mean Δu′v′", "shape", "absolute level", "spectrum"},
                  {true, false, true});
  Json models = Json::array();
  for (const MeasuredModel& m : measured_) {
    auto [cells, record] = measured_row(m, measured_neighbour_step_);
    table.row(cells);
    models.push_back(std::move(record));
  }
  html_measured_ = fmt::format(
      "<p>Every model with a fit (an estimation policy) fitted to each measured clear sky of "
      "Kider et al. 2014 (Cornell, 2013-05-27, 81 directions of spectral radiance per scan, "
      "Apache-2.0) from {}: {} captures, sun elevation {:.0f}–{:.0f}° (median {:.0f}°). Per "
      "capture the model's free parameters by the library's fit floor (as <code>skylight "
      "measured</code>), the sun's azimuth from the sky's symmetry, the samples more than {:g}° "
      "from the sun; the physical models whose tables cost seconds are searched with "
      "<code>nishita</code>'s single scattering and compared on {} of them (the middle first; "
      "<code>skylight measured</code> compares them on all, docs/MEASURED.md). "
      "Medians over the captures [min, max]. <b>Shape</b>: the RMS of log<sub>10</sub>(scale × "
      "model / measured) with the rule of <a href=\"#trust\">the trust table</a> against the "
      "median step between neighbouring clear CIE types at the captures' sun ({}). <b>Absolute "
      "level</b>: the scale (measured / model) within ×{:g} either way is <i>use</i>, within "
      "×{:g} <i>use with care</i> (the multiple-scattering atmospheres computed from the solar "
      "spectrum meet the scans within 11–13 %: the scans' level is not the 2× question). "
      "<b>Spectrum</b>: the relative RMS of scale × the model's spectral radiance against the "
      "measured one, 380–780 nm, up to {:g} % <i>use</i>, {:g} % <i>use with care</i>. Clear "
      "skies of one site and one day: no verdict here reaches overcast or intermediate skies."
      "</p>\n{}{}",
      kider_source_, kider_.size(),
      [&] {
        double lo = kInf;
        for (const auto& m : measured_)
          for (const auto& r : m.captures) lo = std::min(lo, 90.0 - rad_to_deg(r.sun.sun.zenith));
        return lo;
      }(),
      [&] {
        double hi = -kInf;
        for (const auto& m : measured_)
          for (const auto& r : m.captures) hi = std::max(hi, 90.0 - rad_to_deg(r.sun.sun.zenith));
        return hi;
      }(),
      measured_sun_elevation_deg_, defaults.exclude_sun_deg, cfg_.measured_costly_captures,
      g3(measured_neighbour_step_), kAbsoluteUseFactor, kAbsoluteCareFactor,
      100.0 * kSpectrumUseRms, 100.0 * kSpectrumCareRms, table.html(), html_measured_figures_);
  json_["against_measured_skies"] = {
      {"source", kider_opt_text()},
      {"captures", kider_.size()},
      {"chosen_capture", kider_[kider_.size() / 2].name},
      {"exclude_sun_deg", defaults.exclude_sun_deg},
      {"sun_azimuth_from", "symmetry"},
      {"clear_neighbour_rms_log10", num(measured_neighbour_step_)},
      {"rules",
       fmt::format("shape: the trust table's rule on the median RMS log10; absolute: scale within "
                   "x{:g} use, x{:g} care; spectrum: RMS <= {:g} use, <= {:g} care",
                   kAbsoluteUseFactor, kAbsoluteCareFactor, kSpectrumUseRms, kSpectrumCareRms)},
      {"models", models}};
}

}  // namespace skylight::report::detail
