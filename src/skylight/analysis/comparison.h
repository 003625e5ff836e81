// Comparing sky models' luminance distributions (the analyses of Zotti, Wilkie & Purgathofer 2007,
// "A Critical Review of the Preetham Skylight Model", WSCG): Preetham's negative zenith luminance,
// zenith-normalised RMS of log ratios, absolute luminance ratios, the best CIE type per turbidity,
// the best turbidity per CIE type, the antisolar horizon, and validity maps. Angles in radians.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/analysis/hemisphere.h"
#include "skylight/models/sky_model.h"

namespace skylight::analysis {

// ---- Preetham's zenith luminance (Zotti Fig. 1) ------------------------------------------------

// A point of the boundary Yz(T, theta_s) = 0 of Preetham's zenith luminance (Preetham A.2, Zotti
// eq. 1): at sun zenith theta_s, Yz changes sign at turbidity T; Yz < 0 on the side
// `negative_above` (true: for T just above, false: just below).
struct ZenithRoot {
  double sun_zenith = 0.0;  // [rad]
  double turbidity = 0.0;
  bool negative_above = false;
};
// For each sun zenith, every sign change of Yz over T in [t_min, t_max]: bracketed on a grid of
// `t_step`, then bisected to |dT| < 1e-10.
std::vector<ZenithRoot> preetham_zenith_roots(const std::vector<double>& sun_zeniths, double t_min,
                                              double t_max, double t_step = 0.01);
// A model and its parameters; the sun position is set per use.
struct ModelSpec {
  std::string name;  // registry name
  SkyParameters params;
  std::string label;  // for legends and tables
};
std::unique_ptr<SkyModel> make_model(const ModelSpec& spec, double sun_zenith, double sun_azimuth);

// One sky of a registered model as the report compares it (its entry's ReportPolicy): the model's
// example values, the values the policy holds, and `value` of the policy's axis (required when the
// policy has an axis, refused when it has none); labelled "<title> <axis_label><value>", e.g.
// "Preetham T = 3", "CIE type 12", "Nishita (Earth defaults)". Throws InvalidArgument for a
// model without a report policy.
ModelSpec comparison_spec(std::string_view model, std::optional<double> value = std::nullopt);
// The colour of the model's curves (its ReportPolicy).
std::string comparison_colour(std::string_view model);

// How two luminance distributions are compared (Zotti's normalisation: to the zenith).
struct ComparisonSettings {
  std::vector<double> sun_zeniths;       // [rad], pooled
  double sun_azimuth = kPi;              // [rad]
  double sun_exclusion = 5.0 * kDegree;  // directions closer to the sun are left out [rad]
  int n_theta = 36, n_phi = 144;         // hemisphere_grid
};

// Relative distributions L / L(zenith) of one model at each sun zenith of the settings, on the
// grid; entries within the exclusion are NaN, as are all entries where L(zenith) <= 0.
struct RelativeSamples {
  std::vector<std::vector<double>> relative;  // [sun zenith][direction]
  std::vector<std::vector<double>> absolute;  // [sun zenith][direction], cd/m^2
};
RelativeSamples relative_samples(const ModelSpec& spec, const ComparisonSettings& settings,
                                 const HemisphereGrid& grid);
// Solid-angle-weighted RMS of log10(rel_a / rel_b) over all directions and sun zeniths where both
// are finite and positive; +inf where none is.
double relative_log_rms(const RelativeSamples& a, const RelativeSamples& b,
                        const HemisphereGrid& grid);
// Absolute luminance of `a` against `b` (the model it approximates), pooled over sample sets
// (e.g. a parameter's values) and their sun zeniths, solid-angle weighted over the directions
// where b > 0 (those within the sun exclusion are left out): the median and 95th percentile of
// |a / b - 1|, and the RMS of log10(a / b) with a clamped to at least 1e-3 b (a model that rings
// below zero counts as 1000 times too dark there, not as undefined).
struct SourceError {
  double median = 0.0, p95 = 0.0, rms_log10 = 0.0;
  std::size_t directions = 0;  // pooled
};
SourceError source_error(const std::vector<const RelativeSamples*>& a,
                         const std::vector<const RelativeSamples*>& b, const HemisphereGrid& grid);

// Ratio of absolute luminances a / b: per sun zenith the solid-angle-weighted geometric mean over
// the directions; `mean` is the geometric mean over the sun zeniths.
struct LuminanceRatio {
  double mean = 0.0, min = 0.0, max = 0.0;
};
LuminanceRatio absolute_luminance_ratio(const RelativeSamples& a, const RelativeSamples& b,
                                        const HemisphereGrid& grid);
// Colour and level of `a` against a reference `b` (the physical atmosphere) over the sky at the
// sun zeniths of the settings (directions within the sun exclusion left out, and those where
// either luminance is not positive): the solid-angle-weighted mean and 95th percentile of the
// CIE 1976 chromaticity distance |(u', v')_a - (u', v')_b|, and the RMS of log10(Y_a / Y_b).
// NaN everywhere when no direction counts.
struct ColourDifference {
  double mean_duv = 0.0, p95_duv = 0.0, rms_log10 = 0.0;
  std::size_t directions = 0;
};
ColourDifference colour_difference(const ModelSpec& a, const ModelSpec& b,
                                   const ComparisonSettings& settings, const HemisphereGrid& grid);

// Four readings of "a is k times as bright as b" (Zotti's absolute comparisons), each per sun
// zenith of the samples as a / b, then min, max and geometric mean over the sun zeniths:
// `geometric_mean`: the solid-angle-weighted geometric mean over the directions
// (absolute_luminance_ratio); `peak`: the brightest direction of each (outside the sun exclusion,
// i.e. the sky's maximum, not the sun); `zenith`; `diffuse`: the horizontal illuminance of the
// sky, sum of L cos(theta) dOmega over the grid (the excluded directions left out of both).
struct LuminanceReadings {
  LuminanceRatio geometric_mean, peak, zenith, diffuse;
};
LuminanceReadings luminance_readings(const ModelSpec& a, const ModelSpec& b,
                                     const ComparisonSettings& settings,
                                     const HemisphereGrid& grid);

// The darkening opposite a low sun in one model's own terms: over the antisolar half (view azimuth
// at least 90 deg from the sun's; sun azimuth pi), the darkest luminance and where it is, the mean
// luminance of the cells below `horizon_band` elevation, and the zenith luminance [cd/m^2].
// depth(): darkest / zenith; contrast(): horizon / darkest (how deep the dip is seen from the
// horizon).
struct AntisolarDip {
  double zenith = 0.0, darkest = 0.0, horizon = 0.0;
  double darkest_elevation = 0.0;  // [rad]
  double depth() const { return darkest / zenith; }
  double contrast() const { return horizon / darkest; }
};
AntisolarDip antisolar_dip(const ModelSpec& spec, double sun_zenith, const HemisphereGrid& grid,
                           double horizon_band);

// For one Preetham turbidity: the CIE types ranked by relative_log_rms, and the luminance ratio
// Preetham / CIE (Kittler-Darula typical zenith luminance) for the best type.
struct CieTypeMatch {
  double turbidity = 0.0;
  std::array<double, 16> rms_by_type{};  // index type - 1
  int best_type = 0, second_type = 0;
  double best_rms = 0.0, second_rms = 0.0;
  LuminanceRatio ratio_best;  // Preetham / CIE best type
};
std::vector<CieTypeMatch> best_cie_type_per_turbidity(const std::vector<double>& turbidities,
                                                      const ComparisonSettings& settings);
// The same ranking for any model (`turbidity` is then copied from spec.params; the ratio is
// spec / CIE best type).
CieTypeMatch rank_cie_types(const ModelSpec& spec, const ComparisonSettings& settings);

// The Preetham turbidity whose relative distribution best matches CIE type `cie_type`: a grid over
// [t_min, t_max] (step t_step), refined by golden-section search around the best grid point.
struct TurbidityFit {
  double turbidity = 0.0, rms = 0.0;
  std::vector<double> curve_t, curve_rms;  // the grid
};
TurbidityFit best_preetham_turbidity_for_cie(int cie_type, double t_min, double t_max,
                                             double t_step, const ComparisonSettings& settings);

// Luminance near the horizon opposite the sun: Preetham (turbidity T) over CIE type 12 with the
// Kittler-Darula typical zenith luminance, absolute and zenith-normalised.
struct AntisolarRow {
  double sun_zenith = 0.0, view_elevation = 0.0;  // [rad]
  double preetham = 0.0, cie = 0.0;               // [cd/m^2]
  double ratio = 0.0;                             // preetham / cie
  double relative_ratio = 0.0;                    // (preetham / Yz) / (cie / Lz)
};
std::vector<AntisolarRow> antisolar_horizon_ratios(double turbidity,
                                                   const std::vector<double>& sun_zeniths,
                                                   const std::vector<double>& view_elevations);
// ---- Zotti's findings, measured over regions of the sky --------------------------------------

// Turbidities between which Preetham's luminance is negative somewhere in the sky at every sun
// position: the gradation term of the Perez function (Preetham A.2 Y coefficients, Zotti eq. 4),
// 1 + A e^{B / cos theta}, is 1 at the horizon and 1 + A e^B at the zenith; for
// t_low < T < t_high its zenith value is negative (A < 0, B < 0), so Y = Yz F / F(0, theta_s)
// changes sign between zenith and horizon. t_low: B(T) = 0 (closed form); t_high: 1 + A e^B = 0
// (bisection to 1e-12).
struct NegativeSkyRange {
  double t_low = 0.0, t_high = 0.0;
};
NegativeSkyRange preetham_negative_sky_range();

// Ratio of model a over model b in one region of the hemisphere at one sun zenith: absolute
// luminances and zenith-normalised ones (a / a(zenith)) / (b / b(zenith)); min and max over the
// directions of `grid` in the region, and the view elevation where each minimum lies.
struct RegionRatio {
  double sun_zenith = 0.0;  // [rad]
  double absolute_min = 0.0, absolute_max = 0.0, relative_min = 0.0, relative_max = 0.0;
  double absolute_min_elevation = 0.0, relative_min_elevation = 0.0;  // [rad]
  int directions = 0;                                                 // in the region
  double absolute_geomean = 0.0;  // solid-angle-weighted geometric mean of a / b over the region
};
// The region: directions d with in_region(d, sun direction); sun azimuth pi. Directions where
// either model is not positive are left out; no direction: NaN everywhere.
using SkyRegion = std::function<bool(Vec3 view, Vec3 sun)>;
RegionRatio region_ratio(const ModelSpec& a, const ModelSpec& b, double sun_zenith,
                         const HemisphereGrid& grid, const SkyRegion& in_region);
// The antisolar half: azimuth at least 90 deg from the sun's.
bool in_antisolar_half(Vec3 view, Vec3 sun);

// Preetham (T) over CIE `cie_type` per sun position of `settings` (absolute_luminance_ratio), with
// the CIE zenith luminance at the typical Kittler-Darula value and at the ends of the band
// kittler_darula_zenith_luminance_band: geometric means over the sun positions.
struct RatioBand {
  double typical = 0.0;
  double against_cie_low = 0.0;   // CIE at the band's low end: the larger ratio
  double against_cie_high = 0.0;  // CIE at the band's high end: the smaller ratio
};
RatioBand preetham_cie_ratio_band(double turbidity, int cie_type,
                                  const ComparisonSettings& settings);

// ---- validity ----------------------------------------------------------------------------------

// domain().worst() of `spec` with the sun at each zenith [rad] (azimuth pi) and, per row, the
// model parameter named `row_parameter` (a schema name, e.g. "turbidity") set to the row's value
// (no rows: `row_values` empty). Parameters the model rejects give Validity::undefined.
std::vector<std::vector<Validity>> validity_grid(const ModelSpec& spec,
                                                 const std::vector<double>& sun_zeniths,
                                                 const std::vector<double>& row_values,
                                                 const std::string& row_parameter);
}  // namespace skylight::analysis
