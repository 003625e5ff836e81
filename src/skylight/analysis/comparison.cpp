#include "skylight/analysis/comparison.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

#include "skylight/core/error.h"
#include "skylight/core/golden_section.h"
#include "skylight/core/numbers.h"
#include "skylight/core/parallel.h"
#include "skylight/models/cie_sky.h"
#include "skylight/models/preetham.h"

namespace skylight::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// Bisection of Yz(T) = 0 stops when the bracket is narrower than this (in T).
constexpr double kRootTolerance = 1e-10;
// Golden-section search for the best turbidity stops at this bracket width (in T).
constexpr double kTurbidityTolerance = 1e-4;
// Bisection of 1 + A e^B = 0 stops at this bracket width (in T).
constexpr double kNegativeSkyTolerance = 1e-12;

}  // namespace

// ---- Preetham's zenith luminance ---------------------------------------------------------------

std::vector<ZenithRoot> preetham_zenith_roots(const std::vector<double>& sun_zeniths, double t_min,
                                              double t_max, double t_step) {
  require_in_range("t_min", t_min, 1.0, 1e3);
  require_in_range("t_max", t_max, t_min, 1e3);
  require_in_range("t_step", t_step, 1e-6, t_max - t_min + 1.0);
  std::vector<ZenithRoot> roots;
  for (double ts : sun_zeniths) {
    require_in_range("sun_zenith", ts, 0.0, kPi / 2);
    auto yz = [ts](double T) { return preetham_zenith_luminance(T, ts); };
    const int n = static_cast<int>(std::ceil((t_max - t_min) / t_step));
    double a = t_min, ya = yz(a);
    for (int i = 1; i <= n; ++i) {
      const double b = std::min(t_max, t_min + i * t_step), yb = yz(b);
      if ((ya < 0.0) != (yb < 0.0)) {
        double lo = a, hi = b;
        const bool lo_negative = ya < 0.0;
        while (hi - lo > kRootTolerance) {
          const double mid = 0.5 * (lo + hi);
          if ((yz(mid) < 0.0) == lo_negative)
            lo = mid;
          else
            hi = mid;
        }
        roots.push_back({ts, 0.5 * (lo + hi), !lo_negative});
      }
      a = b;
      ya = yb;
    }
  }
  return roots;
}

std::unique_ptr<SkyModel> make_model(const ModelSpec& spec, double sun_zenith, double sun_azimuth) {
  SkyParameters p = spec.params;
  p.sun = {sun_zenith, wrap_azimuth(sun_azimuth)};
  return make_sky_model(spec.name, p);
}
RelativeSamples relative_samples(const ModelSpec& spec, const ComparisonSettings& s,
                                 const HemisphereGrid& grid) {
  RelativeSamples r;
  for (double ts : s.sun_zeniths) {
    const auto model = make_model(spec, ts, s.sun_azimuth);
    std::vector<double> abs = sky_luminance(*model, grid.directions);
    const double z = model->tristimulus({0.0, 0.0, 1.0}).Y;
    const Vec3 sun = model->sun().direction();
    std::vector<double> rel(abs.size(), kNaN);
    for (std::size_t i = 0; i < abs.size(); ++i) {
      if (angle_between(grid.directions[i], sun) < s.sun_exclusion) {
        abs[i] = kNaN;
        continue;
      }
      if (z > 0.0) rel[i] = abs[i] / z;
    }
    r.relative.push_back(std::move(rel));
    r.absolute.push_back(std::move(abs));
  }
  return r;
}

double relative_log_rms(const RelativeSamples& a, const RelativeSamples& b,
                        const HemisphereGrid& grid) {
  SKYLIGHT_CHECK(a.relative.size() == b.relative.size(), "sample sets of different sun zeniths");
  double sw = 0.0, sd = 0.0;
  for (std::size_t k = 0; k < a.relative.size(); ++k) {
    for (std::size_t i = 0; i < grid.solid_angle.size(); ++i) {
      const double x = a.relative[k][i], y = b.relative[k][i];
      if (!(x > 0.0) || !(y > 0.0) || !std::isfinite(x) || !std::isfinite(y)) continue;
      const double d = std::log10(x / y);
      sw += grid.solid_angle[i];
      sd += grid.solid_angle[i] * d * d;
    }
  }
  return sw > 0.0 ? std::sqrt(sd / sw) : kInf;
}

