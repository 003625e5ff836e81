#include "skylight/io/file.h"

#include <gtest/gtest.h>

#include <string>

namespace skylight::io {
namespace {

TEST(File, OneLineJoinsLinesEscapesControlCharactersAndBoundsTheLength) {
  EXPECT_EQ(one_line("first\nsecond\r\n"), "first second");
  // Found by the fuzz target image_exr (docs/TESTING.md): OpenEXR quotes a channel name from the
  // file, control characters included.
  EXPECT_EQ(one_line(std::string("channel \"\x01\x1b\x7f\" is invalid")),
            "channel \"\\x01\\x1b\\x7f\" is invalid");
  const std::string cut = one_line(std::string(100000, 'a'));
  EXPECT_EQ(cut.size(), kMaxOneLineChars + 3);
  EXPECT_EQ(cut.substr(cut.size() - 4), "a...");
}

}  // namespace
}  // namespace skylight::io
