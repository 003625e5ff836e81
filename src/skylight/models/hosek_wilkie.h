// Hosek & Wilkie 2012, "An Analytic Model for Full Spectral Sky-Dome Radiance" (ACM TOG 31(4),
// SIGGRAPH 2012), with the solar radiance function of Hosek & Wilkie 2013, "Adding a Solar Radiance
// Function to the Hosek Skylight Model" (IEEE CG&A 33(3)). Data: data/hosek_wilkie/ (the published
// ArHosekSkyModel v1.4a datasets, 3-clause BSD, see PROVENANCE.md there).
//
// The model (2012 paper eq. 8-9 and §5; v1.4a `ArHosekSkyModel_GetRadianceInternal`):
//   L(theta, gamma) = F(theta, gamma) * L_M
//   F = (1 + A exp(B / (cos theta + 0.01))) *
//       (C + D exp(E gamma) + F cos^2 gamma + G chi(H, gamma) + I sqrt(cos theta))
//   chi(H, gamma) = (1 + cos^2 gamma) / (1 + H^2 - 2 H cos gamma)^(3/2)   (Mie aureole)
// theta: view zenith angle, gamma: angle between view and sun centre [rad]. Each of A..I and the
// radiance scale L_M is a quintic Bezier in x = (solar_elevation / (pi/2))^(1/3) (eq. 10, 6 control
// points), linearly interpolated in turbidity between integer knots 1..10 and in ground albedo
// between the knots 0 and 1. This "state" is computed once per (turbidity, albedo, elevation);
// evaluation per direction is then one F.
//
// Everything here reproduces the reference implementation ArHosekSkyModel.c v1.4a; the functions
// with reference-style arguments (HwViewAngles) match its output to <= 1e-9 relative (tested on
// every row of data/hosek_wilkie/reference_values/, see hosek_wilkie_test.cpp). Where v1.4a is
// undefined (NaN, assertions) this code defines the value; each such case is listed below.
#pragma once

#include <array>

#include "skylight/models/sky_model.h"

