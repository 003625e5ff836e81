// The SkyModel interface and the model registry (DESIGN.md §3).
//
// A SkyModel is immutable once built for one SkyParameters. It answers per direction (the simple
// reference path) and per batch of directions (the fast path: SIMD + threads). Every model
// documents what it returns and reports its valid domain; below-horizon views and a sun below the
// horizon are defined cases (documented values, never NaN).
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/atmosphere/parameters.h"
#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"

namespace skylight {

// All inputs a model may use. Angles in radians; each model reads the fields it needs and ignores
// the rest (ModelInfo::parameters lists which).
struct SkyParameters {
  SunPosition sun{kPi / 4, kPi};  // default: 45 deg zenith angle, due south
  // Atmospheric turbidity T (Preetham: ratio of the optical thickness of haze + air to pure air),
  // [1, 64]. Models flag where it is outside their fitted range.
  double turbidity = 3.0;
  // Ground albedo, [0, 1] (models without a ground ignore it).
  double ground_albedo = 0.3;
  // CIE Standard General Sky type: 1..15, or 16 for the traditional CIE overcast sky.
  int cie_type = 12;
  // Absolute zenith luminance [cd/m^2], > 0. Required by `perez`; optional for `cie` (otherwise
  // the Kittler-Darula typical value); ignored by `preetham` (which has its own Yz).
  std::optional<double> zenith_luminance;
  // Perez all-weather coefficients A, B, C, D, E (dimensionless) for the `perez` model.
  std::optional<std::array<double, 5>> perez_coefficients;
  // Observer altitude above the ground [m], [0, 1e7] (physically based models; `nishita`).
  double observer_altitude_m = 0.0;
  // Flat extraterrestrial solar spectral irradiance [W m^-2 nm^-1], > 0, at every wavelength;
  // nullopt = the model's real solar spectrum. With 1, radiances are per unit irradiance [sr^-1]
  // (physically based models; `nishita`).
  std::optional<double> solar_irradiance;
  // Planet and atmosphere for `nishita` (models/atmosphere/parameters.h); nullopt = Earth
  // defaults. Its ground_albedo (not the field above) switches the ground reflection on.
  std::optional<atmosphere::AtmosphereParameters> atmosphere;
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
  std::string message;  // one sentence: what and why
};

struct Domain {
  std::vector<DomainIssue> issues;
  Validity worst() const;
  bool valid() const { return worst() == Validity::valid; }
};

// Directions as structure of arrays (unit vectors, ENU), the batch path's input.
struct DirectionsSoA {
  std::span<const float> x, y, z;
  std::size_t size() const { return x.size(); }
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
  const SkyParameters& parameters() const { return params_; }

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

  // Where this model, with these parameters, is valid.
  virtual Domain domain() const = 0;

 protected:
  explicit SkyModel(const SkyParameters& p) : params_(p) {}

 private:
  SkyParameters params_;
};

// Evaluates the batch path over all directions on all threads (parallel_for over chunks).
void tristimulus_parallel(const SkyModel& model, const DirectionsSoA& dirs, const XyzSoA& out);

// ---- Registry -----------------------------------------------------------------------------------

// A model parameter as the user sees it (CLI flag / JSON), with unit, range and default.
struct ParameterInfo {
  std::string name;  // flag name without dashes, e.g. "turbidity"
  std::string unit;  // "1", "deg", "cd/m^2"
  double min = 0.0;  // inclusive valid range (CLI rejects values outside)
  double max = 0.0;
  std::string default_value;  // as text ("45", "required", "Kittler-Darula typical")
  std::string description;
};

struct ModelInfo {
  std::string name;
  std::string description;
  std::string output;                     // what tristimulus()/luminance mean, with units
  std::vector<ParameterInfo> parameters;  // the parameters this model reads
  std::string domain;                     // where it is valid, in words
  bool spectral = false;
  bool sun = false;
  std::function<std::unique_ptr<SkyModel>(const SkyParameters&)> make;
};

const std::vector<ModelInfo>& model_registry();
// nullptr if unknown.
const ModelInfo* find_model(std::string_view name);
// Builds a model; throws InvalidArgument for an unknown name or a parameter out of range (the
// message names the parameter and the value).
std::unique_ptr<SkyModel> make_sky_model(std::string_view name, const SkyParameters& params);

// Validation shared by models: throws InvalidArgument("<name> = <value> is outside [min, max]...")
// for NaN or out-of-range values.
void require_in_range(std::string_view name, double value, double min, double max);

}  // namespace skylight
