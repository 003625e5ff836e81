#include "skylight/models/neural_sky.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

#include "skylight/core/error.h"
#include "support/batch_check.h"
#include "support/scratch_dir.h"

namespace skylight {
namespace {

// The batch path in float (state and rotation folded into layer 1) against the double scalar
// path: the bound of nn/sky_network_test.cpp (kSkyBatchRelativeTolerance, 1e-5) plus the float
// RGB -> XYZ matrix (a few ulp).
constexpr double kNeuralBatchRelativeTolerance = 2e-5;
// Values this far below the sky's largest are compared absolutely.
constexpr double kNeuralBatchAbsoluteFloor = 1e-6;

std::unique_ptr<SkyModel> nn_model(double turbidity, double sun_zenith_deg, double azimuth_deg,
                                   const std::string& weights = {}) {
  SkyParameters p;
  p.sun = {deg_to_rad(sun_zenith_deg), deg_to_rad(azimuth_deg)};
  p.values.set("turbidity", turbidity);
  if (!weights.empty()) p.values.set("weights", weights.c_str());
  return make_sky_model("nn", p);
}

TEST(NeuralSky, IsTheNetworksOwnForward) {
  const auto m = nn_model(3.5, 40.0, 130.0);
  const auto& nm = dynamic_cast<const NeuralSkyModel&>(*m);
  const nn::SkyNetwork& net = embedded_sky_network();
  EXPECT_EQ(net.provenance.source, "preetham");
  EXPECT_EQ(net.net.layout().parameter_count(), 123u);  // the paper's 6-12-3 network
  for (const Vec3 v :
       {Vec3{0, 0, 1}, direction_from_angles(1.2, 0.3), direction_from_angles(0.7, 2.27)}) {
    const Rgb want = net.rgb(nm.state(), v);
    const Rgb got = m->rgb(v);
    EXPECT_EQ(got.r, want.r);
    EXPECT_EQ(got.g, want.g);
    EXPECT_EQ(got.b, want.b);
    EXPECT_EQ(m->tristimulus(v).Y, linear_srgb_to_xyz(want).Y);
  }
  EXPECT_EQ(m->tristimulus({0.0, 0.6, -0.8}).Y, 0.0);  // below the horizon
}

TEST(NeuralSky, BatchMatchesScalar) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  std::vector<Vec3> dirs;
  for (int i = 0; i < 3000; ++i) dirs.push_back(normalize({g(rng), g(rng), g(rng)}));
  dirs.push_back({0, 0, 1});
  dirs.push_back({1, 0, 0});
  for (double T : {2.0, 4.5, 6.0})
    for (double zs : {0.0, 35.0, 70.0, 89.0}) {
      SCOPED_TRACE(testing::Message() << "T " << T << " zs " << zs);
      testing_support::expect_batch_matches_scalar(
          *nn_model(T, zs, 250.0), dirs, kNeuralBatchRelativeTolerance, kNeuralBatchAbsoluteFloor);
    }
}

TEST(NeuralSky, DomainAndSunBelowTheHorizon) {
  EXPECT_TRUE(nn_model(4.0, 30.0, 180.0)->domain().valid());
  EXPECT_EQ(nn_model(9.0, 30.0, 180.0)->domain().worst(), Validity::extrapolated);
  const auto below = nn_model(4.0, 100.0, 180.0);
  EXPECT_EQ(below->domain().worst(), Validity::undefined);
  EXPECT_EQ(below->tristimulus({0, 0, 1}).Y, 0.0);
}

TEST(NeuralSky, WeightsFilesAreCheckedWhenLoaded) {
  testing_support::ScratchDir dir;
  const std::string missing = (dir.path() / "missing.json").string();
  EXPECT_THROW(nn_model(3.0, 30.0, 180.0, missing), IoError);
  const std::string corrupt = (dir.path() / "corrupt.json").string();
  std::ofstream(corrupt) << R"({"format": "skylight-nn-sky", "version": 1})";
  try {
    nn_model(3.0, 30.0, 180.0, corrupt);
    ADD_FAILURE() << "a corrupt file was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find(corrupt), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'architecture'"), std::string::npos) << e.what();
  }
  // A written copy of the embedded network gives the same sky.
  const std::string copy = (dir.path() / "copy.json").string();
  std::ofstream(copy) << nn::to_json(embedded_sky_network());
  const Vec3 v = direction_from_angles(0.9, 1.0);
  EXPECT_EQ(nn_model(3.0, 30.0, 180.0, copy)->tristimulus(v).Y,
            nn_model(3.0, 30.0, 180.0)->tristimulus(v).Y);
  const nn::SkyNetwork loaded = load_sky_network_file(copy);
  const auto a = loaded.net.parameters(), b = embedded_sky_network().net.parameters();
  EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
  // load_sky_network_file and the model read sky networks only: a Pietras file is refused saying
  // what it is (the model pietras reads it).
  const std::string pietras = std::string(SKYLIGHT_TEST_DATA_DIR) + "/nn/log3.json";
  try {
    (void)load_sky_network_file(pietras);
    ADD_FAILURE() << "a Pietras file was read as a sky network";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find(pietras + ": a Pietras network (skylight-nn-pietras), "
                                                   "not a sky network (skylight-nn-sky)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(nn_model(3.0, 30.0, 180.0, pietras), InvalidArgument);
}

// The report judges the embedded network against its source over its training range
// (ReportPolicy beside the registry entry): both must be the weights file's own.
TEST(NeuralSky, ReportPolicyMatchesTheEmbeddedNetwork) {
  const auto model = make_sky_model(NeuralSkyModel::kName, {});
  const auto& provenance = dynamic_cast<const NeuralSkyModel&>(*model).network().provenance;
  const ReportPolicy& policy = find_model(NeuralSkyModel::kName)->report;
  EXPECT_EQ(policy.source, provenance.source);
  ASSERT_TRUE(policy.axis_range.has_value());
  ASSERT_FALSE(provenance.turbidities.empty());
  EXPECT_EQ((*policy.axis_range)[0],
            *std::min_element(provenance.turbidities.begin(), provenance.turbidities.end()));
  EXPECT_EQ((*policy.axis_range)[1],
            *std::max_element(provenance.turbidities.begin(), provenance.turbidities.end()));
}

}  // namespace
}  // namespace skylight
