// Golden-section search for the minimum of a unimodal function of one variable (Kiefer 1953):
// the one routine behind the report's best turbidity (analysis/comparison.cpp) and the luminance
// fits' profile search (fit/luminance_fit.cpp).
#pragma once

#include <cmath>
#include <type_traits>
#include <utility>

namespace skylight {

// The final bracket [a, b] and its two interior points with their values.
template <class V>
struct GoldenSection {
  double a = 0.0, b = 0.0;
  double x1 = 0.0, x2 = 0.0;  // a < x1 < x2 < b
  V f1{}, f2{};
};

// Narrows [a, b] until it is at most `tolerance` wide. f(x) returns a value V; better(u, v) is
// true when u is to be kept over v (the bracket then moves towards x1): `<` keeps the right
// point on ties, `<=` the left one. f is called once per step after the first two.
template <class F, class Better>
auto golden_section(F&& f, double a, double b, double tolerance, Better&& better) {
  using V = std::decay_t<std::invoke_result_t<F&, double>>;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  V f1 = f(x1), f2 = f(x2);
  while (b - a > tolerance) {
    if (better(f1, f2)) {
      b = x2;
      x2 = x1;
      f2 = std::move(f1);
      x1 = b - g * (b - a);
      f1 = f(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = std::move(f2);
      x2 = a + g * (b - a);
      f2 = f(x2);
    }
  }
  return GoldenSection<V>{a, b, x1, x2, std::move(f1), std::move(f2)};
}

}  // namespace skylight
