// tests/unit/test_atomic_file.cpp — nscd::atomic_write: the file appears whole; every failure
// (rename onto a directory, a folder that cannot take the file, a writer that throws) throws
// nscd::Error naming the file and the reason, leaves no .tmp behind and the old file intact.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "error_assertions.hpp"
#include "nscd/io/atomic_file.hpp"

namespace {

namespace fs = std::filesystem;
using nscd::testing_support::Contains;
using nscd::testing_support::error_message;

std::string read_text(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class AtomicWrite : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("nscd_atomic_" + std::to_string(::getpid()) + "_" +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override {
    fs::permissions(dir, fs::perms::owner_all, fs::perm_options::add);
    fs::remove_all(dir);
  }
  fs::path dir;
};

TEST_F(AtomicWrite, WritesWholeFileAndReplacesTheOld) {
  const fs::path f = dir / "summary.txt";
  nscd::atomic_write(f, "a = 1\n");
  EXPECT_EQ(read_text(f), "a = 1\n");
  nscd::atomic_write(f, [](std::ostream& out) { out << "a = " << 2 << "\n"; });
  EXPECT_EQ(read_text(f), "a = 2\n");
  EXPECT_FALSE(fs::exists(dir / "summary.txt.tmp"));
}

TEST_F(AtomicWrite, RenameOntoADirectoryFailsCleanly) {
  const fs::path target = dir / "out";
  fs::create_directories(target / "inside");  // a non-empty directory where the file should go
  const std::string msg = error_message([&] { nscd::atomic_write(target, "x"); });
  EXPECT_TRUE(Contains(msg, target.string()));
  EXPECT_TRUE(Contains(msg, "rename"));
  EXPECT_FALSE(fs::exists(dir / "out.tmp"));
  EXPECT_TRUE(fs::is_directory(target / "inside"));
}

TEST_F(AtomicWrite, WriterThatThrowsLeavesTheOldFile) {
  const fs::path f = dir / "data.csv";
  nscd::atomic_write(f, "old\n");
  // a std::exception becomes nscd::Error naming the file and the writer's reason
  const std::string msg = error_message([&] {
    nscd::atomic_write(f, [](std::ostream& out) {
      out << "half a row";
      throw std::runtime_error("the writer gave up");
    });
  });
  EXPECT_TRUE(Contains(msg, f.string()));
  EXPECT_TRUE(Contains(msg, "the writer gave up"));
  // an nscd::Error passes through unchanged
  EXPECT_EQ(error_message([&] { nscd::atomic_write(f, [](std::ostream&) { throw nscd::Error("own words"); }); }), "own words");
  EXPECT_EQ(read_text(f), "old\n");
  EXPECT_FALSE(fs::exists(dir / "data.csv.tmp"));
}

TEST_F(AtomicWrite, FolderThatCannotHoldTheFile) {
  // the parent is a regular file (fails for every user, root included)
  const fs::path parent = dir / "plain_file";
  nscd::atomic_write(parent, "not a folder\n");
  const std::string msg = error_message([&] { nscd::atomic_write(parent / "x.txt", "x"); });
  EXPECT_TRUE(Contains(msg, (parent / "x.txt").string()));
  EXPECT_TRUE(Contains(msg, "cannot create"));
  EXPECT_EQ(read_text(parent), "not a folder\n");
  // a temporary name taken by a directory: it is neither used nor removed, the old file stays
  const fs::path f = dir / "checkpoint.nscd";
  nscd::atomic_write(f, "first");
  fs::create_directory(dir / "checkpoint.nscd.tmp");
  EXPECT_TRUE(Contains(error_message([&] { nscd::atomic_write(f, "second"); }), "checkpoint.nscd.tmp"));
  EXPECT_EQ(read_text(f), "first");
  EXPECT_TRUE(fs::is_directory(dir / "checkpoint.nscd.tmp"));
}

TEST_F(AtomicWrite, UnwritableFolder) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders: the permission check cannot fail";
  const fs::path ro = dir / "ro";
  fs::create_directory(ro);
  nscd::atomic_write(ro / "f.txt", "old");
  fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
  const std::string msg = error_message([&] { nscd::atomic_write(ro / "f.txt", "new"); });
  fs::permissions(ro, fs::perms::owner_all);
  EXPECT_TRUE(Contains(msg, (ro / "f.txt").string()));
  EXPECT_EQ(read_text(ro / "f.txt"), "old");
  EXPECT_FALSE(fs::exists(ro / "f.txt.tmp"));
}

}  // namespace
