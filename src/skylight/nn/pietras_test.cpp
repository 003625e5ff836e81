#include "skylight/nn/pietras.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/nn/random.h"
#include "skylight/nn/train.h"

namespace skylight::nn {
namespace {

// Float batch (MlpBatch) vs the double path, relative to the largest channel over the views:
// float rounding of inputs, weights and ~50 operations per sub-network (mlp_test.cpp's bound for
// one network is 1e-5); pietras decoding multiplies two outputs.
constexpr double kPietrasBatchRelativeTolerance = 1e-5;
// Closed forms evaluated in double.
constexpr double kPietrasExact = 1e-12;

PietrasNetwork random_network(PietrasKind kind, std::uint64_t seed) {
  PietrasNetwork net;
  net.kind = kind;
  net.max_value = 1234.5;
  Rng rng(seed);
  for (const MlpLayout& l : pietras_layouts(kind)) net.subnets.push_back(initial_network(l, rng));
  net.provenance.colour = "test";
  net.provenance.source_parameters = {{"ground-radius", 6360e3}, {"mie-g", 0.8}};
  net.provenance.iterations = {1, 2, 3};
  return net;
}

TEST(Pietras, LayoutsHaveThePapersWeightCounts) {
  // §III: four 4-8-4-1 sub-networks, 324 weights; log3: three 4-16-16-1, 1,107 weights.
  EXPECT_EQ(random_network(PietrasKind::pietras, 1).parameter_count(), 324u);
  EXPECT_EQ(random_network(PietrasKind::log3, 1).parameter_count(), 1107u);
}

TEST(Pietras, DecodesThePapersNormalisation) {
  // M = 0.9 N / max N + 0.05 -> N = max N (M - 0.05) / 0.9; R, G, B = I / N.
  const double o[4] = {0.5, 1.0, 0.25, 0.05 + 0.9 * 0.4};
  const Rgb c = decode_pietras(PietrasKind::pietras, 100.0, o);
  EXPECT_NEAR(c.r, 20.0, kPietrasExact);
  EXPECT_NEAR(c.g, 40.0, kPietrasExact);
  EXPECT_NEAR(c.b, 10.0, kPietrasExact);
  // Night: M below the 0.05 offset decodes to exactly 0.
  const double night[4] = {0.5, 1.0, 0.25, 0.049};
  const Rgb d = decode_pietras(PietrasKind::pietras, 100.0, night);
  EXPECT_EQ(d.r, 0.0);
  EXPECT_EQ(d.g, 0.0);
  EXPECT_EQ(d.b, 0.0);
}

TEST(Pietras, DecodesLog3) {
  // l = ln(Y / Y_max + eps), r = R/S, b = B/S: the luminance of the decoded rgb is Y.
  const double y = 0.25, r = 0.2, b = 0.5;
  const double o[3] = {std::log(y + kLog3Epsilon), r, b};
  const Rgb c = decode_pietras(PietrasKind::log3, 1000.0, o);
  EXPECT_NEAR(0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b, 250.0, 1e-9);
  EXPECT_NEAR(c.r / (c.r + c.g + c.b), r, kPietrasExact);
  EXPECT_NEAR(c.b / (c.r + c.g + c.b), b, kPietrasExact);
  const double night[3] = {std::log(kLog3Epsilon) - 0.5, r, b};
  EXPECT_EQ(decode_pietras(PietrasKind::log3, 1000.0, night).g, 0.0);
}

TEST(Pietras, NightBoundIsGeometric) {
  // theta = pi/2 + 2 acos(R0 / (R0 + 60 km)) + acos(R0 / (R0 + h)).
  const PietrasNetwork net = random_network(PietrasKind::pietras, 2);
  const double t0 = kPi / 2 + 2.0 * std::acos(6360.0 / 6420.0);
  EXPECT_NEAR(net.night_cos_sun_zenith(0.0), std::cos(t0), kPietrasExact);
  EXPECT_NEAR(net.night_cos_sun_zenith(10e3), std::cos(t0 + std::acos(6360.0 / 6370.0)),
              kPietrasExact);
  const Rgb c = net.rgb_at(0.0, 1.0, 0.0, std::cos(t0) - 1e-9);
  EXPECT_EQ(c.r + c.g + c.b, 0.0);
}

TEST(Pietras, JsonRoundTripIsExact) {
  for (PietrasKind k : {PietrasKind::pietras, PietrasKind::log3}) {
    const PietrasNetwork a = random_network(k, 3);
    const PietrasNetwork b = pietras_from_json(to_json(a), "test.json");
    ASSERT_EQ(b.subnets.size(), a.subnets.size());
    EXPECT_EQ(b.kind, k);
    EXPECT_EQ(b.max_value, a.max_value);
    for (std::size_t i = 0; i < a.subnets.size(); ++i) {
      const auto pa = a.subnets[i].parameters(), pb = b.subnets[i].parameters();
      EXPECT_TRUE(std::equal(pa.begin(), pa.end(), pb.begin(), pb.end()));
    }
    EXPECT_EQ(b.provenance.source_parameters, a.provenance.source_parameters);
    EXPECT_EQ(b.provenance.iterations, a.provenance.iterations);
    EXPECT_TRUE(is_pietras_json(to_json(a)));
  }
  EXPECT_FALSE(is_pietras_json("{\"format\": \"skylight-nn-sky\"}"));
  EXPECT_FALSE(is_pietras_json("not json"));
}

TEST(Pietras, LoaderRejectsWrongLayouts) {
  std::string s = to_json(random_network(PietrasKind::pietras, 4));
  const auto at = s.find("\"network\": \"pietras\"");
  ASSERT_NE(at, std::string::npos);
  s.replace(at, 20, "\"network\": \"log3\"");  // 4 sub-networks of 4-8-4-1 are not log3's
  try {
    pietras_from_json(s, "w.json");
    FAIL() << "accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("w.json: field 'subnets'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(pietras_from_json("{\"format\": \"skylight-nn-pietras\"}", "w"), InvalidArgument);
}

TEST(Pietras, BatchMatchesScalar) {
  // Also with weights x 40, as trained networks have: pre-activations far beyond +-64, where
  // 2^{2x} leaves the range of the float exponential.
  for (auto [k, gain] : {std::pair{PietrasKind::pietras, 1.0}, std::pair{PietrasKind::log3, 1.0},
                         std::pair{PietrasKind::pietras, 40.0}}) {
    PietrasNetwork net = random_network(k, 5);
    for (Mlp& m : net.subnets)
      for (double& w : m.parameters()) w *= gain;
    const double h = 3000.0, cs = std::cos(deg_to_rad(50.0));
    const PietrasBatch batch(net, h, cs);
    constexpr std::size_t n = 37;
    std::vector<float> ca(n), cb(n), r(n), g(n), b(n);
    Rng rng(9);
    for (std::size_t i = 0; i < n; ++i) {
      ca[i] = static_cast<float>(rng.uniform(-1.0, 1.0));
      cb[i] = static_cast<float>(rng.uniform(-1.0, 1.0));
    }
    batch.rgb(ca.data(), cb.data(), r.data(), g.data(), b.data(), n);
    std::vector<Rgb> ref(n);
    double top = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      ref[i] = net.rgb_at(h, ca[i], cb[i], cs);
      top = std::max({top, ref[i].r, ref[i].g, ref[i].b});
    }
    ASSERT_GT(top, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_NEAR(r[i], ref[i].r, kPietrasBatchRelativeTolerance * top);
      EXPECT_NEAR(g[i], ref[i].g, kPietrasBatchRelativeTolerance * top);
      EXPECT_NEAR(b[i], ref[i].b, kPietrasBatchRelativeTolerance * top);
    }
  }
}

}  // namespace
}  // namespace skylight::nn