namespace skylight {

// ---- dataset layout ----
// Spectral bands: 320, 360, ..., 720 nm (v1.4a `dataset320` .. `dataset720`).
inline constexpr int kHwBands = 11;
inline constexpr double kHwFirstBandNm = 320.0;
inline constexpr double kHwBandStepNm = 40.0;
inline constexpr double kHwLastBandNm = 720.0;
// Turbidity knots 1..10 (integers), albedo knots 0 and 1.
inline constexpr double kHwTurbidityMin = 1.0;
inline constexpr double kHwTurbidityMax = 10.0;
// Angular radius of the solar disc used by v1.4a: `( 0.51 DEGREES ) / 2.0` (= 0.255 deg,
// 4.4506e-3 rad); the reference solar values (hw_ref_solar_radiance.csv) were made with it.
inline constexpr double kHwSolarRadius = 0.51 * kDegree / 2.0;
// v1.4a adds this to cos(theta) in the gradation term B / (cos theta + 0.01) (2012 eq. 9).
inline constexpr double kHwCosThetaOffset = 0.01;

// The 9 parameters of F in the datasets' storage order: A, B, C, D, E, F, G, I, H (index 7 is I,
// the sqrt(cos theta) term, index 8 is H, the Mie anisotropy in chi).
using HwConfig = std::array<double, 9>;
namespace hw_index {
inline constexpr int A = 0, B = 1, C = 2, D = 3, E = 4, F = 5, G = 6, I = 7, H = 8;
}

enum class HwDataset {
  spectral,  // 11 bands, radiance in W m^-2 sr^-1 nm^-1
  ciexyz,    // CIE 1931 XYZ; times 683 (kMaxLuminousEfficacy) Y is luminance in cd/m^2
  rgb,       // the native RGB fit, same scale as ciexyz (linear sRGB primaries, see the model)
};

// Inputs of a state (v1.4a: `arhosek_xyz_skymodelstate_alloc_init(turbidity, albedo, elevation)`;
// note that the spectral `arhosekskymodelstate_alloc_init(elevation, turbidity, albedo)` takes
// them in another order - named fields avoid the mix-up).
struct HwStateParameters {
  double turbidity = 3.0;        // [1], 1..10 (InvalidArgument outside)
  double albedo = 0.3;           // ground albedo [1], 0..1 (InvalidArgument outside)
  double solar_elevation = 0.0;  // [rad], 0..pi/2 (InvalidArgument outside: v1.4a gives NaN)
};

// Direction arguments in the reference's convention.
struct HwViewAngles {
  double theta = 0.0;  // view zenith angle [rad]; cos theta < 0 is treated as 0 (v1.4a: NaN)
  double gamma = 0.0;  // angle between the view and the sun centre [rad]
};

// One channel (band) of a state: the 9 interpolated parameters and the radiance scale L_M.
struct HwChannelState {
  HwConfig config{};
  double radiance = 0.0;  // L_M (unit of the dataset)
};

// ArHosekSkyModel_CookConfiguration + ArHosekSkyModel_CookRadianceConfiguration for one channel
// (index into the dataset: 0..2 for ciexyz/rgb, 0..10 for spectral bands).
HwChannelState hw_channel_state(HwDataset dataset, int channel, const HwStateParameters& p);

// F(theta, gamma) of the header equation for one configuration (dimensionless).
double hw_extended_perez(const HwConfig& c, HwViewAngles a);
// The same with cos theta and cos gamma given (the model's paths; cos_theta clamped to [0, 1]).
double hw_extended_perez(const HwConfig& c, double cos_theta, double gamma, double cos_gamma);

// Tristimulus state: X,Y,Z or R,G,B channels. Per-channel albedo is allowed (each channel has its
// own state in v1.4a too); the single-albedo form sets all channels to p.albedo.
struct HwTristimState {
  HwDataset dataset = HwDataset::ciexyz;
  std::array<HwChannelState, 3> channels{};
};
HwTristimState hw_tristim_state(HwDataset dataset, const HwStateParameters& p);
HwTristimState hw_tristim_state(HwDataset dataset, const HwStateParameters& p,
                                const std::array<double, 3>& channel_albedo);
// arhosek_tristim_skymodel_radiance: F * L_M for channel 0..2 (dataset units, i.e. NOT times 683).
double hw_tristim_radiance(const HwTristimState& s, HwViewAngles a, int channel);

// Spectral state: the 11 band states plus what the solar function needs.
struct HwSpectralState {
  std::array<HwChannelState, kHwBands> bands{};
  double turbidity = 3.0;
  double solar_elevation = 0.0;
};
HwSpectralState hw_spectral_state(const HwStateParameters& p);
HwSpectralState hw_spectral_state(const HwStateParameters& p,
                                  const std::array<double, kHwBands>& band_albedo);

// arhosekskymodel_radiance: sky spectral radiance [W m^-2 sr^-1 nm^-1] at nm, linearly
// interpolated between the two neighbouring bands (40 nm apart; as v1.4a, a fraction below 1e-6 of
// the step returns the lower band). Returns 0 outside [320, 720] nm. (v1.4a itself returns band
// 320 for 280 < nm < 320 and a fading fraction of band 720 for 720 < nm < 760: not reproduced.)
double hw_spectral_radiance(const HwSpectralState& s, HwViewAngles a, double nm);

// ---- the 2013 solar radiance function -----------------------------------------------------------
// Direct (un-scattered) spectral radiance of the solar disc (arhosekskymodel_solar_radiance_
// internal2): the sun-centre radiance from the piecewise cubic in solar elevation h (45 pieces,
// piece p starts at h = (p/45)^3 pi/2), linearly interpolated in turbidity (1..10) and wavelength
// (320..720 nm), times the limb darkening sum_k ld_k(nm) mu^k (5th order), with
// mu = sqrt(1 - sin^2 gamma / sin^2 r_sun) ("sampleCosine"), r_sun = kHwSolarRadius.
struct HwSolarInputs {
  double turbidity = 3.0;        // [1], 1..10
  double solar_elevation = 0.0;  // [rad]; below 0 the value is 0 (v1.4a: NaN)
  double gamma = 0.0;            // angle from the sun centre [rad]
};
// [W m^-2 sr^-1 nm^-1]; nm in [320, 720] (InvalidArgument outside, v1.4a asserts). As v1.4a, no
// cut-off at the disc edge: for gamma > r_sun mu = 0 and the value is ld_0 times the centre value
// (the model's sun_* functions return 0 outside the disc instead).
double hw_solar_direct_radiance(const HwSolarInputs& in, double nm);
// The sun-centre radiance before limb darkening, and the interpolated limb-darkening coefficients.
double hw_solar_centre_radiance(double turbidity, double solar_elevation, double nm);
std::array<double, 6> hw_limb_darkening(double nm);
// arhosekskymodel_solar_radiance(state, theta, gamma, nm) = direct + sky: v1.4a takes the elevation
// for the direct part as pi/2 - theta (the reference calls it with theta = the sun's zenith).
double hw_solar_radiance(const HwSpectralState& s, HwViewAngles a, double nm);

// The spectral model integrated to XYZ: the 11 band radiances L_b give the interpolated spectrum,
// so XYZ = sum_b L_b W_b with W_b = K_m int hat_b(nm) cmf(nm) dnm (1 nm trapezoid, 360-720 nm:
// the CMFs start at 360, the model ends at 720). Y in cd/m^2.
const std::array<Xyz, kHwBands>& hw_band_xyz_weights();

// ---- the `hosek` model ----
// Parameters: sun position, turbidity [1, 10] and ground albedo [0, 1] (both rejected outside with
// InvalidArgument: the datasets have no knots there). Outputs:
//  * tristimulus(): the CIE XYZ dataset times 683 lm/W (kMaxLuminousEfficacy): Y is luminance in
//    cd/m^2, as the dataset's header says ("after multiplication with 683 lm / W, the Y channel now
//    corresponds to luminance").
//  * rgb(): the native RGB dataset, also times 683, so it is on the same photometric scale as
//    tristimulus() (the RGB fit is in the same radiometric units as the XYZ fit; its primaries are
//    linear sRGB/Rec.709 as docs/MODELS.md states; the data files do not say). It is a separate
//    fit, so it differs from xyz_to_linear_srgb(tristimulus()) by a few percent (tested bound in
//    the tests).
//  * spectral_radiance(): 320-720 nm (nullopt outside), W m^-2 sr^-1 nm^-1, v1.4a interpolation.
//  * tristimulus_from_spectral() / rgb_from_spectral(): the spectral model integrated (see
//    hw_band_xyz_weights).
//  * sun: disc of radius kHwSolarRadius around the sun direction; sun_spectral_radiance() is the
//    direct radiance only (hw_solar_direct_radiance at the sun's elevation), 320-720 nm, 0 outside
//    the disc; sky + sun equals v1.4a's arhosekskymodel_solar_radiance (which adds the sky).
//    sun_tristimulus() integrates it over 360-720 nm (1 nm trapezoid, Y in cd/m^2), limb
//    darkening included: XYZ(mu) = sum_k mu^k XYZ_k, with XYZ_k precomputed per state.
//  * Views below the horizon (z < 0): 0. Sun below the horizon (elevation < 0): the model does not
//    cover twilight; everything is 0 and domain() says `undefined`. The fit itself dips below 0
//    exactly at the horizon (cos theta = 0) for low suns (solar elevation below ~12 deg, mostly
//    albedo < 0.5) and in the spectral bands; the model's outputs are clamped to >= 0 there (the
//    hw_* free functions return v1.4a's raw values). tristimulus_from_spectral() clamps each band.
//  * tristimulus_batch(): single-precision SIMD (hosek_kernel.cpp) with the same clamps. Bound vs
//    the scalar double path: 1e-5 relative (measured 3.8e-6 over 90 states x 5004 directions,
//    aureole included); values below 1e-6 of the sky's largest channel value are compared
//    absolutely (cancellation next to the horizon with the sun on it). hosek_wilkie_test.cpp,
//    kHosekBatchRelativeTolerance.
//  * Set-up (the constructor): the XYZ, RGB and 11 spectral band states (Bezier weights formed
//    once per state) and the sun's XYZ polynomial in mu in closed form over the band intervals.
struct HosekParameters {
  SunPosition sun;
  double turbidity = 3.0;  // --turbidity T [1], [kHwTurbidityMin, kHwTurbidityMax] (dataset knots)
  double albedo = 0.3;     // --albedo: ground albedo [1], [0, 1] (dataset knots 0 and 1)

