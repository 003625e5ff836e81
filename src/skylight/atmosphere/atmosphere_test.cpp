#include "skylight/atmosphere/atmosphere.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "skylight/core/error.h"

namespace skylight::atmosphere {
namespace {

// Simpson with 2 x 256 intervals on the u^2-mapped ray: a smooth Gaussian-like integrand
// sampled at >= 20 points per width; observed < 1e-9.
constexpr double kQuadratureRelTol = 1e-7;
// Table entries: Simpson with 2 x 32 intervals (observed 1e-5 at the ground for H = 1.2 km) and
// float storage (6e-8).
constexpr double kTableVerticalRelTol = 3e-5;
// Bilinear interpolation in (rho, sqrt(mu)) of a 256 x 256 table, horizontal and reflected
// (Pietras eq. 8) rays: observed <= 7.2e-5.
constexpr double kTableHorizontalRelTol = 1e-4;
// Above ~4 scale heights rho < 1/255 lies in the table's first rho cell (linear from rho_top):
// observed <= 1.8e-3 relative there, on optical lengths < 2e-2 of the ground value.
constexpr double kTableThinRelTol = 3e-3;
// Fast path vs brute force: the bound docs/MODELS.md states for `nishita` (0.5 %).
constexpr double kFastVsReferenceRelTol = 5e-3;
// Radiances below this fraction of the largest radiance of the same observer and planet are
// compared absolutely: deep twilight / views of space from orbit, where a relative error of a
// value 1e-4 of the sky's scale is immaterial.
constexpr double kRelativeFloor = 1e-4;
// Additivity of single scattering and multiplicativity of transmittance, both from table
// differences (errors of the individual lookups, <= 1e-3 of the optical length).
constexpr double kAdditivityRelTol = 2e-3;

AtmosphereParameters off_earth() {
  // A 1000 km planet with a 100 km atmosphere and its own components (no Earth constant).
  AtmosphereParameters p;
  p.ground_radius_m = 1000e3;
  p.top_radius_m = 1100e3;
  p.components = {
      {"gas", 12e3, 2e-5, 2e-5, 500.0, 4.0, PhaseKind::rayleigh, 0.0},
      {"dust", 3e3, 6e-6, 9e-6, 500.0, 1.0, PhaseKind::henyey_greenstein, 0.6},
  };
  return p;
}

Vec3 dir_el_az(double el_deg, double az_deg) {
  return direction_from_angles(deg_to_rad(90 - el_deg), deg_to_rad(az_deg));
}

TEST(Atmosphere, VerticalOpticalLengthClosedForm) {
  // Vertical ray from altitude h: t = H (exp(-h/H) - exp(-(r_top - R0)/H))
  //                                 = rho(h) H (1 - exp(-(r_top - r)/H)).
  for (const auto& p : {AtmosphereParameters{}, off_earth()}) {
    Atmosphere atm(p);
    for (std::size_t i = 0; i < p.components.size(); ++i) {
      const double H = p.components[i].scale_height_m;
      for (double h : {0.0, 1e3, 10e3, 40e3}) {
        const double r = p.ground_radius_m + h;
        const double exact = std::exp(-h / H) * H * (1 - std::exp(-(p.top_radius_m - r) / H));
        const double q =
            optical_length_quadrature(r, 1.0, p.components[i], p.ground_radius_m, p.top_radius_m);
        EXPECT_NEAR(q, exact, kQuadratureRelTol * exact) << "H " << H << " h " << h;
        EXPECT_NEAR(atm.optical_length(i, r, 1.0), exact, kTableVerticalRelTol * exact)
            << "H " << H << " h " << h;
      }
    }
  }
}

// Atmospheres whose components have the same profile, radii and table settings share the table
// (atmosphere.cpp's cache); a component with another profile gets its own, and a table rebuilt
// after the cache let it go holds the same numbers.
TEST(Atmosphere, TablesAreSharedByProfileAndRebuiltEqual) {
  AtmosphereParameters a = off_earth();
  AtmosphereParameters b = a;
  b.components[1].g = -0.3;  // phase and coefficients: not the table's
  b.components[1].scattering_per_m *= 2;
  b.components[1].extinction_per_m *= 2;
  AtmosphereParameters c = a;
  c.components[1].scale_height_m = 2.5e3;  // another profile
  const Atmosphere ta(a), tb(b), tc(c);
  EXPECT_EQ(ta.table(0).data(), tb.table(0).data());
  EXPECT_EQ(ta.table(1).data(), tb.table(1).data());
  EXPECT_EQ(ta.table(0).data(), tc.table(0).data());
  EXPECT_NE(ta.table(1).data(), tc.table(1).data());
  EXPECT_NE(ta.table(1)[ta.table(1).size() - 1], tc.table(1)[tc.table(1).size() - 1]);
  const std::vector<float> kept(ta.table(1).begin(), ta.table(1).end());
  // More distinct profiles than the cache keeps: a's tables leave it, ta keeps them alive.
  for (int k = 0; k < 40; ++k) {
    AtmosphereParameters d = a;
    d.components[0].scale_height_m = 5e3 + 100.0 * k;
    d.components[1].scale_height_m = 1e3 + 50.0 * k;
    const Atmosphere td(d, FastSettings{.table_rho = 16, .table_mu = 16});
    EXPECT_GT(td.optical_length(0, d.ground_radius_m, 1.0), 0.0);
  }
  const Atmosphere again(a);
  EXPECT_NE(again.table(1).data(), ta.table(1).data());
  EXPECT_TRUE(std::equal(kept.begin(), kept.end(), again.table(1).begin()));
  EXPECT_TRUE(std::equal(kept.begin(), kept.end(), ta.table(1).begin()));
  const double r = a.ground_radius_m + 2e3;
  EXPECT_EQ(ta.optical_length(1, r, 0.3), again.optical_length(1, r, 0.3));
}

TEST(Atmosphere, HorizontalAndReflectedOpticalLength) {
  // Against a high-accuracy quadrature (2 x 20000 intervals); rays below the horizontal use the
  // table's reflection rule L[rho, -c] = 2 L[rho_x, 0] - L[rho, c].
  for (const auto& p : {AtmosphereParameters{}, off_earth()}) {
    Atmosphere atm(p);
    const double R0 = p.ground_radius_m, Rt = p.top_radius_m;
    for (std::size_t i = 0; i < p.components.size(); ++i) {
      const double H = p.components[i].scale_height_m;
      for (double h : {0.0, 2e3, 20e3}) {
        const double r = R0 + h;
        for (double mu : {0.0, 0.01, -0.001, -0.02}) {
          if (mu < 0 && r * std::sqrt(1 - mu * mu) < R0) continue;  // would hit the ground
          const double exact = optical_length_quadrature(r, mu, p.components[i], R0, Rt, 20000);
          EXPECT_NEAR(optical_length_quadrature(r, mu, p.components[i], R0, Rt), exact,
                      kQuadratureRelTol * exact)
              << "H " << H << " h " << h << " mu " << mu;
          const double tol = h > 4 * H ? kTableThinRelTol : kTableHorizontalRelTol;
          EXPECT_NEAR(atm.optical_length(i, r, mu), exact, tol * exact)
              << "H " << H << " h " << h << " mu " << mu;
        }
      }
    }
  }
}

TEST(Atmosphere, TransmittanceMultiplicative) {
  const AtmosphereParameters p;
  Atmosphere atm(p);
  const std::vector<double> nm{440, 550, 680}, one(3, 1.0);
  const Spectral spec = make_spectral(p, nm, one);
  for (double h : {0.0, 5e3}) {
    const Vec3 a{0, 0, p.ground_radius_m + h};
    for (double el : {60.0, 5.0, 0.0, -0.5}) {
      const Vec3 d = dir_el_az(el, 30);
      const double s1 = 40e3, s2 = 90e3;
      std::vector<double> tab(3), tbc(3), tac(3);
      atm.transmittance(a, d, s1, spec, tab);
      atm.transmittance(a + s1 * d, d, s2 - s1, spec, tbc);
      atm.transmittance(a, d, s2, spec, tac);
      for (int l = 0; l < 3; ++l) {
        EXPECT_GT(tac[l], 0.0);
        EXPECT_NEAR(tab[l] * tbc[l], tac[l], kAdditivityRelTol * tac[l])
            << "h " << h << " el " << el << " nm " << nm[l];
      }
    }
  }
}

TEST(Atmosphere, FullPlanetShadowIsExactlyZero) {
  // Sun far below the horizon: every point of the atmosphere visible from the ground (or 10 km
  // up) is in the planet's shadow, so nothing is scattered to the observer. Earth: -30 and -60
  // deg; the small planet's visible atmosphere spans +-25 deg of arc, so only the sun at the
  // nadir (-90) darkens all of it.
  for (const auto& [p, elevations] : {std::pair{AtmosphereParameters{}, std::vector{-30.0, -60.0}},
                                      std::pair{off_earth(), std::vector{-90.0}}}) {
    Atmosphere atm(p);
    const std::vector<double> nm{440, 550, 680}, one(3, 1.0);
    const Spectral spec = make_spectral(p, nm, one);
    for (double sun_el : elevations)
      for (double h : {0.0, 10e3})
        for (double el : {90.0, 30.0, 5.0, 0.0, -1.0})
          for (double az : {0.0, 90.0, 180.0}) {
            std::vector<double> f(3), r(3);
            const Vec3 pos{0, 0, p.ground_radius_m + h};
            atm.single_scattering(pos, dir_el_az(el, az), dir_el_az(sun_el, 180), spec, f);
            atm.single_scattering_reference(pos, dir_el_az(el, az), dir_el_az(sun_el, 180), spec, r,
                                            {50, 8});
            for (int l = 0; l < 3; ++l) {
              EXPECT_EQ(f[l], 0.0) << "sun " << sun_el << " h " << h << " el " << el;
              EXPECT_EQ(r[l], 0.0) << "sun " << sun_el << " h " << h << " el " << el;
            }
          }
  }
}

// Fast path vs reference over altitudes, sun elevations and view directions (3 wavelengths).
// Returns the worst relative difference and where it occurs.
std::pair<double, std::string> sweep(const AtmosphereParameters& p,
                                     const std::vector<double>& nm = {440, 550, 680}) {
  Atmosphere atm(p);
  const std::vector<double> one(3, 1.0);
  const Spectral spec = make_spectral(p, nm, one);
  // Reference: 400 trapezoid intervals per piece (converged to 3e-5 against 6400 on Earth) and
  // Simpson 2 x 32 per sun-ray piece (1e-5).
  const ReferenceSettings rs{400, 32};
  double worst = 0;
  std::string where;
  for (double h : {0.0, 1e3, 10e3, 100e3, 1000e3}) {
    const Vec3 pos{0, 0, p.ground_radius_m + h};
    struct Res {
      double fast, ref;
      std::string tag;
    };
    std::vector<Res> res;
    double scale = 0;
    // Sun at -10 ... 90 deg (exactly 0 is avoided: from the ground the observer then sits on the
    // terminator and a horizontal view ray runs along the shadow's boundary, an ill-posed case).
    for (double sun_el : {-10.0, -4.0, -1.0, 0.5, 2.0, 10.0, 45.0, 90.0}) {
      const Vec3 sun = dir_el_az(sun_el, 180);
      for (double v_el : {90.0, 30.0, 5.0, 0.0, -1.0, -5.0, -30.0, -90.0})
        for (double v_az : {180.0, 60.0, 0.0}) {
          std::vector<double> f(3), r(3);
          atm.single_scattering(pos, dir_el_az(v_el, v_az), sun, spec, f);
          atm.single_scattering_reference(pos, dir_el_az(v_el, v_az), sun, spec, r, rs);
          for (int l = 0; l < 3; ++l) {
            res.push_back({f[l], r[l],
                           fmt::format("h {} m, sun el {}, view el {} az {}, {} nm", h, sun_el,
                                       v_el, v_az, nm[l])});
            scale = std::max(scale, r[l]);
          }
        }
    }
    for (const auto& x : res) {
      const double d = std::abs(x.fast - x.ref) / std::max(x.ref, kRelativeFloor * scale);
      if (d > worst) {
        worst = d;
        where = fmt::format("{}: fast {} reference {}", x.tag, x.fast, x.ref);
      }
    }
  }
  return {worst, where};
}

TEST(Atmosphere, FastMatchesReferenceEarth) {
  const auto [worst, where] = sweep(AtmosphereParameters{});
  std::printf("Earth: worst fast/reference relative difference %.3g at %s\n", worst, where.c_str());
  EXPECT_LT(worst, kFastVsReferenceRelTol) << where;
}

// Earth with the 300 DU ozone layer; 600 nm is near the peak of its Chappuis band.
AtmosphereParameters earth_with_ozone() {
  AtmosphereParameters p;
  p.components.push_back(earth_ozone());
  return p;
}

TEST(Atmosphere, FastMatchesReferenceEarthWithOzone) {
  const auto [worst, where] = sweep(earth_with_ozone(), {440, 600, 680});
  std::printf("Earth + ozone: worst fast/reference relative difference %.3g at %s\n", worst,
              where.c_str());
  EXPECT_LT(worst, kFastVsReferenceRelTol) << where;
}

// Column of the tent profile above altitude h (closed form): integral_h^top max(0, 1 - |z - c| /
// w) dz for a tent inside the atmosphere.
double tent_column_above(double h, double c, double w) {
  const auto F = [&](double z) {  // antiderivative of the tent on [c - w, c + w], 0 below
    if (z <= c - w) return 0.0;
    if (z <= c) return (z - (c - w)) * (z - (c - w)) / (2 * w);
    if (z <= c + w) return w - (c + w - z) * (c + w - z) / (2 * w);
    return w;
  };
  return w - F(h);
}

TEST(Atmosphere, OzoneTentOpticalLengthClosedForm) {
  // Vertical optical length of the ozone tent (peak 25 km, half width 15 km, inside the 60 km
  // atmosphere): the closed-form column above h (15 km at the ground).
  const AtmosphereParameters p = earth_with_ozone();
  const Atmosphere atm(p);
  const std::size_t oz = 2;
  const Component& c = p.components[oz];
  // The quadrature cuts the ray at the tent's kinks, so Simpson integrates polynomials-like
  // pieces: observed <= 1e-9.
  constexpr double kTentQuadratureRelTol = 1e-7;
  // The table interpolates linearly between levels 235 m apart (L is piecewise quadratic in h):
  // observed <= 0.47 m, i.e. 3.1e-5 of the full 15 km column (the error is absolute: near the
  // layer's top, where L -> 0, it is 3.5e-3 of the local value, which the column dwarfs).
  constexpr double kTentTableColumnTol = 1e-4;
  for (double h : {0.0, 5e3, 10e3, 17e3, 25e3, 31e3, 38e3}) {
    const double exact = tent_column_above(h, kOzonePeakAltitude, kOzoneHalfWidth);
    const double r = p.ground_radius_m + h;
    EXPECT_NEAR(optical_length_quadrature(r, 1.0, c, p.ground_radius_m, p.top_radius_m), exact,
                kTentQuadratureRelTol * exact)
        << "h " << h;
    EXPECT_NEAR(atm.optical_length(oz, r, 1.0), exact, kTentTableColumnTol * kOzoneHalfWidth)
        << "h " << h;
  }
  EXPECT_DOUBLE_EQ(tent_column_above(0, kOzonePeakAltitude, kOzoneHalfWidth), 15e3);
}

TEST(Atmosphere, OzoneColumnAndBluerTwilightZenith) {
  // Vertical transmittance of the ozone layer alone, ground to space:
  //   T = exp(-N sigma(lambda)),  N = 300 DU x 2.687e20 m^-2 (Beer-Lambert, closed form).
  AtmosphereParameters only;
  only.components = {earth_ozone()};
  const Atmosphere atm(only);
  const ReferenceSpectra& bs = bruneton_spectra();
  const std::vector<double> nm{440, 600, 680};
  const Spectral spec = make_spectral(only, nm, std::vector<double>(3, 1.0));
  std::vector<double> T(3);
  const Vec3 ground{0, 0, only.ground_radius_m};
  atm.transmittance(ground, {0, 0, 1}, only.top_radius_m - only.ground_radius_m, spec, T);
  constexpr double kColumnTransmittanceRelTol = 1e-5;  // table error 1e-4 x optical depth < 0.04
  for (int l = 0; l < 3; ++l) {
    const auto& w = bs.ozone_cross_section.wavelengths();
    const auto it = std::find(w.begin(), w.end(), nm[l]);
    ASSERT_NE(it, w.end());
    const double sigma = bs.ozone_cross_section.values()[static_cast<std::size_t>(it - w.begin())];
    const double exact = std::exp(-kEarthOzoneColumn * kDobsonUnit * sigma);
    EXPECT_NEAR(T[l], exact, kColumnTransmittanceRelTol) << nm[l] << " nm";
  }
  std::printf("300 DU ozone column: vertical transmittance %.4f / %.4f / %.4f at 440/600/680 nm\n",
              T[0], T[1], T[2]);

  // With the sun at the horizon, the zenith sky's light crosses the ozone layer on a long slant
  // path: ozone absorbs its orange-red (Chappuis band) and keeps the twilight zenith blue.
  const AtmosphereParameters plain, with = earth_with_ozone();
  const Atmosphere a0(plain), a1(with);
  const Spectral s0 = make_spectral(plain, nm, std::vector<double>(3, 1.0));
  const Spectral s1 = make_spectral(with, nm, std::vector<double>(3, 1.0));
  const Vec3 sun = dir_el_az(0.5, 180);
  std::vector<double> i0(3), i1(3);
  a0.single_scattering(ground, {0, 0, 1}, sun, s0, i0);
  a1.single_scattering(ground, {0, 0, 1}, sun, s1, i1);
  std::printf(
      "zenith, sun at 0.5 deg: 440/600 nm ratio %.3f without ozone, %.3f with; "
      "600 nm radiance x %.3f\n",
      i0[0] / i0[1], i1[0] / i1[1], i1[1] / i0[1]);
  EXPECT_GT(i1[0] / i1[1], 1.5 * (i0[0] / i0[1]));      // observed 2.9x bluer
  for (int l = 0; l < 3; ++l) EXPECT_LT(i1[l], i0[l]);  // ozone only absorbs
}

TEST(Atmosphere, EverySimdTargetAgrees) {
  // The kernel is compiled for every Highway target (SSE2 ... AVX-512) and dispatched at run time;
  // each target this machine can run must give the same radiance. Differences come from float
  // rounding (FMA vs separate multiply-add, vector widths in the sums): observed ~1e-7.
  constexpr double kTargetRelTol = 1e-5;
  const AtmosphereParameters p = earth_with_ozone();
  const Atmosphere atm(p);
  const std::vector<double> nm{400, 440, 500, 550, 600, 650, 680};  // 7: vector + remainder
  const Spectral spec = make_spectral(p, nm, std::vector<double>(nm.size(), 1.0));
  const auto evaluate = [&] {
    std::vector<double> all;
    for (double h : {0.0, 20e3, 1000e3})
      for (double sun_el : {-4.0, 3.0, 45.0})
        for (double el : {90.0, 10.0, 0.0, -20.0}) {
          std::vector<double> out(nm.size());
          atm.single_scattering({0, 0, p.ground_radius_m + h}, dir_el_az(el, 150),
                                dir_el_az(sun_el, 180), spec, out);
          all.insert(all.end(), out.begin(), out.end());
        }
    return all;
  };
  const std::vector<double> best = evaluate();
  const auto targets = hwy::SupportedAndGeneratedTargets();
  for (const int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    const std::vector<double> v = evaluate();
    for (std::size_t k = 0; k < v.size(); ++k)
      EXPECT_NEAR(v[k], best[k], kTargetRelTol * std::abs(best[k]) + 1e-30)
          << hwy::TargetName(target) << " value " << k;
  }
  hwy::SetSupportedTargetsForTest(0);  // back to the real CPU
  std::printf("SIMD targets compared: %zu\n", targets.size());
  EXPECT_GE(targets.size(), 1u);
}

TEST(Atmosphere, FastMatchesReferenceOffEarth) {
  const auto [worst, where] = sweep(off_earth());
  std::printf("Off-Earth: worst fast/reference relative difference %.3g at %s\n", worst,
              where.c_str());
  EXPECT_LT(worst, kFastVsReferenceRelTol) << where;
}

TEST(Atmosphere, SingleScatteringIsAdditiveAlongTheRay) {
  // Pietras §IV: the light scattered between p and q is the difference of two evaluations,
  // I(p) = I(p -> q) + T(p, q) I(q).
  const AtmosphereParameters p;
  Atmosphere atm(p);
  const std::vector<double> nm{440, 550, 680}, one(3, 1.0);
  const Spectral spec = make_spectral(p, nm, one);
  const Vec3 o{0, 0, p.ground_radius_m + 300}, sun = dir_el_az(20, 180);
  for (double el : {10.0, 1.0, -0.3}) {
    const Vec3 d = dir_el_az(el, 150);
    const double dist = 30e3;
    std::vector<double> full(3), part(3), rest(3), t(3);
    atm.single_scattering(o, d, sun, spec, full);
    atm.single_scattering(o, d, sun, spec, part, dist);
    atm.single_scattering(o + dist * d, d, sun, spec, rest);
    atm.transmittance(o, d, dist, spec, t);
    for (int l = 0; l < 3; ++l)
      EXPECT_NEAR(part[l] + t[l] * rest[l], full[l], kAdditivityRelTol * full[l])
          << "el " << el << " nm " << nm[l];
  }
}

TEST(Atmosphere, AerialPerspectiveOfABlackSurfaceIsTheInScatteredLight) {
  const AtmosphereParameters p;
  Atmosphere atm(p);
  const std::vector<double> nm{440, 550, 680}, one(3, 1.0), black(3, 0.0), white(3, 1.0);
  const Spectral spec = make_spectral(p, nm, one);
  const Vec3 o{0, 0, p.ground_radius_m + 2000}, sun = dir_el_az(40, 180);
  const Vec3 d = dir_el_az(-3, 170);
  const double dist = 20e3;
  std::vector<double> a(3), b(3), w(3), t(3);
  atm.aerial_perspective(o, d, dist, black, sun, spec, a);
  atm.single_scattering(o, d, sun, spec, b, dist);
  atm.aerial_perspective(o, d, dist, white, sun, spec, w);
  atm.transmittance(o, d, dist, spec, t);
  for (int l = 0; l < 3; ++l) {
    EXPECT_EQ(a[l], b[l]);
    EXPECT_GT(w[l], a[l]);  // a lit white surface adds light
    EXPECT_LT(t[l], 1.0);
    if (l > 0) {
      EXPECT_GT(t[l], t[l - 1]);  // blue is attenuated most (nm ascending)
    }
  }
}

TEST(Atmosphere, RayleighColourRatios) {
  // Pure Rayleigh atmosphere (Earth): B/R = I(440 nm)/I(680 nm), unit solar irradiance.
  AtmosphereParameters p;
  p.components = {earth_rayleigh()};
  Atmosphere atm(p);
  const std::vector<double> nm{440, 680}, one(2, 1.0);
  const Spectral spec = make_spectral(p, nm, one);
  const Vec3 o{0, 0, p.ground_radius_m};
  const auto blue_red = [&](double sun_el, Vec3 view) {
    std::vector<double> f(2);
    atm.single_scattering(o, view, dir_el_az(sun_el, 180), spec, f);
    return f[0] / f[1];
  };
  const double zenith_high = blue_red(60, {0, 0, 1});
  const double horizon_high = blue_red(60, dir_el_az(1, 0));
  const double horizon_sunset = blue_red(1, dir_el_az(1, 180));
  const double zenith_sunset = blue_red(1, {0, 0, 1});
  std::printf(
      "Rayleigh B/R (440/680 nm): sun 60 deg: zenith %.3f, horizon (1 deg, north) %.3f; "
      "sun 1 deg: zenith %.3f, horizon towards the sun %.3f\n",
      zenith_high, horizon_high, zenith_sunset, horizon_sunset);
  // Optically thin zenith: close to the lambda^-4 ratio (680/440)^4 = 5.71; the long horizontal
  // path saturates the blue and lowers the ratio.
  EXPECT_GT(zenith_high, horizon_high);
  EXPECT_GT(zenith_high, 3.0);
  EXPECT_LT(zenith_high, 5.71);
  // Near sunset the light towards the sun has crossed ~38 air masses: red dominates.
  EXPECT_LT(horizon_sunset, 1.0);
  EXPECT_LT(horizon_sunset, horizon_high);
}

TEST(Atmosphere, GroundReflectionMatchesReference) {
  // Lambertian ground (albedo 0.3) seen from 1 km and 100 km: fast (tables) vs reference
  // (quadrature) transmittances of the reflected sunlight plus the in-scattered light.
  AtmosphereParameters p;
  p.ground_albedo = 0.3;
  Atmosphere atm(p);
  const std::vector<double> nm{440, 550, 680}, one(3, 1.0);
  const Spectral spec = make_spectral(p, nm, one);
  for (double h : {1e3, 100e3})
    for (double sun_el : {5.0, 30.0, 80.0})
      for (double el : {-10.0, -45.0, -90.0}) {
        const Vec3 pos{0, 0, p.ground_radius_m + h};
        std::vector<double> f(3), r(3), plain(3);
        atm.single_scattering(pos, dir_el_az(el, 20), dir_el_az(sun_el, 180), spec, f);
        atm.single_scattering_reference(pos, dir_el_az(el, 20), dir_el_az(sun_el, 180), spec, r,
                                        {200, 32});
        for (int l = 0; l < 3; ++l)
          EXPECT_NEAR(f[l], r[l], kFastVsReferenceRelTol * r[l])
              << "h " << h << " sun " << sun_el << " el " << el << " nm " << nm[l];
      }
}

TEST(Atmosphere, GroundReflectionIsContinuousInAltitude) {
  // An observer on the ground looking down sees the ground at distance 0: the reflected sunlight
  // with a view transmittance of 1, the limit of an observer 1 mm above it (in-scattering over a
  // path of <= 12 mm and the view transmittance differ from it by ~1e-8 relative). Fast path and
  // reference, with and without an albedo (without: 0 on the ground).
  constexpr double kAltitudeLimitRelTol = 1e-6;
  for (const bool with_albedo : {true, false}) {
    AtmosphereParameters p;
    if (with_albedo) p.ground_albedo = 0.3;
    Atmosphere atm(p);
    const std::vector<double> nm{440, 550, 680}, one(3, 1.0);
    const Spectral spec = make_spectral(p, nm, one);
    for (double sun_el : {5.0, 40.0})
      for (double el : {-5.0, -30.0, -90.0}) {
        const Vec3 view = dir_el_az(el, 20), sun = dir_el_az(sun_el, 180);
        std::vector<double> f0(3), f1(3), r0(3), r1(3);
        atm.single_scattering({0, 0, p.ground_radius_m}, view, sun, spec, f0);
        atm.single_scattering({0, 0, p.ground_radius_m + 1e-3}, view, sun, spec, f1);
        atm.single_scattering_reference({0, 0, p.ground_radius_m}, view, sun, spec, r0, {200, 32});
        atm.single_scattering_reference({0, 0, p.ground_radius_m + 1e-3}, view, sun, spec, r1,
                                        {200, 32});
        for (int l = 0; l < 3; ++l) {
          const std::string where =
              fmt::format("albedo {} sun {} el {} nm {}", with_albedo, sun_el, el, nm[l]);
          if (with_albedo) {
            EXPECT_GT(f0[l], 0.0) << where;
          } else {
            EXPECT_EQ(f0[l], 0.0) << where;
            EXPECT_EQ(r0[l], 0.0) << where;
          }
          // Absolute floor: 1e-6 of the reflected radiance of the albedo case's scale (I0 = 1).
          const double floor = kAltitudeLimitRelTol * 0.3 / kPi;
          EXPECT_NEAR(f0[l], f1[l], kAltitudeLimitRelTol * f1[l] + floor) << where;
          EXPECT_NEAR(r0[l], r1[l], kAltitudeLimitRelTol * r1[l] + floor) << where;
          EXPECT_NEAR(f0[l], r0[l], kFastVsReferenceRelTol * r0[l] + floor) << where;
        }
      }
  }
}

TEST(Atmosphere, BadParametersAreRejected) {
  const auto bad = [](auto change) {
    AtmosphereParameters p;
    change(p);
    return p;
  };
  EXPECT_THROW(Atmosphere(bad([](auto& p) { p.top_radius_m = p.ground_radius_m; })),
               InvalidArgument);
  EXPECT_THROW(Atmosphere(bad([](auto& p) { p.ground_radius_m = -1; })), InvalidArgument);
  EXPECT_THROW(Atmosphere(bad([](auto& p) { p.components[0].scale_height_m = 0; })),
               InvalidArgument);
  EXPECT_THROW(Atmosphere(bad([](auto& p) { p.components[1].g = 1.0; })), InvalidArgument);
  EXPECT_THROW(Atmosphere(bad([](auto& p) { p.components[1].extinction_per_m = 1e-6; })),
               InvalidArgument);
  EXPECT_THROW(Atmosphere(bad([](auto& p) { p.ground_albedo = 1.5; })), InvalidArgument);
  EXPECT_THROW(
      Atmosphere(bad([](auto& p) { p.components.resize(kMaxComponents + 1, earth_mie()); })),
      InvalidArgument);
  EXPECT_THROW(Atmosphere(bad([](auto& p) { p.components[0].scattering_per_m = std::nan(""); })),
               InvalidArgument);
}

TEST(Atmosphere, PhaseFunctionsAreNormalised) {
  // Integral over the sphere of F = 1 (2 pi integral_{-1}^{1} F(mu) dmu), midpoint rule.
  constexpr double kNormTol = 1e-4;  // 20000 midpoints, peaked g = 0.8 lobes
  for (const auto& c : {earth_rayleigh(), earth_mie(),
                        Component{"hg", 1, 0, 0, 550, 0, PhaseKind::henyey_greenstein, 0.7}}) {
    double sum = 0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) sum += phase(c, -1 + 2.0 * (k + 0.5) / n) * 2.0 / n;
    EXPECT_NEAR(2 * kPi * sum, 1.0, kNormTol) << c.name;
  }
}

}  // namespace
}  // namespace skylight::atmosphere