// The q-quantile of (value, weight) pairs sorted by value, whose weights sum to `total`.
static double weighted_quantile(const std::vector<std::pair<double, double>>& sorted, double total,
                                double q) {
  double acc = 0.0;
  for (const auto& [v, w] : sorted) {
    acc += w;
    if (acc >= q * total) return v;
  }
  return sorted.back().first;
}

SourceError source_error(const std::vector<const RelativeSamples*>& a,
                         const std::vector<const RelativeSamples*>& b, const HemisphereGrid& grid) {
  SKYLIGHT_CHECK(a.size() == b.size(), "source_error: sample sets differ in number");
  constexpr double kFloor = 1e-3;  // a is clamped to at least this fraction of b in the log
  std::vector<std::pair<double, double>> errors;  // (|a/b - 1|, solid angle)
  double sw = 0.0, sd = 0.0;
  for (std::size_t s = 0; s < a.size(); ++s) {
    SKYLIGHT_CHECK(a[s]->absolute.size() == b[s]->absolute.size(),
                   "source_error: sample sets of different sun zeniths");
    for (std::size_t k = 0; k < a[s]->absolute.size(); ++k)
      for (std::size_t i = 0; i < grid.solid_angle.size(); ++i) {
        const double x = a[s]->absolute[k][i], y = b[s]->absolute[k][i];
        if (!(y > 0.0) || !std::isfinite(y) || !std::isfinite(x)) continue;
        const double w = grid.solid_angle[i];
        errors.emplace_back(std::abs(x / y - 1.0), w);
        const double d = std::log10(std::max(x, kFloor * y) / y);
        sw += w;
        sd += w * d * d;
      }
  }
  SourceError r;
  r.directions = errors.size();
  if (errors.empty()) return {kNaN, kNaN, kNaN, 0};
  std::sort(errors.begin(), errors.end());
  r.median = weighted_quantile(errors, sw, 0.5);
  r.p95 = weighted_quantile(errors, sw, 0.95);
  r.rms_log10 = std::sqrt(sd / sw);
  return r;
}

LuminanceRatio absolute_luminance_ratio(const RelativeSamples& a, const RelativeSamples& b,
                                        const HemisphereGrid& grid) {
  SKYLIGHT_CHECK(a.absolute.size() == b.absolute.size(), "sample sets of different sun zeniths");
  LuminanceRatio r{kNaN, kInf, -kInf};
  double sum_log = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < a.absolute.size(); ++k) {
    double sw = 0.0, sl = 0.0;
    for (std::size_t i = 0; i < grid.solid_angle.size(); ++i) {
      const double x = a.absolute[k][i], y = b.absolute[k][i];
      if (!(x > 0.0) || !(y > 0.0) || !std::isfinite(x) || !std::isfinite(y)) continue;
      sw += grid.solid_angle[i];
      sl += grid.solid_angle[i] * std::log10(x / y);
    }
    if (!(sw > 0.0)) continue;
    const double ratio = std::pow(10.0, sl / sw);
    r.min = std::min(r.min, ratio);
    r.max = std::max(r.max, ratio);
    sum_log += sl / sw;
    ++n;
  }
  if (n == 0) return {kNaN, kNaN, kNaN};
  r.mean = std::pow(10.0, sum_log / n);
  return r;
}

namespace {
const ReportPolicy& report_policy(std::string_view model) {
  const ModelInfo* info = find_model(model);
  if (info == nullptr || info->report.title.empty())
    throw InvalidArgument(fmt::format("model '{}' is not in the report", excerpt(model)));
  return info->report;
}
}  // namespace

ModelSpec comparison_spec(std::string_view model, std::optional<double> value) {
  const ReportPolicy& r = report_policy(model);
  if (r.axis.empty() == value.has_value())
    throw InvalidArgument(fmt::format("model '{}': the report {} a value of {}", model,
                                      value ? "takes no" : "needs",
                                      r.axis.empty() ? "an axis" : r.axis));
  ModelSpec s{std::string(model), {}, r.title};
  s.params.values = find_model(model)->example;
  for (const auto& [name, v] : r.fixed.all()) s.params.values.set(name, v);
  if (value) {
    s.params.values.set(r.axis, *value);
    s.label += fmt::format(" {}{:g}", r.axis_label, *value);
  }
  return s;
}

