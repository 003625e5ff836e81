#include "skylight/fit/measured_training.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skylight/core/error.h"

namespace skylight::fit {
namespace {

// A short training (the tests' budget): the paper's 6-12-3 network, LM, one start.
NeuralTraining short_training(int iterations) {
  NeuralTraining t;
  t.options.max_iterations = iterations;
  t.options.seed = 1;
  t.starts = 1;
  return t;
}

// On the shipped captures: every capture left out once, its turbidity input the fitted Preetham
// turbidity, its error measured as `skylight measured` measures a model; reproducible to the last
// digit; refused (FitFailed) under a bound it cannot meet.
TEST(MeasuredTraining, LeavesEachCaptureOutAndIsReproducible) {
  const auto captures = io::shipped_kider_subset();
  const MeasuredSettings settings;
  const MeasuredTrainingResult r = train_on_measured(captures, short_training(40), settings);
  ASSERT_EQ(r.folds.size(), captures.size());
  MeasuredSettings preetham;
  preetham.model = "preetham";
  const auto direct = compare_to_measured(captures, preetham);
  for (std::size_t k = 0; k < captures.size(); ++k) {
    EXPECT_EQ(r.folds[k].capture, captures[k].name);
    EXPECT_EQ(r.turbidities[k], direct[k].fit.parameters[0].value);
    EXPECT_NEAR(r.folds[k].turbidity_model_rms_shape, direct[k].luminance_rms_shape, 1e-12);
    EXPECT_TRUE(std::isfinite(r.folds[k].luminance_rms_shape));
  }
  // Measured on the shipped subset (docs/MEASURED.md): a short training already generalises
  // between captures within the bound.
  EXPECT_LE(r.median_shape, kMeasuredMaxShapeRms);
  EXPECT_EQ(r.examples, 15u * 80u - 4u);  // the samples more than 10 deg from each sun
  const MeasuredTrainingResult again = train_on_measured(captures, short_training(40), settings);
  EXPECT_EQ(again.median_shape, r.median_shape);
  EXPECT_EQ(again.errors.rmse, r.errors.rmse);
  NeuralTraining strict = short_training(5);
  strict.max_relative_p95 = 1e-4;
  EXPECT_THROW(train_on_measured(captures, strict, settings), FitFailed);
  EXPECT_THROW(train_on_measured({captures[0], captures[1]}, short_training(5), settings),
               InvalidArgument);
}

}  // namespace
}  // namespace skylight::fit
