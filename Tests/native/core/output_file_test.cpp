// Output files: paths checked before work, atomic writes that never damage the previous file.
// The tests run as root, where permission bits do not stop a write, so unwritable places are
// made by other means: a regular file used as a folder, a missing folder, a folder as target,
// and /proc (no new files can be created there, even by root).
#include "lightsolver/output_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace lightsolver::test {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_plain(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

// A fresh empty folder per test.
class OutputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("lightsolver-output-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Entries in the folder: temporary files must never be left behind.
  std::size_t entries() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {}));
  }

  fs::path dir_;
};

// The error message, or "" when none was thrown.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const OutputError& e) {
    return e.what();
  }
  return "";
}

TEST_F(OutputFile, WritesANewFileAndReplacesAnOldOne) {
  const fs::path p = dir_ / "r.json";
  write_file_atomically(p.string(), "first");
  EXPECT_EQ(read(p), "first");
  write_file_atomically(p.string(), std::string(3'000'000, 'x'));  // larger than one write()
  EXPECT_EQ(read(p), std::string(3'000'000, 'x'));
  write_file_atomically(p.string(), "");
  EXPECT_EQ(read(p), "");
  EXPECT_EQ(entries(), 1u);  // no temporary file left
}

TEST_F(OutputFile, ReplacedFileKeepsItsPermissionsAndNewFilesAreNotPrivate) {
  const fs::path p = dir_ / "r.json";
  write_plain(p, "old");
  ASSERT_EQ(::chmod(p.c_str(), 0640), 0);
  write_file_atomically(p.string(), "new");
  struct stat st {};
  ASSERT_EQ(::stat(p.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
  const fs::path fresh = dir_ / "fresh.json";
  const mode_t old_mask = ::umask(022);
  write_file_atomically(fresh.string(), "x");
  ::umask(old_mask);
  ASSERT_EQ(::stat(fresh.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0644u);  // 0666 minus the umask, not mkstemp's 0600
}

TEST_F(OutputFile, ASymbolicLinkIsFollowedAndKept) {
  const fs::path real = dir_ / "real.json", link = dir_ / "link.json";
  write_plain(real, "old");
  fs::create_symlink(real, link);
  write_file_atomically(link.string(), "new");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read(real), "new");
}

TEST_F(OutputFile, MissingFolderIsNamed) {
  const fs::path p = dir_ / "missing" / "r.json";
  const std::string check = error_of([&] { check_writable(p.string(), "results file"); });
  EXPECT_NE(check.find("results file"), std::string::npos) << check;
  EXPECT_NE(check.find((dir_ / "missing").string() + "' does not exist"), std::string::npos)
      << check;
  const std::string write = error_of([&] { write_file_atomically(p.string(), "x"); });
  EXPECT_NE(write.find((dir_ / "missing").string()), std::string::npos) << write;
  EXPECT_FALSE(fs::exists(dir_ / "missing"));
}

TEST_F(OutputFile, AFolderAsTargetIsRefusedAndLeftAlone) {
  const fs::path p = dir_ / "r.json";
  fs::create_directory(p);
  write_plain(p / "inside", "keep");
  for (const std::string& path : {p.string(), p.string() + "/"}) {
    EXPECT_NE(error_of([&] { check_writable(path, "results file"); }).find("it is a folder"),
              std::string::npos);
    EXPECT_NE(error_of([&] { write_file_atomically(path, "x"); }).find("it is a folder"),
              std::string::npos);
  }
  EXPECT_EQ(read(p / "inside"), "keep");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputFile, AFileUsedAsAFolderIsRefused) {
  const fs::path file = dir_ / "plain";
  write_plain(file, "keep");
  const fs::path p = file / "r.json";
  EXPECT_NE(error_of([&] { check_writable(p.string(), "plot"); }).find("is not a folder"),
            std::string::npos);
  EXPECT_NE(error_of([&] { write_file_atomically(p.string(), "x"); }), "");
  EXPECT_EQ(read(file), "keep");
}

TEST_F(OutputFile, AFailedWriteLeavesTheOldFileIntact) {
  // /proc/version exists, is readable, and no file can be created next to it: the write fails
  // at the temporary file and the old content must be untouched.
  const std::string before = read("/proc/version");
  ASSERT_FALSE(before.empty());
  const std::string err = error_of([] { write_file_atomically("/proc/version", "garbage"); });
  EXPECT_NE(err.find("/proc/version"), std::string::npos) << err;
  EXPECT_EQ(read("/proc/version"), before);
  EXPECT_NE(error_of([] { check_writable("/proc/version", "results file"); }).find("/proc"),
            std::string::npos);
  EXPECT_NE(error_of([] { check_writable("/proc/lightsolver.json", "results file"); }), "");
  EXPECT_FALSE(fs::exists("/proc/lightsolver.json"));
}

TEST_F(OutputFile, CheckLeavesNothingBehindAndAcceptsAnExistingFile) {
  EXPECT_EQ(error_of([&] { check_writable((dir_ / "new.json").string(), "results file"); }), "");
  EXPECT_EQ(entries(), 0u);
  write_plain(dir_ / "old.json", "old");
  EXPECT_EQ(error_of([&] { check_writable((dir_ / "old.json").string(), "results file"); }), "");
  EXPECT_EQ(read(dir_ / "old.json"), "old");
  EXPECT_EQ(entries(), 1u);
  EXPECT_NE(error_of([] { check_writable("", "results file"); }), "");
  EXPECT_NE(error_of([] { check_writable("/dev/null", "results file"); }).find("regular file"),
            std::string::npos);  // never replace a device node
}

}  // namespace
}  // namespace lightsolver::test
