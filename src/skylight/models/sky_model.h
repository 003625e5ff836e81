// The SkyModel interface and the model registry (docs/ARCHITECTURE.md).
//
// A SkyModel is immutable once built for one SkyParameters. It answers per direction (the simple
// reference path) and per batch of directions (the fast path: SIMD + threads). Every model
// documents what it returns and reports its valid domain; below-horizon views and a sun below the
// horizon are defined cases (documented values, never NaN).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/colorimetry.h"
#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/parameters.h"
#include "skylight/models/gpu_sky.h"
#include "skylight/sh/polynomial.h"

namespace skylight {

// ---- parameters
// -----------------------------------------------------------------------------------

// The sun, common to every model. Inside the library a SunPosition in radians; at the command
// line and in metadata in degrees, declared once in sun_parameter_specs().
inline constexpr double kDefaultSunZenithDeg = 45.0;
inline constexpr double kDefaultSunAzimuthDeg = 180.0;  // due south
// "sun-zenith" [deg] 0 .. 180 (> 90: below the horizon) and "sun-azimuth" [deg] -360 .. 360 from
// north towards east.
const std::vector<ParameterSpec>& sun_parameter_specs();
// The sun from degrees, checked against sun_parameter_specs(); the azimuth is wrapped into
// [0, 2 pi). Throws InvalidArgument naming the flag and value.
SunPosition sun_from_degrees(double zenith_deg, double azimuth_deg);
// Throws InvalidArgument unless the zenith angle is in [0, pi] and the azimuth is finite.
void validate_sun(const SunPosition& sun);

// Absolute zenith luminance accepted by the models that take one (`perez`, `cie`) [cd/m^2].
inline constexpr double kMinZenithLuminance = 1e-9;
inline constexpr double kMaxZenithLuminance = 1e9;

// A model's inputs as the registry takes them: the sun, and named values of the model's own
// parameters (ModelInfo::parameters; e.g. {"turbidity": 4}). Each model binds them into its typed
// parameter struct (PreethamParameters, ...) through its ParameterSchema, which applies the
// defaults and checks every value. Library code may also build a model from its typed struct.
struct SkyParameters {
  SunPosition sun{kDefaultSunZenithDeg * kDegree, kDefaultSunAzimuthDeg* kDegree};
  ParameterValues values;
  // The day of the year (1..366) of the date the sun was computed for, when it came from a time
  // (`--time`): models that depend on the date (the Perez sky from irradiance: the
  // extraterrestrial irradiance) read it when their own day-of-year parameter is not given.
  std::optional<int> day_of_year;
};

// Where a model's result stands for given parameters.
enum class Validity {
  valid,         // inside the range the model was built or fitted for
  extrapolated,  // outside the fitted range: numbers are defined but not validated
  unphysical,    // the model's formula gives physically wrong values (e.g. negative luminance)
  undefined,     // the model does not cover this case; the documented fallback value is returned
};
std::string_view to_string(Validity v);

struct DomainIssue {
  std::string parameter;  // e.g. "turbidity", "sun_zenith"
  Validity validity = Validity::valid;
  std::string message;         // one sentence: what and why
  bool spectral_only = false;  // concerns spectral_radiance() only, not XYZ/RGB
};

struct Domain {
  std::vector<DomainIssue> issues;
  // The worst validity of the XYZ/RGB outputs (issues that concern spectral output only are left
  // out); worst_spectral() includes them.
  Validity worst() const;
  Validity worst_spectral() const;
  bool valid() const { return worst() == Validity::valid; }
};

// Directions as structure of arrays (unit vectors, ENU), the batch path's input.
struct DirectionsSoA {
  std::span<const float> x, y, z;
  std::size_t size() const { return x.size(); }
};
// The horizontal light a sky was built from when it was measured (the Perez sky of --dni/--dhi):
// what fixes the sky's radiometric level and its direct sun (`skylight irradiance`).
struct MeasuredLight {
  double dni_w_m2 = 0.0, dhi_w_m2 = 0.0;  // direct normal, diffuse horizontal irradiance
  double dni_lux = 0.0, dhi_lux = 0.0;    // the same as illuminance (the efficacy models)
  double air_mass = 0.0;                  // relative optical air mass of the sun
  double extraterrestrial_w_m2 = 0.0;     // normal irradiance outside the atmosphere, that day
};

// XYZ output as structure of arrays.
struct XyzSoA {
  std::span<float> X, Y, Z;
  std::size_t size() const { return X.size(); }
};

class SkyModel {
 public:
  virtual ~SkyModel() = default;
  SkyModel(const SkyModel&) = delete;
  SkyModel& operator=(const SkyModel&) = delete;

