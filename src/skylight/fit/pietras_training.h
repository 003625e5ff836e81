// Training and validating the per-vertex networks of nn/pietras.h on the `nishita` model (Pietras
// §III; the `pietras` model and the surface colour of §IV are models/pietras.h). docs/PIETRAS.md.
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
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/models/nishita.h"
#include "skylight/models/pietras.h"
#include "skylight/nn/pietras.h"
#include "skylight/nn/train.h"

namespace skylight::fit {

// Which inputs to draw: the training distribution (above), or the validation sets: altitude
// uniform 0-20 km, upward views (cos alpha0 uniform in [0, 1]) and cos theta0 uniform over
// day (theta0 <= 85 deg), twilight (85-96 deg) or night (96-180 deg).
// sky_dome: the training distribution of --region sky-dome: upward views, altitude uniform 0-20 km,
// cos theta0 uniform over sun zenith 0-100 deg (day and twilight as seen from the ground).
enum class PietrasSampling { training, day, twilight, night, sky_dome };

// What a Pietras network is trained on (`nn train --region`): the full input range (any view,
// altitude to the top, any sun: the planet from orbit) or the sky dome seen from the ground
// (PietrasSampling::sky_dome), where the validation sets lie.
enum class PietrasRegion { full, sky_dome };

// Everything that differs between the regions, declared once (pietras_training.cpp).
struct PietrasRegionPolicy {
  std::string_view name;      // --region's value; provenance.region
  PietrasSampling sampling;   // the training samples
  std::string_view geometry;  // provenance.geometry: how the training inputs were drawn
  // The default bound of the held-out check (PietrasCheck) on the p95 of the day luminance error,
  // above the p95 of every seed measured with the defaults (docs/PIETRAS.md, "Held-out check").
  double max_luminance_p95;
};
const PietrasRegionPolicy& pietras_region_policy(PietrasRegion region);

struct PietrasSamples {
  std::vector<nn::PietrasInput> inputs;
  std::vector<double> altitude_m;
  std::vector<Rgb> rgb;  // nishita's
  std::size_t size() const { return inputs.size(); }
};
// n samples from Rng(seed), evaluated in parallel (deterministic).
PietrasSamples sample_nishita(const NishitaSampler& source, PietrasSampling sampling, std::size_t n,
                              std::uint64_t seed);

// Training defaults per sub-network (docs/PIETRAS.md): full-batch L-BFGS (at 800 000 samples LM's
// J^T J costs seconds per iteration), up to kPietrasIterations or kPietrasTimeLimitS of CPU time
// on average (4 sub-networks: <= 280 s; the committed networks trained for longer,
// docs/PIETRAS.md): sub-network k gets time_limit_s * pietras_time_shares(kind)[k] (the shares
// average 1).
inline constexpr nn::Trainer kPietrasTrainer = nn::Trainer::lbfgs;
inline constexpr int kPietrasIterations = 4000;
inline constexpr double kPietrasTimeLimitS = 70.0;
inline nn::TrainOptions pietras_train_options() {
  nn::TrainOptions o;
  o.trainer = kPietrasTrainer;
  o.max_iterations = kPietrasIterations;
  o.time_limit_s = kPietrasTimeLimitS;
  return o;
}

std::vector<double> pietras_time_shares(nn::PietrasKind kind);

struct PietrasTraining {
  nn::PietrasKind kind = nn::PietrasKind::pietras;
  NishitaParameters atmosphere;  // sun and observer ignored
  std::size_t samples = 800000;
  PietrasRegion region = PietrasRegion::full;
  // Per sub-network; seed is also the sampling seed.
  nn::TrainOptions options = pietras_train_options();
  // Warm start (nn train --init): every sub-network continues from this network's. It must be of
  // `kind`; its max_value is kept (the targets stay those its weights learnt) and the
  // atmosphere should be its own (nishita_parameters_of). The iterations and seconds recorded
  // in the result's provenance are the totals, the initial network's included.
  const nn::PietrasNetwork* initial = nullptr;
  // progress(sub-network index, entry) after every iteration; return false to stop.
  std::function<bool(int, const nn::TrainLogEntry&)> progress;
  // The held-out check (PietrasCheck); false skips it (tests of the trainer alone).
  bool check = true;
  // Its bound on the p95 of the luminance error; absent: the region's (PietrasRegionPolicy).
  std::optional<double> max_luminance_p95;
};

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

// The held-out check of a trained network: its errors on kPietrasCheckSamples day samples
// (PietrasSampling::day: upward views, 0-20 km, sun zenith <= 85 deg, where a user looks at the
// sky; both regions cover them) drawn from Rng(seed + kPietrasCheckSeedOffset), a stream the
// training never draws from. Beyond the bound on the p95 of the luminance error, train_pietras
// throws FitFailed with summary() and nn train writes nothing.
inline constexpr std::size_t kPietrasCheckSamples = 20000;
inline constexpr std::uint64_t kPietrasCheckSeedOffset = 0x5eedc4ec;
struct PietrasCheck {
  PietrasErrors errors;
  std::uint64_t seed = 0;
  double max_luminance_p95 = 0.0;
  bool passed() const { return errors.luminance_p95 <= max_luminance_p95; }
  // "held-out check (20000 day samples, seed ...): luminance error median .. %, p95 .. % (bound
  // .. %), chromaticity ..."
  std::string summary() const;
};
PietrasCheck check_pietras(const nn::PietrasNetwork& net, std::uint64_t training_seed,
                           double max_luminance_p95);

struct PietrasTrainingResult {
  nn::PietrasNetwork network;
  std::optional<PietrasCheck> check;  // absent with PietrasTraining::check = false
};
// Trains every sub-network, then (with t.check) the held-out check: FitFailed beyond its bound.
PietrasTrainingResult train_pietras(const PietrasTraining& t);

}  // namespace skylight::fit
