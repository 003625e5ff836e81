#include "skylight/io/file.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <memory>
#include <system_error>
#include <utility>

#include "skylight/core/error.h"

namespace skylight::io {
namespace {

namespace fs = std::filesystem;

}  // namespace

std::string errno_message(int err) {
  return std::error_code(err, std::generic_category()).message();
}

std::string one_line(std::string s) {
  std::string out;
  out.reserve(std::min(s.size(), kMaxOneLineChars) + 3);
  for (const char c : s) {
    if (out.size() >= kMaxOneLineChars) {
      out += "...";
      break;
    }
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n' || c == '\r')
      out += ' ';
    else if (u < 0x20 || u == 0x7f)
      out += fmt::format("\\x{:02x}", u);
    else
      out += c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

void throw_write_error(const fs::path& path, const std::string& why) {
  throw IoError(fmt::format("cannot write '{}': {}", path.string(), one_line(why)));
}
void throw_read_error(const fs::path& path, const std::string& why) {
  throw IoError(fmt::format("cannot read '{}': {}", path.string(), one_line(why)));
}

FilePtr open_for_read(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw_read_error(path, "is a directory");
  FilePtr f(std::fopen(path.c_str(), "rb"));
  if (!f) throw_read_error(path, errno_message(errno));
  return f;
}

std::vector<char> read_file(const fs::path& path) {
  FilePtr f = open_for_read(path);
  std::vector<char> bytes;
  char buffer[1 << 16];
  for (;;) {
    const size_t n = std::fread(buffer, 1, sizeof buffer, f.get());
    bytes.insert(bytes.end(), buffer, buffer + n);
    if (n < sizeof buffer) break;
  }
  if (std::ferror(f.get())) throw_read_error(path, errno_message(errno));
  return bytes;
}

std::string read_text_file(const fs::path& path) {
  const std::vector<char> bytes = read_file(path);
  return std::string(bytes.begin(), bytes.end());
}

// ---- AtomicFile ---------------------------------------------------------------------------------

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0;; ++attempt) {
    temp_ = target_.parent_path() /
            fmt::format(".skylight-{}-{}.tmp", static_cast<long>(::getpid()), counter++);
    file_ = std::fopen(temp_.c_str(), "wbx");  // x: exclusive, never clobbers another writer
    if (file_ != nullptr) break;
    const int err = errno;
    if (err != EEXIST || attempt >= 100) throw_write_error(target_, errno_message(err));
  }
}

AtomicFile::~AtomicFile() {
  if (file_ != nullptr) std::fclose(file_);
  if (!committed_) {
    std::error_code ignored;
    fs::remove(temp_, ignored);
  }
}

void AtomicFile::write(const void* bytes, size_t n) {
  if (failed_) throw_write_error(target_, errno_message(failed_errno_));
  if (n > 0 && std::fwrite(bytes, 1, n, file_) != n) fail(errno);
}

std::uint64_t AtomicFile::tell() noexcept {
  const off_t pos = ::ftello(file_);
  if (pos >= 0) return static_cast<std::uint64_t>(pos);
  remember(errno);
  return 0;
}

void AtomicFile::seek(std::uint64_t pos) {
  if (::fseeko(file_, static_cast<off_t>(pos), SEEK_SET) != 0) fail(errno);
}

void AtomicFile::commit() {
  if (failed_) throw_write_error(target_, errno_message(failed_errno_));
  if (std::fflush(file_) != 0 || ::fsync(::fileno(file_)) != 0) fail(errno);
  std::FILE* f = std::exchange(file_, nullptr);
  if (std::fclose(f) != 0) fail(errno);
  if (OutputTransaction* tx = OutputTransaction::current()) {
    tx->adopt(temp_, target_);  // renamed (or removed) with the other outputs
    committed_ = true;
    return;
  }
  std::error_code ec;
  fs::rename(temp_, target_, ec);
  if (ec) throw_write_error(target_, ec.message());
  committed_ = true;
}

// ---- OutputTransaction --------------------------------------------------------------------------

namespace {
thread_local OutputTransaction* t_transaction = nullptr;
}

OutputTransaction::OutputTransaction() {
  SKYLIGHT_CHECK(t_transaction == nullptr, "output transactions do not nest");
  t_transaction = this;
}

OutputTransaction::~OutputTransaction() {
  t_transaction = nullptr;
  if (committed_) return;
  for (const auto& [temp, target] : files_) {
    std::error_code ignored;
    fs::remove(temp, ignored);
  }
}

OutputTransaction* OutputTransaction::current() {
  return t_transaction;
}

void OutputTransaction::adopt(fs::path temp, fs::path target) {
  files_.emplace_back(std::move(temp), std::move(target));
}

void OutputTransaction::commit() {
  t_transaction = nullptr;
  for (std::size_t i = 0; i < files_.size(); ++i) {
    std::error_code ec;
    fs::rename(files_[i].first, files_[i].second, ec);
    if (ec) {
      for (std::size_t j = i; j < files_.size(); ++j) {
        std::error_code ignored;
        fs::remove(files_[j].first, ignored);
      }
      committed_ = true;
      throw_write_error(files_[i].second, ec.message());
    }
  }
  committed_ = true;
}

// Failures are remembered: OpenEXR swallows exceptions thrown while it closes a file.
void AtomicFile::remember(int err) noexcept {
  if (failed_) return;
  failed_ = true;
  failed_errno_ = err != 0 ? err : EIO;
}

void AtomicFile::fail(int err) {
  remember(err);
  throw_write_error(target_, errno_message(failed_errno_));
}

void write_text_file(const fs::path& path, std::string_view content) {
  AtomicFile file(path);
  file.write(content.data(), content.size());
  file.commit();
}

}  // namespace skylight::io
