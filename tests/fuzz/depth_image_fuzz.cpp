// libFuzzer target: the one-channel reader of depth maps (`skylight haze --depth`):
// io::read_scalar_image on a 16-bit PNG, an EXR (Z, Y or R) or a PFM, the format chosen from the
// input's signature (89 50 4e 47: PNG, 76 2f 31 01: EXR, else PFM). An accepted image has one
// channel, a consistent shape and finite values.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_support.h"
#include "image_fuzz.h"
#include "skylight/io/image.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  static fuzz::ScratchFile png(".png"), exr(".exr"), pfm(".pfm");
  auto starts = [&](const char* magic) { return size >= 4 && std::memcmp(data, magic, 4) == 0; };
  fuzz::ScratchFile& file = starts("\x89PNG") ? png : starts("v/1\x01") ? exr : pfm;
  const auto& path = file.write(data, size);
  fuzz::expect_parsed_or_refused([&] {
    const io::ImageF depth = io::read_scalar_image(path, {.max_pixels = fuzz::kMaxPixels});
    fuzz::require(depth.width > 0 && depth.height > 0, "empty image accepted");
    fuzz::require(depth.channels == 1, "not one channel");
    fuzz::require(depth.data.size() == static_cast<std::size_t>(depth.width) *
                                           static_cast<std::size_t>(depth.height),
                  "pixel count");
    for (const float v : depth.data) fuzz::require_finite(v, "depth");
  });
  return 0;
}
