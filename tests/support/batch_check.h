// Test support (header only, used by the *_test.cpp files): a model's float SIMD batch path
// against its double scalar path on the same (float) directions.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "skylight/models/sky_model.h"

namespace skylight::testing_support {

// Checks |batch - scalar| <= max(rel_tol |scalar|, abs_floor_fraction * largest value of the
// sky) for X, Y and Z of every direction, and that the threaded driver reproduces the batch
// exactly. Returns the worst relative error among values above the floor.
inline double expect_batch_matches_scalar(const SkyModel& m, const std::vector<Vec3>& dirs,
                                          double rel_tol, double abs_floor_fraction) {
  std::vector<float> x, y, z;
  for (const Vec3& v : dirs) {
    x.push_back(static_cast<float>(v.x));
    y.push_back(static_cast<float>(v.y));
    z.push_back(static_cast<float>(v.z));
  }
  const std::size_t n = dirs.size();
  std::vector<float> X(n), Y(n), Z(n);
  m.tristimulus_batch({x, y, z}, {X, Y, Z});
  std::vector<Xyz> ref(n);
  double max_v = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    ref[i] = m.tristimulus({x[i], y[i], z[i]});  // exactly the directions the batch saw
    max_v = std::max({max_v, ref[i].X, ref[i].Y, ref[i].Z});
  }
  const double floor = abs_floor_fraction * max_v;
  double worst = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double got[3] = {X[i], Y[i], Z[i]};
    const double want[3] = {ref[i].X, ref[i].Y, ref[i].Z};
    for (int c = 0; c < 3; ++c) {
      const double err = std::abs(got[c] - want[c]);
      if (err > floor) worst = std::max(worst, err / std::abs(want[c]));
      if (!std::isfinite(got[c]) || err > std::max(floor, rel_tol * std::abs(want[c]))) {
        ADD_FAILURE() << m.name() << ": batch " << got[c] << " vs scalar " << want[c]
                      << " (channel " << c << ") at direction " << x[i] << "," << y[i] << ","
                      << z[i];
        return worst;
      }
    }
  }
  std::vector<float> X2(n), Y2(n), Z2(n);
  tristimulus_parallel(m, {x, y, z}, {X2, Y2, Z2});
  EXPECT_EQ(X2, X);
  EXPECT_EQ(Y2, Y);
  EXPECT_EQ(Z2, Z);
  return worst;
}

}  // namespace skylight::testing_support
