// Section 10 of the report: light on planes. For the weather year of section 9, the annual
// irradiation of a south façade and a 30 deg south roof (`skylight irradiance --epw`,
// daylight/plane_series.h): each model with a ReportPolicy::planes integrated over the plane's
// view (the `sky` method: the model's sky distribution, the hour's measured level) against Perez
// et al. 1990's transposition of the same hours, with the parts that explain the differences.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

#include "skylight/core/math.h"
#include "skylight/daylight/plane_series.h"
#include "skylight/report/detail/writer.h"

namespace skylight::report::detail {
namespace {

struct ReportPlane {
  const char* name;
  double tilt_deg, azimuth_deg;
};
constexpr ReportPlane kReportPlanes[] = {{"south façade (tilt 90°)", 90.0, 180.0},
                                         {"south roof (tilt 30°)", 30.0, 180.0}};

// A method's year on one plane [kWh/m^2]: global, sky diffuse and the sky's three parts.
struct PlaneYear {
  std::string method;
  double global = 0.0, sky = 0.0, circumsolar = 0.0, horizon = 0.0, rest = 0.0;
};

PlaneYear year_of(std::string method, const daylight::PlaneSeries& s) {
  PlaneYear y;
  y.method = std::move(method);
  for (const daylight::PlaneChannels& c : s.light) {
    const daylight::PlaneLight& p = *c.irradiance;
    y.global += p.global().value_or(0.0) / 1000.0;
    y.sky += p.sky_diffuse / 1000.0;
    y.circumsolar += p.circumsolar.value_or(0.0) / 1000.0;
    y.horizon += p.horizon.value_or(0.0) / 1000.0;
    y.rest += p.isotropic.value_or(0.0) / 1000.0;
  }
  return y;
}

// The label and the series settings of a model's sky method (its ReportPolicy::planes values).
std::pair<std::string, daylight::SeriesSettings> model_settings(
    const ModelInfo& info, const daylight::SeriesSettings& base) {
  daylight::SeriesSettings s = base;
  s.weather_sky = info.weather_sky;
  std::string label = "sky: " + info.name;
  if (!info.weather_sky) {
    s.model = daylight::sky_for_sun(info.name, *info.report.planes);
    for (const auto& [name, value] : info.report.planes->all())
      label += fmt::format(" {} {}", name, std::get<double>(value));
  }
  return {label, s};
}

std::string plane_table(const std::vector<PlaneYear>& rows) {
  HtmlTable t({"method", "global", "sky diffuse", "sky vs perez1990", "circumsolar", "horizon band",
               "rest"});
  const PlaneYear& ref = rows.front();
  for (const PlaneYear& r : rows)
    t.row(
        {r.method, fmt::format("{:.1f}", r.global), fmt::format("{:.1f}", r.sky),
         &r == &ref ? std::string("—") : fmt::format("{:+.1f} %", 100.0 * (r.sky / ref.sky - 1.0)),
         fmt::format("{:.1f}", r.circumsolar), fmt::format("{:.1f}", r.horizon),
         fmt::format("{:.1f}", r.rest)});
  return t.html();
}

// Why a sky method differs from perez1990 on a plane, from the parts: the largest difference.
std::string difference_reason(const PlaneYear& m, const PlaneYear& ref) {
  const double dc = m.circumsolar - ref.circumsolar, dh = m.horizon - ref.horizon,
               dr = m.rest - ref.rest;
  const double largest = std::max({std::abs(dc), std::abs(dh), std::abs(dr)});
  const char* part = largest == std::abs(dc)   ? "circumsolar"
                     : largest == std::abs(dh) ? "horizon-band"
                                               : "remaining";
  const double d = largest == std::abs(dc) ? dc : largest == std::abs(dh) ? dh : dr;
  return fmt::format(
      "{}: {:+.1f} kWh/m² of sky diffuse light against perez1990, most of it in "
      "the {} part ({:+.1f} kWh/m²)",
      m.method, m.sky - ref.sky, part, d);
}

// Each plane's table, the reasons of its differences, and its report.json record.
std::string planes_tables(const std::vector<std::vector<PlaneYear>>& years, Json& planes) {
  std::string html;
  for (std::size_t k = 0; k < years.size(); ++k) {
    html += fmt::format("<h3>{}</h3>\n", kReportPlanes[k].name) + plane_table(years[k]) + "<ul>\n";
    Json rows = Json::array();
    for (const PlaneYear& y : years[k]) {
      if (&y != &years[k].front())
        html += "<li>" + esc_html(difference_reason(y, years[k].front())) + "</li>\n";
      rows.push_back({{"method", y.method},
                      {"global_kwh_m2", num(y.global)},
                      {"sky_diffuse_kwh_m2", num(y.sky)},
                      {"circumsolar_kwh_m2", num(y.circumsolar)},
                      {"horizon_kwh_m2", num(y.horizon)},
                      {"rest_kwh_m2", num(y.rest)}});
    }
    html += "</ul>\n";
    planes.push_back({{"plane", kReportPlanes[k].name},
                      {"tilt_deg", kReportPlanes[k].tilt_deg},
                      {"surface_azimuth_deg", kReportPlanes[k].azimuth_deg},
                      {"methods", rows}});
  }
  return html;
}

}  // namespace

void ReportWriter::section_planes() {
  const io::HorizonProfile flat;
  std::vector<daylight::PlaneContext> sky, perez;
  for (const ReportPlane& p : kReportPlanes) {
    const daylight::Plane plane{deg_to_rad(p.tilt_deg), deg_to_rad(p.azimuth_deg)};
    sky.push_back(daylight::plane_context(plane, daylight::Transposition::sky, flat));
    perez.push_back(daylight::plane_context(plane, daylight::Transposition::perez1990, flat));
  }
  const auto pointers = [](const std::vector<daylight::PlaneContext>& v) {
    std::vector<const daylight::PlaneContext*> out;
    for (const auto& c : v) out.push_back(&c);
    return out;
  };
  daylight::SeriesSettings settings;
  // The quick report's records, where the file has them (a shorter file: all of it).
  const std::string& hours = cfg_.planes_hours;
  const std::size_t last = hours.empty() ? 0 : std::stoul(hours.substr(hours.find('-') + 1));
  if (last <= weather_.records.size()) settings.hours = hours;
  std::vector<std::vector<PlaneYear>> years(std::size(kReportPlanes));
  auto add = [&](const std::string& method, const std::vector<daylight::PlaneSeries>& s) {
    for (std::size_t k = 0; k < s.size(); ++k) years[k].push_back(year_of(method, s[k]));
  };
  add("perez1990 (the record's light)",
      daylight::plane_series(weather_, pointers(perez), settings, weather_name_));
  std::vector<std::string> left_out;
  for (const ModelInfo& info : model_registry()) {
    if (!info.report.planes) continue;
    if (info.costly_setup && !cfg_.planes_costly) {
      left_out.push_back(info.name);
      continue;
    }
    const auto [label, s] = model_settings(info, settings);
    add(label, daylight::plane_series(weather_, pointers(sky), s, weather_name_));
  }
  std::string html = fmt::format(
      "<p>The weather year of section 9 ({}{}) on two planes: the annual irradiation [kWh/m²] "
      "by Perez et al. 1990's transposition of each record's light and by the <code>sky</code> "
      "method, each model's sky integrated over the plane's view and scaled to the hour's "
      "measured diffuse light (<code>skylight irradiance --epw</code>; docs/IRRADIANCE.md). "
      "Direct and ground light are the same for every method (DNI cos AOI, and the record's "
      "albedo or 0.2); the differences are the sky's. Parts: perez1990's three terms; the "
      "<code>sky</code> method's circumsolar (within 25° of the sun), horizon band (below 6.5°) "
      "and rest.</p>\n",
      esc_html(weather_name_), settings.hours.empty() ? "" : ", records " + settings.hours);
  Json planes = Json::array();
  html += planes_tables(years, planes);
  html +=
      "<p>Where the methods differ, the parts say why (each list names the largest). The "
      "mechanisms: perez1990's F1 (a point source at the sun) and F2 (an infinitely thin band "
      "at the horizon) follow each hour's clearness, and in overcast bins F2 &lt; 0 darkens the "
      "horizon. The <code>sky</code> method integrates a distribution. The all-weather Perez sky "
      "(<code>sky: perez</code>) follows the hour's clearness too, but spreads its circumsolar "
      "and horizon light over regions of finite size. Hosek–Wilkie and Bruneton keep a clear "
      "sky's distribution (a bright horizon band, an aureole) in every hour, scaled to the "
      "hour's diffuse light: on overcast hours that is not the real sky's shape, and no "
      "measured sky of this file says which is closer (the shipped year is synthetic). A "
      "vertical plane sees the whole horizon band and little of the zenith, so it shows these "
      "differences most; a 30° roof sees mostly the upper sky, and the methods agree more "
      "closely there.</p>\n";
  if (!left_out.empty())
    html += fmt::format(
        "<p class=\"note\">The quick report leaves out {} (its tables take "
        "seconds per sky).</p>\n",
        esc_html(fmt::format("{}", fmt::join(left_out, ", "))));
  html_planes_ = html;
  json_["light_on_planes"] = {{"file", weather_name_}, {"planes", planes}};
}

}  // namespace skylight::report::detail