std::string comparison_colour(std::string_view model) {
  return report_policy(model).colour;
}

std::vector<RelativeSamples> cie_type_samples(const ComparisonSettings& s,
                                              const HemisphereGrid& grid) {
  std::vector<RelativeSamples> out;
  for (int type = 1; type <= kCieTypeCount; ++type)
    out.push_back(relative_samples(comparison_spec(CieSkyModel::kName, type), s, grid));
  return out;
}

namespace {

CieTypeMatch rank_against(const RelativeSamples& target, const std::vector<RelativeSamples>& cie,
                          const HemisphereGrid& grid) {
  CieTypeMatch m;
  std::vector<int> order(kCieTypeCount);
  for (int t = 0; t < kCieTypeCount; ++t) {
    m.rms_by_type[t] = relative_log_rms(target, cie[t], grid);
    order[t] = t;
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](int x, int y) { return m.rms_by_type[x] < m.rms_by_type[y]; });
  m.best_type = order[0] + 1;
  m.second_type = order[1] + 1;
  m.best_rms = m.rms_by_type[order[0]];
  m.second_rms = m.rms_by_type[order[1]];
  m.ratio_best = absolute_luminance_ratio(target, cie[order[0]], grid);
  return m;
}

}  // namespace

CieTypeMatch rank_cie_types(const ModelSpec& spec, const ComparisonSettings& s) {
  const HemisphereGrid grid = hemisphere_grid(s.n_theta, s.n_phi);
  CieTypeMatch m = rank_against(relative_samples(spec, s, grid), cie_type_samples(s, grid), grid);
  m.turbidity = spec.params.values.number("turbidity").value_or(0.0);
  return m;
}

std::vector<CieTypeMatch> best_cie_type_per_turbidity(const std::vector<double>& turbidities,
                                                      const ComparisonSettings& s) {
  const HemisphereGrid grid = hemisphere_grid(s.n_theta, s.n_phi);
  const auto cie = cie_type_samples(s, grid);
  std::vector<CieTypeMatch> out;
  for (double T : turbidities) {
    CieTypeMatch m = rank_against(
        relative_samples(comparison_spec(PreethamModel::kName, T), s, grid), cie, grid);
    m.turbidity = T;
    out.push_back(m);
  }
  return out;
}

TurbidityFit best_preetham_turbidity_for_cie(int cie_type, double t_min, double t_max,
                                             double t_step, const ComparisonSettings& s) {
  require_in_range("cie_type", cie_type, 1, kCieTypeCount);
  require_in_range("t_min", t_min, 1.0, 64.0);
  require_in_range("t_max", t_max, t_min, 64.0);
  require_in_range("t_step", t_step, 1e-4, 64.0);
  const HemisphereGrid grid = hemisphere_grid(s.n_theta, s.n_phi);
  const RelativeSamples cie =
      relative_samples(comparison_spec(CieSkyModel::kName, cie_type), s, grid);
  auto rms = [&](double T) {
    return relative_log_rms(relative_samples(comparison_spec(PreethamModel::kName, T), s, grid),
                            cie, grid);
  };
  TurbidityFit fit;
  const int n = std::max(1, static_cast<int>(std::lround((t_max - t_min) / t_step)));
  for (int i = 0; i <= n; ++i) {
    const double T = i == n ? t_max : std::min(t_max, t_min + i * t_step);
    fit.curve_t.push_back(T);
    fit.curve_rms.push_back(rms(T));
  }
  const auto best = static_cast<std::size_t>(
      std::min_element(fit.curve_rms.begin(), fit.curve_rms.end()) - fit.curve_rms.begin());
  // Golden-section search in the grid cells on either side of the best grid point.
  const auto gs = golden_section(rms, fit.curve_t[best > 0 ? best - 1 : 0],
                                 fit.curve_t[std::min(best + 1, fit.curve_t.size() - 1)],
                                 kTurbidityTolerance, std::less<>());
  fit.turbidity = 0.5 * (gs.a + gs.b);
  fit.rms = rms(fit.turbidity);
  if (fit.curve_rms[best] < fit.rms) {  // the search can only refine the grid's best point
    fit.turbidity = fit.curve_t[best];
    fit.rms = fit.curve_rms[best];
  }
  return fit;
}

