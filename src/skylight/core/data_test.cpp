#include "skylight/core/data.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "skylight/core/error.h"
#include "support/error_message.h"

namespace skylight {
namespace {

std::string error_of(const std::function<void()>& f) {
  return testing_support::error_message<IoError>(f, "");
}

TEST(Data, EveryTableIsEmbedded) {
  const auto files = data::embedded_files();
  EXPECT_GE(files.size(), 10u);
  // 471 rows of CMFs; CRLF line endings are accepted.
  EXPECT_EQ(data::load_table("cie_colorimetry/CIE_xyz_1931_2deg.csv", false, 4).rows(), 471u);
  EXPECT_EQ(data::load_table("cie_colorimetry/CIE_illum_Dxx_comp.csv", false, 4).rows(), 107u);
  EXPECT_NE(error_of([] { data::embedded_file("nope.csv"); }).find("nope.csv"), std::string::npos);
}

TEST(Data, BadFieldIsNamedWithLineAndColumn) {
  const data::CsvTable t("a,b\n1,2\n3,x7\n", "test.csv", true);
  EXPECT_EQ(t.number(0, 1), 2.0);
  const std::string msg = error_of([&] { t.number(1, 1); });
  EXPECT_NE(msg.find("test.csv line 3 column 2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'x7'"), std::string::npos) << msg;
  EXPECT_NE(error_of([&] { data::CsvTable("a,b\n1,2,3\n", "t.csv", true); }).find("t.csv line 2"),
            std::string::npos);
  EXPECT_EQ(error_of([&] { data::CsvTable("a\nnan\n", "n.csv", true).number(0, 0); }),
            "n.csv line 2 column 1: 'nan' is not a number")
      << "NaN in a table is an error";
  EXPECT_EQ(error_of([&] { data::CsvTable("a\n-1e-999\n", "u.csv", true).number(0, 0); }),
            "u.csv line 2 column 1: '-1e-999' underflows to 0 (the smallest non-zero number is "
            "4.94e-324)");
  EXPECT_NE(error_of([&] { t.column("c"); }).find("no column 'c'"), std::string::npos);
}

}  // namespace
}  // namespace skylight
