// Exclusive atomic writes and capped reads (base/atomic_file.h, base/file_read.h): a link planted
// at the temporary name is replaced, never written through; a failing writer leaves no partial
// file and the old content; a device or an over-large file is refused before it is read.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "base/atomic_file.h"
#include "base/file_read.h"

namespace fs = std::filesystem;

namespace weft::base {
namespace {

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / "weft_file_io_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AtomicFile, ALinkAtThePartialNameIsNotFollowed) {
  const fs::path dir = fresh("link");
  std::ofstream(dir / "victim") << "precious";
  fs::create_symlink(dir / "victim", dir / "out.txt.partial");
  write_file_atomically(dir / "out.txt", "new");
  EXPECT_EQ(bytes_of(dir / "victim"), "precious");
  EXPECT_EQ(bytes_of(dir / "out.txt"), "new");
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "out.txt.partial")));
}

TEST(AtomicFile, AFailingWriterLeavesTheOldFileAndNoPartial) {
  const fs::path dir = fresh("fail");
  write_file_atomically(dir / "out.txt", "old");
  EXPECT_THROW(write_atomically(dir / "out.txt",
                                [](ExclusiveFile& f) {
                                  f.write("half");
                                  throw std::runtime_error("disk full");
                                }),
               std::runtime_error);
  EXPECT_EQ(bytes_of(dir / "out.txt"), "old");
  EXPECT_FALSE(fs::exists(dir / "out.txt.partial"));
}

TEST(FileRead, ADeviceAFolderAndALargeFileAreRefusedBeforeReading) {
  const fs::path dir = fresh("read");
  for (const fs::path& path : {fs::path("/dev/zero"), dir}) {
    try {
      read_file_capped(path, 1 << 20, "a test file");
      ADD_FAILURE() << path;
    } catch (const FileReadError& e) {
      EXPECT_NE(std::string(e.what()).find(path.string() + ": cannot read a test file (not a regular file"),
                std::string::npos) << e.what();
    }
  }
  std::ofstream(dir / "big") << std::string(2000, 'x');
  try {
    read_file_capped(dir / "big", 1000, "a test file");
    ADD_FAILURE();
  } catch (const FileReadError& e) {
    EXPECT_NE(std::string(e.what()).find("has 2000 bytes"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_file_capped(dir / "big", 2000, "a test file").size(), 2000u);
}

}  // namespace
}  // namespace weft::base
