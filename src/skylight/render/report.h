// The validation and comparison report (`skylight report`): which sky model to trust where.
// Reproduces the analyses of Zotti, Wilkie & Purgathofer 2007 ("A Critical Review of the Preetham
// Skylight Model", WSCG) for the models of the registry, and writes a self-contained HTML page with
// SVG/PNG figures and a report.json of the headline numbers. Methods: docs/REPORT.md.
//
// Every analysis is a library function returning numbers (tested in report_test.cpp); write_report
// only arranges them into files. Angles are radians here; the files use degrees.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/frame.h"
#include "skylight/models/sky_model.h"
#include "skylight/render/measurements.h"

namespace skylight::render {

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

// ---- sampling the sky --------------------------------------------------------------------------

// Midpoint grid over the upper hemisphere: n_theta rings of equal zenith-angle width, n_phi
// azimuth sectors; each cell's exact solid angle (cos theta0 - cos theta1) dphi [sr].
struct HemisphereGrid {
  std::vector<Vec3> directions;
  std::vector<double> solid_angle;  // [sr], sums to 2 pi
};
HemisphereGrid hemisphere_grid(int n_theta, int n_phi);

// A model and its parameters; the sun position is set per use.
struct ModelSpec {
  std::string name;  // registry name
  SkyParameters params;
  std::string label;  // for legends and tables
};
std::unique_ptr<SkyModel> make_model(const ModelSpec& spec, double sun_zenith, double sun_azimuth);

// Scalar (double) sky luminance Y [cd/m^2] of `model` at each direction, on all threads.
std::vector<double> sky_luminance(const SkyModel& model, const std::vector<Vec3>& directions);

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
// Ratio of absolute luminances a / b: per sun zenith the solid-angle-weighted geometric mean over
// the directions; `mean` is the geometric mean over the sun zeniths.
struct LuminanceRatio {
  double mean = 0.0, min = 0.0, max = 0.0;
};
LuminanceRatio absolute_luminance_ratio(const RelativeSamples& a, const RelativeSamples& b,
                                        const HemisphereGrid& grid);

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

// ---- horizontal illuminance and irradiance -----------------------------------------------------

struct IlluminationSettings {
  int n_theta = 90, n_phi = 180;                          // sky hemisphere grid (luminance)
  int n_theta_spectral = 24, n_phi_spectral = 48;         // coarser grid for spectral irradiance
  int sun_rings = 8, sun_sectors = 16;                    // polar grid over the solar disc
  double nm_min = 380.0, nm_max = 720.0, nm_step = 10.0;  // spectral range [nm], trapezoid rule
};
// Horizontal illuminance [lx] and irradiance [W/m^2] of one model:
//  * diffuse = the sky's luminance (radiance) integrated over the upper hemisphere with weight
//    cos theta (midpoint rule on hemisphere_grid);
//  * direct = the solar disc's luminance (radiance) integrated over the disc with weight
//    max(cos theta, 0) (polar grid), for models with a sun; 0 otherwise;
//  * irradiance: spectral radiance integrated over [nm_min, nm_max] as well; nullopt for models
//    without spectral output (and direct nullopt without a sun).
struct HorizontalIllumination {
  double sun_elevation = 0.0;  // [rad]
  double diffuse_lx = 0.0, direct_lx = 0.0;
  bool has_sun = false;
  std::optional<double> diffuse_w_m2, direct_w_m2;
  double global_lx() const { return diffuse_lx + direct_lx; }
};
double diffuse_horizontal_illuminance(const SkyModel& model, int n_theta, int n_phi);
double direct_horizontal_illuminance(const SkyModel& model, int rings, int sectors);
HorizontalIllumination horizontal_illumination(const SkyModel& model,
                                               const IlluminationSettings& settings, bool spectral);

// ---- validity ----------------------------------------------------------------------------------

// domain().worst() of `spec` with the sun at each zenith [rad] (azimuth pi) and, per row, the
// parameters changed by `row_setter(params, row_value)`.
std::vector<std::vector<Validity>> validity_grid(
    const ModelSpec& spec, const std::vector<double>& sun_zeniths,
    const std::vector<double>& row_values,
    const std::function<void(SkyParameters&, double)>& row_setter);

// ---- the report --------------------------------------------------------------------------------

struct ReportOptions {
  std::filesystem::path output_dir;
  // A sky-luminance scan (measurements.h); nullopt: the shipped synthetic example.
  std::optional<std::filesystem::path> measurements;
  // Override the scan's sun position (both or neither), [rad].
  std::optional<double> measurement_sun_azimuth, measurement_sun_elevation;
  // Reduced resolution and fewer sun positions: for tests (a few seconds instead of ~20 s).
  bool quick = false;
  // Progress: step `done` of `total` finished (called on the calling thread).
  std::function<void(int done, int total, std::string_view step)> progress;
};

// The headline numbers (also in report.json).
struct ReportSummary {
  std::vector<ZenithRoot> negative_zenith_boundary;
  double antisolar_ratio = 0.0;  // Preetham / CIE 12 at the conditions below
  double antisolar_sun_zenith = 0.0, antisolar_view_elevation = 0.0, antisolar_turbidity = 0.0;
  TurbidityFit best_turbidity_for_cie12;
  std::vector<CieTypeMatch> cie_matches;
  std::vector<std::string> files;  // written, relative to output_dir
};

// Writes DIR/index.html, DIR/report.json and the figures (DIR/*.svg, DIR/*.png), each atomically
// (temporary file + rename); creates DIR if needed. Throws InvalidArgument for bad options or a bad
// measurement file, IoError when a file cannot be read or written.
ReportSummary write_report(const ReportOptions& options);

}  // namespace skylight::render
