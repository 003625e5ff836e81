#include "skylight/fit/pietras_training.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/io/file.h"

namespace skylight::fit {
namespace {

// The committed networks of data/nn (data/nn/PROVENANCE.md, docs/PIETRAS.md) on reduced
// validation sets: kCommittedSamples per set with the seed of `nn validate` (so `nn validate
// --weights data/nn/FILE --samples 2000` prints the measured values quoted below). Each bound is
// the measured value plus ~10 % (another compiler's rounding of nishita and of the network moves
// them by far less); an untrained network is off by ~100 %.
constexpr std::size_t kCommittedSamples = 2000;
constexpr std::uint64_t kCommittedSeed = 1000003;
// Upper bounds on nn validate's day luminance median and p95, day chromaticity median and
// twilight luminance median.
struct CommittedBounds {
  double day_median, day_p95, day_chromaticity, twilight_median;
};
// pietras.json, measured: day median 8.77 %, p95 30.6 %, chromaticity median 0.0012; twilight
// median 40.8 %.
constexpr CommittedBounds kPietrasBounds{0.097, 0.34, 0.0014, 0.45};
// log3.json, measured: day median 1.34 %, p95 4.14 %, chromaticity median 0.00055; twilight
// median 2.99 %. Night: no dark sample lit (the shadow test).
constexpr CommittedBounds kLog3Bounds{0.0147, 0.0455, 0.00061, 0.0329};

// Validates data/nn/<name> and checks it against the bounds; night must be exactly dark.
void expect_committed_within(const std::string& name, nn::PietrasKind kind,
                             const CommittedBounds& b) {
  const std::string path = std::string(SKYLIGHT_TEST_DATA_DIR "/nn/") + name;
  const nn::PietrasNetwork net = nn::pietras_from_json(io::read_text_file(path), path);
  EXPECT_EQ(net.kind, kind);
  const PietrasValidation v = validate_pietras(net, kCommittedSamples, kCommittedSeed);
  EXPECT_LT(v.day.luminance_median, b.day_median);
  EXPECT_LT(v.day.luminance_p95, b.day_p95);
  EXPECT_LT(v.day.chromaticity_median, b.day_chromaticity);
  EXPECT_LT(v.twilight.luminance_median, b.twilight_median);
  EXPECT_GT(v.night_reference_dark, 0u);
  EXPECT_EQ(v.night_nonzero, 0u);  // night exactly dark
}

// The reduced training of the tests: 20 000 samples, at most 60 LM iterations per sub-network.
PietrasTraining small_training(nn::PietrasKind kind) {
  PietrasTraining t;
  t.kind = kind;
  t.samples = 20000;
  t.options.max_iterations = 60;
  t.options.time_limit_s = 30.0;
  t.check = false;  // the trainer alone; the check: PietrasTraining.TheHeldOutCheckBoundsTheFit
  return t;
}

const nn::PietrasNetwork& small_pietras() {
  static const nn::PietrasNetwork net =
      train_pietras(small_training(nn::PietrasKind::pietras)).network;
  return net;
}

// The held-out check (kPietrasCheckSamples day samples, a seed the training does not draw from):
// the committed log3 network passes the full range's bound with the day errors nn validate
// measures for it; a network after 3 iterations fails a 5 % bound with FitFailed naming the check,
// and with a bound it meets the result carries the check.
TEST(PietrasTraining, TheHeldOutCheckBoundsTheFit) {
  const std::string path = SKYLIGHT_TEST_DATA_DIR "/nn/log3.json";
  const nn::PietrasNetwork log3 = nn::pietras_from_json(io::read_text_file(path), path);
  const double full_bound = pietras_region_policy(PietrasRegion::full).max_luminance_p95;
  const PietrasCheck c = check_pietras(log3, 1, full_bound);
  EXPECT_TRUE(c.passed());
  EXPECT_EQ(c.seed, 1 + kPietrasCheckSeedOffset);
  EXPECT_EQ(c.errors.count, kPietrasCheckSamples);
  EXPECT_EQ(c.errors.excluded, 0u);  // day samples are lit
  EXPECT_LT(c.errors.luminance_median, kLog3Bounds.day_median);
  EXPECT_LT(c.errors.luminance_p95, kLog3Bounds.day_p95);

  PietrasTraining t = small_training(nn::PietrasKind::pietras);
  t.options.max_iterations = 3;
  t.check = true;
  t.max_luminance_p95 = 0.05;
  try {
    (void)train_pietras(t);
    ADD_FAILURE() << "a network after 3 iterations met a 5 % bound";
  } catch (const FitFailed& e) {
    EXPECT_NE(std::string(e.what()).find("fails its held-out check (20000 day samples"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("(bound 5 %)"), std::string::npos) << e.what();
  }
  t.max_luminance_p95 = 1e4;
  const PietrasTrainingResult r = train_pietras(t);
  ASSERT_TRUE(r.check.has_value());
  EXPECT_TRUE(r.check->passed());
  EXPECT_GT(r.check->errors.luminance_p95, 0.05);
  EXPECT_EQ(r.network.provenance.region, "full");
}

// The time budget's shares per sub-network average 1 (the budget is time_limit_s times their
// number); the paper network's M, which carries the luminance, gets the most.
TEST(PietrasTraining, TimeSharesSplitTheBudget) {
  for (const nn::PietrasKind kind : {nn::PietrasKind::pietras, nn::PietrasKind::log3}) {
    const std::vector<double> shares = pietras_time_shares(kind);
    ASSERT_EQ(shares.size(), nn::pietras_layouts(kind).size());
    double sum = 0.0;
    for (double x : shares) {
      EXPECT_GT(x, 0.0);
      sum += x;
    }
    EXPECT_NEAR(sum / static_cast<double>(shares.size()), 1.0, 1e-12);
  }
  const std::vector<double> paper = pietras_time_shares(nn::PietrasKind::pietras);
  EXPECT_EQ(*std::max_element(paper.begin(), paper.end()), paper[3]);
}

TEST(PietrasTraining, TrainingSamplesAreConsistentGeometry) {
  const NishitaSampler sampler(NishitaParameters{});
  const PietrasSamples s = sample_nishita(sampler, PietrasSampling::training, 2000, 7);
  for (const nn::PietrasInput& x : s.inputs) {
    // cos beta = cos a cos t + sin a sin t cos phi lies within cos(a -+ t).
    const double a = std::acos(x.cos_view_zenith), t = std::acos(x.cos_sun_zenith);
    EXPECT_LE(x.cos_view_sun, std::cos(a - t) + 1e-12);
    EXPECT_GE(x.cos_view_sun, std::cos(a + t) - 1e-12);
    EXPECT_GE(x.density, std::exp(-60e3 / 8000.0) - 1e-15);
    EXPECT_LE(x.density, 1.0);
  }
}

// --region sky-dome: skies seen from the ground: upward views, altitudes 0-20 km, sun zenith
// 0-100 deg (day and twilight), every sample consistent geometry.
TEST(PietrasTraining, SkyDomeSamplesAreSkiesSeenFromTheGround) {
  const NishitaSampler sampler(NishitaParameters{});
  const PietrasSamples s = sample_nishita(sampler, PietrasSampling::sky_dome, 2000, 7);
  double lowest_sun = 1.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const nn::PietrasInput& x = s.inputs[i];
    EXPECT_GE(x.cos_view_zenith, 0.0);
    EXPECT_GE(s.altitude_m[i], 0.0);
    EXPECT_LE(s.altitude_m[i], 20e3);
    EXPECT_GE(x.cos_sun_zenith, std::cos(deg_to_rad(100.0)) - 1e-12);
    lowest_sun = std::min(lowest_sun, x.cos_sun_zenith);
  }
  EXPECT_LT(lowest_sun, std::cos(deg_to_rad(99.0)));  // the range is covered to its end
}

// The targets' scale: on the full range the brightest training sample's N; on the sky dome their
// 99.9th percentile (nearest rank from below), 0.1 % of the samples above it.
TEST(PietrasTraining, TheScaleIsTheSamplesMaximumOrTheirPercentileOnTheDome) {
  const NishitaSampler sampler(NishitaParameters{});
  PietrasTraining t = small_training(nn::PietrasKind::pietras);
  const PietrasSamples full =
      sample_nishita(sampler, PietrasSampling::training, t.samples, t.options.seed);
  double brightest = 0.0;
  for (const Rgb& c : full.rgb) brightest = std::max({brightest, c.r, c.g, c.b});
  EXPECT_EQ(small_pietras().max_value, brightest);
  t.region = PietrasRegion::sky_dome;
  t.options.max_iterations = 1;
  const nn::PietrasNetwork net = train_pietras(t).network;
  const PietrasSamples s =
      sample_nishita(sampler, PietrasSampling::sky_dome, t.samples, t.options.seed);
  std::size_t lit = 0, above = 0;
  for (const Rgb& c : s.rgb) {
    const double n = std::max({c.r, c.g, c.b});
    lit += n > 0.0;
    above += n > net.max_value;
  }
  const auto k = static_cast<std::size_t>(0.999 * static_cast<double>(lit - 1));
  EXPECT_EQ(above, lit - 1 - k);
}

// PietrasNetwork::lit is exactly where nishita is not 0: nishita cuts its view rays at the shadow
// boundaries, so a ray is dark there iff every piece is in shadow. Over every geometry the
// training draws (altitudes to the top, views into the ground) and the night set.
TEST(PietrasTraining, LitIsWhereNishitaIsNotDark) {
  const NishitaSampler sampler(NishitaParameters{});
  const nn::PietrasNetwork net = nn::initial_pietras_network(nn::PietrasKind::pietras, 1);
  ASSERT_EQ(net.ground_radius_m, sampler.parameters().ground_radius_m);
  ASSERT_EQ(net.top_altitude_m,
            sampler.parameters().top_radius() - sampler.parameters().ground_radius_m);
  for (PietrasSampling set : {PietrasSampling::training, PietrasSampling::night}) {
    const PietrasSamples s = sample_nishita(sampler, set, 20000, 11);
    std::size_t dark = 0, wrong = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const nn::PietrasInput& x = s.inputs[i];
      const bool reference = s.rgb[i].r > 0 || s.rgb[i].g > 0 || s.rgb[i].b > 0;
      dark += !reference;
      wrong += net.lit(s.altitude_m[i], x.cos_view_zenith, x.cos_view_sun, x.cos_sun_zenith) !=
               reference;
    }
    EXPECT_GT(dark, s.size() / 3);  // both sets are dark in large part
    EXPECT_EQ(wrong, 0u);
  }
  // An observer above the top looking away from the planet sees no atmosphere.
  EXPECT_FALSE(net.lit(100e3, 0.5, 0.9, 0.9));
  EXPECT_TRUE(net.lit(100e3, -0.99, 0.1, 0.9));
}

TEST(PietrasTraining, SmallPaperNetworkBeatsStatedErrors) {
  // 20 000 samples and 60 LM iterations per sub-network (the full-size run: docs/PIETRAS.md).
  const nn::PietrasNetwork& net = small_pietras();
  EXPECT_EQ(net.parameter_count(), 324u);
  const PietrasValidation v = validate_pietras(net, 4000, 11);
  // Measured 0.45 (the full-size run: docs/PIETRAS.md); an untrained network is off by ~100 %.
  EXPECT_LT(v.day.luminance_median, 0.6) << v.day.luminance_median;
  EXPECT_LT(v.day.chromaticity_median, 0.02) << v.day.chromaticity_median;
  // Beyond the geometric night bound the network returns exactly 0 (and so does nishita).
  EXPECT_GT(v.night_reference_dark, 0u);
  const double h = 5000.0;
  const double c = net.night_cos_sun_zenith(h) - 1e-6;
  const Rgb night = net.rgb_at(h, 0.5, 0.0, c);
  EXPECT_EQ(night.r + night.g + night.b, 0.0);
}

TEST(PietrasTraining, CommittedPaperNetworkErrors) {
  expect_committed_within("pietras.json", nn::PietrasKind::pietras, kPietrasBounds);
}

TEST(PietrasTraining, CommittedLog3NetworkErrors) {
  expect_committed_within("log3.json", nn::PietrasKind::log3, kLog3Bounds);
}

// reference_scaled_median: nishita's value in the network's own scale, N / max N (pietras) or
// Y / Y_max (log3), median over the samples with Y > 0 (nearest rank of three values here).
TEST(PietrasTraining, ScaledMedianIsTheReferenceInTheNetworksScale) {
  PietrasSamples s;
  for (const Rgb& c : {Rgb{1, 2, 3}, Rgb{4, 1, 1}, Rgb{0.5, 0.5, 2}, Rgb{0, 0, 0}}) {
    s.inputs.push_back({0.5, 0.5, 0.5, 1.0});
    s.altitude_m.push_back(0.0);
    s.rgb.push_back(c);
  }
  nn::PietrasNetwork net = nn::initial_pietras_network(nn::PietrasKind::pietras, 3);
  net.max_value = 8.0;
  PietrasErrors e = pietras_errors(net, s);
  EXPECT_EQ(e.excluded, 1u);
  EXPECT_DOUBLE_EQ(e.scaled_median, 3.0 / 8.0);  // N = 3, 4, 2
  net = nn::initial_pietras_network(nn::PietrasKind::log3, 3);
  net.max_value = 8.0;
  e = pietras_errors(net, s);
  // sRGB luminance Y = 0.2126 r + 0.7152 g + 0.0722 b: 1.8596, 1.6378, 0.6083; the middle one.
  EXPECT_DOUBLE_EQ(e.scaled_median, (0.2126 * 4.0 + 0.7152 + 0.0722) / 8.0);
}

}  // namespace
}  // namespace skylight::fit
