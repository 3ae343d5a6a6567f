// SPDX-License-Identifier: MIT
// write_atomically(): a unique temporary file beside the target (O_EXCL, never through a
// symlink), the target's mode kept, no temporary left behind; the state-file lock of the
// emulators refuses a second holder.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "hil/serial/file_lock.hpp"
#include "hil/serial/item_transfer.hpp"

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void spit(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("hil-atomic-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  /// Every entry of the folder except `keep`.
  std::vector<std::string> others(std::initializer_list<std::string> keep) const {
    std::vector<std::string> r;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const auto name = e.path().filename().string();
      if (std::find(keep.begin(), keep.end(), name) == keep.end()) r.push_back(name);
    }
    return r;
  }
  fs::path dir_;
};

}  // namespace

TEST_F(AtomicFile, AUsersOwnTmpFileIsNotTouched) {
  const auto out = dir_ / "OUT";
  spit(dir_ / "OUT.tmp", "mine");
  ASSERT_FALSE(hil::serial::write_atomically(out, "new"));
  EXPECT_EQ(slurp(out), "new");
  EXPECT_EQ(slurp(dir_ / "OUT.tmp"), "mine");
  EXPECT_TRUE(others({"OUT", "OUT.tmp"}).empty()) << "no temporary left behind";
}

TEST_F(AtomicFile, ASymlinkBesideTheTargetIsNeverFollowed) {
  const auto victim = dir_ / "victim";
  spit(victim, "precious");
  fs::create_symlink(victim, dir_ / "OUT.tmp");
  ASSERT_FALSE(hil::serial::write_atomically(dir_ / "OUT", "new"));
  EXPECT_EQ(slurp(victim), "precious");
  EXPECT_EQ(slurp(dir_ / "OUT"), "new");
  EXPECT_TRUE(fs::is_symlink(dir_ / "OUT.tmp"));
}

TEST_F(AtomicFile, TheTargetKeepsItsMode) {
  const auto out = dir_ / "secret";
  spit(out, "old");
  fs::permissions(out, fs::perms::owner_read | fs::perms::owner_write);
  ASSERT_FALSE(hil::serial::write_atomically(out, "new"));
  EXPECT_EQ(slurp(out), "new");
  EXPECT_EQ(fs::status(out).permissions(), fs::perms::owner_read | fs::perms::owner_write);
}

TEST_F(AtomicFile, ANewFileGetsTheUmasksMode) {
  const mode_t old = ::umask(027);
  const auto w = hil::serial::write_atomically(dir_ / "fresh", "x");
  ::umask(old);
  ASSERT_FALSE(w);
  EXPECT_EQ(fs::status(dir_ / "fresh").permissions(),
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
}

TEST_F(AtomicFile, AFailedWriteLeavesTheOldFileAndNoTemporary) {
  const auto out = dir_ / "sub" / "OUT";  // the folder does not exist
  EXPECT_TRUE(hil::serial::write_atomically(out, "x"));
  const auto keep = dir_ / "OUT";
  spit(keep, "old");
  fs::permissions(dir_, fs::perms::owner_read | fs::perms::owner_exec);  // no new entries
  const auto e = hil::serial::write_atomically(keep, "new");
  fs::permissions(dir_, fs::perms::owner_all);
  if (::geteuid() != 0) {
    EXPECT_TRUE(e);
    EXPECT_EQ(slurp(keep), "old");
  }
  EXPECT_TRUE(others({"OUT"}).empty());
}

TEST_F(AtomicFile, TheStateFileLockRefusesASecondHolder) {
  const auto state = dir_ / "clm14.json";
  auto first = hil::serial::FileLock::acquire(state);
  ASSERT_TRUE(first) << first.error();
  auto second = hil::serial::FileLock::acquire(state);
  ASSERT_FALSE(second);
  EXPECT_NE(second.error().find("clm14.json is in use by another process"), std::string::npos) << second.error();
  EXPECT_NE(second.error().find(std::to_string(::getpid())), std::string::npos) << "names the holder";
  first = std::unexpected(std::string("released"));
  auto third = hil::serial::FileLock::acquire(state);
  EXPECT_TRUE(third) << "free again once the first holder is gone";
}
