#include "skylight/nn/sky_network.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "skylight/core/error.h"
#include "skylight/nn/random.h"
#include "skylight/nn/train.h"

namespace skylight::nn {
namespace {

// SIMD batch (float, state and rotation folded into layer 1) vs the double scalar path, relative
// to the largest channel value of the sky: float rounding of the inputs (~6e-8), of the folded
// weights and of ~100 operations, amplified by cancellation in the sums. Measured max 4e-7 for
// these random networks and 6.5e-6 for the trained 6-12-3 networks (LM leaves weights up to 3e3),
// against model errors of ~1e-2.
constexpr double kSkyBatchRelativeTolerance = 1e-5;
// Rotation invariance (eq. 10) is exact up to double round-off.
constexpr double kRotationTolerance = 1e-12;

SkyNetwork random_sky(const InputSpec& inputs, std::vector<int> hidden, OutputEncoding enc,
                      Activation act, std::uint64_t seed) {
  SkyNetwork s;
  s.inputs = inputs;
  s.encoding = enc;
  s.target_scale = 683.0;
  const Activation out = enc == OutputEncoding::satilmis ? act : Activation::identity;
  Rng rng(seed);
  s.net =
      initial_network(MlpLayout::make(static_cast<int>(inputs.size()), hidden, 3, act, out), rng);
  return s;
}

struct Directions {
  std::vector<float> x, y, z;
};
Directions directions(std::size_t n, std::uint64_t seed) {
  Directions d;
  Rng rng(seed);
  for (std::size_t i = 0; i < n; ++i) {
    // Mostly above the horizon, some below; unit vectors in float.
    const Vec3 v =
        direction_from_angles(std::acos(rng.uniform(-0.3, 1.0)), rng.uniform(0, 2 * kPi));
    d.x.push_back(static_cast<float>(v.x));
    d.y.push_back(static_cast<float>(v.y));
    d.z.push_back(static_cast<float>(v.z));
  }
  return d;
}

void expect_batch_matches(const SkyNetwork& sky, bool allow_unrolled) {
  const std::size_t n = 333;  // odd: exercises the padded tail
  const Directions dirs = directions(n, 4);
  for (double azimuth : {kPi, 0.3, 4.0}) {
    SkyState st;
    st.turbidity = 2.5;
    st.sun_zenith = 0.9;
    st.sun_azimuth = azimuth;
    const SkyNetworkBatch batch(sky, st, allow_unrolled);
    std::vector<float> r(n), g(n), b(n);
    batch.rgb(dirs.x.data(), dirs.y.data(), dirs.z.data(), r.data(), g.data(), b.data(), n);
    double scale = 0.0;
    std::vector<Rgb> ref(n);
    for (std::size_t i = 0; i < n; ++i) {
      ref[i] = sky.rgb(st, {dirs.x[i], dirs.y[i], dirs.z[i]});
      scale = std::max({scale, ref[i].r, ref[i].g, ref[i].b});
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (dirs.z[i] < 0.0f) {
        EXPECT_EQ(r[i], 0.0f);
        continue;
      }
      EXPECT_NEAR(r[i], ref[i].r, kSkyBatchRelativeTolerance * scale) << i;
      EXPECT_NEAR(g[i], ref[i].g, kSkyBatchRelativeTolerance * scale) << i;
      EXPECT_NEAR(b[i], ref[i].b, kSkyBatchRelativeTolerance * scale) << i;
    }
  }
}

TEST(SkyNetworkBatch, PaperNetworkMatchesScalar) {
  // 6-12-3 satilmis, L_s folded into a square: the unrolled kernel and the generic one.
  const SkyNetwork sky =
      random_sky(satilmis_inputs(), {12}, OutputEncoding::satilmis, Activation::satilmis, 1);
  expect_batch_matches(sky, true);
  expect_batch_matches(sky, false);
}

TEST(SkyNetworkBatch, OtherLayoutsMatchScalar) {
  const InputSpec extra = parse_inputs(
      "sqrt_turbidity,cos_sun_zenith,view_x,view_y,view_z,chord,log_chord,sqrt_view_z");
  // log encoding, two hidden layers: the generic kernel.
  expect_batch_matches(random_sky(extra, {10, 6}, OutputEncoding::log, Activation::tanh, 2), true);
  // log encoding, one satilmis layer of 24 with 5 direction inputs: unrolled.
  expect_batch_matches(random_sky(extra, {24}, OutputEncoding::log, Activation::satilmis, 3), true);
  // Symmetric inputs (no v_x: the rotated v_y is one kernel input), 3 and 7 kernel inputs.
  expect_batch_matches(random_sky(parse_inputs("sqrt_turbidity,sun_zenith,view_y,view_z,chord"),
                                  {16}, OutputEncoding::log, Activation::satilmis, 7),
                       true);
  const SkyNetwork sym = random_sky(
      parse_inputs("sun_elevation_cbrt,turbidity,view_y,view_z,chord,log_chord,sqrt_view_z"), {12},
      OutputEncoding::log, Activation::satilmis, 8);
  expect_batch_matches(sym, true);
  expect_batch_matches(sym, false);
  // root4 / root8 encodings (scale folded into the last layer), aureole input.
  const InputSpec aureole = parse_inputs("sqrt_turbidity,sun_zenith,view_y,view_z,chord,aureole");
  expect_batch_matches(random_sky(aureole, {8}, OutputEncoding::root4, Activation::satilmis, 9),
                       true);
  expect_batch_matches(random_sky(aureole, {12}, OutputEncoding::root8, Activation::satilmis, 10),
                       true);
  // satilmis encoding with a sigmoid output: the 0.5 (1/y - 1) output path.
  SkyNetwork s =
      random_sky(satilmis_inputs(), {7}, OutputEncoding::satilmis, Activation::sigmoid, 4);
  expect_batch_matches(s, true);
}

// max_radiance bounds every path's decoding: set at the median of a random network's radiance, it
// clamps about half of the views, and the batch still equals the scalar path; the file keeps it.
TEST(SkyNetwork, MaxRadianceBoundsTheDecodedRadiance) {
  for (const auto& [enc, act] : {std::pair{OutputEncoding::satilmis, Activation::satilmis},
                                 {OutputEncoding::satilmis, Activation::sigmoid},
                                 {OutputEncoding::log, Activation::satilmis},
                                 {OutputEncoding::root4, Activation::satilmis}}) {
    SkyNetwork sky = random_sky(satilmis_inputs(), {12}, enc, act, 5);
    SkyState st;
    st.turbidity = 3.0;
    st.sun_zenith = 0.7;
    const Directions dirs = directions(200, 6);
    std::vector<double> g;
    for (std::size_t i = 0; i < dirs.x.size(); ++i)
      if (dirs.z[i] >= 0.0f) g.push_back(sky.rgb(st, {dirs.x[i], dirs.y[i], dirs.z[i]}).g);
    std::nth_element(g.begin(), g.begin() + g.size() / 2, g.end());
    const double bound = g[g.size() / 2];
    sky.max_radiance = bound / sky.target_scale;
    int clamped = 0;
    for (std::size_t i = 0; i < dirs.x.size(); ++i) {
      const Rgb c = sky.rgb(st, {dirs.x[i], dirs.y[i], dirs.z[i]});
      EXPECT_LE(std::max({c.r, c.g, c.b}), bound * (1 + 1e-12)) << i;
      if (c.g == bound) ++clamped;
    }
    EXPECT_GT(clamped, 50);
    expect_batch_matches(sky, true);
    expect_batch_matches(sky, false);
    const SkyNetwork back = sky_network_from_json(to_json(sky), "test");
    ASSERT_TRUE(back.max_radiance.has_value());
    EXPECT_EQ(*back.max_radiance, *sky.max_radiance);
  }
}

TEST(SkyNetwork, RotationInvariance) {
  const SkyNetwork sky =
      random_sky(satilmis_inputs(), {12}, OutputEncoding::satilmis, Activation::satilmis, 5);
  SkyState a, b;
  a.sun_zenith = b.sun_zenith = 0.8;
  a.sun_azimuth = kPi;
  b.sun_azimuth = 2.2;
  const Vec3 va = direction_from_angles(0.5, 1.0);
  const Vec3 vb =
      direction_from_angles(0.5, 1.0 + (2.2 - kPi));  // the same view relative to the sun
  const Rgb ca = sky.rgb(a, va), cb = sky.rgb(b, vb);
  EXPECT_NEAR(ca.r, cb.r, kRotationTolerance * ca.r);
  EXPECT_NEAR(ca.b, cb.b, kRotationTolerance * ca.b);
  EXPECT_EQ(sky.rgb(a, {0.0, 0.6, -0.8}).g, 0.0);  // below the horizon
}

TEST(SkyNetwork, JsonRoundTripsExactly) {
  SkyNetwork sky =
      random_sky(parse_inputs("sqrt_turbidity,sun_zenith,view_x,view_y,view_z,log_chord"), {9},
                 OutputEncoding::log, Activation::satilmis, 6);
  sky.provenance.source = "hosek";
  sky.provenance.turbidities = {1.0, 2.5};
  sky.provenance.seed = 18446744073709551615ull;  // the largest seed survives
  sky.provenance.training_mse = 1.0 / 3.0;
  sky.provenance.validation_rmse = 0.1 + 0.2;
  const std::string text = to_json(sky);
  const SkyNetwork back = sky_network_from_json(text, "mem.json");
  EXPECT_EQ(back.inputs, sky.inputs);
  EXPECT_EQ(back.encoding, sky.encoding);
  EXPECT_EQ(back.target_scale, sky.target_scale);
  EXPECT_EQ(back.net.layout().describe(), sky.net.layout().describe());
  ASSERT_EQ(back.net.parameters().size(), sky.net.parameters().size());
  for (std::size_t p = 0; p < sky.net.parameters().size(); ++p) {
    EXPECT_EQ(back.net.parameters()[p], sky.net.parameters()[p]);
  }
  EXPECT_EQ(back.provenance.seed, sky.provenance.seed);
  EXPECT_EQ(back.provenance.training_mse, sky.provenance.training_mse);
  EXPECT_EQ(back.provenance.validation_rmse, sky.provenance.validation_rmse);
  EXPECT_FALSE(back.provenance.validation_relative_p95.has_value());
  EXPECT_EQ(to_json(back), text);
}

// Every corruption is an InvalidArgument naming the file and the field.
TEST(SkyNetwork, CorruptWeightsFilesNameTheField) {
  const SkyNetwork sky =
      random_sky(satilmis_inputs(), {12}, OutputEncoding::satilmis, Activation::satilmis, 3);
  const std::string good = to_json(sky);
  auto expect_error = [](const std::string& text, const std::string& needle) {
    try {
      sky_network_from_json(text, "w.json");
      ADD_FAILURE() << "accepted: " << needle;
    } catch (const InvalidArgument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("w.json"), std::string::npos) << what;
      EXPECT_NE(what.find(needle), std::string::npos) << what;
    }
  };
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const auto pos = s.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    return s.replace(pos, from.size(), to);
  };
  expect_error(good.substr(0, good.size() / 2), "not valid JSON");
  expect_error("[1, 2]", "not a JSON object");
  expect_error(replaced("\"version\": 1", "\"version\": 2"), "'version'");
  expect_error(replaced("\"format\": \"skylight-nn-sky\"", "\"format\": \"x\""), "'format'");
  expect_error(replaced("\"output_encoding\": \"satilmis\"", "\"output_encoding\": \"cube\""),
               "'output_encoding'");
  expect_error(replaced("\"target_scale\": 683.0", "\"target_scale\": -1"), "'target_scale'");
  expect_error(replaced("\"target_scale\": 683.0", "\"target_scale\": \"683\""), "'target_scale'");
  expect_error(replaced("\"sqrt_turbidity\"", "\"sqrt_t\""), "'inputs'");
  expect_error(replaced("\"sqrt_turbidity\",", ""), "'inputs'");
  expect_error(replaced("\"parameters\": [", "\"parameters\": [1.0,"), "'parameters'");
  expect_error(replaced("\"parameters\": [", "\"parameters\": [\"x\","), "'parameters'");
  expect_error(replaced("\"source\"", "\"origin\""), "'provenance.source'");
  expect_error(replaced("\"provenance\"", "\"p\""), "'provenance'");
  expect_error(replaced("\"satilmis\"", "\"swish\""), "'architecture.activations'");
  // Found by the nn_weights_json fuzz target (docs/TESTING.md): a number beyond the double range
  // escaped as nlohmann::json::out_of_range instead of our error.
  expect_error(replaced("\"parameters\": [", "\"parameters\": [1e400,"), "not valid JSON");
  // A weight beyond single precision (1e39: the GLSL export wrote `inf * x[0]`) or absurdly large
  // (1e30: nn validate reported an error of 4e58 %) is refused, naming the element.
  const auto first_weight = [&](const std::string& value) {
    std::string s = good;
    const std::size_t start = s.find("\"parameters\": [") + std::string("\"parameters\": [").size();
    return s.replace(start, s.find(',', start) - start, value);
  };
  expect_error(first_weight("1e39"), "field 'parameters' holds 1e+39 (element 1), beyond +-1e+06");
  expect_error(first_weight("-1e30"), "(element 1), beyond +-1e+06");
  EXPECT_NO_THROW(sky_network_from_json(first_weight("-999999.5"), "w.json"));
}

}  // namespace
}  // namespace skylight::nn
