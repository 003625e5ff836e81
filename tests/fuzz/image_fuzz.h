// The image-reader targets (PFM, EXR, HDR) share this: the input as a file with the format's
// extension, read through io::read_image (our wrapper, not the third-party reader directly). An
// accepted image must have a consistent shape and finite pixels. The pixel limit is lowered to
// 2^20 (12 MB of RGB floats) so that a header asking for a large image is refused instead of
// running into libFuzzer's 2 GB malloc limit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.h"
#include "skylight/io/image.h"

namespace skylight::fuzz {

inline constexpr std::int64_t kMaxPixels = std::int64_t{1} << 20;

inline int read_image_target(const std::uint8_t* data, std::size_t size,
                             std::string_view extension) {
  static ScratchFile file(extension);
  const auto& path = file.write(data, size);
  expect_parsed_or_refused([&] {
    const io::ImageF image = io::read_image(path, {.max_pixels = kMaxPixels});
    require(image.width > 0 && image.height > 0, "empty image accepted");
    require(image.channels == 1 || image.channels == 3, "channel count");
    require(image.data.size() == static_cast<std::size_t>(image.width) *
                                     static_cast<std::size_t>(image.height) *
                                     static_cast<std::size_t>(image.channels),
            "pixel count");
    for (const float v : image.data) require_finite(v, "pixel");
  });
  return 0;
}

}  // namespace skylight::fuzz
