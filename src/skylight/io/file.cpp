#include "skylight/io/file.h"

#include <fmt/format.h>
#include <unistd.h>

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <memory>
#include <mutex>
#include <set>
#include <system_error>
#include <utility>

#include "skylight/core/error.h"

namespace skylight::io {
namespace {

namespace fs = std::filesystem;

// `.skylight-<pid>-<n><suffix>` in `dir`: the names of this process's temporaries and backups.
fs::path private_name(const fs::path& dir, std::string_view suffix) {
  static std::atomic<unsigned> counter{0};
  return dir / fmt::format(".skylight-{}-{}{}", static_cast<long>(::getpid()), counter++, suffix);
}

// Whether process `pid` still runs: it exists and is not a zombie (a killed process whose parent
// has not reaped it yet, which never writes again).
bool process_running(long pid) {
  if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) return false;
  std::FILE* f = std::fopen(fmt::format("/proc/{}/stat", pid).c_str(), "r");
  if (f == nullptr) return true;  // no procfs: assume it runs
  char state = 0;
  const int read = std::fscanf(f, "%*d (%*[^)]) %c", &state);
  std::fclose(f);
  return read != 1 || state != 'Z';
}

// Removes, once per directory and process, the temporaries and backups (`.skylight-<pid>-<n>.tmp`
// / `.old`) that a process which no longer runs left in `dir` (killed before it could clean up).
void remove_stale_temporaries(const fs::path& dir) {
  static std::mutex mutex;
  static std::set<fs::path> done;
  std::error_code ec;
  const fs::path key = fs::weakly_canonical(dir.empty() ? fs::path(".") : dir, ec);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (!done.insert(ec ? dir : key).second) return;
  }
  for (fs::directory_iterator it(dir.empty() ? fs::path(".") : dir, ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    long pid = 0;
    unsigned n = 0;
    char suffix[5] = {};
    if (std::sscanf(name.c_str(), ".skylight-%ld-%u.%3s", &pid, &n, suffix) != 3) continue;
    if (std::string_view(suffix) != "tmp" && std::string_view(suffix) != "old") continue;
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (process_running(pid)) continue;
    std::error_code ignored;
    fs::remove(it->path(), ignored);
  }
}

// Whether two paths name one file: the same file where both exist (links included), else the
// same normalised absolute path.
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::equivalent(a, b, ec) && !ec) return true;
  std::error_code ea, eb;
  const fs::path ca = fs::weakly_canonical(fs::absolute(a, ea), ea);
  const fs::path cb = fs::weakly_canonical(fs::absolute(b, eb), eb);
  return !ea && !eb && ca == cb;
}

[[noreturn]] void throw_input_overwritten(const fs::path& path) {
  throw InvalidArgument(
      fmt::format("'{}' is an input of this command and one of its outputs; write to another file",
                  shown_path(path)));
}

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

std::string shown_path(const fs::path& path) {
  std::string out;
  for (const char c : path.string()) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f)
      out += fmt::format("\\x{:02x}", u);
    else
      out += c;
  }
  return out;
}

void throw_write_error(const fs::path& path, const std::string& why) {
  throw IoError(fmt::format("cannot write '{}': {}", shown_path(path), one_line(why)));
}
void throw_read_error(const fs::path& path, const std::string& why) {
  throw IoError(fmt::format("cannot read '{}': {}", shown_path(path), one_line(why)));
}

FilePtr open_for_read(const fs::path& path) {
  OutputTransaction::note_input(path);
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
  remove_stale_temporaries(target_.parent_path());
  for (int attempt = 0;; ++attempt) {
    temp_ = private_name(target_.parent_path(), ".tmp");
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
// The open transaction for inputs read on any thread (note_input), and its lock.
std::atomic<OutputTransaction*> g_transaction{nullptr};
std::mutex g_inputs_mutex;
}  // namespace

OutputTransaction::OutputTransaction() {
  SKYLIGHT_CHECK(t_transaction == nullptr, "output transactions do not nest");
  t_transaction = this;
  g_transaction = this;
}

OutputTransaction::~OutputTransaction() {
  if (t_transaction == this) t_transaction = nullptr;
  OutputTransaction* self = this;
  g_transaction.compare_exchange_strong(self, nullptr);
  if (!committed_) remove_temporaries(0);
}

OutputTransaction* OutputTransaction::current() {
  return t_transaction;
}

void OutputTransaction::remove_temporaries(std::size_t from) noexcept {
  for (std::size_t j = from; j < files_.size(); ++j) {
    std::error_code ignored;
    fs::remove(files_[j].first, ignored);
  }
}

void OutputTransaction::adopt(fs::path temp, fs::path target) {
  const std::lock_guard<std::mutex> lock(g_inputs_mutex);
  for (const auto& [t, other] : files_)
    if (same_file(other, target))
      throw InvalidArgument(
          fmt::format("two outputs of this command name the same file '{}'; give each its own",
                      shown_path(target)));
  for (const fs::path& input : inputs_)
    if (same_file(input, target)) throw_input_overwritten(target);
  files_.emplace_back(std::move(temp), std::move(target));
}

void OutputTransaction::note_input(const fs::path& path) {
  OutputTransaction* tx = g_transaction.load();
  if (tx == nullptr) return;
  const std::lock_guard<std::mutex> lock(g_inputs_mutex);
  for (const auto& [temp, target] : tx->files_)
    if (same_file(target, path)) throw_input_overwritten(path);
  tx->inputs_.push_back(path);
}

void OutputTransaction::commit() {
  t_transaction = nullptr;
  OutputTransaction* self = this;
  g_transaction.compare_exchange_strong(self, nullptr);
  committed_ = true;  // from here on, this function cleans up
  std::error_code ec;
  for (const auto& [temp, target] : files_)
    if (fs::is_directory(target, ec)) {
      remove_temporaries(0);
      throw_write_error(target, "is a directory");
    }
  // Each old target is kept under a backup name until every new file is in place.
  struct Done {
    fs::path target, backup;  // backup empty: the target did not exist
  };
  std::vector<Done> done;
  const auto undo = [&done]() noexcept {
    for (auto it = done.rbegin(); it != done.rend(); ++it) {
      std::error_code ignored;
      if (it->backup.empty())
        fs::remove(it->target, ignored);
      else
        fs::rename(it->backup, it->target, ignored);
    }
  };
  for (std::size_t i = 0; i < files_.size(); ++i) {
    const auto& [temp, target] = files_[i];
    Done d{target, {}};
    if (fs::exists(fs::symlink_status(target, ec))) {
      d.backup = private_name(target.parent_path(), ".old");
      fs::create_hard_link(target, d.backup, ec);
      if (ec) fs::copy_file(target, d.backup, ec);
      if (ec) {
        undo();
        remove_temporaries(i);
        throw_write_error(
            target, "cannot keep the old file until all outputs are written: " + ec.message());
      }
    }
    fs::rename(temp, target, ec);
    if (ec) {
      const std::string why = ec.message();
      if (!d.backup.empty()) fs::remove(d.backup, ec);
      undo();
      remove_temporaries(i);
      throw_write_error(target, why);
    }
    done.push_back(std::move(d));
  }
  for (const Done& d : done)
    if (!d.backup.empty()) fs::remove(d.backup, ec);
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