std::vector<AntisolarRow> antisolar_horizon_ratios(double turbidity,
                                                   const std::vector<double>& sun_zeniths,
                                                   const std::vector<double>& view_elevations) {
  std::vector<AntisolarRow> out;
  for (double ts : sun_zeniths) {
    // Sun in the south (azimuth pi); the antisolar direction is north (azimuth 0).
    const auto pr = make_model(comparison_spec(PreethamModel::kName, turbidity), ts, kPi);
    const auto cie = make_model(comparison_spec(CieSkyModel::kName, 12), ts, kPi);
    const double pz = pr->tristimulus({0, 0, 1}).Y, cz = cie->tristimulus({0, 0, 1}).Y;
    for (double e : view_elevations) {
      const Vec3 v = direction_from_angles(kPi / 2 - e, 0.0);
      AntisolarRow r;
      r.sun_zenith = ts;
      r.view_elevation = e;
      r.preetham = pr->tristimulus(v).Y;
      r.cie = cie->tristimulus(v).Y;
      r.ratio = r.cie > 0.0 ? r.preetham / r.cie : kNaN;
      r.relative_ratio = (pz > 0.0 && r.cie > 0.0) ? (r.preetham / pz) / (r.cie / cz) : kNaN;
      out.push_back(r);
    }
  }
  return out;
}
// ---- Zotti's findings over regions of the sky -------------------------------------------------

NegativeSkyRange preetham_negative_sky_range() {
  const PerezCoefficients c0 = preetham_perez_coefficients(0.0).Y;
  const PerezCoefficients c1 = preetham_perez_coefficients(1.0).Y;
  // B(T) = b1 T + b0 is linear in T (Preetham A.2).
  const double b1 = c1.B - c0.B, b0 = c0.B;
  NegativeSkyRange r;
  r.t_low = -b0 / b1;
  auto zenith_term = [](double T) {
    const PerezCoefficients c = preetham_perez_coefficients(T).Y;
    return 1.0 + c.A * std::exp(c.B);
  };
  // Just above t_low the term is negative (A(t_low) < -1); it is positive by T = 6.
  double lo = r.t_low + 1e-9, hi = 6.0;
  SKYLIGHT_CHECK(zenith_term(lo) < 0.0 && zenith_term(hi) > 0.0, "no sign change of 1 + A e^B");
  while (hi - lo > kNegativeSkyTolerance) {
    const double mid = 0.5 * (lo + hi);
    (zenith_term(mid) < 0.0 ? lo : hi) = mid;
  }
  r.t_high = 0.5 * (lo + hi);
  return r;
}

bool in_antisolar_half(Vec3 view, Vec3 sun) {
  // Horizontal components: the azimuth difference is >= 90 deg where their dot product is <= 0.
  return view.x * sun.x + view.y * sun.y <= 0.0;
}

RegionRatio region_ratio(const ModelSpec& a, const ModelSpec& b, double sun_zenith,
                         const HemisphereGrid& grid, const SkyRegion& in_region) {
  const auto ma = make_model(a, sun_zenith, kPi), mb = make_model(b, sun_zenith, kPi);
  const Vec3 sun = ma->sun().direction();
  std::vector<Vec3> dirs;
  std::vector<double> weights;
  for (std::size_t i = 0; i < grid.directions.size(); ++i)
    if (in_region(grid.directions[i], sun)) {
      dirs.push_back(grid.directions[i]);
      weights.push_back(grid.solid_angle[i]);
    }
  double sum_w = 0.0, sum_log = 0.0;
  const std::vector<double> la = sky_luminance(*ma, dirs), lb = sky_luminance(*mb, dirs);
  const double za = ma->tristimulus({0, 0, 1}).Y, zb = mb->tristimulus({0, 0, 1}).Y;
  RegionRatio r{sun_zenith, kInf, -kInf, kInf, -kInf, kNaN, kNaN, 0, kNaN};
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    if (!(la[i] > 0.0) || !(lb[i] > 0.0)) continue;
    const double elevation = kPi / 2 - std::acos(std::clamp(dirs[i].z, -1.0, 1.0));
    const double q = la[i] / lb[i];
    ++r.directions;
    sum_w += weights[i];
    sum_log += weights[i] * std::log(q);
    if (q < r.absolute_min) {
      r.absolute_min = q;
      r.absolute_min_elevation = elevation;
    }
    r.absolute_max = std::max(r.absolute_max, q);
    if (za > 0.0 && zb > 0.0) {
      const double rel = q * zb / za;
      if (rel < r.relative_min) {
        r.relative_min = rel;
        r.relative_min_elevation = elevation;
      }
      r.relative_max = std::max(r.relative_max, rel);
    }
  }
  if (r.directions == 0) return {sun_zenith, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, 0, kNaN};
  r.absolute_geomean = std::exp(sum_log / sum_w);
  if (!std::isfinite(r.relative_min)) r.relative_min = r.relative_max = kNaN;
  return r;
}

