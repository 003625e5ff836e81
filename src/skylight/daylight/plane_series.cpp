#include "skylight/daylight/plane_series.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/models/perez.h"
#include "skylight/models/perez_kernel.h"

namespace skylight::daylight {
namespace {

// The hour's Perez all-weather sky, lv at the grid's cells (the batch path of the `perez` model:
// the same distribution, unscaled).
void weather_sky(const PerezSky& sky, const SkyGrid& grid, std::vector<float>& L,
                 std::vector<float>& scratch) {
  PerezDistribution d;
  d.mode = PerezDistribution::Mode::luminance;
  const auto& k = sky.coefficients;
  d.coefficients[0] = PerezCoefficients{k[0], k[1], k[2], k[3], k[4], 1.0};
  d.sun = sky.sun.direction();
  scratch.resize(2 * grid.size());
  L.resize(grid.size());
  const std::span<float> X(scratch.data(), grid.size()),
      Z(scratch.data() + grid.size(), grid.size());
  d.evaluate_batch({grid.x(), grid.y(), grid.z()}, {X, L, Z});
}

// A model's skies for suns at the table's zenith angles and azimuth 0, built once each.
class ShapeTable {
 public:
  ShapeTable(const SkyForSun& model, const SkyGrid& grid) : model_(model), grid_(grid) {}
  // Builds the rows the hours need (each on all threads).
  void build(const std::vector<WeatherHour>& hours,
             const std::function<void(std::size_t, std::size_t, std::string_view)>& progress) {
    std::vector<int> rows;
    for (const WeatherHour& h : hours) {
      const int k = row_of(h.sun.zenith);
      rows.push_back(k);
      rows.push_back(k + 1);
    }
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double zenith = std::min(rows[i] * kSeriesZenithStep, 0.5 * kPi);
      const auto model = model_(SunPosition{zenith, 0.0});
      table_[rows[i]] = sky_luminance_on_grid(*model, grid_);
      if (progress) progress(i + 1, rows.size(), "skies");
    }
  }
  std::size_t size() const { return table_.size(); }
  // The sky of sun `sun` at the grid's cells: rows k, k + 1 turned to the sun's azimuth.
  void sky(const SunPosition& sun, std::vector<float>& L) const {
    const int k = row_of(sun.zenith);
    const double tz = sun.zenith / kSeriesZenithStep - k;
    const auto& a = table_.at(k);
    const auto& b = table_.at(k + 1);
    const int sectors = grid_.spec().sectors;
    // L(theta, phi) = L0(theta, phi - A): sector s takes the fractional sector s - A / dphi.
    const double shift = wrap_azimuth(sun.azimuth) / (2.0 * kPi) * sectors;
    const int whole = static_cast<int>(std::floor(shift));
    const double ts = shift - whole;
    L.resize(grid_.size());
    const auto n = static_cast<std::size_t>(sectors);
    for (std::size_t r = 0; r < grid_.size() / n; ++r) {
      for (int s = 0; s < sectors; ++s) {
        // Sectors s - whole - 1 (weight ts) and s - whole (weight 1 - ts), cyclically.
        const auto s1 = static_cast<std::size_t>(((s - whole) % sectors + sectors) % sectors);
        const std::size_t s0 = (s1 + n - 1) % n;
        const std::size_t i0 = r * n + s0, i1 = r * n + s1;
        const double va = (1.0 - ts) * a[i1] + ts * a[i0], vb = (1.0 - ts) * b[i1] + ts * b[i0];
        L[r * n + static_cast<std::size_t>(s)] = static_cast<float>((1.0 - tz) * va + tz * vb);
      }
    }
  }

 private:
  static int row_of(double zenith) {
    return std::min(static_cast<int>(std::floor(zenith / kSeriesZenithStep)),
                    static_cast<int>(std::ceil(0.5 * kPi / kSeriesZenithStep)) - 1);
  }
  const SkyForSun& model_;
  const SkyGrid& grid_;
  std::map<int, std::vector<float>> table_;
};

}  // namespace

SkyForSun sky_for_sun(std::string name, ParameterValues values) {
  return [name = std::move(name), values = std::move(values)](const SunPosition& sun) {
    SkyParameters sp;
    sp.sun = sun;
    sp.values = values;
    return make_sky_model(name, sp);
  };
}

