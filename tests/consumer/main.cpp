// Links against the installed library and evaluates one sky two ways (the registry with named
// values, and the model's typed parameters): exits 0 only if both give Preetham's closed-form
// zenith luminance (T = 3, theta_s = 45 deg: 7320.358 cd/m^2) and a bad value is refused with
// skylight::InvalidArgument.
#include <cmath>
#include <cstdio>

#include "skylight/models/preetham.h"
#include "skylight/models/sky_model.h"
#include "skylight/version.h"

int main() {
  skylight::SkyParameters p;
  p.sun.zenith = skylight::deg_to_rad(45.0);
  p.values.set("turbidity", 3.0);
  const auto sky = skylight::make_sky_model("preetham", p);
  const double Y = sky->tristimulus({0.0, 0.0, 1.0}).Y;

  skylight::PreethamParameters typed;
  typed.sun = p.sun;
  typed.turbidity = 3.0;
  const double Y2 = skylight::PreethamModel(typed).tristimulus({0.0, 0.0, 1.0}).Y;

  bool refused = false;
  try {
    p.values.set("turbidity", 100.0);
    skylight::make_sky_model("preetham", p);
  } catch (const skylight::InvalidArgument& e) {
    refused = true;
    std::printf("refused as expected: %s\n", e.what());
  }
  std::printf("skylight %s: preetham zenith luminance %.3f cd/m^2\n", skylight::kVersion, Y);
  const double want = 7320.358316713677;
  return std::abs(Y - want) < 1e-6 && std::abs(Y2 - want) < 1e-6 && refused ? 0 : 1;
}
