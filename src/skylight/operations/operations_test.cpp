#include "skylight/operations/operations.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <set>
#include <string>

#include "support/scratch_dir.h"

namespace skylight {
namespace {

TEST(Operations, DocsTablesMatchTheSchemas) {
  const std::string doc = testing_support::source_file("docs/OPERATIONS.md");
  ASSERT_FALSE(doc.empty()) << "docs/OPERATIONS.md not found";
  for (const auto& op : operations::registry()) {
    const std::string block = operations::markdown(op);
    EXPECT_NE(doc.find(block), std::string::npos)
        << "docs/OPERATIONS.md lacks this table of '" << op.name
        << "' (regenerate it with `skylight operations --markdown`):\n"
        << block;
  }
}

TEST(Operations, NamesAndParametersAreUnique) {
  std::set<std::string> names;
  for (const auto& op : operations::registry()) {
    EXPECT_TRUE(names.insert(op.name).second) << op.name;
    EXPECT_EQ(&operations::find(op.name), &op);
    EXPECT_FALSE(op.description.empty()) << op.name;
    std::set<std::string> params;
    for (const auto& p : op.parameters) {
      EXPECT_TRUE(params.insert(p.name).second) << op.name << ": " << p.name;
      EXPECT_FALSE(p.description.empty()) << op.name << ": " << p.name;
    }
  }
  EXPECT_GE(names.size(), 20u);  // render, eval, estimate, sun, bench, report, sh *, haze *, nn *
}

// Every operation is executable and its declaration is whole: work and a result, relations between
// parameters it has, result fields named once, file parameters of text kind, an output's
// formats; and the JSON front ends read carries all of it.
TEST(Operations, EveryOperationIsExecutableAndItsDeclarationsAreConsistent) {
  const nlohmann::json json = nlohmann::json::parse(operations::operations_json());
  ASSERT_EQ(json.size(), operations::registry().size());
  std::size_t i = 0;
  for (const auto& op : operations::registry()) {
    SCOPED_TRACE(op.name);
    EXPECT_TRUE(static_cast<bool>(op.run));
    EXPECT_FALSE(op.result.empty());
    for (const auto& r : op.relations) {
      EXPECT_NE(op.find(r.a), nullptr) << r.a;
      EXPECT_NE(op.find(r.b), nullptr) << r.b;
      EXPECT_NE(r.a, r.b);
    }
    std::set<std::string> fields;
    for (const auto& f : op.result) {
      EXPECT_TRUE(fields.insert(f.name).second) << f.name;
      EXPECT_FALSE(f.meaning.empty()) << f.name;
      const bool nested =
          f.kind == operations::FieldKind::record || f.kind == operations::FieldKind::records;
      EXPECT_EQ(nested, !f.fields.empty()) << f.name;
    }
    for (const auto& p : op.parameters) {
      if (p.file != FileRole::none) {
        EXPECT_EQ(p.kind, ParameterKind::text) << p.name;
      }
    }
    const auto& j = json[i++];
    EXPECT_EQ(j["name"], op.name);
    EXPECT_EQ(j["relations"].size(), op.relations.size());
    EXPECT_EQ(j["result"]["fields"].size(), op.result.size());
    EXPECT_EQ(j["parameters"].size(), op.parameters.size());
  }
}

}  // namespace
}  // namespace skylight
