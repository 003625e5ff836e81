#include "skylight/io/exif.h"

#include <gtest/gtest.h>

#include <string>

#include "skylight/core/error.h"
#include "support/error_message.h"

namespace skylight::io {
namespace {

using testing_support::error_message;

// tests/data/exif/make_fixtures.py writes both files byte by byte; the values below are its.
const std::string kDir = std::string(SKYLIGHT_SOURCE_DIR) + "/tests/data/exif/";
// Rationals of small integers and their sums: exact but for the last bits of the division.
constexpr double kExact = 1e-12;

TEST(Exif, JpegTimePlaceAndFocalLength) {
  const ExifInfo e = read_exif(kDir + "capture.jpg");
  EXPECT_EQ(e.make, "SkylightTest");
  EXPECT_EQ(e.model, "Fisheye 8mm");
  EXPECT_EQ(e.date_time, "2024:06:21 15:00:00");
  EXPECT_EQ(e.utc_offset, "+02:00");
  ASSERT_TRUE(e.focal_length_mm && e.focal_length_px);
  EXPECT_NEAR(*e.focal_length_mm, 8.0, kExact);
  EXPECT_NEAR(*e.focal_length_px, 8.0 * 300.0 / 10.0, kExact);  // 300 per cm
  EXPECT_EQ(e.pixel_width, 4000);
  EXPECT_NEAR(*e.latitude_deg, 48.0 + 8.0 / 60.0, kExact);
  EXPECT_NEAR(*e.longitude_deg, 11.0 + 34.0 / 60.0 + 30.0 / 3600.0, kExact);
  EXPECT_NEAR(*e.altitude_m, 520.0, kExact);
  EXPECT_EQ(e.time_iso8601(std::nullopt, "capture.jpg"), "2024-06-21T15:00:00+02:00");
  EXPECT_EQ(e.time_iso8601("-05:00", "capture.jpg"), "2024-06-21T15:00:00-05:00");
}

// Little-endian TIFF, southern and western hemisphere, the focal plane per inch, no offset.
TEST(Exif, TiffSignsUnitsAndAMissingOffset) {
  const ExifInfo e = read_exif(kDir + "capture.tif");
  EXPECT_EQ(e.model, "Compact");
  EXPECT_NEAR(*e.focal_length_mm, 4.5, kExact);
  EXPECT_NEAR(*e.focal_length_px, 4.5 * 5080.0 / 25.4, kExact);
  EXPECT_FALSE(e.pixel_width);
  EXPECT_NEAR(*e.latitude_deg, -(33.0 + 51.0 / 60.0 + 36.0 / 3600.0), kExact);
  EXPECT_NEAR(*e.longitude_deg, -(151.0 + 12.0 / 60.0 + 36.0 / 3600.0), kExact);
  EXPECT_FALSE(e.altitude_m);
  EXPECT_FALSE(e.utc_offset);
  EXPECT_EQ(error_message([&] { e.time_iso8601(std::nullopt, "capture.tif"); }),
            "'capture.tif': the EXIF time 2023:12:01 08:30:00 has no UTC offset "
            "(OffsetTimeOriginal, EXIF 2.31); give it with --utc-offset");
  EXPECT_EQ(e.time_iso8601("+11:00", "capture.tif"), "2023-12-01T08:30:00+11:00");
}

TEST(Exif, OtherFilesAreRefusedByName) {
  EXPECT_THROW(read_exif(kDir + "make_fixtures.py"), InvalidArgument);
  EXPECT_THROW(read_exif(kDir + "missing.jpg"), IoError);
  // A TIFF whose first IFD starts beyond the 64 KiB libexif reads.
  const char far[] = {'I', 'I', '*', '\0', '\0', '\0', '\1', '\0'};  // IFD0 at 65 536
  EXPECT_EQ(error_message([&] { parse_exif(far, "big.tif"); }),
            "'big.tif': its first IFD lies beyond the first 64 KiB, which libexif does not read; "
            "give the capture's JPEG");
  const ExifInfo none;
  EXPECT_EQ(error_message([&] { none.time_iso8601(std::nullopt, "x.jpg"); }),
            "'x.jpg': the EXIF has no DateTimeOriginal");
}

}  // namespace
}  // namespace skylight::io