  virtual std::string_view name() const = 0;
  // The sun position the model was built for.
  const SunPosition& sun() const { return sun_; }
  // The parameters the model read (its schema's names and units, defaults applied; the sun is
  // sun()): what outputs record as metadata. A parameter of the schema that the model does not
  // read with these values (e.g. nn's turbidity for a network without that input) is left out,
  // and a front end warns when it was given.
  virtual ParameterValues parameter_values() const = 0;

  // Sky (without the solar disc) CIE 1931 XYZ in direction `view` (unit vector, ENU), Y =
  // luminance [cd/m^2]. Directions below the horizon return 0 for the analytic sky models.
  virtual Xyz tristimulus(Vec3 view) const = 0;
  // Linear sRGB (D65) of the sky on the same photometric scale (derived from XYZ unless the model
  // has a native RGB fit, which its documentation then says).
  virtual Rgb rgb(Vec3 view) const { return xyz_to_linear_srgb(tristimulus(view)); }
  // Sky spectral radiance [W m^-2 sr^-1 nm^-1] at wavelength nm, or nullopt if the model has no
  // spectral output (or nm is outside its range).
  virtual std::optional<double> spectral_radiance(Vec3 view, double nm) const;

  // Batch fast path: out[i] = tristimulus(dirs[i]) in single precision, each model stating its
  // error bound against the scalar path. Runs on the calling thread only (callers parallelise over
  // chunks with parallel_for); the default implementation is the scalar loop.
  virtual void tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const;

  // The solar disc: angular radius [rad] used, and its XYZ radiance (Y in cd/m^2) in direction
  // `view` (0 outside the disc). Models without a sun return 0 / nullopt.
  virtual bool has_sun() const { return false; }
  virtual double sun_angular_radius() const { return 0.0; }
  virtual Xyz sun_tristimulus(Vec3 view) const;
  virtual std::optional<double> sun_spectral_radiance(Vec3 view, double nm) const;

  // The measured light the sky was normalised to; nullopt for a model that computes its own
  // light (every model but the Perez sky from irradiance).
  virtual std::optional<MeasuredLight> measured_light() const { return std::nullopt; }

  // Where this model, with these parameters, is valid.
  virtual Domain domain() const = 0;

  // The sky (tristimulus() or rgb(), without the solar disc) as a shader's function with this
  // model's set-up (models/gpu_sky.h: `render --gpu`, `skylight view`), or nullopt for a model
  // that has none (its ModelInfo::no_gpu says why).
  virtual std::optional<GpuSky> gpu_sky() const { return std::nullopt; }

 protected:
  // Checks the sun (validate_sun).
  explicit SkyModel(const SunPosition& sun);
  // A domain that holds, when the sun is below the horizon (zenith > 90 deg), the entry
  // "sun below the horizon: <consequence>" at `validity`, and nothing otherwise: the start of
  // domain() for the models whose validity ends at the horizon.
  Domain sun_below_horizon(Validity validity, std::string_view consequence) const;

