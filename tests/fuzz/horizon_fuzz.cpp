// libFuzzer target: horizon profiles (io/horizon.h; CSV azimuth_deg,elevation_deg and PVGIS's CSV
// and JSON). Every accepted profile has points in range, sorted, each azimuth once, and
// interpolates to an elevation within its points' range at any azimuth.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.h"
#include "skylight/io/horizon.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::expect_parsed_or_refused([&] {
    const io::HorizonProfile h = io::parse_horizon(text, "fuzz.csv");
    const auto& p = h.points();
    fuzz::require(!p.empty(), "a profile without points accepted");
    double lo = 90.0, hi = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      fuzz::require(p[i].azimuth_deg >= 0.0 && p[i].azimuth_deg < 360.0, "azimuth range");
      fuzz::require(p[i].elevation_deg >= 0.0 && p[i].elevation_deg <= 90.0, "elevation range");
      if (i > 0) fuzz::require(p[i].azimuth_deg > p[i - 1].azimuth_deg, "points not sorted once");
      lo = std::min(lo, p[i].elevation_deg);
      hi = std::max(hi, p[i].elevation_deg);
    }
    for (int k = -3; k < 40; ++k) {
      const double e = h.elevation(k * 0.2) * 180.0 / 3.14159265358979323846;
      fuzz::require_finite(e, "elevation");
      fuzz::require(e >= lo - 1e-9 && e <= hi + 1e-9, "interpolation outside the points' range");
    }
  });
  return 0;
}
