#include "skylight/sh/basis.h"

#include <array>
#include <cmath>
#include <string>

#include "skylight/core/error.h"
#include "skylight/core/math.h"

namespace skylight::sh {
namespace {

long double factorial(int n) {
  long double f = 1.0L;
  for (int k = 2; k <= n; ++k) f *= k;
  return f;
}

// K_lm for l < kMaxBands, m = 0 .. l, as the product (l - m)! / (l + m)! = 1 / prod_{k=l-m+1}^{l+m}
// k (no overflow of the factorials themselves).
struct NormalisationTable {
  std::array<double, kMaxBands * kMaxBands> k{};
  NormalisationTable() {
    for (int l = 0; l < kMaxBands; ++l) {
      for (int m = 0; m <= l; ++m) {
        long double ratio = 1.0L;
        for (int j = l - m + 1; j <= l + m; ++j) ratio /= j;
        k[static_cast<std::size_t>(index(l, m))] =
            static_cast<double>(std::sqrt((2.0L * l + 1.0L) / (4.0L * kPi) * ratio));
      }
    }
  }
};

const NormalisationTable& table() {
  static const NormalisationTable t;
  return t;
}

}  // namespace

DegreeOrder degree_order(int i) {
  SKYLIGHT_CHECK(i >= 0, "SH index must be non-negative");
  int l = static_cast<int>(std::sqrt(static_cast<double>(i)));
  while (l * l > i) --l;
  while ((l + 1) * (l + 1) <= i) ++l;
  return {l, i - l * (l + 1)};
}

void check_bands(int bands) {
  if (bands < 1 || bands > kMaxBands) {
    throw InvalidArgument("bands = " + std::to_string(bands) + " is outside the valid range [1, " +
                          std::to_string(kMaxBands) + "]");
  }
}

double normalisation(int l, int m) {
  SKYLIGHT_CHECK(l >= 0 && l < kMaxBands && m >= 0 && m <= l, "normalisation: bad (l, m)");
  return table().k[static_cast<std::size_t>(index(l, m))];
}

void evaluate_basis(int bands, Vec3 d, std::span<double> out) {
  check_bands(bands);
  SKYLIGHT_CHECK(out.size() >= static_cast<std::size_t>(coefficient_count(bands)),
                 "evaluate_basis: output too small");
  const auto& k = table().k;
  const double z = d.z;
  const double sqrt2 = std::sqrt(2.0);
  // a + i b = (y + i x)^m = sin^m theta (cos m phi + i sin m phi) in the frame of core/frame.h.
  double a = 1.0, b = 0.0;
  double pmm = 1.0;  // Q_m^m = (2m - 1)!!, P_l^m = sin^m theta Q_l^m(z)
  for (int m = 0; m < bands; ++m) {
    if (m > 0) {
      const double a1 = a * d.y - b * d.x;
      b = a * d.x + b * d.y;
      a = a1;
      pmm *= 2.0 * m - 1.0;
    }
    double q_lm2 = 0.0, q_lm1 = pmm;
    for (int l = m; l < bands; ++l) {
      double q;
      if (l == m) {
        q = pmm;
      } else if (l == m + 1) {
        q = z * (2.0 * m + 1.0) * pmm;
      } else {
        // (l - m) P_l^m = (2l - 1) z P_{l-1}^m - (l + m - 1) P_{l-2}^m
        q = ((2.0 * l - 1.0) * z * q_lm1 - (l + m - 1.0) * q_lm2) / (l - m);
      }
      if (l > m) {
        q_lm2 = q_lm1;
        q_lm1 = q;
      }
      const double kq = k[static_cast<std::size_t>(index(l, m))] * q;
      if (m == 0) {
        out[static_cast<std::size_t>(index(l, 0))] = kq;
      } else {
        out[static_cast<std::size_t>(index(l, m))] = sqrt2 * kq * a;
        out[static_cast<std::size_t>(index(l, -m))] = sqrt2 * kq * b;
      }
    }
  }
}

std::vector<double> evaluate_basis(int bands, Vec3 d) {
  check_bands(bands);
  std::vector<double> out(static_cast<std::size_t>(coefficient_count(bands)));
  evaluate_basis(bands, d, out);
  return out;
}

double basis_reference(int l, int m, double theta, double phi) {
  SKYLIGHT_CHECK(l >= 0 && std::abs(m) <= l, "basis_reference: bad (l, m)");
  const int am = std::abs(m);
  const long double x = std::cos(static_cast<long double>(theta));
  long double sum = 0.0L;
  for (int kk = 0; 2 * kk <= l - am; ++kk) {
    const long double term = factorial(2 * l - 2 * kk) /
                             (factorial(kk) * factorial(l - kk) * factorial(l - 2 * kk - am)) *
                             std::pow(x, l - 2 * kk - am);
    sum += (kk % 2 == 0) ? term : -term;
  }
  const long double s = std::sin(static_cast<long double>(theta));
  const long double p = sum * std::pow(s, am) / std::pow(2.0L, l);
  const long double kn =
      std::sqrt((2.0L * l + 1.0L) / (4.0L * kPi) * factorial(l - am) / factorial(l + am));
  if (m == 0) return static_cast<double>(kn * p);
  const long double ang = am * static_cast<long double>(phi);
  const long double trig = m > 0 ? std::cos(ang) : std::sin(ang);
  return static_cast<double>(std::sqrt(2.0L) * kn * p * trig);
}

}  // namespace skylight::sh
