// libFuzzer target: the directions CSV of `skylight eval` (io/directions.h). Every accepted row
// must hold finite angles in range, and its text must be the row as written.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.h"
#include "skylight/core/math.h"
#include "skylight/io/directions.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::expect_parsed_or_refused([&] {
    for (const auto& row : io::parse_directions_csv(text, "fuzz.csv")) {
      fuzz::require_finite(row.zenith, "zenith");
      fuzz::require_finite(row.azimuth, "azimuth");
      fuzz::require(row.zenith >= 0.0 && row.zenith <= kPi, "zenith outside [0, pi]");
      fuzz::require(row.azimuth >= 0.0 && row.azimuth < 2.0 * kPi, "azimuth outside [0, 2 pi)");
      fuzz::require(row.line >= 2, "a row on the header's line");
      fuzz::require(row.text.data() >= text.data() &&
                        row.text.data() + row.text.size() <= text.data() + text.size(),
                    "row text outside the input");
    }
  });
  return 0;
}
