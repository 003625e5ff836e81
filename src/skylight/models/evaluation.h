// A model evaluated in given directions, as `skylight eval` and the Python package return it: the
// quantity (linear sRGB, XYZ, luminance or spectral radiance at given wavelengths) of the sky, the
// solar disc or both, checked to be finite. The options are declared once here (their schemas);
// models/sky_model.h has the model's own parameters.
#pragma once

#include <string>
#include <vector>

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

}  // namespace skylight
