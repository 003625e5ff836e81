#include "skylight/estimate/hosek_fit.h"

#include <gtest/gtest.h>

#include "skylight/core/error.h"
#include "skylight/models/hosek_wilkie.h"
#include "support/sky_photo.h"

namespace skylight::estimate {
namespace {

// Samples of the model itself (float pixels): LM ends at the generating (T, albedo) to the float
// storage of the luminance (~1e-7 relative) amplified by the conditioning of the fit.
constexpr double kExactTurbidityTol = 1e-3;
constexpr double kExactAlbedoTol = 0.01;
// With 30 % of the sky under synthetic clouds, RANSAC's estimate stays within this of the truth
// (as the Preetham fit's requirement).
constexpr double kCloudTol = 0.1;

TEST(HosekFit, RecoversTurbidityAndAlbedoOfARenderedSky) {
  const SunPosition sun{50 * kDegree, 120 * kDegree};
  const SkyCamera cam{PhotoProjection::fisheye, 200, 200, {}};
  for (const auto& [t, a] : {std::pair{2.5, 0.1}, std::pair{4.0, 0.3}, std::pair{7.0, 0.8}}) {
    const HosekWilkieModel model(HosekParameters{sun, t, a});
    io::ImageF img = testing_support::render_photo(model, cam);
    for (float& v : img.data) v *= 1e-3f;  // any exposure
    const SkyMask mask = sky_mask(img, cam, MaskSettings{}, sun);
    EstimateSettings s;
    s.bootstrap = 8;
    const HosekFit f = fit_hosek(sample_sky(img, cam, mask, 100, 3), sun, s);
    EXPECT_NEAR(f.turbidity, t, kExactTurbidityTol) << "T " << t << " albedo " << a;
    EXPECT_NEAR(f.albedo, a, kExactAlbedoTol) << "T " << t << " albedo " << a;
    EXPECT_EQ(f.inliers, 100);
    EXPECT_LT(f.turbidity_sigma, kExactTurbidityTol);
  }
}

TEST(HosekFit, RansacRejectsSyntheticClouds) {
  const SunPosition sun{58.4 * kDegree, wrap_azimuth(-179.4 * kDegree)};
  const SkyCamera cam{PhotoProjection::fisheye, 300, 300, {}};
  const HosekWilkieModel model(HosekParameters{sun, 4.0, 0.3});
  io::ImageF img = testing_support::render_photo(model, cam);
  const SkyMask clear = sky_mask(img, cam, MaskSettings{}, sun);
  testing_support::paint_clouds(img, clear.sky, 0.3, 25.0, 2.5, 0.4, 17);
  const SkyMask mask = sky_mask(img, cam, MaskSettings{}, sun);
  EstimateSettings s;
  s.bootstrap = 0;
  const auto samples = sample_sky(img, cam, mask, 100, 5);
  const HosekFit r = fit_hosek(samples, sun, s);
  EXPECT_NEAR(r.turbidity, 4.0, kCloudTol);
  EXPECT_LT(r.inlier_fraction, 0.85);
  s.ransac = false;
  EXPECT_GT(std::abs(fit_hosek(samples, sun, s).turbidity - 4.0), kCloudTol);
  EXPECT_THROW(fit_hosek(samples, SunPosition{100 * kDegree, 0.0}, s), InvalidArgument);
}

}  // namespace
}  // namespace skylight::estimate
