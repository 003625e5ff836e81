#include "skylight/io/file.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "skylight/core/error.h"
#include "support/scratch_dir.h"

namespace skylight::io {
namespace {

TEST(File, OneLineJoinsLinesEscapesControlCharactersAndBoundsTheLength) {
  EXPECT_EQ(one_line("first\nsecond\r\n"), "first second");
  // Found by the fuzz target image_exr (docs/TESTING.md): OpenEXR quotes a channel name from the
  // file, control characters included.
  EXPECT_EQ(one_line(std::string("channel \"\x01\x1b\x7f\" is invalid")),
            "channel \"\\x01\\x1b\\x7f\" is invalid");
  const std::string cut = one_line(std::string(100000, 'a'));
  EXPECT_EQ(cut.size(), kMaxOneLineChars + 3);
  EXPECT_EQ(cut.substr(cut.size() - 4), "a...");
}

TEST(File, ShownPathsStayOnOneLine) {
  EXPECT_EQ(shown_path("out\nput.exr"), "out\\x0aput.exr");
  try {
    throw_write_error("a\nb.exr", "No such file or directory");
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write 'a\\x0ab.exr': No such file or directory");
  }
}

namespace fs = std::filesystem;
using testing_support::slurp;

void write_through(const fs::path& path, const std::string& text) {
  AtomicFile f(path);
  f.write(text);
  f.commit();
}

// The names in a directory that are this project's temporaries or backups.
std::vector<std::string> leftovers(const testing_support::ScratchDir& dir) {
  std::vector<std::string> out;
  for (const std::string& name : dir.entries())
    if (name.rfind(".skylight-", 0) == 0) out.push_back(name);
  return out;
}

// A rename that fails half-way: the outputs renamed before it get their old content back (or
// disappear if they were new); nothing else is left in the directory.
TEST(OutputTransaction, AFailedRenameRollsBackTheOutputsBeforeIt) {
  testing_support::ScratchDir dir;
  write_through(dir / "a.txt", "old a");
  {
    OutputTransaction tx;
    write_through(dir / "a.txt", "new a");
    write_through(dir / "new.txt", "new file");
    write_through(dir / "b.txt", "new b");
    // b's temporary vanishes before the commit (as on a full or yanked disk): its rename fails.
    for (const std::string& name : leftovers(dir))
      if (slurp(dir / name) == "new b") fs::remove(dir / name);
    EXPECT_THROW(tx.commit(), IoError);
  }
  EXPECT_EQ(slurp(dir / "a.txt"), "old a");
  EXPECT_FALSE(fs::exists(dir / "new.txt"));
  EXPECT_FALSE(fs::exists(dir / "b.txt"));
  EXPECT_TRUE(leftovers(dir).empty());
}

TEST(OutputTransaction, ATargetThatIsADirectoryFailsBeforeAnyRename) {
  testing_support::ScratchDir dir;
  fs::create_directory(dir / "log");
  {
    OutputTransaction tx;
    write_through(dir / "weights.json", "{}");
    write_through(dir / "log", "restart,iteration");
    try {
      tx.commit();
      ADD_FAILURE() << "committed onto a directory";
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(fs::exists(dir / "weights.json"));
  EXPECT_TRUE(fs::is_directory(dir / "log"));
  EXPECT_TRUE(leftovers(dir).empty());
}

TEST(OutputTransaction, TwoOutputsOfOneFileOrAnOutputOverAnInputAreRefused) {
  testing_support::ScratchDir dir;
  write_through(dir / "in.txt", "input");
  {
    fs::create_directory(dir / "sub");
    OutputTransaction tx;
    write_through(dir / "x.txt", "first");
    EXPECT_THROW(write_through(dir / "sub/../x.txt", "second"), InvalidArgument);
  }
  EXPECT_FALSE(fs::exists(dir / "x.txt"));
  {
    OutputTransaction tx;
    EXPECT_EQ(read_text_file(dir / "in.txt"), "input");
    EXPECT_THROW(write_through(dir / "in.txt", "clobbered"), InvalidArgument);
  }
  {
    // The other order: an output first, then read as an input (a hard link names the same file).
    fs::create_hard_link(dir / "in.txt", dir / "link.txt");
    OutputTransaction tx;
    write_through(dir / "link.txt", "clobbered");
    EXPECT_THROW(read_text_file(dir / "in.txt"), InvalidArgument);
  }
  EXPECT_EQ(slurp(dir / "in.txt"), "input");
  EXPECT_TRUE(leftovers(dir).empty());
}

// What a killed process left (its temporaries and backups) is removed by the next one writing in
// that directory; a running process's are not.
TEST(OutputTransaction, ARerunRemovesWhatAKilledProcessLeft) {
  testing_support::ScratchDir dir;
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);  // `child` no longer runs
  const std::string dead = fmt::format(".skylight-{}-7.tmp", child);
  const std::string dead_old = fmt::format(".skylight-{}-8.old", child);
  const std::string alive = fmt::format(".skylight-{}-9.tmp", ::getppid());
  // A directory this process has not written in yet.
  const fs::path other = dir / "fresh";
  fs::create_directory(other);
  for (const std::string& name : {dead, dead_old, alive}) std::ofstream(other / name) << "partial";
  write_through(other / "out.txt", "complete");
  EXPECT_FALSE(fs::exists(other / dead));
  EXPECT_FALSE(fs::exists(other / dead_old));
  EXPECT_TRUE(fs::exists(other / alive));
}

}  // namespace
}  // namespace skylight::io
