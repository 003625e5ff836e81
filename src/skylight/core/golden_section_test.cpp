#include "skylight/core/golden_section.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace skylight {
namespace {

// The bracket shrinks by 1 / phi per step: its final width is below the tolerance.
constexpr double kTolerance = 1e-9;

TEST(GoldenSection, FindsTheMinimumOfAParabola) {
  int calls = 0;
  const auto f = [&](double x) {
    ++calls;
    return (x - 0.3) * (x - 0.3);  // minimum 0: no offset hides the differences near 0.3
  };
  const auto gs = golden_section(f, -1.0, 2.0, kTolerance, std::less<>());
  EXPECT_LE(gs.b - gs.a, kTolerance);
  EXPECT_NEAR(0.5 * (gs.a + gs.b), 0.3, kTolerance);
  EXPECT_LT(gs.a, gs.x1);
  EXPECT_LT(gs.x2, gs.b);
  // Two evaluations to start, then one per step: ceil(ln(3 / tol) / ln(phi)) steps.
  const int steps = static_cast<int>(std::ceil(std::log(3.0 / kTolerance) /
                                               std::log(0.5 * (1.0 + std::sqrt(5.0)))));
  EXPECT_NEAR(calls, steps + 2, 1);
}

TEST(GoldenSection, KeepsTheValuesOfItsPoints) {
  struct Value {
    double x, cost;
  };
  const auto f = [](double x) { return Value{x, std::abs(x - 1.5)}; };
  const auto gs = golden_section(f, 0.0, 4.0, 1e-6,
                                 [](const Value& u, const Value& v) { return u.cost <= v.cost; });
  EXPECT_EQ(gs.f1.x, gs.x1);
  EXPECT_EQ(gs.f2.x, gs.x2);
  EXPECT_NEAR(gs.x1, 1.5, 1e-6);
}

}  // namespace
}  // namespace skylight
