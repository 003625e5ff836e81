// The operations framework on a toy operation: prepare() refuses every usage error before any
// work, with the messages the front ends show (unknown names with the nearest one, values out of
// range, missing required values, broken relations, files), warns of and drops what a request does
// not read; execute() commits all outputs or none, keeps outputs in memory for a front end that
// asks, and refuses a record with a non-finite number or an undeclared field; text_of() writes a
// record's labelled lines from its declared fields.
#include "skylight/operations/operation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "skylight/io/file.h"
#include "support/scratch_dir.h"

namespace skylight::operations {
namespace {

namespace fs = std::filesystem;

std::string p(const testing_support::ScratchDir& dir, const std::string& name) {
  return (dir / name).string();
}

struct Toy {
  double area = 0.0;
  std::optional<double> ratio;  // null without --divisor
  std::vector<std::string> names;
};

ResultSchema<Toy> toy_result() {
  ResultSchema<Toy> s;
  s.number("area_m2", "m^2", "the area", &Toy::area)
      .number("ratio", "1", "width / divisor; null without one", &Toy::ratio)
      .texts("names", "what was written", &Toy::names);
  return s;
}

ParameterSpec number(std::string name, double min, double max, ParameterDefault d) {
  return {.name = std::move(name),
          .unit = "m",
          .kind = ParameterKind::number,
          .min = min,
          .max = max,
          .default_value = std::move(d),
          .description = "a length"};
}

ParameterSpec file(std::string name, FileRole role, std::vector<std::string> formats,
                   ParameterDefault d = Absent{"none"}) {
  return {.name = std::move(name),
          .kind = ParameterKind::text,
          .default_value = std::move(d),
          .description = "a file",
          .file = role,
          .formats = std::move(formats)};
}

// width x height written as text to --output (required) and --log (optional); --divisor gives the
// ratio; --scale is read only with --divisor; --nan makes the area NaN (a defect the framework
// must catch); --input a text file read; --fail fails after the first output is written.
OperationInfo toy() {
  OperationInfo op;
  op.name = "toy";
  op.description = "a toy operation";
  op.parameters = {number("width", 0, 10, Required{}),
                   number("height", 0, 10, ParameterValue(2.0)),
                   number("divisor", 1, 10, Absent{"none"}),
                   number("scale", 1, 10, Absent{"none"}),
                   number("radius", 0, 10, Absent{"none"}),
                   {.name = "nan",
                    .kind = ParameterKind::flag,
                    .default_value = ParameterValue(false),
                    .description = "a NaN area"},
                   {.name = "fail",
                    .kind = ParameterKind::flag,
                    .default_value = ParameterValue(false),
                    .description = "fail after writing the output"},
                   file("input", FileRole::input, {".txt"}),
                   file("output", FileRole::output, {".txt"}, Required{}),
                   file("log", FileRole::output, {".txt", ".csv"})};
  op.relations = {excludes("radius", "height", "a disc has no height"), needs("divisor", "width"),
                  unread_without("scale", "divisor")};
  op.result = toy_result().fields();
  op.check = [](Request& r) {
    if (r.number("width") == 0.0 && r.given("divisor"))
      throw InvalidArgument("width 0 with a divisor");
  };
  op.run = [](const Request& r, const ProgressSink&) {
    Result out;
    Toy t;
    const double w = *r.number("width");
    const double h = r.number("height").value_or(2.0);
    t.area = r.given("nan") && std::get<bool>(*r.values().find("nan")) ? std::nan("") : w * h;
    if (r.given("divisor")) t.ratio = w / *r.number("divisor") * r.number("scale").value_or(1.0);
    std::string text = "area " + std::to_string(t.area) + "\n";
    if (r.has_input("input")) text += r.text_file("input");
    r.write_text(out, "output", text);
    t.names.push_back("output");
    if (r.given("fail") && std::get<bool>(*r.values().find("fail")))
      throw std::runtime_error("failed after the output");
    if (r.output_wanted("log")) {
      r.write_text(out, "log", "log\n");
      t.names.push_back("log");
    }
    r.progress(1, 1, "done");
    out.record = toy_result().record(t);
    return out;
  };
  return op;
}

ParameterValues values(std::initializer_list<std::pair<const char*, ParameterValue>> list) {
  ParameterValues v;
  for (const auto& [name, value] : list) v.set(name, value);
  return v;
}

std::string usage_error(const OperationInfo& op, ParameterValues v, Frontend fe = {}) {
  try {
    (void)prepare(op, std::move(v), std::move(fe));
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "(no error)";
}

struct Warnings {
  std::vector<std::string> lines;
  Frontend frontend() {
    Frontend fe;
    fe.warn = [this](const std::string& w) { lines.push_back(w); };
    return fe;
  }
};

TEST(Operation, PrepareRefusesUnknownNamesWithTheNearestOne) {
  const OperationInfo op = toy();
  const std::string out = (testing_support::ScratchDir() / "o.txt").string();
  EXPECT_EQ(usage_error(op, values({{"width", 1.0}, {"hieght", 2.0}, {"output", out}})),
            "hieght is not a parameter of toy; did you mean 'height'?");
  EXPECT_EQ(usage_error(op, values({{"width", 11.0}, {"output", out}})).substr(0, 7), "width =");
  EXPECT_EQ(usage_error(op, values({{"output", out}})).find("width"), 0u)
      << usage_error(op, values({{"output", out}}));
}

TEST(Operation, PrepareChecksRelationsAndWarnsOfWhatIsNotRead) {
  const OperationInfo op = toy();
  testing_support::ScratchDir dir;
  const std::string out = p(dir, "o.txt");
  EXPECT_EQ(
      usage_error(op, values({{"width", 1.0}, {"radius", 1.0}, {"height", 1.0}, {"output", out}})),
      "radius and height exclude each other (a disc has no height)");
  EXPECT_EQ(usage_error(op, values({{"width", 0.0}, {"divisor", 2.0}, {"output", out}})),
            "width 0 with a divisor");  // op.check runs last
  Warnings w;
  Request r = prepare(op, values({{"width", 4.0}, {"scale", 3.0}, {"output", out}}), w.frontend());
  ASSERT_EQ(w.lines.size(), 1u);
  EXPECT_EQ(w.lines[0], "scale is not read without divisor; ignored");
  EXPECT_FALSE(r.given("scale"));  // dropped: the work never sees it
  EXPECT_FALSE(fs::exists(out));   // prepare does no work
}

TEST(Operation, PrepareChecksFilesBeforeAnyWork) {
  const OperationInfo op = toy();
  testing_support::ScratchDir dir;
  const std::string in = p(dir, "in.txt"), out = p(dir, "o.txt");
  std::ofstream(in) << "hello\n";
  auto error = [&](std::initializer_list<std::pair<const char*, ParameterValue>> extra) {
    ParameterValues v = values({{"width", 1.0}});
    for (const auto& [n, x] : extra) v.set(n, x);
    return usage_error(op, v);
  };
  EXPECT_NE(error({{"input", p(dir, "nope.txt")}, {"output", out}})
                .find("nope.txt': no such "
                      "file"),
            std::string::npos);
  EXPECT_NE(error({{"input", p(dir, "")}, {"output", out}}).find("is a directory"),
            std::string::npos);
  EXPECT_NE(error({{"output", p(dir, "o.exr")}}).find("write .txt"), std::string::npos);
  EXPECT_NE(error({{"input", in}, {"output", in}})
                .find("is the input input: an output never overwrites an input"),
            std::string::npos);
  EXPECT_NE(error({{"output", out}, {"log", p(dir, "./o.txt")}})
                .find("output and log name the same file"),
            std::string::npos);
  // An output's missing directory is an I/O error (exit 1), not a usage error.
  EXPECT_THROW((void)prepare(op, values({{"width", 1.0}, {"output", p(dir, "no/o.txt")}}), {}),
               IoError);
  EXPECT_EQ(error({{"input", in}, {"output", out}}), "(no error)");
  EXPECT_FALSE(fs::exists(out));
}

TEST(Operation, ExecuteCommitsEveryOutputOrNone) {
  const OperationInfo op = toy();
  testing_support::ScratchDir dir;
  const std::string out = p(dir, "o.txt"), log = p(dir, "l.csv");
  // A failure after the first output was written: neither file exists.
  Request failing =
      prepare(op, values({{"width", 3.0}, {"fail", true}, {"output", out}, {"log", log}}), {});
  EXPECT_THROW((void)execute(failing), std::runtime_error);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(log));
  // A NaN in the record is refused and nothing is written.
  Request nan = prepare(op, values({{"width", 3.0}, {"nan", true}, {"output", out}}), {});
  try {
    (void)execute(nan);
    ADD_FAILURE() << "a NaN record was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "the result's area_m2 is not finite; nothing was written");
  }
  EXPECT_FALSE(fs::exists(out));
  // A failure of the front end's presentation writes nothing either.
  Request good = prepare(op, values({{"width", 3.0}, {"output", out}, {"log", log}}), {});
  EXPECT_THROW((void)execute(good, [](const Result&) { throw IoError("stdout closed"); }), IoError);
  EXPECT_FALSE(fs::exists(out));
  const Result r = execute(good);
  EXPECT_EQ(testing_support::slurp(out), "area 6.000000\n");
  EXPECT_EQ(testing_support::slurp(log), "log\n");
  EXPECT_EQ(r.record.dump(), R"({"area_m2":6.0,"ratio":null,"names":["output","log"]})");
  EXPECT_EQ(r.notices.size(), 2u);
}

TEST(Operation, OutputsWithoutAPathStayInMemoryForAFrontEndThatKeepsThem) {
  const OperationInfo op = toy();
  // Without keep_outputs the required output is missing.
  EXPECT_NE(usage_error(op, values({{"width", 2.0}})).find("output"), std::string::npos);
  Frontend fe;
  fe.keep_outputs = true;
  fe.texts["input"] = "from memory\n";
  int steps = 0;
  fe.progress = [&](int done, int total, std::string_view step) {
    EXPECT_EQ(done, total);
    EXPECT_EQ(step, "done");
    ++steps;
  };
  const Result r = execute(prepare(op, values({{"width", 2.0}, {"divisor", 4.0}}), fe));
  EXPECT_EQ(r.texts.at("output"), "area 4.000000\nfrom memory\n");
  EXPECT_EQ(r.texts.count("log"), 0u);  // an optional output not asked for is not made
  EXPECT_EQ(r.record["ratio"].get<double>(), 0.5);
  EXPECT_EQ(steps, 1);
}

TEST(Operation, ResultSchemaDeclaresNullableFieldsFromOptionalMembers) {
  const auto fields = toy_result().fields();
  ASSERT_EQ(fields.size(), 3u);
  EXPECT_FALSE(fields[0].nullable);
  EXPECT_TRUE(fields[1].nullable);
  EXPECT_EQ(fields[2].kind, FieldKind::texts);
}

TEST(Operation, TextOfLabelsFieldsWithoutTheirUnitSuffixAndSkipsNulls) {
  const auto fields = toy_result().fields();
  Toy t{.area = 12.5, .ratio = std::nullopt, .names = {"a", "b"}};
  EXPECT_EQ(text_of(fields, toy_result().record(t)), "area   12.5 m^2\nnames  a,b\n");
  t.ratio = 1.0 / 3.0;
  EXPECT_EQ(text_of(fields, toy_result().record(t)),
            "area   12.5 m^2\nratio  0.3333333\nnames  a,b\n");
  // Two fields that would read alike keep their suffixes.
  std::vector<FieldSpec> alike = {{.name = "elevation_m", .unit = "m"},
                                  {.name = "elevation_deg", .unit = "deg"}};
  Record rec = {{"elevation_m", 500}, {"elevation_deg", 30.5}};
  EXPECT_EQ(text_of(alike, rec), "elevation m    500 m\nelevation deg  30.5 deg\n");
  // Lines the work lays out itself come verbatim, without a label.
  struct Table {
    std::vector<std::string> lines;
  };
  ResultSchema<Table> table;
  table.lines("lines", "a table", &Table::lines);
  EXPECT_EQ(text_of(table.fields(), table.record(Table{{"model  ms", "cie    0.5"}})),
            "model  ms\ncie    0.5\n");
}

}  // namespace
}  // namespace skylight::operations
