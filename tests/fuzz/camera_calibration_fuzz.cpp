// libFuzzer target: the camera calibration file (io/camera_calibration.h). An accepted file gives
// a camera for its image size whose pixels map to unit directions and back.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "skylight/io/camera_calibration.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  const std::string text(reinterpret_cast<const char*>(data), size);
  fuzz::expect_parsed_or_refused([&] {
    const io::CameraCalibration c = io::parse_camera_calibration(text, "fuzz.json");
    const auto [w, h] = c.image_size.value_or(std::array<int, 2>{64, 48});
    const Camera cam = c.camera(w, h, 50.0);
    for (const auto& [col, row] : {std::pair{0.5, 0.5}, std::pair{0.5 * w, 0.5 * h}})
      if (const auto d = cam.direction(col, row))
        fuzz::require(std::abs(length(*d) - 1.0) < 1e-9, "direction not a unit vector");
  });
  return 0;
}