std::vector<PlaneSeries> plane_series(
    const io::EpwFile& epw, const std::vector<const PlaneContext*>& planes,
    const SeriesSettings& settings, const std::string& source,
    const std::function<void(std::size_t, std::size_t, std::string_view)>& progress) {
  SKYLIGHT_CHECK(!planes.empty(), "a series needs a plane");
  const WeatherYear year = weather_hours(
      epw, settings.hours, settings.compat, source, [&](std::size_t done, std::size_t total) {
        const std::size_t step = std::max<std::size_t>(1, total / 20);
        if (progress && (done % step == 0 || done == total)) progress(done, total, "records");
      });
  const auto& hours = year.hours;
  const PlaneContext& first = *planes.front();
  const bool sky = first.method == Transposition::sky;
  for (const PlaneContext* p : planes)
    SKYLIGHT_CHECK(p->method == first.method && p->weights.grid == first.weights.grid,
                   "the planes of one series share a method and a grid");
  SKYLIGHT_CHECK(!sky || settings.weather_sky || settings.model,
                 "the sky method's series needs a weather sky or a model");
  const SkyGrid& grid = *first.weights.grid;
  ShapeTable table(settings.model, grid);
  if (sky && !settings.weather_sky) table.build(hours, progress);
  std::vector<PlaneSeries> out(planes.size());
  for (PlaneSeries& s : out) {
    s.year.sun_down = year.sun_down;
    s.sky_models_built = table.size();
    s.light.resize(hours.size());
    s.albedo.resize(hours.size());
  }
  parallel_for(hours.size(), 64, [&](std::size_t b, std::size_t e) {
    std::vector<float> L, scratch;
    for (std::size_t i = b; i < e; ++i) {
      const WeatherHour& h = hours[i];
      const double albedo = settings.albedo.value_or(h.albedo.value_or(kDefaultGroundAlbedo));
      const MeasuredLight m = measured_light_of(h.sky);
      if (sky) {
        if (settings.weather_sky)
          weather_sky(h.sky, grid, L, scratch);
        else
          table.sky(h.sun, L);
      }
      for (std::size_t p = 0; p < planes.size(); ++p) {
        out[p].albedo[i] = albedo;
        out[p].light[i] = sky ? measured_sky_light(L, m, h.sun, *planes[p], albedo)
                              : transposed_measured_light(m, h.sun, *planes[p], albedo);
      }
    }
  });
  for (PlaneSeries& s : out) s.year.hours = hours;
  return out;
}

PlaneSeries plane_series(
    const io::EpwFile& epw, const PlaneContext& plane, const SeriesSettings& settings,
    const std::string& source,
    const std::function<void(std::size_t, std::size_t, std::string_view)>& progress) {
  return std::move(
      plane_series(epw, std::vector<const PlaneContext*>{&plane}, settings, source, progress)
          .front());
}

std::vector<std::string> plane_keys(const std::string& suffix) {
  std::vector<std::string> keys;
  for (const char* part :
       {"global", "direct", "sky_diffuse", "ground_diffuse", "isotropic", "circumsolar", "horizon"})
    keys.push_back(fmt::format("poa_{}_{}", part, suffix));
  return keys;
}

std::optional<double> plane_value(const PlaneLight& p, std::size_t k) {
  switch (k) {
    case 0:
      return p.global();
    case 1:
      return p.direct;
    case 2:
      return p.sky_diffuse;
    case 3:
      return p.ground_diffuse;
    case 4:
      return p.isotropic;
    case 5:
      return p.circumsolar;
    case 6:
      return p.horizon;
    default:
      SKYLIGHT_CHECK(false, "a plane key's index");
      return std::nullopt;
  }
}

namespace {

// The series' channels: irradiance always (measured light), illuminance except perez1990.
bool series_has_illuminance(const PlaneContext& plane) {
  return plane.method != Transposition::perez1990;
}

}  // namespace

std::vector<std::string> series_columns(const PlaneContext& plane) {
  std::vector<std::string> c = {
      "record",          "month",    "day",      "hour",   "sun_zenith_deg",
      "sun_azimuth_deg", "dni_w_m2", "dhi_w_m2", "albedo", "angle_of_incidence_deg"};
  for (const auto& k : plane_keys("w_m2")) c.push_back(k);
  if (series_has_illuminance(plane))
    for (const auto& k : plane_keys("lx")) c.push_back(k);
  return c;
}

std::vector<double> series_values(const PlaneSeries& s, const PlaneContext& plane) {
  std::vector<double> v;
  const std::size_t keys = plane_keys("").size();
  for (std::size_t i = 0; i < s.year.hours.size(); ++i) {
    const MatrixHour& h = s.year.hours[i].header;
    const PlaneChannels& c = s.light[i];
    for (double x :
         {static_cast<double>(h.record), static_cast<double>(h.month), static_cast<double>(h.day),
          static_cast<double>(h.hour), h.sun_zenith_deg, h.sun_azimuth_deg, h.dni_w_m2, h.dhi_w_m2,
          s.albedo[i], rad_to_deg(c.angle_of_incidence)})
      v.push_back(x);
    for (std::size_t k = 0; k < keys; ++k) v.push_back(plane_value(*c.irradiance, k).value_or(0.0));
    if (series_has_illuminance(plane))
      for (std::size_t k = 0; k < keys; ++k)
        v.push_back(plane_value(*c.illuminance, k).value_or(0.0));
  }
  return v;
}

}  // namespace skylight::daylight
