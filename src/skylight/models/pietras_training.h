// Training and validating the per-vertex networks of nn/pietras.h on the `nishita` model (Pietras
// §III), and the colour of a surface point seen through the air (§IV). docs/PIETRAS.md.
//
// The colour learnt is nishita's rgb(): linear sRGB on the photometric scale (Y in cd/m^2 for the
// ASTM G-173 sun), no ground reflection (views meeting the ground see the air up to the ground).
// Geometry: the training inputs are drawn as consistent geometry, not from the box
// [-1,1]^3 x [0,1]: cos alpha0, cos theta0 uniform in [-1, 1], the view's azimuth about the zenith
// relative to the sun uniform, so cos beta0 = cos a cos t + sin a sin t cos phi; rho0 uniform in
// [0, 1] (clamped to the density at the top of the atmosphere, i.e. h <= the top).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "skylight/models/nishita.h"
#include "skylight/nn/pietras.h"
#include "skylight/nn/train.h"

namespace skylight {

// nishita's rgb() for any observer altitude, view and sun with one set of optical-length tables
// (equal to NishitaModel::rgb for the same setup; tested).
class NishitaSampler {
 public:
  explicit NishitaSampler(const NishitaParameters& atmosphere);
  Rgb rgb(double altitude_m, Vec3 view, Vec3 sun) const;
  const NishitaParameters& parameters() const { return params_; }
  const atmosphere::Atmosphere& atmosphere() const { return model_.atmosphere(); }
  // Light from a surface point q = P + distance view (P the observer at altitude h): nishita's
  // aerial perspective (Atmosphere::aerial_perspective, grey Lambertian albedo) as rgb, and the
  // parts of §IV: the reflected sunlight T(P, q) albedo/pi E_sun(q) alone, and T(P, q) per channel
  // (at the wavelengths kSurfaceChannelNm).
  Rgb aerial_perspective(double altitude_m, Vec3 view, double distance_m, double albedo,
                         Vec3 sun) const;
  Rgb reflected(double altitude_m, Vec3 view, double distance_m, double albedo, Vec3 sun) const;
  std::array<double, 3> channel_transmittance(double altitude_m, Vec3 view,
                                              double distance_m) const;

 private:
  Rgb to_rgb(const std::array<double, kNishitaXyzCount>& radiance) const;
  Vec3 position(double altitude_m) const;