ColourDifference colour_difference(const ModelSpec& a, const ModelSpec& b,
                                   const ComparisonSettings& settings, const HemisphereGrid& grid) {
  auto uv = [](const Xyz& c) {
    const double d = c.X + 15.0 * c.Y + 3.0 * c.Z;
    return std::array<double, 2>{4.0 * c.X / d, 9.0 * c.Y / d};
  };
  std::vector<std::pair<double, double>> duv;  // (distance, solid angle)
  double sw = 0.0, sd = 0.0;
  for (double ts : settings.sun_zeniths) {
    const auto ma = make_model(a, ts, settings.sun_azimuth);
    const auto mb = make_model(b, ts, settings.sun_azimuth);
    const Vec3 sun = ma->sun().direction();
    for (std::size_t i = 0; i < grid.directions.size(); ++i) {
      const Vec3 v = grid.directions[i];
      if (angle_between(v, sun) < settings.sun_exclusion) continue;
      const Xyz ca = ma->tristimulus(v), cb = mb->tristimulus(v);
      if (!(ca.Y > 0.0) || !(cb.Y > 0.0) || !std::isfinite(ca.Y) || !std::isfinite(cb.Y)) continue;
      const auto pa = uv(ca), pb = uv(cb);
      const double w = grid.solid_angle[i];
      duv.emplace_back(std::hypot(pa[0] - pb[0], pa[1] - pb[1]), w);
      const double d = std::log10(ca.Y / cb.Y);
      sw += w;
      sd += w * d * d;
    }
  }
  if (duv.empty()) return {kNaN, kNaN, kNaN, 0};
  ColourDifference r;
  r.directions = duv.size();
  double mean = 0.0;
  for (const auto& [d, w] : duv) mean += w * d;
  r.mean_duv = mean / sw;
  std::sort(duv.begin(), duv.end());
  r.p95_duv = weighted_quantile(duv, sw, 0.95);
  r.rms_log10 = std::sqrt(sd / sw);
  return r;
}

LuminanceReadings luminance_readings(const ModelSpec& a, const ModelSpec& b,
                                     const ComparisonSettings& settings,
                                     const HemisphereGrid& grid) {
  const RelativeSamples sa = relative_samples(a, settings, grid),
                        sb = relative_samples(b, settings, grid);
  LuminanceReadings r;
  r.geometric_mean = absolute_luminance_ratio(sa, sb, grid);
  // min, max and geometric mean of per-sun ratios
  auto summarise = [](const std::vector<double>& q) {
    LuminanceRatio lr{kNaN, kInf, -kInf};
    double sum_log = 0.0;
    int n = 0;
    for (double v : q) {
      if (!(v > 0.0) || !std::isfinite(v)) continue;
      lr.min = std::min(lr.min, v);
      lr.max = std::max(lr.max, v);
      sum_log += std::log(v);
      ++n;
    }
    if (n == 0) return LuminanceRatio{kNaN, kNaN, kNaN};
    lr.mean = std::exp(sum_log / n);
    return lr;
  };
  std::vector<double> peak, zenith, diffuse;
  for (std::size_t k = 0; k < settings.sun_zeniths.size(); ++k) {
    double pa = 0.0, pb = 0.0, ea = 0.0, eb = 0.0;
    for (std::size_t i = 0; i < grid.solid_angle.size(); ++i) {
      const double x = sa.absolute[k][i], y = sb.absolute[k][i];
      if (!std::isfinite(x) || !std::isfinite(y)) continue;  // the sun exclusion
      pa = std::max(pa, x);
      pb = std::max(pb, y);
      ea += x * grid.directions[i].z * grid.solid_angle[i];
      eb += y * grid.directions[i].z * grid.solid_angle[i];
    }
    peak.push_back(pa / pb);
    diffuse.push_back(ea / eb);
    const double ts = settings.sun_zeniths[k];
    zenith.push_back(make_model(a, ts, settings.sun_azimuth)->tristimulus({0.0, 0.0, 1.0}).Y /
                     make_model(b, ts, settings.sun_azimuth)->tristimulus({0.0, 0.0, 1.0}).Y);
  }
  r.peak = summarise(peak);
  r.zenith = summarise(zenith);
  r.diffuse = summarise(diffuse);
  return r;
}

