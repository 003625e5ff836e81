#include "skylight/core/parameters.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <string>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "support/error_message.h"

namespace skylight {
namespace {

// A parameter struct of every field kind the schema binds.
struct Example {
  double height_m = 2.0;
  double angle = 0.0;  // [rad]; the user gives degrees
  std::optional<double> optional_scale;
  int count = 3;
  std::optional<std::array<double, 2>> pair;
  std::string path;
  bool fast = false;

  static const ParameterSchema<Example>& schema() {
    static const auto s = [] {
      ParameterSchema<Example> s;
      s.number(&Example::height_m, {.name = "height",
                                    .unit = "m",
                                    .min = 0.0,
                                    .max = 10.0,
                                    .default_value = ParameterValue(2.0),
                                    .description = "a height"});
      s.number(&Example::angle,
               {.name = "angle",
                .unit = "deg",
                .min = -90.0,
                .max = 90.0,
                .default_value = ParameterValue(0.0),
                .description = "an angle"},
               kDegree);
      s.optional_number(&Example::optional_scale, {.name = "scale",
                                                   .unit = "1",
                                                   .min = 0.5,
                                                   .max = 2.0,
                                                   .default_value = Absent{"no scaling"},
                                                   .description = "a factor"});
      s.integer(&Example::count, {.name = "count",
                                  .unit = "1",
                                  .kind = ParameterKind::integer,
                                  .min = 1,
                                  .max = 9,
                                  .default_value = ParameterValue(3.0),
                                  .description = "a count"});
      s.optional_numbers(&Example::pair, {.name = "pair",
                                          .unit = "1",
                                          .kind = ParameterKind::numbers,
                                          .min = -1.0,
                                          .max = 1.0,
                                          .count = 2,
                                          .default_value = Required{},
                                          .description = "two values"});
      s.text(&Example::path, {.name = "path",
                              .kind = ParameterKind::text,
                              .default_value = Absent{"none"},
                              .description = "a file"});
      s.flag(&Example::fast,
             {.name = "fast", .kind = ParameterKind::flag, .description = "go fast"});
      return s;
    }();
    return s;
  }
};

TEST(Parameters, BindAppliesValuesOverDefaultsAndConvertsUnits) {
  Example e;
  ParameterValues v;
  v.set("angle", 30.0).set("pair", std::vector<double>{0.5, -0.5}).set("fast", true);
  v.set("count", 7.0).set("path", std::string("sky.exr"));
  Example::schema().bind(v, e, "test");
  EXPECT_EQ(e.height_m, 2.0);  // default kept
  EXPECT_DOUBLE_EQ(e.angle, 30.0 * kDegree);
  EXPECT_FALSE(e.optional_scale.has_value());
  EXPECT_EQ(e.count, 7);
  ASSERT_TRUE(e.pair.has_value());
  EXPECT_EQ((*e.pair)[1], -0.5);
  EXPECT_EQ(e.path, "sky.exr");
  EXPECT_TRUE(e.fast);
  // Back to named values in the user's units.
  const ParameterValues back = Example::schema().values_of(e);
  EXPECT_DOUBLE_EQ(*back.number("angle"), 30.0);
  EXPECT_EQ(*back.number("height"), 2.0);
  EXPECT_FALSE(back.has("scale"));
}

TEST(Parameters, BindRejectsUnknownMissingAndOutOfRange) {
  Example e;
  const auto& s = Example::schema();
  EXPECT_EQ(testing_support::error_message([&] { s.bind(ParameterValues(), e, "model 'x'"); }),
            "pair is required (model 'x'): two values");
  const auto pair = ParameterValue(std::vector<double>{0, 0});
  EXPECT_EQ(testing_support::error_message(
                [&] { s.bind(ParameterValues().set("pair", pair).set("bogus", 1.0), e, "t"); }),
            "bogus is not a parameter (t) (parameters: height, angle, scale, count, "
            "pair, path, fast)");
  EXPECT_EQ(testing_support::error_message(
                [&] { s.bind(ParameterValues().set("pair", pair).set("height", 11.0), e, "t"); }),
            "height = 11 is outside [0, 10] (t)");
  EXPECT_EQ(testing_support::error_message(
                [&] { s.bind(ParameterValues().set("pair", pair).set("count", 2.5), e, "t"); }),
            "count = 2.5 is not an integer (t)");
  EXPECT_EQ(testing_support::error_message([&] {
              s.bind(ParameterValues().set("pair", std::vector<double>{0, 0, 0}), e, "t");
            }),
            "pair needs 2 values, got 3 (t)");
  EXPECT_EQ(testing_support::error_message([&] {
              s.bind(ParameterValues().set("pair", std::vector<double>{0, 1.5}), e, "t");
            }),
            "pair = 1.5 (value 2) is outside [-1, 1] (t)");
  EXPECT_NE(testing_support::error_message([&] {
              s.bind(ParameterValues().set("pair", pair).set("height", std::nan("")), e, "t");
            }),
            "no error");
  EXPECT_NE(testing_support::error_message(
                [&] { s.bind(ParameterValues().set("pair", pair).set("path", 1.0), e, "t"); }),
            "no error");
}

TEST(Parameters, ValidateChecksAStructBuiltInCode) {
  Example e;
  e.pair = std::array<double, 2>{0.0, 0.0};
  EXPECT_NO_THROW(Example::schema().validate(e, "t"));
  e.angle = 100 * kDegree;
  EXPECT_EQ(testing_support::error_message([&] { Example::schema().validate(e, "t"); }),
            "angle = 100 is outside [-90, 90] (t)");
  e.angle = 0;
  e.pair.reset();
  EXPECT_EQ(testing_support::error_message([&] { Example::schema().validate(e, "t"); }),
            "pair is required (t): two values");
}

// A front end's spelling (the CLI's flags) reaches every message of the schema; the library's own
// is the name.
TEST(Parameters, MessagesUseTheFrontEndsSpelling) {
  Example e;
  e.pair = std::array<double, 2>{0.0, 0.0};
  e.angle = 100 * kDegree;
  set_parameter_spelling([](std::string_view name) { return fmt::format("<{}>", name); });
  const std::string spelled_by_front_end =
      testing_support::error_message([&] { Example::schema().validate(e, "t"); });
  const std::string unknown = testing_support::error_message([&] {
    Example::schema().bind(ParameterValues().set("pair", std::vector<double>{0, 0}).set("x", 1.0),
                           e, "t");
  });
  set_parameter_spelling(nullptr);
  EXPECT_EQ(spelled_by_front_end, "<angle> = 100 is outside [-90, 90] (t)");
  EXPECT_EQ(unknown.rfind("<x> is not a parameter (t) (parameters: <height>, <angle>", 0), 0u)
      << unknown;
  EXPECT_EQ(spelled("angle"), "angle");
}

TEST(Parameters, TextFormsAndMetadataKeys) {
  const auto& specs = Example::schema().entries();
  EXPECT_EQ(specs[0].spec.metadata_key(), "skylight:height_m");
  EXPECT_EQ(specs[1].spec.metadata_key(), "skylight:angle_deg");
  EXPECT_EQ(specs[2].spec.metadata_key(), "skylight:scale");
  EXPECT_EQ(specs[2].spec.default_text(), "none (no scaling)");
  EXPECT_EQ(specs[4].spec.default_text(), "required");
  EXPECT_EQ(specs[0].spec.help(), "a height [m], 0 .. 10; default 2");
  // An integer's bounds and default are written whole; a dimensionless unit is not shown.
  const ParameterSpec seed{.name = "seed",
                           .unit = "1",
                           .kind = ParameterKind::integer,
                           .min = 0,
                           .max = 2147483647,
                           .default_value = ParameterValue{1234567.0},
                           .description = "a seed"};
  EXPECT_EQ(seed.range_text(), "0 .. 2147483647");
  EXPECT_EQ(seed.help(), "a seed, 0 .. 2147483647; default 1234567");
  EXPECT_EQ(std::get<std::vector<double>>(specs[4].spec.parse("0.5,-1")),
            (std::vector<double>{0.5, -1.0}));
  EXPECT_EQ(specs[4].spec.format(std::vector<double>{0.5, -1.0}), "0.5,-1");
  EXPECT_EQ(specs[0].spec.format(0.1), "0.1");  // shortest round trip
  EXPECT_THROW(specs[0].spec.parse("0x1"), InvalidArgument);
  EXPECT_THROW(specs[3].spec.parse("2.5"), InvalidArgument);
  EXPECT_THROW(specs[4].spec.parse("1,,2"), InvalidArgument);
  const std::string table = markdown_table(Example::schema().specs());
  EXPECT_NE(table.find("| `--pair` | 1 | 2 values, each -1 .. 1 | required | two values |"),
            std::string::npos)
      << table;
}

}  // namespace
}  // namespace skylight
