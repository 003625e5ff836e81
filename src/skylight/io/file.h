// Files: reading whole files with one-line errors, and atomic output (a temporary file next to the
// target, renamed onto it only when everything was written). Every output of the library and the
// CLI goes through AtomicFile, so a target is either untouched or complete.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace skylight::io {

// The system's message for errno value `err`.
std::string errno_message(int err);
// A message on one line: newlines and carriage returns become spaces, other control characters
// are escaped as \xHH, text beyond kMaxOneLineChars is cut with "...", trailing spaces removed
// (library messages, OpenEXR's in particular, may span lines and quote bytes of the file; ours
// are one printable line).
inline constexpr std::size_t kMaxOneLineChars = 512;
std::string one_line(std::string s);
// A path as messages show it: control characters escaped as \xHH (a newline in a file name stays
// on the message's one line), the rest as it is.
std::string shown_path(const std::filesystem::path& path);
// IoError("cannot write '<path>': <why>") / IoError("cannot read '<path>': <why>").
[[noreturn]] void throw_write_error(const std::filesystem::path& path, const std::string& why);
[[noreturn]] void throw_read_error(const std::filesystem::path& path, const std::string& why);

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;
// Opens a regular file for reading (binary), or throws an IoError naming the path with the
// system's reason ("is a directory" for a directory). While an OutputTransaction is open (on any
// thread), the file is one of its inputs (OutputTransaction::note_input).
FilePtr open_for_read(const std::filesystem::path& path);

// The whole content of a regular file. Throws IoError naming the path (missing, unreadable, a
// directory, read error).
std::vector<char> read_file(const std::filesystem::path& path);
std::string read_text_file(const std::filesystem::path& path);

// A temporary file next to the target, `.skylight-<pid>-<counter>.tmp` (short, so that any legal
// target name works), renamed onto the target by commit(). Destroyed uncommitted, it removes the
// temporary, so the target is either untouched or complete. The first AtomicFile of a process in
// a directory removes the temporaries there that a killed process left (`.skylight-<pid>-*` of a
// pid that no longer runs), so a rerun after a kill leaves nothing behind. Every write is checked;
// commit() flushes and fsyncs before the rename. Errors are IoErrors naming the target. While an
// OutputTransaction is open on the thread, commit() completes the file but leaves the rename to
// the transaction.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  const std::filesystem::path& target() const { return target_; }

  void write(const void* bytes, std::size_t n);
  void write(std::string_view s) { write(s.data(), s.size()); }
  // Never throws (OpenEXR calls it from a destructor); a failure is remembered and reported by the
  // next write() or by commit().
  std::uint64_t tell() noexcept;
  void seek(std::uint64_t pos);
  void commit();

 private:
  void remember(int err) noexcept;
  [[noreturn]] void fail(int err);

  std::filesystem::path target_;
  std::filesystem::path temp_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
  bool failed_ = false;
  int failed_errno_ = 0;
};

// All-or-nothing outputs of one command: while a transaction is open on a thread, every
// AtomicFile committed on that thread is written completely to its temporary, and only commit()
// renames them all onto their targets. Destroyed without commit() (an error on the way), it
// removes every temporary: no target is touched. Transactions do not nest (one per process).
// Two outputs naming the same file, or an output naming a file the command read (open_for_read,
// on any thread), are an InvalidArgument when the second of them is adopted or read: nothing is
// written.
class OutputTransaction {
 public:
  OutputTransaction();
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;
  ~OutputTransaction();
  // Renames every completed temporary onto its target, all or none: a target that is a directory
  // fails before any rename, and if a rename fails the targets renamed before it get their old
  // content back (kept under a hard link, or a copy, until all are in place) or are removed if
  // they did not exist. Throws IoError naming the target that failed.
  void commit();
  // Called by AtomicFile::commit(): takes over a completed temporary.
  void adopt(std::filesystem::path temp, std::filesystem::path target);
  // Called by open_for_read: `path` is an input of the open transaction, if any (any thread).
  static void note_input(const std::filesystem::path& path);
  // The transaction open on this thread, or nullptr.
  static OutputTransaction* current();

 private:
  void remove_temporaries(std::size_t from) noexcept;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> files_;  // temp, target
  std::vector<std::filesystem::path> inputs_;
  bool committed_ = false;
};

// Writes bytes (e.g. HTML, SVG, JSON, CSV text) to a file atomically.
void write_text_file(const std::filesystem::path& path, std::string_view content);

}  // namespace skylight::io
