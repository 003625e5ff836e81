// libFuzzer target: the image list of `skylight nn train --images` (estimate/sky_sequence.h). An
// accepted list has at least one row; each names a file (not a folder, no control character; a
// relative name inside the list's folder), gives the sun's two angles together and in range or
// none, never angles and a time both, on ascending lines.
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
      // A relative name lies in the list's folder; an absolute one is kept as written.
      fuzz::require(row.file.is_absolute() || row.file.string().rfind("folder/", 0) == 0,
                    "relative file outside the list's folder");
      for (const auto* p : {&row.file, &row.mask}) {
        if (p->empty()) continue;
        const std::string last = p->filename().string();
        fuzz::require(!last.empty() && last != "." && last != "..", "a folder accepted as a file");
        for (const char ch : p->string())
          fuzz::require(static_cast<unsigned char>(ch) >= 0x20, "control character in a name");
      }
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