AntisolarDip antisolar_dip(const ModelSpec& spec, double sun_zenith, const HemisphereGrid& grid,
                           double horizon_band) {
  const auto model = make_model(spec, sun_zenith, kPi);
  const Vec3 sun = model->sun().direction();
  std::vector<Vec3> dirs;
  std::vector<double> weights;
  for (std::size_t i = 0; i < grid.directions.size(); ++i)
    if (in_antisolar_half(grid.directions[i], sun)) {
      dirs.push_back(grid.directions[i]);
      weights.push_back(grid.solid_angle[i]);
    }
  const std::vector<double> l = sky_luminance(*model, dirs);
  AntisolarDip d{model->tristimulus({0.0, 0.0, 1.0}).Y, kInf, kNaN, kNaN};
  double hw = 0.0, hl = 0.0;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const double elevation = kPi / 2 - std::acos(std::clamp(dirs[i].z, -1.0, 1.0));
    if (l[i] < d.darkest) {
      d.darkest = l[i];
      d.darkest_elevation = elevation;
    }
    if (elevation < horizon_band) {
      hw += weights[i];
      hl += weights[i] * l[i];
    }
  }
  if (hw > 0.0) d.horizon = hl / hw;
  if (!std::isfinite(d.darkest)) d.darkest = kNaN;
  return d;
}

RatioBand preetham_cie_ratio_band(double turbidity, int cie_type, const ComparisonSettings& s) {
  const HemisphereGrid grid = hemisphere_grid(s.n_theta, s.n_phi);
  double sum[3] = {0.0, 0.0, 0.0};
  int n = 0;
  for (double ts : s.sun_zeniths) {
    ComparisonSettings one = s;
    one.sun_zeniths = {ts};
    const LuminanceRatio r = absolute_luminance_ratio(
        relative_samples(comparison_spec(PreethamModel::kName, turbidity), one, grid),
        relative_samples(comparison_spec(CieSkyModel::kName, cie_type), one, grid), grid);
    const ZenithLuminanceBand band = kittler_darula_zenith_luminance_band(cie_type, kPi / 2 - ts);
    if (!std::isfinite(r.mean) || !(band.low > 0.0)) continue;
    // The CIE luminance is proportional to its zenith luminance: rescale the ratio.
    sum[0] += std::log10(r.mean);
    sum[1] += std::log10(r.mean * band.typical / band.low);
    sum[2] += std::log10(r.mean * band.typical / band.high);
    ++n;
  }
  if (n == 0) return {kNaN, kNaN, kNaN};
  return {std::pow(10.0, sum[0] / n), std::pow(10.0, sum[1] / n), std::pow(10.0, sum[2] / n)};
}

// ---- validity ----------------------------------------------------------------------------------

std::vector<std::vector<Validity>> validity_grid(const ModelSpec& spec,
                                                 const std::vector<double>& sun_zeniths,
                                                 const std::vector<double>& row_values,
                                                 const std::string& row_parameter) {
  const std::size_t cols = sun_zeniths.size(), rows = std::max<std::size_t>(row_values.size(), 1);
  std::vector<std::vector<Validity>> out(rows, std::vector<Validity>(cols, Validity::valid));
  parallel_for(rows * cols, 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const std::size_t r = i / cols, c = i % cols;
      SkyParameters p = spec.params;
      if (!row_values.empty()) p.values.set(row_parameter, row_values[r]);
      p.sun = {sun_zeniths[c], kPi};
      try {
        out[r][c] = make_sky_model(spec.name, p)->domain().worst();
      } catch (const InvalidArgument&) {
        out[r][c] = Validity::undefined;  // parameters the model rejects
      }
    }
  });
  return out;
}

// ================================================================================================
// The report files.
// ================================================================================================
}  // namespace skylight::analysis