 private:
  SunPosition sun_;
};

// Batch paths of models that compute linear sRGB: `out` holds r, g, b in its X, Y, Z spans and is
// converted to XYZ in place (the sRGB (D65) matrix in float).
void linear_srgb_to_xyz_in_place(const XyzSoA& out);

// Evaluates the batch path over all directions on all threads (parallel_for over chunks).
void tristimulus_parallel(const SkyModel& model, const DirectionsSoA& dirs, const XyzSoA& out);

// "model '<name>'": the context of a model's parameter errors.
std::string model_context(std::string_view name);

// The typed parameters P of model `name` from generic SkyParameters: P's defaults, the sun, and
// the values bound through P::schema() (unknown, missing and out-of-range values throw).
template <class P>
P bind_parameters(const SkyParameters& sp, std::string_view name) {
  P p;
  p.sun = sp.sun;
  P::schema().bind(sp.values, p, model_context(name));
  return p;
}

// ---- Registry -----------------------------------------------------------------------------------

// What the rest of the library needs to know about a model, declared in its registry entry (the
// model's own source file) so that no operation tests a model's name (docs/ARCHITECTURE.md, "The
// registry").

// How the neural-sky tools sample the model (Satilmis et al. 2016 §III-D, §IV-A;
// fit/neural_training.h): the network learns rgb() / target_scale over these turbidities.
struct NeuralPolicy {
  double target_scale = 1000.0;
  // {0}: the model has no turbidity (one sky state per sun; the network's turbidity input unused).
  std::vector<double> training_turbidities{0.0};
  std::vector<double> validation_turbidities{0.0};
  // The held-out check every trained network passes (fit/neural_training.h): turbidities on a
  // dense grid, between the training ones included, and the bound on the p95 of the relative
  // radiance error there beyond which training fails (`nn train --max-error`).
  std::vector<double> held_out_turbidities{0.0};
  double max_relative_p95 = 0.30;
  // Training T = first, first + 1, ..., last; validation the midpoints between them (the paper's
  // Preetham 2..6 / 2.5..5.5 and Hosek 1..10 / 1.5..9.5); the held-out check every 0.1.
  static NeuralPolicy over_turbidity(double first, double last, double target_scale = 1000.0);
  // This policy with the held-out bound max_relative_p95 = p95.
  NeuralPolicy bounded(double p95) const {
    NeuralPolicy p = *this;
    p.max_relative_p95 = p95;
    return p;
  }
};

// How a photo's luminance samples are fitted with the model (`skylight estimate`,
// fit/luminance_fit.h): the parameters fitted (numbers of its schema, each with the range the fit
// searches and the grid it starts from), the method, and the model's luminance up to a constant
// factor (the fit's free scale s absorbs it: r_i = ln Y_i - ln s - ln L(v_i; p)).
struct EstimationPolicy {
  enum class Method {
    // One parameter: a scan of its grid with ln s in closed form, Levenberg-Marquardt from the
    // best point, golden section in the bracket as the fallback; RANSAC fits every minimal set.
    profile_scan,
    // Any parameters: the grid of all axes, RANSAC on the grid, Levenberg-Marquardt in the box.
    grid_ransac,
    // One integer parameter: every value ranked by inliers around the median scale, then residual.
    ranking,
  };
  struct Axis {
    std::string parameter;          // the schema's name, e.g. "turbidity"
    std::string label;              // in the text output, e.g. "CIE sky type"
    std::string note{};             // after the value in the text output, e.g. "(of 15, CIE S 011)"
    double min = 0.0, max = 0.0;    // the range searched (the fit's box)
    int grid_points = 2;            // the starting grid (ranking: max - min + 1 values)
    double derivative_step = 1e-4;  // central differences of ln L
  };
  // ln L(v_i; p) for the indices `idx` of the views the closure was prepared for (p in axes
  // order), into out (idx.size() values); -infinity where L <= 0.
  using LogLuminance = std::function<void(std::span<const double> p,
                                          std::span<const std::size_t> idx, std::span<double> out)>;
  Method method = Method::grid_ransac;
  std::vector<Axis> axes;
  // Prepares the closure for a sun and the sample views (e.g. the angles to the sun, once).
  std::function<LogLuminance(const SunPosition& sun, std::span<const Vec3> views)> prepare;
  std::string description;  // what is fitted, after which paper
  bool is_default = false;  // the model `skylight estimate` fits without --model (one model)
  // A model whose policy (the same axes) searches the parameters in this one's place, for a model
  // too costly to evaluate hundreds of times (a table per parameter set): its fit, then this
  // model's own ln s and residual at the parameters found (fit/luminance_fit.h). Empty: none.
  std::string surrogate{};
  // ranking: the JSON array of every value, best first, and the key of each entry's value (e.g.
  // "cie_ranking" of {"type": 12, ...}).
  std::string ranking_field{}, ranking_key{};
};

// A grid_ransac policy over `axes` whose luminance is the registered model `name` itself, built
// with the axes' values and its other parameters at their defaults: for a model without a closed
// form of its luminance's dependence (the networks, the tables, the physical atmospheres).
EstimationPolicy registry_estimation(std::string name, std::vector<EstimationPolicy::Axis> axes,
                                     std::string description);

// How `skylight sh fit` fits the model's SH polynomial table (Habel et al. 2008 eq. 1;
// fit/sh_fit.h): the second varying parameter tau and, when the fit varies it, its default range
// and the table's structure.
struct ShFitPolicy {
  // A number of the schema; empty: the fit is in the sun zenith only.
  std::string parameter;
  // The default range of tau [its unit]; absent: the parameter's whole range.
  std::optional<std::array<double, 2>> range{};
  // Hosek & Wilkie's structure: one tau piece per unit of tau (their knots at the integers),
  // these degrees (theta, tau) unless given, grid_tau points per piece (0: the default), the sun
  // zenith axis theta_axis.
  bool unit_pieces = false;
  std::optional<std::array<int, 2>> degrees{};
  int grid_tau = 0;
  sh::ThetaAxis theta_axis = sh::ThetaAxis::theta;
};

// How the benchmarks use the model (`skylight bench`, bench/bench_models.cpp; perf/workloads.h).
struct BenchPolicy {
  bool by_default = false;  // timed by `skylight bench` without --models
  // A model whose batch path this one is compared with (the cost it replaces); empty: none.
  std::string baseline{};
  // How that comparison names the benchmarked sky (default: the model's name).
  std::string label{};
  // A further workload of perf/workloads.h: the SH table's evaluation against projecting the
  // table's model, each network kind (with the trainer's initial weights) against nishita, or
  // the precomputation a model does before its first frame (tables and LUTs; timed first, before
  // anything in the process has built them).
  enum class Extra { none, sh_table, network_kinds, precomputation };
  Extra extra = Extra::none;
};

// How the validation report (src/skylight/report/, docs/REPORT.md) labels and draws the model:
// one sky of it is "<title> <axis_label><value>" (e.g. "Preetham T = 3", "CIE type 12"), or the
// title alone for a model the report does not vary. A model without a title is not in the report.
struct ReportPolicy {
  std::string title{};
  std::string axis{};        // the parameter the report varies ("turbidity", "cie-type"), or ""
  std::string axis_label{};  // before the value in labels: "T = ", "type "
  ParameterValues fixed{};   // values the report holds (e.g. Hosek's ground albedo 0.3)
  std::string colour{};      // of its curves and markers in the report's plots (#rrggbb)
  // The values of `axis` the report samples, when narrower than the parameter's range (e.g. the
  // fitted range of the embedded table); empty: the parameter's range.
  std::optional<std::array<double, 2>> axis_range{};
  // A model this one approximates with its default data (the registry name, e.g. the embedded
  // network's training source): the report also judges it against that source, at the same
  // sun and axis value. Empty: none.
  std::string source{};
  // An integer parameter that truncates the approximation (e.g. SH bands): the report sweeps it
  // over `truncation_range` against the source. Empty: none.
  std::string truncation{};
  std::array<int, 2> truncation_range{};
  // The report's physical atmosphere: the reference of its colour and twilight table (one model
  // of the registry declares it: the one closest to the path tracer).
  bool physical_reference = false;
  // A physically based atmosphere: a row of the report's maps of the physical atmospheres (its
  // Earth defaults), in registry order (single scattering first).
  bool physical_atmosphere = false;
  // The report's "light on planes" section: the annual light of this model's sky on a façade and
  // a roof of the weather year (`irradiance --epw`, daylight/plane_series.h) at these values;
  // absent: the model is not in that section.
  std::optional<ParameterValues> planes{};
};

// Binds the generic values into the model's typed parameters (its schema applies defaults and
// checks them) and builds the model.
using ModelFactory = std::function<std::unique_ptr<SkyModel>(const SkyParameters&)>;

// `eval --reference`: the value of a direction by the model's reference integrator (the brute force
// or the Monte Carlo path tracer its fast path is checked against), with standard errors (0 for a
// deterministic integrator), in the quantity's columns (models/evaluation.h).
struct EvaluationOptions;
struct ReferenceRequest {
  std::uint64_t paths = 20000;  // Monte Carlo paths per wavelength
  std::uint64_t seed = 1;
};
struct ReferenceValue {
  std::vector<double> value, standard_error;
};
using ReferencePath = std::function<ReferenceValue(
    const SkyModel&, Vec3 view, const EvaluationOptions&, const ReferenceRequest&)>;

struct ModelInfo {
  std::string name;
  std::string description;
  std::string output;  // what tristimulus()/luminance mean, with units
  std::vector<ParameterSpec>
      parameters;      // the model's own parameters (the sun comes first, common)
  std::string domain;  // where it is valid, in words
  bool spectral = false;
  bool sun = false;
  // The model gives luminance only, its XYZ at the D65 white point: its images are grey by
  // design (colour_note()).
  bool luminance_only = false;
  ModelFactory make;
  // Values that make a typical sky where the defaults do not (the required parameters): used by
  // benchmarks, the report and the docs' examples.
  ParameterValues example{};
  // Values the tests that build the model at every parameter edge hold fixed (on top of
  // `example`), for a model whose set-up at a full setting is too slow to repeat for each edge
  // (bruneton: 2 scattering orders, ~1 s of tables per atmosphere instead of ~4 s).
  ParameterValues sweep{};
  // The set-up takes 0.1 s or more (tables, LUTs per sun): the edge sweeps of such a model are
  // their own ctest suite (Registry/CostlyEdgeSweeps), which the sanitizer pass of
  // scripts/test.sh leaves to the Release pass (each takes minutes under ASan; the model's own
  // tests run there).
  bool costly_setup = false;
  // With a weather file (`irradiance --epw`, daylight/plane_series.h) the model's sky is each
  // hour's Perez all-weather sky of the record's light (`perez`); otherwise the model's own sky at
  // its parameters, scaled to the hour's diffuse light.
  bool weather_sky = false;
  // The output may be negative (and is non-zero below the horizon): `sh`, whose reconstruction is
  // returned unclamped; every other model is non-negative.
  bool unclamped = false;
  NeuralPolicy neural{};
  // Absent: `skylight estimate` does not fit this model.
  std::optional<EstimationPolicy> estimation{};
  // Absent: no SH table is fitted to this model (`sh`: a table is not fitted to a table).
  std::optional<ShFitPolicy> sh_fit{};
  BenchPolicy bench{};
  ReportPolicy report{};
  // Why gpu_sky() gives no shader for this model (one sentence); empty: it gives one.
  std::string no_gpu{};
  // The reference integrator of `eval --reference` and what it is; empty: none.
  ReferencePath reference{};
  std::string reference_description{};

