// libFuzzer target: the image list of `skylight nn train --images` (estimate/sky_sequence.h). An
// accepted list has at least one row; each names a file inside the list's folder, gives the sun's
// two angles together and in range or none, never angles and a time both, on ascending lines.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "skylight/estimate/sky_sequence.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::expect_parsed_or_refused([&] {
    const auto rows = estimate::parse_sequence_list(text, "fuzz.csv", "folder");
    fuzz::require(!rows.empty(), "an empty list accepted");
    int line = 0;
    for (const auto& row : rows) {
      fuzz::require(row.line > line, "rows out of line order");
      line = row.line;
      fuzz::require(row.file.has_parent_path() && !row.file.filename().empty() &&
                        row.file.string().rfind("folder/", 0) == 0,
                    "file outside the list's folder");
      fuzz::require(row.sun_zenith_deg.has_value() == row.sun_azimuth_deg.has_value(),
                    "one sun angle without the other");
      if (row.sun_zenith_deg) {
        fuzz::require(*row.sun_zenith_deg >= 0.0 && *row.sun_zenith_deg <= 90.0, "zenith range");
        fuzz::require(*row.sun_azimuth_deg >= -360.0 && *row.sun_azimuth_deg <= 360.0,
                      "azimuth range");
        fuzz::require(row.time.empty(), "angles and a time both accepted");
      }
    }
  });
  return 0;
}
