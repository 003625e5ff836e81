#include "skylight/sh/detail/evaluate_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace skylight::sh::detail {
namespace {

// Float sums of <= 300 products of values in [-1, 1]: the rounding error is below
// terms * 2^-24 * sum |p x| ~ 2e-5 of the sum of magnitudes; 1e-5 of it is ample for pairwise
// vector sums (every indexing error is of order 1).
constexpr double kFloatSumTolerance = 1e-5;

TEST(ShEvaluateKernel, DotRowsMatchesDoubleSumsForEveryRowAndTailCount) {
  // Row counts around the 4-row blocks and term counts around every vector width's tail.
  for (std::size_t rows : {1u, 3u, 4u, 5u, 84u}) {
    for (std::size_t terms : {1u, 7u, 8u, 17u, 63u, 234u, 300u}) {
      std::vector<float> p(rows * terms), x(terms), out(rows, -1.0f);
      for (std::size_t k = 0; k < p.size(); ++k) p[k] = static_cast<float>(std::sin(0.7 * k + 0.1));
      for (std::size_t t = 0; t < terms; ++t) x[t] = static_cast<float>(std::cos(1.3 * t));
      dot_rows(p.data(), x.data(), rows, terms, out.data());
      for (std::size_t r = 0; r < rows; ++r) {
        double sum = 0.0, magnitude = 0.0;
        for (std::size_t t = 0; t < terms; ++t) {
          sum += static_cast<double>(p[r * terms + t]) * x[t];
          magnitude += std::abs(static_cast<double>(p[r * terms + t]) * x[t]);
        }
        EXPECT_NEAR(out[r], sum, kFloatSumTolerance * magnitude)
            << "rows " << rows << " terms " << terms << " row " << r;
      }
    }
  }
}

}  // namespace
}  // namespace skylight::sh::detail
