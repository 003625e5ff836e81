#include "skylight/core/numbers.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <string>

#include "skylight/core/error.h"
#include "support/error_message.h"

namespace skylight {
namespace {

TEST(Numbers, AcceptsDecimalLiterals) {
  EXPECT_EQ(parse_number("0"), 0.0);
  EXPECT_EQ(parse_number("-1.5e-3"), -1.5e-3);
  EXPECT_EQ(parse_number("+2"), 2.0);
  EXPECT_EQ(parse_number(".5"), 0.5);
  EXPECT_EQ(parse_number("5."), 5.0);
  EXPECT_EQ(parse_number("1E+2"), 100.0);
  EXPECT_TRUE(std::signbit(*parse_number("-0")));
  EXPECT_EQ(parse_number("1.7976931348623157e308"), DBL_MAX);
}

TEST(Numbers, AcceptsSubnormals) {
  ASSERT_TRUE(parse_number("1e-310").has_value());
  EXPECT_EQ(std::fpclassify(*parse_number("1e-310")), FP_SUBNORMAL);
  EXPECT_EQ(parse_number("4.9e-324"), std::numeric_limits<double>::denorm_min());
}

TEST(Numbers, RejectsEverythingElse) {
  for (const char* bad : {"",    " 1",   "1 ",  "1e",  "1e+",   "5x",     "0x10",   "0X1p3",
                          "inf", "-inf", "nan", "NaN", "1e400", "-1e400", "1e-400", "+-1",
                          "--1", "1,5",  ".",   "-.",  "e5",    "1.2.3",  "\t2",    "1\n"})
    EXPECT_FALSE(parse_number(bad).has_value()) << "'" << bad << "'";
}

TEST(Numbers, IntegersAreWholeDecimalNumbers) {
  EXPECT_EQ(parse_integer("42"), 42);
  EXPECT_EQ(parse_integer("+7"), 7);
  EXPECT_EQ(parse_integer("-3"), -3);
  for (const char* bad :
       {"", "4.0", "1e3", "0x10", " 1", "1 ", "-", "+", "+-1", "99999999999999999999"})
    EXPECT_FALSE(parse_integer(bad).has_value()) << "'" << bad << "'";
}

TEST(Numbers, ErrorsNameTheFieldAndQuoteAnExcerpt) {
  using testing_support::error_message;
  EXPECT_EQ(error_message([] { parse_number("12abc", "--turbidity"); }),
            "--turbidity: '12abc' is not a number");
  EXPECT_EQ(error_message([] { parse_integer("4.5", "--cie-type"); }),
            "--cie-type: '4.5' is not an integer");
  // A number a double cannot hold says which way it fails.
  EXPECT_EQ(error_message([] { parse_number("1e-400", "--zenith-luminance"); }),
            "--zenith-luminance: '1e-400' underflows to 0 (the smallest non-zero number is "
            "4.94e-324)");
  EXPECT_EQ(error_message([] { parse_number("-1e400", "--albedo"); }),
            "--albedo: '-1e400' overflows (the largest number is 1.8e+308)");
}

TEST(Numbers, ListsRejectEmptyElements) {
  EXPECT_EQ(parse_number_list("1,2.5,-3", "--x"), (std::vector<double>{1.0, 2.5, -3.0}));
  EXPECT_EQ(parse_number_list("7", "--x"), (std::vector<double>{7.0}));
  for (const char* bad : {"", "1,,2", "1,2,", ",1", "1, 2", "1,x"})
    EXPECT_THROW(parse_number_list(bad, "--x"), InvalidArgument) << "'" << bad << "'";
  EXPECT_EQ(testing_support::error_message([] { parse_number_list("550,,650", "--wavelengths"); }),
            "--wavelengths: element 2 of '550,,650' is empty");
}

TEST(Numbers, ExcerptIsBoundedAndPrintable) {
  EXPECT_EQ(excerpt("abc"), "abc");
  EXPECT_EQ(excerpt(std::string("a\nb\0c\x1b'\\", 8)), "a\\nb\\x00c\\x1b\\'\\\\");
  const std::string huge(10'000'000, 'x');
  const std::string e = excerpt(huge);
  EXPECT_LT(e.size(), 100u);
  EXPECT_NE(e.find("(10000000 characters)"), std::string::npos);
}

}  // namespace
}  // namespace skylight
