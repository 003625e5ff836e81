// libFuzzer target: HDR files read through io::read_image (image_fuzz.h).
#include <cstddef>
#include <cstdint>

#include "image_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return skylight::fuzz::read_image_target(data, size, ".hdr");
}
