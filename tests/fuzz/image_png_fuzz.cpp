// libFuzzer target: 8-bit PNG files (sky masks of `skylight estimate`) read through io::read_png.
// An accepted image must have a consistent shape; the pixel limit is image_fuzz.h's.
#include <cstddef>
#include <cstdint>

#include "image_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  static fuzz::ScratchFile file(".png");
  const auto& path = file.write(data, size);
  fuzz::expect_parsed_or_refused([&] {
    const io::Image8 image = io::read_png(path, {.max_pixels = fuzz::kMaxPixels});
    fuzz::require(image.width > 0 && image.height > 0, "empty image accepted");
    fuzz::require(image.data.size() == static_cast<std::size_t>(image.width) *
                                           static_cast<std::size_t>(image.height) * 3,
                  "pixel count");
  });
  return 0;
}
