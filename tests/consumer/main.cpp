// Links against the installed library and evaluates one sky: exits 0 only if the zenith luminance
// equals Preetham's closed form (T = 3, theta_s = 45 deg: 7320.358 cd/m^2).
#include <cmath>
#include <cstdio>

#include "skylight/models/sky_model.h"
#include "skylight/version.h"

int main() {
  skylight::SkyParameters p;
  p.turbidity = 3.0;
  p.sun.zenith = skylight::deg_to_rad(45.0);
  const auto sky = skylight::make_sky_model("preetham", p);
  const double Y = sky->tristimulus({0.0, 0.0, 1.0}).Y;
  std::printf("skylight %s: preetham zenith luminance %.3f cd/m^2\n", skylight::kVersion, Y);
  return std::abs(Y - 7320.358316713677) < 1e-6 ? 0 : 1;
}
