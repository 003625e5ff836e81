#include "skylight/fit/neural_training.h"

#include <gtest/gtest.h>

#include "skylight/core/error.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/sky_model.h"

namespace skylight::fit {
namespace {

// A 6-8-3 network trained for 60 Levenberg-Marquardt iterations on a reduced Preetham set (T =
// 2..6, 6 suns, 5 x 8 views: 1200 examples) reaches a validation RMSE of 0.00441 (measured) on
// the reduced validation set (T = 2.5..5.5, 6 suns at random azimuths, 5 x 8 views); the bound
// leaves room for other SIMD targets' round-off (the J^T J sums, train.h) without letting a
// failed fit (RMSE > 0.01) pass.
constexpr double kTinyPreethamRmseBound = 0.006;
// The embedded 6-12-3 network (0.00175, 1.7 % on the paper's full validation set, docs/NN.md;
// 0.00160, 1.7 % on the reduced one here) against the targets for the paper protocol: half of
// Table 1's RMSE (0.0145 / 2) and a relative radiance error median of at most 3 %.
constexpr double kEmbeddedPreethamRmseBound = 0.0073;
constexpr double kEmbeddedPreethamRelMedianBound = 0.03;

NeuralTraining tiny_preetham() {
  NeuralTraining t;
  t.source = "preetham";
  t.hidden = {8};
  t.sun_count = 6;
  t.view_zeniths = 5;
  t.view_azimuths = 8;
  t.options.max_iterations = 60;
  t.options.time_limit_s = 1e6;  // iterations stop it: deterministic
  t.options.seed = 3;
  t.check = false;  // far from the product's bound: the tests below check the trainer
  return t;
}

TEST(NeuralTraining, PaperProtocolSizes) {
  auto count = [](const nn::SamplingSpec& s) {
    return s.turbidities.size() * s.sun_count * s.view_zeniths * s.view_azimuths;
  };
  EXPECT_EQ(count(neural_training_spec("preetham")), 20000u);          // Table 1 "example size"
  EXPECT_EQ(count(neural_training_spec("hosek")), 40000u);             // Table 1
  EXPECT_EQ(count(neural_validation_spec("preetham")), 4u * 7 * 200);  // T = 2.5..5.5, 7 suns
  EXPECT_EQ(count(neural_validation_spec("hosek")), 9u * 7 * 200);     // T = 1.5..9.5
  EXPECT_DOUBLE_EQ(default_target_scale("preetham"), 1000.0);
  EXPECT_DOUBLE_EQ(default_target_scale("hosek"), 683.0);
  // A model without turbidity: one state per sun, the turbidity input 0.
  EXPECT_EQ(neural_training_spec("cie").turbidities, std::vector<double>{0.0});
  EXPECT_THROW(neural_training_spec("nosuch"), InvalidArgument);
}

TEST(NeuralTraining, SourceIsTheModelsRgb) {
  const nn::SkySource src = sky_model_source("hosek");
  nn::SkyState s;
  s.turbidity = 4.0;
  s.sun_zenith = 0.8;
  s.sun_azimuth = 2.0;
  s.ground_albedo = 0.5;
  SkyParameters p;
  p.sun = {0.8, 2.0};
  p.values.set("turbidity", 4.0).set("albedo", 0.5);
  const auto m = make_sky_model("hosek", p);
  const Vec3 v = direction_from_angles(0.5, 1.0);
  EXPECT_EQ(src(s)(v).g, m->rgb(v).g);
}

TEST(NeuralTraining, TinyNetworkLearnsPreethamDeterministically) {
  const NeuralTrainingResult a = train_neural_sky(tiny_preetham());
  ASSERT_TRUE(a.validation.has_value());
  EXPECT_EQ(a.train.iterations, 60);
  EXPECT_LT(a.validation->errors.rmse, kTinyPreethamRmseBound);
  EXPECT_EQ(a.network.provenance.validation_rmse, a.validation->errors.rmse);
  EXPECT_EQ(a.network.target_scale, 1000.0);
  // The decoding's bound: twice the brightest training radiance.
  nn::SamplingSpec spec = neural_training_spec("preetham");
  spec.sun_count = 6;
  spec.view_zeniths = 5;
  spec.view_azimuths = 8;
  const nn::Dataset data =
      nn::build_dataset(spec, tiny_preetham().inputs, sky_model_source("preetham"));
  ASSERT_TRUE(a.network.max_radiance.has_value());
  EXPECT_EQ(*a.network.max_radiance, nn::kMaxRadianceMargin * data.max_radiance());
  const NeuralTrainingResult b = train_neural_sky(tiny_preetham());
  ASSERT_EQ(a.network.net.parameters().size(), b.network.net.parameters().size());
  for (std::size_t i = 0; i < a.network.net.parameters().size(); ++i)
    ASSERT_EQ(a.network.net.parameters()[i], b.network.net.parameters()[i]) << i;
}

// A source without turbidity (cie): trained with the input 0, and the model feeds it 0.
TEST(NeuralTraining, SourceWithoutTurbidityGetsInputZero) {
  NeuralTraining t = tiny_preetham();
  t.source = "cie";
  t.options.max_iterations = 5;
  t.validate = false;
  const NeuralTrainingResult r = train_neural_sky(t);
  EXPECT_EQ(r.network.provenance.turbidities, std::vector<double>{0.0});
  NeuralSkyParameters p;
  p.sun = {0.6, 2.0};
  p.turbidity = 5.0;
  const NeuralSkyModel m(p, r.network);
  EXPECT_EQ(m.state().turbidity, 0.0);
  EXPECT_TRUE(m.domain().valid());
  const Vec3 v = direction_from_angles(0.4, 1.0);
  EXPECT_EQ(m.rgb(v).g, r.network.rgb(m.state(), v).g);
}

// The held-out check fails a network outside its bound (FitFailed, saying what was measured) and
// returns nothing; within it the result carries the check.
TEST(NeuralTraining, HeldOutCheckFailsANetworkOutsideItsBound) {
  NeuralTraining t = tiny_preetham();
  t.check = true;
  t.max_relative_p95 = 1e-4;  // no 8-neuron network of 60 iterations gets there
  try {
    (void)train_neural_sky(t);
    ADD_FAILURE() << "a network outside its bound was returned";
  } catch (const FitFailed& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("held-out check"), std::string::npos) << what;
    EXPECT_NE(what.find("(bound 0.01 %) over T 2-6 (41 values)"), std::string::npos) << what;
    EXPECT_NE(what.find("--max-error"), std::string::npos) << what;
  }
  t.max_relative_p95 = 1e6;
  const NeuralTrainingResult r = train_neural_sky(t);
  ASSERT_TRUE(r.check.has_value());
  EXPECT_TRUE(r.check->passed());
  EXPECT_EQ(r.check->turbidities, 41u);  // T 2-6 every 0.1: between the training T included
  EXPECT_GT(r.check->errors.relative_p95, r.check->errors.relative_median);
}

// The starts are judged on held-out skies: with four starts the kept network is at least as good
// on the selection set (the encoded outputs' mean squared error, what the starts are compared
// by) as the first start (seed s, stream 0) trained alone for as long.
TEST(NeuralTraining, StartsKeepTheBestOnHeldOutSkies) {
  NeuralTraining one = tiny_preetham();
  one.options.max_iterations = 30;
  NeuralTraining four = one;
  four.starts = 4;
  four.start_iterations = 30;  // the kept start is returned as it is
  const NeuralTrainingResult a = train_neural_sky(one), b = train_neural_sky(four);
  const nn::Dataset sel = nn::build_dataset(neural_selection_spec("preetham"), one.inputs,
                                            sky_model_source("preetham"));
  const std::vector<double> targets = sel.targets(one.encoding);
  const nn::Examples ex{sel.inputs, targets, sel.size()};
  EXPECT_LE(nn::mean_squared_error(b.network.net, ex), nn::mean_squared_error(a.network.net, ex));
  EXPECT_EQ(b.train.iterations, 30);
}

// The committed network passes the held-out check of its source (docs/NN.md, "Every seed").
TEST(NeuralTraining, EmbeddedNetworkPassesTheHeldOutCheck) {
  const HeldOutCheck c = check_neural_sky(embedded_sky_network());
  EXPECT_DOUBLE_EQ(c.max_relative_p95, 0.12);  // Preetham's NeuralPolicy
  EXPECT_TRUE(c.passed()) << c.summary();
  EXPECT_LT(c.errors.relative_median, kEmbeddedPreethamRelMedianBound) << c.summary();
}

TEST(NeuralTraining, EmbeddedNetworkMeetsHalfOfTable1) {
  const NeuralValidation v = validate_neural_sky(embedded_sky_network(), 3, 5, 10);
  EXPECT_LT(v.errors.rmse, kEmbeddedPreethamRmseBound);
  EXPECT_LT(v.errors.relative_median, kEmbeddedPreethamRelMedianBound);
  EXPECT_EQ(v.irradiance.reference.size(), 4u * 3);  // 4 turbidities x 3 suns
}

}  // namespace
}  // namespace skylight::fit
