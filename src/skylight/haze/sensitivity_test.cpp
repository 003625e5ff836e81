#include "skylight/haze/sensitivity.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "skylight/core/error.h"
#include "support/error_message.h"

namespace skylight::haze {
namespace {

TEST(HazeCamera, EmbeddedCamerasByNormalisedName) {
  const auto names = camera_names();
  EXPECT_EQ(names.size(), 40u);  // data/camera_sensitivity/PROVENANCE.md: 40 cameras
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  for (const char* n : {"canon-eos-5d", "sony-ilce-7m3", "arashi-vision-insta360-x5",
                        "canon-eos-1d-x-mark-ii", "nikon-z-f"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
  const CameraSensitivity& eos = find_camera("canon-eos-5d");
  EXPECT_EQ(eos.description, "Canon EOS 5D");
  for (const Spectrum& q : eos.channel) {
    EXPECT_EQ(q.size(), 81u);
    EXPECT_DOUBLE_EQ(q.min_nm(), 380.0);
    EXPECT_DOUBLE_EQ(q.max_nm(), 780.0);
  }
  // The CSV's first R sample of the Insta360 X5 (row 2 of the file), exactly.
  EXPECT_EQ(find_camera("arashi-vision-insta360-x5").channel[0](380.0), 0.00012566972686144686);
  // Blue peaks in the blue, red in the red.
  EXPECT_GT(eos.channel[2](450.0), eos.channel[2](620.0));
  EXPECT_GT(eos.channel[0](620.0), eos.channel[0](450.0));
}

TEST(HazeCamera, UnknownNameListsTheKnownOnes) {
  try {
    find_camera("canon eos 5d");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("canon-eos-5d"), std::string::npos) << e.what();
  }
}

TEST(HazeCamera, UserCsvParsesStrictly) {
  const CameraSensitivity c =
      parse_camera_csv("nm,r,g,b\n370,0,0,1\n580,0.5,1,0.5\r\n800,1,0,0\n", "cam.csv");
  EXPECT_DOUBLE_EQ(c.channel[0](475.0), 0.25);
  EXPECT_DOUBLE_EQ(c.channel[1](580.0), 1.0);
  const auto message = [](const std::string& text) {
    return testing_support::error_message([&] { parse_camera_csv(text, "cam.csv"); });
  };
  EXPECT_EQ(message("nm,red,g,b\n380,1,1,1\n780,1,1,1\n"),
            "cam.csv line 1: the header must be 'nm,r,g,b', not 'nm,red,g,b'");
  EXPECT_EQ(message("nm,r,g,b\n380,1,1,1\n780,1,x,1\n"),
            "cam.csv line 3 column 3: 'x' is not a number");
  EXPECT_EQ(message("nm,r,g,b\n380,1,1,1\n780,1,-1,1\n"),
            "cam.csv line 3 column 3: '-1' is negative (a sensitivity is >= 0)");
  EXPECT_EQ(message("nm,r,g,b\n380,1,1,1\n380,1,1,1\n"),
            "cam.csv line 3: wavelength 380 nm is not above the previous 380 nm");
  EXPECT_EQ(message("nm,r,g,b\n400,1,1,1\n780,1,1,1\n"),
            "cam.csv: the wavelengths must cover 380 .. 780 nm");
  EXPECT_EQ(message("nm,r,g,b\n380,1,0,1\n780,1,0,1\n"),
            "cam.csv: channel g is zero over 380 .. 780 nm");
  EXPECT_EQ(message("nm,r,g,b\n380,1,1\n"), "cam.csv line 2: 3 fields, expected 4 (nm,r,g,b)");
  EXPECT_EQ(message(""), "cam.csv: empty (expected a header 'nm,r,g,b')");
}

}  // namespace
}  // namespace skylight::haze
