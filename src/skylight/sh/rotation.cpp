#include "skylight/sh/rotation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/sh/basis.h"

namespace skylight::sh {

Coefficients rotate_about_zenith(const Coefficients& c, double phi) {
  check_bands(c.bands);
  Coefficients out = c;
  const double c1 = std::cos(phi), s1 = std::sin(phi);
  double cm = 1.0, sm = 0.0;  // cos(m phi), sin(m phi)
  for (int m = 1; m < c.bands; ++m) {
    const double cn = cm * c1 - sm * s1;
    sm = sm * c1 + cm * s1;
    cm = cn;
    for (int l = m; l < c.bands; ++l) {
      const auto ip = static_cast<std::size_t>(index(l, m));
      const auto in = static_cast<std::size_t>(index(l, -m));
      for (int ch = 0; ch < 3; ++ch) {
        // eq. 4 with m > 0 (sgn = +1) and with -m (sgn = -1)
        out.c[ip][ch] = c.c[ip][ch] * cm - c.c[in][ch] * sm;
        out.c[in][ch] = c.c[in][ch] * cm + c.c[ip][ch] * sm;
      }
    }
  }
  return out;
}

namespace {

// One band's (2l + 1) x (2l + 1) rotation matrix, indices m, n = -l .. l.
struct BandMatrix {
  int l = 0;
  std::vector<double> a;
  double operator()(int m, int n) const {
    return a[static_cast<std::size_t>((m + l) * (2 * l + 1) + (n + l))];
  }
  double& at(int m, int n) { return a[static_cast<std::size_t>((m + l) * (2 * l + 1) + (n + l))]; }
};

// Ivanic & Ruedenberg 1996, Table 2: the helper P of the recurrence, from band 1 (r1) and band
// l - 1 (prev).
double ir_p(int i, int a, int b, int l, const BandMatrix& r1, const BandMatrix& prev) {
  if (b == l) return r1(i, 1) * prev(a, l - 1) - r1(i, -1) * prev(a, -l + 1);
  if (b == -l) return r1(i, 1) * prev(a, -l + 1) + r1(i, -1) * prev(a, l - 1);
  return r1(i, 0) * prev(a, b);
}

// Band l from band 1 and band l - 1: M_mn = u U + v V + w W (Ivanic & Ruedenberg 1996 eq. 8.1,
// Table 1 for u, v, w; Table 2 with the 1998 erratum for U, V, W).
BandMatrix ir_band(int l, const BandMatrix& r1, const BandMatrix& prev) {
  BandMatrix out{l, std::vector<double>(static_cast<std::size_t>((2 * l + 1) * (2 * l + 1)))};
  for (int m = -l; m <= l; ++m) {
    for (int n = -l; n <= l; ++n) {
      const double d = m == 0 ? 1.0 : 0.0;
      const double denom = std::abs(n) == l ? 2.0 * l * (2.0 * l - 1.0) : double(l + n) * (l - n);
      const int am = std::abs(m);
      const double u = std::sqrt(double(l + m) * (l - m) / denom);
      const double v =
          0.5 * std::sqrt((1.0 + d) * (l + am - 1.0) * (l + am) / denom) * (1.0 - 2.0 * d);
      const double w =
          -0.5 * std::sqrt(std::max(0.0, (l - am - 1.0) * (l - am)) / denom) * (1.0 - d);
      double sum = 0.0;
      if (u != 0.0) sum += u * ir_p(0, m, n, l, r1, prev);
      if (v != 0.0) {
        double vv;
        if (m == 0) {
          vv = ir_p(1, 1, n, l, r1, prev) + ir_p(-1, -1, n, l, r1, prev);
        } else if (m > 0) {
          const double d1 = m == 1 ? 1.0 : 0.0;
          vv = ir_p(1, m - 1, n, l, r1, prev) * std::sqrt(1.0 + d1) -
               ir_p(-1, -m + 1, n, l, r1, prev) * (1.0 - d1);
        } else {
          const double d1 = m == -1 ? 1.0 : 0.0;
          vv = ir_p(1, m + 1, n, l, r1, prev) * (1.0 - d1) +
               ir_p(-1, -m - 1, n, l, r1, prev) * std::sqrt(1.0 + d1);
        }
        sum += v * vv;
      }
      if (w != 0.0) {
        const double ww = m > 0 ? ir_p(1, m + 1, n, l, r1, prev) + ir_p(-1, -m - 1, n, l, r1, prev)
                                : ir_p(1, m - 1, n, l, r1, prev) - ir_p(-1, -m + 1, n, l, r1, prev);
        sum += w * ww;
      }
      out.at(m, n) = sum;
    }
  }
  return out;
}

}  // namespace

Coefficients rotate(const Coefficients& c, const RotationMatrix& r) {
  check_bands(c.bands);
  SKYLIGHT_CHECK(c.c.size() == static_cast<std::size_t>(coefficient_count(c.bands)),
                 "rotate: coefficient count != bands^2");
  Coefficients out = c;
  if (c.bands < 2) return out;
  // Band 1: Y_1,-1, Y_10, Y_11 are proportional to x, z, y; a linear function k . d turned by R
  // is (R k) . d, so the matrix is R with rows and columns in the order (x, z, y).
  constexpr int kOrder[3] = {0, 2, 1};
  BandMatrix r1{1, std::vector<double>(9)};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r1.at(i - 1, j - 1) =
          r[static_cast<std::size_t>(kOrder[i])][static_cast<std::size_t>(kOrder[j])];
    }
  }
  BandMatrix band = r1;
  for (int l = 1; l < c.bands; ++l) {
    if (l >= 2) band = ir_band(l, r1, band);
    for (int m = -l; m <= l; ++m) {
      Triple sum{};
      for (int n = -l; n <= l; ++n) {
        const Triple& in = c.c[static_cast<std::size_t>(index(l, n))];
        for (int ch = 0; ch < 3; ++ch) sum[ch] += band(m, n) * in[ch];
      }
      out.c[static_cast<std::size_t>(index(l, m))] = sum;
    }
  }
  return out;
}

