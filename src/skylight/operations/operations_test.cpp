#include "skylight/operations/operations.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace skylight
