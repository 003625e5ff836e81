// libFuzzer target: the sky-luminance scan CSV (analysis/scan.h, `report --measurements`). Every
// accepted sample must be finite and in range, and the scan must survive format -> parse.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.h"
#include "skylight/analysis/scan.h"
#include "skylight/core/math.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::expect_parsed_or_refused([&] {
    const auto scan = analysis::parse_sky_scan(text, "fuzz.csv");
    fuzz::require(!scan.samples.empty(), "a scan without samples accepted");
    if (scan.sun_azimuth) fuzz::require_finite(*scan.sun_azimuth, "sun azimuth");
    if (scan.sun_elevation) fuzz::require_finite(*scan.sun_elevation, "sun elevation");
    for (const auto& s : scan.samples) {
      fuzz::require_finite(s.azimuth, "azimuth");
      fuzz::require_finite(s.elevation, "elevation");
      fuzz::require_finite(s.luminance, "luminance");
      fuzz::require(s.azimuth >= 0.0 && s.azimuth < 2.0 * kPi, "azimuth outside [0, 2 pi)");
      fuzz::require(s.elevation >= 0.0 && s.elevation <= kPi / 2, "elevation outside [0, pi/2]");
      fuzz::require(s.luminance > 0.0, "luminance not positive");
    }
    // What we write we read back (6 significant digits: the sample count must survive).
    const auto again = analysis::parse_sky_scan(analysis::format_sky_scan(scan, {}), "again");
    fuzz::require(again.samples.size() == scan.samples.size(), "format -> parse lost samples");
  });
  return 0;
}
