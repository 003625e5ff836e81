#include "skylight/core/text.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace skylight {
namespace {

TEST(Text, EditDistanceOfKnownPairs) {
  EXPECT_EQ(edit_distance("kitten", "sitting"),
            3u);  // the textbook pair: 2 substitutions, 1 insertion
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("abc", ""), 3u);
  EXPECT_EQ(edit_distance("same", "same"), 0u);
  EXPECT_EQ(edit_distance("turbidty", "turbidity"), 1u);
  EXPECT_EQ(edit_distance("flaw", "lawn"), 2u);
  EXPECT_EQ(edit_distance("trian", "train"), 1u);  // a swap of neighbours is one edit
  EXPECT_EQ(edit_distance("ca", "abc"), 3u);       // optimal string alignment (not 2)
  // Symmetric.
  EXPECT_EQ(edit_distance("sun-zenith", "zenith"), edit_distance("zenith", "sun-zenith"));
}

TEST(Text, NearestNameSuggestsTyposOnly) {
  const std::vector<std::string> flags{"--turbidity", "--albedo", "--sun-zenith", "--sun-azimuth"};
  EXPECT_EQ(nearest_name("--turbidty", flags), "--turbidity");
  EXPECT_EQ(nearest_name("--sun-zenit", flags), "--sun-zenith");
  EXPECT_EQ(nearest_name("--albdeo", flags), "--albedo");  // a swap: 2 edits of 8 characters
  EXPECT_FALSE(nearest_name("--frobnicate", flags).has_value());
  EXPECT_FALSE(nearest_name("--frob", std::vector<std::string>{"--fov"}).has_value());
  EXPECT_FALSE(nearest_name("-i", std::vector<std::string>{"-h", "-o"}).has_value());
  const std::vector<std::string> subcommands{"train", "validate", "export"};
  EXPECT_EQ(nearest_name("trian", subcommands), "train");
  EXPECT_FALSE(nearest_name("x", std::vector<std::string>{}).has_value());
  EXPECT_EQ(did_you_mean("--turbidty", flags), "; did you mean '--turbidity'?");
  EXPECT_EQ(did_you_mean("--frobnicate", flags), "");
}

}  // namespace
}  // namespace skylight
