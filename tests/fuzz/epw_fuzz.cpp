// libFuzzer target: EnergyPlus weather files (io/epw.h). Every accepted file has records, each
// with its fields in the data dictionary's ranges and finite.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.h"
#include "skylight/io/epw.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::expect_parsed_or_refused([&] {
    const io::EpwFile f = io::parse_epw(text, "fuzz.epw");
    fuzz::require(!f.records.empty(), "a file without records accepted");
    fuzz::require(f.location.latitude_deg >= -90.0 && f.location.latitude_deg <= 90.0,
                  "latitude out of range");
    fuzz::require(f.location.time_zone_h >= -12.0 && f.location.time_zone_h <= 14.0,
                  "time zone out of range");
    std::size_t last_line = 8;
    for (const io::EpwRecord& r : f.records) {
      fuzz::require(r.line > last_line, "records out of line order");
      last_line = r.line;
      fuzz::require(r.month >= 1 && r.month <= 12 && r.day >= 1 && r.day <= 31, "date range");
      fuzz::require(r.hour >= 1 && r.hour <= 24, "hour range");
      for (const auto& v : {r.direct_normal_wh_m2, r.diffuse_horizontal_wh_m2,
                            r.global_horizontal_wh_m2, r.diffuse_horizontal_lux})
        if (v) {
          fuzz::require_finite(*v, "radiation");
          fuzz::require(*v >= 0.0 && *v < 999900.0, "radiation range or missing marker");
        }
      if (r.dew_point_c) fuzz::require(*r.dew_point_c < 99.9, "dew point marker read as a value");
    }
  });
  return 0;
}
