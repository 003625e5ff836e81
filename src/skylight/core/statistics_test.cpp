#include "skylight/core/statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace skylight {
namespace {

TEST(Statistics, PercentileIsNearestRank) {
  std::vector<double> v = {5, 1, 4, 2, 3, 6, 8, 7, 10, 9};
  EXPECT_EQ(nearest_rank_percentile(v, 0.5), 5.0);
  EXPECT_EQ(nearest_rank_percentile(v, 0.95), 10.0);
  EXPECT_EQ(nearest_rank_percentile(v, 0.0), 1.0);
  EXPECT_EQ(nearest_rank_percentile(v, 1.0), 10.0);
}

TEST(Statistics, MedianAveragesTheTwoMiddleValuesOfAnEvenCount) {
  EXPECT_EQ(median({5, 1, 4, 2, 3, 6}), 3.5);
  EXPECT_EQ(median({5, 1, 4, 2, 3}), 3.0);
  EXPECT_EQ(median({7}), 7.0);
  std::vector<double> v = {4, 3, 2, 1};
  EXPECT_EQ(kth_smallest(v, 2), 3.0);  // the upper middle value
  EXPECT_EQ(kth_smallest(v, 0), 1.0);
}

TEST(Statistics, SampleStandardDeviationHasNMinusOne) {
  const std::vector<double> v = {2, 4, 4, 4, 5, 5, 7, 9};
  EXPECT_DOUBLE_EQ(mean(v), 5.0);
  // sum of squares 32 over n - 1 = 7
  EXPECT_DOUBLE_EQ(sample_standard_deviation(v), std::sqrt(32.0 / 7.0));
}

}  // namespace
}  // namespace skylight
