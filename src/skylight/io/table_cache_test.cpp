#include "skylight/io/table_cache.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "skylight/io/file.h"
#include "support/scratch_dir.h"

namespace skylight::io {
namespace {

// SKYLIGHT_TABLE_CACHE set for one scope (the value before, the suite's, comes back after).
struct CacheVariable {
  explicit CacheVariable(const std::string& dir) {
    if (const char* v = std::getenv(kTableCacheVariable)) before = v;
    ::setenv(kTableCacheVariable, dir.c_str(), 1);
  }
  ~CacheVariable() {
    if (before)
      ::setenv(kTableCacheVariable, before->c_str(), 1);
    else
      ::unsetenv(kTableCacheVariable);
  }
  std::optional<std::string> before;
};

void write_bytes(const std::filesystem::path& p, const std::vector<char>& bytes) {
  std::ofstream(p, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

TEST(TableCache, OffUnlessTheVariableNamesADirectory) {
  {
    CacheVariable unset("");
    ::unsetenv(kTableCacheVariable);
    EXPECT_FALSE(table_cache_file("kind", "key"));
  }
  const CacheVariable empty("");
  EXPECT_FALSE(table_cache_file("kind", "key"));
}

TEST(TableCache, APayloadComesBackOnlyForItsKeyAndIntact) {
  testing_support::ScratchDir dir;
  const CacheVariable on(dir.path().string());
  const std::string key = "atmosphere 0x1.8p+22 | orders 4";
  const auto file = table_cache_file("tables", key);
  ASSERT_TRUE(file);
  EXPECT_EQ(file->parent_path(), dir.path());
  // Another key, another file.
  EXPECT_NE(*table_cache_file("tables", key + " "), *file);
  EXPECT_FALSE(read_cached_table(*file, key));  // nothing stored yet
  std::vector<char> payload(1000);
  for (std::size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<char>(i * 7);
  ASSERT_TRUE(write_cached_table(*file, key, payload));
  EXPECT_EQ(dir.entries().size(), 1u);  // no temporary left
  EXPECT_EQ(read_cached_table(*file, key), payload);
  EXPECT_FALSE(read_cached_table(*file, key + "x"));  // the file holds the whole key
  const std::vector<char> bytes = read_file(*file);
  // Each byte changed, or the file cut anywhere, is refused.
  for (const std::size_t at :
       {std::size_t{0}, std::size_t{20}, bytes.size() / 2, bytes.size() - 1}) {
    std::vector<char> bad = bytes;
    bad[at] = static_cast<char>(bad[at] ^ 0x10);
    write_bytes(*file, bad);
    EXPECT_FALSE(read_cached_table(*file, key)) << "byte " << at;
  }
  for (const std::size_t size : {std::size_t{0}, std::size_t{10}, bytes.size() - 1}) {
    write_bytes(*file, std::vector<char>(bytes.begin(), bytes.begin() + static_cast<long>(size)));
    EXPECT_FALSE(read_cached_table(*file, key)) << "cut at " << size;
  }
  std::vector<char> longer = bytes;
  longer.push_back('x');
  write_bytes(*file, longer);
  EXPECT_FALSE(read_cached_table(*file, key));
  // A directory that cannot be written: the payload is not stored, nothing thrown.
  write_bytes(dir / "tables-file", {'a'});
  EXPECT_FALSE(write_cached_table(dir.path() / "tables-file" / "x.table", key, payload));
}

}  // namespace
}  // namespace skylight::io
