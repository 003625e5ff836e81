// A file cache of a model's precomputed tables (bruneton's take seconds; read back in
// milliseconds): on when the environment variable SKYLIGHT_TABLE_CACHE names a directory, off
// otherwise. One file per table set, named by the kind and a hash of its key (the key: every
// parameter the tables depend on, exactly, and the table's layout); the file holds the whole key,
// so a file of another key, a truncated, corrupt or foreign file is never used (the tables are
// computed again and the file replaced). Files are written to a temporary next to them and
// renamed (readers never see a part); they are not a command's inputs or outputs (the CLI's
// OutputTransaction, io/file.h, does not hold them back). A directory that cannot be written
// leaves the tables computed but not cached. Format (native byte order,
// checked by a marker): "SKYLIGHT-TABLE 1\n", uint32 0x01020304, uint64 key length, the key,
// uint64 payload length, the payload, uint64 FNV-1a hash of the key and the payload.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace skylight::io {

inline constexpr const char* kTableCacheVariable = "SKYLIGHT_TABLE_CACHE";

// The file of (kind, key) in the cache directory, or none when the cache is off.
std::optional<std::filesystem::path> table_cache_file(std::string_view kind, std::string_view key);
// The payload stored in `file` for `key`: none if the file is missing, holds another key, or is
// not intact.
std::optional<std::vector<char>> read_cached_table(const std::filesystem::path& file,
                                                   std::string_view key);
// Stores the payload for `key` (atomically); false where the file cannot be written.
bool write_cached_table(const std::filesystem::path& file, std::string_view key,
                        std::span<const char> payload);

// FNV-1a 64 of bytes, continuing from `hash`.
std::uint64_t fnv1a(std::span<const char> bytes, std::uint64_t hash = 0xcbf29ce484222325ULL);

}  // namespace skylight::io