double ringing_factor(int l, int bands) {
  check_bands(bands);
  if (l == 0) return 1.0;
  const double x = kPi * l / bands;
  return std::sin(x) / x;
}

Coefficients ringing_filter(const Coefficients& c) {
  check_bands(c.bands);
  Coefficients out = c;
  for (int l = 1; l < c.bands; ++l) {
    const double f = ringing_factor(l, c.bands);
    for (double& v : out.c[static_cast<std::size_t>(index(l, 0))]) v *= f;
  }
  return out;
}

Triple reconstruct(const Coefficients& c, Vec3 d) {
  check_bands(c.bands);
  SKYLIGHT_CHECK(c.c.size() == static_cast<std::size_t>(coefficient_count(c.bands)),
                 "reconstruct: coefficient count != bands^2");
  double y[kMaxBands * kMaxBands];
  evaluate_basis(c.bands, d, std::span<double>(y, c.c.size()));
  Triple out{};
  for (std::size_t i = 0; i < c.c.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) out[ch] += c.c[i][ch] * y[i];
  }
  return out;
}

Triple energy_below(const Coefficients& c, double theta_from) {
  check_bands(c.bands);
  SKYLIGHT_CHECK(theta_from >= kPi / 2 && theta_from <= kPi, "energy_below: theta_from");
  // f_rec^2 has degree 2 (N - 1) in mu and in phi: N Gauss-Legendre nodes integrate degree
  // 2N - 1 exactly, 2N + 1 azimuths resolve frequencies up to 2N.
  const int n = c.bands + 1, n_phi = 2 * c.bands + 2;
  std::vector<double> mu, w;
  gauss_legendre(n, -1.0, std::cos(theta_from), mu, w);
  const double dphi = 2.0 * kPi / n_phi;
  Triple e{};
  for (int r = 0; r < n; ++r) {
    const double theta = std::acos(clamp_cosine(mu[static_cast<std::size_t>(r)]));
    for (int j = 0; j < n_phi; ++j) {
      const Triple v = reconstruct(c, direction_from_angles(theta, (j + 0.5) * dphi));
      for (int ch = 0; ch < 3; ++ch) e[ch] += w[static_cast<std::size_t>(r)] * dphi * v[ch] * v[ch];
    }
  }
  return e;
}

}  // namespace skylight::sh
