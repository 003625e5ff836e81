// What hillaire and bruneton share (models/physical_sky.h): the XYZ quadrature on their 41
// wavelengths.
#include "skylight/models/physical_sky.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "skylight/core/colorimetry.h"
#include "skylight/core/math.h"
#include "skylight/models/bruneton.h"
#include "skylight/models/hillaire.h"

namespace skylight {
namespace physical_sky_test {

// The spectral sampling (docs/ATMOSPHERE.md, "Spectral sampling"): XYZ from the model's 41
// wavelengths (every 10 nm, 380-780 nm, spline_xyz_weights) against a 5 nm trapezoid integration
// 380-780 nm of its own spectral radiance (the aim: 0.5 % in X, Y, Z), by day, at sunset and in
// twilight, on the ground and at 20 km. The quadrature alone (the exact spectral radiance at its
// wavelengths): measured within 0.04 % by day and 0.12 % in twilight (skylight_atmosphere_error
// xyz); tristimulus(), which adds the orders >= 2 from the sky-view LUT (bilinear in the view:
// its own error, Hillaire.TheSkyViewLutIsTheDirectIntegration), within 0.44 % for bruneton and
// 0.54 % for hillaire (here: quadrature 0.08 %, tristimulus 0.31 % and 0.32 %; nishita's 20 CMF
// samples: 2.1 %).
constexpr double kQuadratureRelTol = 0.002;
constexpr double kBrunetonXyzRelTol = 0.005;
constexpr double kHillaireXyzRelTol = 0.007;

std::unique_ptr<PhysicalSkyModel> make(bool bruneton, double sun_el, double altitude) {
  NishitaParameters p;
  p.sun = {.zenith = deg_to_rad(90.0 - sun_el), .azimuth = deg_to_rad(180.0)};
  p.observer_altitude_m = altitude;
  if (bruneton) {
    BrunetonParameters b;
    static_cast<NishitaParameters&>(b) = p;
    b.ozone_du = atmosphere::kEarthOzoneColumn;
    b.scattering_orders = 3;
    return std::make_unique<BrunetonModel>(b);
  }
  HillaireParameters h;
  static_cast<NishitaParameters&>(h) = p;
  h.ozone_du = atmosphere::kEarthOzoneColumn;
  return std::make_unique<HillaireModel>(h);
}

double xyz_error(const Xyz& a, const Xyz& b) {
  return std::max({std::abs(a.X / b.X - 1), std::abs(a.Y / b.Y - 1), std::abs(a.Z / b.Z - 1)});
}

// One model (bruneton or hillaire) at two altitudes and three suns; a test per model keeps each
// under a minute under the sanitizers.
void check_xyz_from_wavelengths(bool bruneton) {
  for (const double altitude : {0.0, 20e3})
    for (const double sun_el : {45.0, 5.0, -3.0}) {
      const auto m = make(bruneton, sun_el, altitude);
      ASSERT_EQ(m->xyz_spectral().nm.size(), static_cast<std::size_t>(kPhysicalXyzCount));
      for (const Vec3 v :
           {direction_from_angles(0.0, 0.0), direction_from_angles(deg_to_rad(85.0), 0.0),
            direction_from_angles(deg_to_rad(89.0), deg_to_rad(90.0)),
            direction_from_angles(deg_to_rad(60.0), kPi)}) {
        std::vector<double> nm, radiance, at_nodes;
        for (double l = 380; l <= 780; l += 5) {
          nm.push_back(l);
          radiance.push_back(*m->spectral_radiance(v, l));
        }
        for (const double l : m->xyz_spectral().nm) at_nodes.push_back(*m->spectral_radiance(v, l));
        const Xyz dense = spectral_radiance_to_xyz(nm, radiance);
        EXPECT_LT(xyz_error(m->to_xyz(at_nodes), dense), kQuadratureRelTol)
            << m->name() << " " << altitude << " " << sun_el;
        EXPECT_LT(xyz_error(m->tristimulus(v), dense),
                  bruneton ? kBrunetonXyzRelTol : kHillaireXyzRelTol)
            << m->name() << " " << altitude << " " << sun_el;
      }
    }
}

TEST(PhysicalSky, XyzFromItsWavelengthsMatchesADenseIntegrationBruneton) {
  check_xyz_from_wavelengths(true);
}
TEST(PhysicalSky, XyzFromItsWavelengthsMatchesADenseIntegrationHillaire) {
  check_xyz_from_wavelengths(false);
}

}  // namespace physical_sky_test
}  // namespace skylight
