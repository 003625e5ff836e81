// libFuzzer target: the strict ISO 8601 date-time parser of `skylight sun --time` and the image
// list's `time` column (sun/time.h). An accepted time has valid fields, and formatting it with nine
// fraction digits parses back to the same fields (seconds within half a nanosecond).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.h"
#include "skylight/sun/time.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::expect_parsed_or_refused([&] {
    const sun::DateTime t = sun::parse_iso8601(text);
    try {
      sun::validate(t);
    } catch (const InvalidArgument& e) {
      fuzz::finding("an accepted time fails validate()", e.what());
    }
    fuzz::require(t.second >= 0.0 && t.second < 60.0, "second outside [0, 60)");
    // At most 9 fraction digits are accepted, so formatting with 9 never rounds or carries.
    sun::DateTime back;
    try {
      back = sun::parse_iso8601(sun::format_iso8601(t, 9));
    } catch (const InvalidArgument& e) {
      fuzz::finding("an accepted time does not format and parse back", e.what());
    }
    fuzz::require(back.year == t.year && back.month == t.month && back.day == t.day &&
                      back.hour == t.hour && back.minute == t.minute &&
                      back.utc_offset_minutes == t.utc_offset_minutes &&
                      std::abs(back.second - t.second) <= 0.5e-9,
                  "format -> parse changed the time");
  });
  return 0;
}
