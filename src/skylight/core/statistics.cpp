#include "skylight/core/statistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "skylight/core/error.h"

namespace skylight {

double kth_smallest(std::vector<double>& v, std::size_t k) {
  SKYLIGHT_CHECK(k < v.size(), "order statistic beyond the values");
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

double median(std::vector<double> v) {
  SKYLIGHT_CHECK(!v.empty(), "median of an empty set");
  const std::size_t n = v.size();
  const double upper = kth_smallest(v, n / 2);
  if (n % 2) return upper;
  // After nth_element the lower middle value is the largest of the first n / 2.
  const double lower = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n / 2));
  return 0.5 * (lower + upper);
}

double nearest_rank_percentile(std::vector<double>& v, double q) {
  SKYLIGHT_CHECK(!v.empty(), "percentile of an empty set");
  const double rank = std::ceil(std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size()));
  return kth_smallest(v, std::max<std::size_t>(1, static_cast<std::size_t>(rank)) - 1);
}

double mean(std::span<const double> v) {
  SKYLIGHT_CHECK(!v.empty(), "mean of an empty set");
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double sample_standard_deviation(std::span<const double> v) {
  SKYLIGHT_CHECK(v.size() >= 2, "a sample standard deviation needs two values");
  const double m = mean(v);
  double q = 0.0;
  for (double x : v) q += (x - m) * (x - m);
  return std::sqrt(q / static_cast<double>(v.size() - 1));
}

}  // namespace skylight
