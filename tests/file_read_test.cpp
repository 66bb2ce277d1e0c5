// input::read_file: regular files only, refused before a byte is read otherwise, and never more
// than the limit.

#include "input/file_read.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

std::string read_error(const std::string& path, std::uint64_t limit = 1 << 20) {
  try {
    input::read_file(path, limit, "test file");
  } catch (const input::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

class FileRead : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("accelbench_file_read_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const char* name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(FileRead, ReadsRegularFilesAndTheirLinks) {
  std::ofstream(path("a.txt"), std::ios::binary) << std::string("hello\0world", 11);
  fs::create_symlink(path("a.txt"), path("link.txt"));
  EXPECT_EQ(input::read_file(path("a.txt"), 11, "test file"), std::string("hello\0world", 11));
  EXPECT_EQ(input::read_file(path("link.txt"), 100, "test file").size(), 11u);
}

TEST_F(FileRead, RefusesWhatIsNotARegularFile) {
  fs::create_symlink("/dev/zero", path("zero"));
  fs::create_directories(path("dir.json"));
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0644), 0);
  EXPECT_EQ(read_error(path("zero")), path("zero") + ": is a character device, not a regular test file");
  EXPECT_EQ(read_error("/dev/urandom"), "/dev/urandom: is a character device, not a regular test file");
  EXPECT_EQ(read_error(path("dir.json")), path("dir.json") + ": is a directory, not a regular test file");
  EXPECT_EQ(read_error(path("fifo")), path("fifo") + ": is a FIFO, not a regular test file");  // no writer: no hang
  EXPECT_EQ(read_error(path("missing")), path("missing") + ": cannot open: No such file or directory");
}

TEST_F(FileRead, RefusesFilesOverTheLimit) {
  std::ofstream(path("big"), std::ios::binary) << std::string(3000, 'x');
  EXPECT_EQ(read_error(path("big"), 2048), path("big") + ": 2.9 KiB is over the 2 KiB limit for test files");
  EXPECT_EQ(input::read_file(path("big"), 3000, "test file").size(), 3000u);
  // /proc files report size 0 but hold text: the read itself stops at the limit.
  const std::string got = read_error("/proc/self/maps", 16);
  EXPECT_EQ(got, "/proc/self/maps: more than 16 B is over the 16 B limit for test files");
}

TEST(ByteText, ReadsLikeAPerson) {
  EXPECT_EQ(input::byte_text(100), "100 B");
  EXPECT_EQ(input::byte_text(256ull << 20), "256 MiB");
  EXPECT_EQ(input::byte_text(3ull << 29), "1.5 GiB");
}

}  // namespace
