#include "skylight/io/table_cache.h"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace skylight::io {

namespace {

constexpr std::string_view kMagic = "SKYLIGHT-TABLE 1\n";
constexpr std::uint32_t kByteOrder = 0x01020304;

template <class T>
void put(std::string& out, T v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// Reads a T at `pos` of `bytes`, advancing pos; false past the end.
template <class T>
bool get(const std::vector<char>& bytes, std::size_t& pos, T& v) {
  if (bytes.size() - pos < sizeof v) return false;
  std::memcpy(&v, bytes.data() + pos, sizeof v);
  pos += sizeof v;
  return true;
}

}  // namespace

std::uint64_t fnv1a(std::span<const char> bytes, std::uint64_t hash) {
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

std::optional<std::filesystem::path> table_cache_file(std::string_view kind, std::string_view key) {
  const char* dir = std::getenv(kTableCacheVariable);
  if (dir == nullptr || *dir == '\0') return std::nullopt;
  return std::filesystem::path(dir) /
         fmt::format("{}-{:016x}.table", kind,
                     fnv1a(std::span<const char>(key.data(), key.size())));
}

std::optional<std::vector<char>> read_cached_table(const std::filesystem::path& file,
                                                   std::string_view key) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  // Read directly, not through open_for_read: the cache is not an input of the command (its
  // OutputTransaction), and a damaged file is replaced by the same command.
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) return std::nullopt;
  std::vector<char> bytes(size);
  std::ifstream in(file, std::ios::binary);
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size))) return std::nullopt;
  std::size_t pos = kMagic.size();
  if (bytes.size() < pos || std::string_view(bytes.data(), pos) != kMagic) return std::nullopt;
  std::uint32_t order = 0;
  std::uint64_t key_size = 0, payload_size = 0, hash = 0;
  if (!get(bytes, pos, order) || order != kByteOrder || !get(bytes, pos, key_size) ||
      key_size != key.size() || bytes.size() - pos < key_size ||
      std::string_view(bytes.data() + pos, key_size) != key)
    return std::nullopt;
  const std::size_t key_at = pos;
  pos += key_size;
  if (!get(bytes, pos, payload_size) || bytes.size() - pos < payload_size) return std::nullopt;
  const std::size_t payload_at = pos;
  pos += payload_size;
  if (!get(bytes, pos, hash) || pos != bytes.size()) return std::nullopt;
  const std::uint64_t h = fnv1a(std::span<const char>(bytes.data() + payload_at, payload_size),
                                fnv1a(std::span<const char>(bytes.data() + key_at, key_size)));
  if (h != hash) return std::nullopt;
  return std::vector<char>(bytes.begin() + static_cast<std::ptrdiff_t>(payload_at),
                           bytes.begin() + static_cast<std::ptrdiff_t>(payload_at + payload_size));
}

bool write_cached_table(const std::filesystem::path& file, std::string_view key,
                        std::span<const char> payload) {
  std::string head(kMagic);
  put(head, kByteOrder);
  put(head, static_cast<std::uint64_t>(key.size()));
  head += key;
  put(head, static_cast<std::uint64_t>(payload.size()));
  std::string tail;
  put(tail, fnv1a(payload, fnv1a(std::span<const char>(key.data(), key.size()))));
  // Written and renamed here, not through AtomicFile: the cache is not an output of the command
  // (its OutputTransaction commits the outputs together; the cache is there for the next one).
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path temp =
      file.parent_path() /
      fmt::format(".{}.{}-{}.tmp", file.filename().string(), ::getpid(), counter.fetch_add(1));
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out.write(head.data(), static_cast<std::streamsize>(head.size()));
    out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
    out.write(tail.data(), static_cast<std::streamsize>(tail.size()));
    out.flush();
    if (!out) {
      std::filesystem::remove(temp, ec);
      return false;
    }
  }
  std::filesystem::rename(temp, file, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    return false;
  }
  return true;
}

}  // namespace skylight::io