  NishitaParameters params_;
  NishitaModel model_;  // at altitude 0: its tables and spectra
  atmosphere::Spectral spectral_, channels_;
  std::array<Cmf, kNishitaXyzCount> cmf_{};
};

// Representative wavelengths of the linear sRGB channels R, G, B for the transmittance of §IV
// [nm] (the dominant wavelengths of the sRGB primaries).
inline constexpr std::array<double, 3> kSurfaceChannelNm = {612.0, 549.0, 465.0};

// Colour of a surface point and of the air in front of it (Pietras §IV) for an observer at
// altitude h looking along `view` at the point q = P + distance view (an upward-facing Lambertian
// surface of grey albedo): two evaluations of the sky function, at the observer and at the probe
// q looking the same way, plus the reflected sunlight from the atmosphere model directly:
//   I = I_sky(P, view) - T(P, q) I_sky(q, view) + T(P, q) albedo/pi E_sun(q).
// The paper subtracts I_sky(q) without T(P, q); with it the split is exact for single scattering
// (I(P) = I(P -> q) + T(P, q) I(q)), up to T taken per channel at kSurfaceChannelNm. The sky
// function is the network (nn::PietrasNetwork::rgb_at) or, for checks, nishita.
using PietrasSkyFunction = std::function<Rgb(double altitude_m, double cos_view_zenith,
                                             double cos_view_sun, double cos_sun_zenith)>;
// The parts of that sum for one surface point: the sky function's arguments at the observer and
// at the probe, T(P, q) per channel and the reflected sunlight (what gpu/planet.h hands each
// vertex of a planet mesh).
struct PietrasSurfaceTerms {
  double observer_altitude_m = 0, probe_altitude_m = 0;
  double cos_view_sun = 1;  // the same at both points
  double observer_cos_view_zenith = 1, observer_cos_sun_zenith = 1;
  double probe_cos_view_zenith = 1, probe_cos_sun_zenith = 1;
  std::array<double, 3> transmittance{};  // T(P, q) at kSurfaceChannelNm
  Rgb reflected{};                        // T(P, q) albedo/pi E_sun(q)
};
PietrasSurfaceTerms pietras_surface_terms(const NishitaSampler& atmosphere, double altitude_m,
                                          Vec3 view, double distance_m, double albedo, Vec3 sun);
Rgb pietras_surface(const PietrasSkyFunction& sky, const NishitaSampler& atmosphere,
                    double altitude_m, Vec3 view, double distance_m, double albedo, Vec3 sun);
// The sky function of a network.
PietrasSkyFunction sky_function(const nn::PietrasNetwork& net);

// Which inputs to draw: the training distribution (above), or the validation sets: altitude
// uniform 0-20 km, upward views (cos alpha0 uniform in [0, 1]) and cos theta0 uniform over
// day (theta0 <= 85 deg), twilight (85-96 deg) or night (96-180 deg).
enum class PietrasSampling { training, day, twilight, night };

struct PietrasSamples {
  std::vector<nn::PietrasInput> inputs;
  std::vector<double> altitude_m;
  std::vector<Rgb> rgb;  // nishita's
  std::size_t size() const { return inputs.size(); }
};
// n samples from Rng(seed), evaluated in parallel (deterministic).
PietrasSamples sample_nishita(const NishitaSampler& source, PietrasSampling sampling, std::size_t n,
                              std::uint64_t seed);

// The nishita parameters a network was trained with, from its provenance (InvalidArgument for an
// unknown name).
NishitaParameters nishita_parameters_of(const nn::PietrasNetwork& net);

// Training defaults per sub-network (docs/PIETRAS.md): full-batch L-BFGS (at 800 000 samples LM's
// J^T J costs seconds per iteration), up to kPietrasIterations or kPietrasTimeLimitS.
inline constexpr nn::Trainer kPietrasTrainer = nn::Trainer::lbfgs;
inline constexpr int kPietrasIterations = 4000;
inline constexpr double kPietrasTimeLimitS = 600.0;
inline nn::TrainOptions pietras_train_options() {
  nn::TrainOptions o;
  o.trainer = kPietrasTrainer;
  o.max_iterations = kPietrasIterations;
  o.time_limit_s = kPietrasTimeLimitS;
  return o;
}

struct PietrasTraining {
  nn::PietrasKind kind = nn::PietrasKind::pietras;
  NishitaParameters atmosphere;  // sun and observer ignored
  std::size_t samples = 800000;
  // Per sub-network; seed is also the sampling seed.
  nn::TrainOptions options = pietras_train_options();
  // Warm start (nn train --init): every sub-network continues from this network's. It must be of
  // `kind`; its max_value is kept (the targets stay those its weights learnt) and the
  // atmosphere should be its own (nishita_parameters_of). The iterations and seconds recorded
  // in the result's provenance are the totals, the initial network's included.
  const nn::PietrasNetwork* initial = nullptr;
  // progress(sub-network index, entry) after every iteration; return false to stop.
  std::function<bool(int, const nn::TrainLogEntry&)> progress;
};
nn::PietrasNetwork train_pietras(const PietrasTraining& t);

// Errors of a network against nishita on one validation set (metrics.h's nearest-rank
// percentiles): relative luminance error |Y_net - Y| / Y over samples with Y > 0, and the
// chromaticity error = Euclidean distance between the CIE 1931 (x, y) of network and nishita.
struct PietrasErrors {
  std::size_t count = 0, excluded = 0;  // excluded: nishita's Y = 0
  double luminance_median = 0, luminance_p95 = 0, luminance_max = 0;
  double chromaticity_median = 0, chromaticity_p95 = 0;
  // Median of nishita's value in the network's own scale over the same samples: N / max N
  // (N = max(r, g, b)) for pietras, Y / Y_max for log3. For pietras an error dM of M is a relative
  // error dM / (0.9 N / max N) of N (§III), so this is what turns M's error into N's.
  double scaled_median = 0;
};
struct PietrasValidation {
  PietrasErrors day, twilight;
  std::size_t night_count = 0;           // night samples (sun zenith 96-180 deg)
  std::size_t night_reference_dark = 0;  // night samples where nishita is 0
  std::size_t night_nonzero = 0;         // night samples where nishita is 0 and the network is not
  // Of those where nishita is 0: the sub-networks' own decoded output (rgb(), without the shadow
  // test of rgb_at) is not 0. What the shadow test contributes to night_nonzero = 0.
  std::size_t night_ungated_nonzero = 0;
};
PietrasErrors pietras_errors(const nn::PietrasNetwork& net, const PietrasSamples& s);
PietrasValidation validate_pietras(const nn::PietrasNetwork& net, std::size_t samples,
                                   std::uint64_t seed);

}  // namespace skylight
