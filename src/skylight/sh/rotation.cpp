#include "skylight/sh/rotation.h"

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
