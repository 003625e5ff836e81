// Order statistics, the project's one median and quantile: every median, percentile and sample
// standard deviation in the library, the fits and the CLI goes through these (docs/ARCHITECTURE.md,
// "Shared numerics").
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace skylight {

// The k-th smallest value of v (k = 0: the minimum), v reordered (std::nth_element). v must hold
// more than k values.
double kth_smallest(std::vector<double>& v, std::size_t k);
// The median: the middle value, or the mean of the two middle values for an even count. v must
// not be empty.
double median(std::vector<double> v);
// The nearest-rank percentile q in [0, 1] (clamped): the ceil(q n)-th smallest value (at least
// the first); v reordered, not empty. The p50 of an even count is the lower middle value.
double nearest_rank_percentile(std::vector<double>& v, double q);
// The mean and the sample standard deviation (n - 1 in the denominator); v holds >= 2 values.
double mean(std::span<const double> v);
double sample_standard_deviation(std::span<const double> v);

}  // namespace skylight
