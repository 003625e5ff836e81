// A model evaluated in given directions, as `skylight eval` and the Python package return it: the
// quantity (linear sRGB, XYZ, luminance or spectral radiance at given wavelengths) of the sky, the
// solar disc or both, checked to be finite. The options are declared once here (their schemas);
// models/sky_model.h has the model's own parameters.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "skylight/core/colorimetry.h"
#include "skylight/core/parameters.h"
#include "skylight/models/sky_model.h"

namespace skylight {

// What is drawn or evaluated: the sky alone (default), sky + solar disc, or the disc alone.
enum class SunMode { sky, sky_and_sun, sun_only };
// "sky", "sky+sun", "sun-only" (as outputs record it).
std::string_view to_string(SunMode mode);
// The solar disc switches --include-sun and --sun-only (a model without a sun refuses both:
// check_sun_mode).
struct SolarDisc {
  SunMode mode = SunMode::sky;
  static const ParameterSchema<SolarDisc>& schema();
};
// InvalidArgument when the mode needs a solar disc the model does not have.
void check_sun_mode(const SkyModel& model, SunMode mode);

// The name of every registered model as one parameter (--model), required.
ParameterSpec model_spec();
// --sun-elevation: --sun-zenith's alternative (zenith = 90 - elevation), its range derived from
// the zenith's (sun_parameter_specs()).
ParameterSpec sun_elevation_spec();

enum class Quantity { rgb, xyz, luminance, spectral };

struct EvaluationOptions {
  Quantity quantity = Quantity::rgb;
  std::vector<double> wavelengths_nm;  // spectral only, [nm]
  SunMode sun = SunMode::sky;

  // --quantity and --wavelengths.
  static const ParameterSchema<EvaluationOptions>& schema();
};

// `eval --reference`, `--paths`, `--seed`: the model's reference integrator instead of its fast
// path (ModelInfo::reference), with a standard-error column per value.
struct ReferenceOptions {
  bool reference = false;
  ReferenceRequest request;
  static const ParameterSchema<ReferenceOptions>& schema();
};
// The reference's value and standard errors of `view` (the sky alone: InvalidArgument for a sun
// mode, or for a model without a reference).
ReferenceValue evaluate_reference(const ModelInfo& info, const SkyModel& model, Vec3 view,
                                  const EvaluationOptions& options,
                                  const ReferenceRequest& request);

// A reference integrator's wavelengths for the options: those of the model's XYZ quadrature
// (`xyz_nm`) for xyz and luminance, the spectral ones (checked against [min_nm, max_nm], naming
// `model`) for spectral; InvalidArgument for rgb. And the quantity's values and standard errors
// from spectral radiances and their standard errors there (independent per wavelength) with the
// quadrature's `weights` (core/xyz_quadrature.h: X = K_m sum_k w_k.x L_k), or the spectral
// radiances themselves.
std::vector<double> reference_wavelengths_of(const EvaluationOptions& options,
                                             std::string_view model, std::span<const double> xyz_nm,
                                             double min_nm, double max_nm);
ReferenceValue weighted_reference_value(const EvaluationOptions& options,
                                        std::span<const Cmf> weights,
                                        std::span<const double> radiance,
                                        std::span<const double> standard_error);

// Checks the options (spectral needs wavelengths; wavelengths only with spectral), then against
// the model (a spectral model for spectral, a solar disc for the sun modes): InvalidArgument
// naming the option.
void validate(const EvaluationOptions& options);
void validate(const EvaluationOptions& options, const SkyModel& model);
// The names of the values evaluate() returns: r,g,b; x,y,z; luminance; L<nm> per wavelength.
std::vector<std::string> quantity_columns(const EvaluationOptions& options);
// The values in direction `view` (unit vector): the sky (rgb() for rgb of the sky alone,
// tristimulus() otherwise) plus the solar disc as the options say. InvalidArgument for a
// wavelength outside the model's range; the caller checks finiteness (non-finite values are an
// overflow of the model's parameters).
std::vector<double> evaluate(const SkyModel& model, Vec3 view, const EvaluationOptions& options);

// Directions evaluated per parallel_for chunk by evaluate_rows and evaluate_angles: the chunk's
// float64 rows, its float structure-of-arrays and its results stay in the L1/L2 cache.
inline constexpr std::size_t kBatchChunk = 1024;

// The batch evaluation of many directions into `out` (directions x quantity_columns(options)
// float64 values, row by row), in chunks on thread_count() threads: the model's single-precision
// SIMD path (tristimulus_batch) for the sky's XYZ or luminance unless `exact`; evaluate() per
// direction otherwise. InvalidArgument naming the first bad direction, a wrong `out` size, or the
// first non-finite value (an overflow of the model's parameters; `out` is then partly written).
// The options must have been validated (validate(options, model)).
//
// evaluate_rows: `directions` holds rows (x, y, z), any finite non-zero length (normalised; a
// direction with |v|^2 within kUnitLengthTolerance of 1 as it is on the SIMD path). The Python
// package's Sky.evaluate_directions, and the C++ batch path for float64 rows
// (bench/bench_models.cpp).
void evaluate_rows(const SkyModel& model, std::span<const double> directions,
                   const EvaluationOptions& options, std::span<double> out, bool exact = false);
// evaluate_soa: the model's SIMD batch path (tristimulus_batch: the sky's XYZ, Y in cd/m^2) on
// float structure-of-arrays, in place of the caller's arrays, checked: every direction a unit
// vector to kFloatUnitLengthTolerance (InvalidArgument naming the first that is not) and every
// result finite. The Python package's Sky.evaluate_soa: no conversion at all.
void evaluate_soa(const SkyModel& model, const DirectionsSoA& directions, const XyzSoA& out);
// evaluate_angles: zenith [0, 180] and azimuth [-360, 360] angles [deg] of one length, the
// directions made as `skylight eval` makes them from its CSV.
void evaluate_angles(const SkyModel& model, std::span<const double> zenith_deg,
                     std::span<const double> azimuth_deg, const EvaluationOptions& options,
                     std::span<double> out, bool exact = false);

}  // namespace skylight