  static const ParameterSchema<HosekParameters>& schema();
};

class HosekWilkieModel final : public SkyModel {
 public:
  explicit HosekWilkieModel(const HosekParameters& params);
  static constexpr std::string_view kName = "hosek";
  // The registry entry: documentation, schema, factory and policy (models/sky_model.h).
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  const HosekParameters& parameters() const { return params_; }
  ParameterValues parameter_values() const override;
  Xyz tristimulus(Vec3 view) const override;
  Rgb rgb(Vec3 view) const override;
  std::optional<double> spectral_radiance(Vec3 view, double nm) const override;
  void tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const override;
  bool has_sun() const override { return true; }
  double sun_angular_radius() const override { return kHwSolarRadius; }
  Xyz sun_tristimulus(Vec3 view) const override;
  std::optional<double> sun_spectral_radiance(Vec3 view, double nm) const override;
  Domain domain() const override;
  std::optional<GpuSky> gpu_sky() const override;

  Xyz tristimulus_from_spectral(Vec3 view) const;
  Rgb rgb_from_spectral(Vec3 view) const {
    return xyz_to_linear_srgb(tristimulus_from_spectral(view));
  }

  const HwTristimState& xyz_state() const { return xyz_; }
  const HwTristimState& rgb_state() const { return rgb_; }
  const HwSpectralState& spectral_state() const { return spectral_; }

 private:
  // cos theta, gamma, cos gamma of a view; false below the horizon or with the sun down.
  bool view_angles(Vec3 view, double& cos_theta, double& gamma, double& cos_gamma) const;
  // mu = sampleCosine inside the disc, or false outside it, below the horizon or with the sun
  // down.
  bool disc_cosine(Vec3 view, double& mu) const;

  HosekParameters params_;
  bool sun_up_ = true;
  Vec3 sun_;
  HwTristimState xyz_, rgb_;
  HwSpectralState spectral_;
  // sun_tristimulus(mu) = sum_k sun_xyz_[k] mu^k (limb darkening is linear in its coefficients).
  std::array<Xyz, 6> sun_xyz_{};
};

}  // namespace skylight
