// The precomputed orders' tables (scattering_orders.h): their file cache. Their physics is tested
// through the `bruneton` model (models/bruneton_test.cpp: one order is nishita, each order adds
// less light than the one before, the error against the path tracer by day and in twilight).
#include "skylight/atmosphere/scattering_orders.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "skylight/core/progress.h"
#include "skylight/io/file.h"
#include "skylight/io/table_cache.h"
#include "support/scratch_dir.h"

namespace skylight::atmosphere {
namespace {

// With SKYLIGHT_TABLE_CACHE set the tables are computed once, stored, and read back equal (no
// computation: no progress reported); a damaged file is not used but computed again and replaced.
TEST(ScatteringOrders, TablesAreStoredInTheTableCacheAndReadBackEqual) {
  testing_support::ScratchDir dir;
  // The suite's own cache directory (scripts/test.sh sets one for the whole run) comes back after.
  const char* before = std::getenv(io::kTableCacheVariable);
  const std::string suite_cache = before ? before : "";
  ::setenv(io::kTableCacheVariable, dir.path().c_str(), 1);
  const Atmosphere atm(AtmosphereParameters{});
  // The tables' wavelengths (any ascending set; the model's are 22 from 360 to 830 nm).
  const std::vector<double> nm{400.0, 550.0, 700.0};
  std::vector<std::string> steps;
  const ScopedProgressSink sink([&](int, int, std::string_view s) { steps.emplace_back(s); });
  const ScatteringOrderTables computed =
      load_or_compute_order_tables(atm, nm, OrderSettings::exactly(2));
  EXPECT_GE(steps.size(), 2u);  // the orders one by one, then done
  ASSERT_EQ(dir.entries().size(), 1u);
  const auto file = dir.path() / dir.entries()[0];
  EXPECT_EQ(file.extension(), ".table");
  const auto same = [&](const ScatteringOrderTables& t) {
    EXPECT_EQ(t.components, computed.components);
    EXPECT_EQ(t.q, computed.q);
    EXPECT_EQ(t.ground_irradiance, computed.ground_irradiance);
    EXPECT_EQ(t.cpu_seconds, computed.cpu_seconds);  // the stored precomputation's
  };
  steps.clear();
  same(load_or_compute_order_tables(atm, nm, OrderSettings::exactly(2)));
  EXPECT_EQ(steps, std::vector<std::string>{"bruneton's tables: read from the table cache"});
  std::vector<char> bytes = io::read_file(file);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 1);
  std::ofstream(file, std::ios::binary).write(bytes.data(), static_cast<long>(bytes.size()));
  steps.clear();
  {
    // As inside a CLI command: the cache file is neither an input nor an output of the command's
    // transaction (reading the damaged file and replacing it is not "an output naming an input").
    io::OutputTransaction command;
    const ScatteringOrderTables again =
        load_or_compute_order_tables(atm, nm, OrderSettings::exactly(2));
    EXPECT_GE(steps.size(), 2u);  // computed
    EXPECT_EQ(again.q, computed.q);
    EXPECT_NE(io::read_file(file), bytes);  // replaced by an intact file before the commit
    command.commit();
  }
  EXPECT_EQ(dir.entries().size(), 1u);  // no temporary left
  if (before)
    ::setenv(io::kTableCacheVariable, suite_cache.c_str(), 1);
  else
    ::unsetenv(io::kTableCacheVariable);
}

}  // namespace
}  // namespace skylight::atmosphere