  // The model's own parameter of that name (not the sun's); nullptr if it has none.
  const ParameterSpec* find_parameter(std::string_view parameter) const;
  // What its images' colours mean, for their metadata (skylight:colour) and `skylight models`:
  // "colour" or "grey by design: luminance only (XYZ at the D65 white point)".
  std::string colour_note() const;
};

// The factory of a model class built from its typed parameters P (bind_parameters).
template <class Model, class P>
ModelFactory model_factory() {
  return [](const SkyParameters& sp) -> std::unique_ptr<SkyModel> {
    return std::make_unique<Model>(bind_parameters<P>(sp, Model::kName));
  };
}

const std::vector<ModelInfo>& model_registry();
// Every parameter of a model as the user sees it: the sun (sun_parameter_specs()) and its own.
std::vector<ParameterSpec> all_parameters(const ModelInfo& model);
// The parameter table of a model in docs/MODELS.md between its markers
// "<!-- parameters NAME -->" and "<!-- end parameters NAME -->" (`skylight models --markdown`).
std::string parameter_docs_block(const ModelInfo& model);
// nullptr if unknown.
const ModelInfo* find_model(std::string_view name);
// The same, or InvalidArgument "unknown model 'X'; did you mean 'Y'? (known: ...)", prefixed with
// the parameter that named it when given ("--sky-model: unknown model ...", spelled()).
const ModelInfo& require_model(std::string_view name, std::string_view parameter = {});
// Builds a model; throws InvalidArgument for an unknown name, a parameter the model does not have,
// a missing required one, or a value out of range (the message names the parameter and the value).
std::unique_ptr<SkyModel> make_sky_model(std::string_view name, const SkyParameters& params);

// Validation of values that are not schema parameters (wavelengths, dataset inputs): throws
// InvalidArgument("<name> = <value> is outside the valid range [min, max]") for NaN or
// out-of-range values.
void require_in_range(std::string_view name, double value, double min, double max);

}  // namespace skylight
