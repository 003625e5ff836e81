// libFuzzer target: the EXIF reader (io/exif.h, libexif underneath) on JPEG- and TIFF-headed
// bytes. An accepted file's numbers must be finite, and its time either converts or is refused
// with InvalidArgument.
#include <cstddef>
#include <cstdint>
#include <span>

#include "fuzz_support.h"
#include "skylight/io/exif.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skylight;
  const std::span<const char> bytes(reinterpret_cast<const char*>(data), size);
  fuzz::expect_parsed_or_refused([&] {
    const io::ExifInfo e = io::parse_exif(bytes, "fuzz.jpg");
    for (const auto& v :
         {e.focal_length_mm, e.focal_length_px, e.latitude_deg, e.longitude_deg, e.altitude_m})
      if (v) fuzz::require_finite(*v, "EXIF number");
    if (e.date_time) (void)e.time_iso8601("+00:00", "fuzz.jpg");
  });
  return 0;
}
