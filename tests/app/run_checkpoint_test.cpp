// The checkpoint's identity of the running build (app/io/run_checkpoint.h): FNV-1a of the GNU build
// ID note the linker wrote, found here independently, by its bytes in the executable file.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "app/io/run_checkpoint.h"

namespace weft::app {
namespace {

TEST(RunCheckpoint, FnvOfKnownBytesIsThePublishedValue) {
  // FNV-1a 64 test vectors (Fowler, Noll, Vo): "" and "a".
  EXPECT_EQ(fnv1a_64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a_64("a"), 0xaf63dc4c8601ec8cULL);
}

TEST(RunCheckpoint, TheBuildHashIsTheHashOfTheExecutablesBuildId) {
  std::ifstream in("/proc/self/exe", std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  const std::string file = bytes.str();
  // An ELF note: name size 4, descriptor size 20 (SHA-1), type 3 (NT_GNU_BUILD_ID), "GNU\0".
  const std::uint32_t header[3] = {4, 20, 3};
  std::string pattern(reinterpret_cast<const char*>(header), sizeof header);
  pattern.append("GNU\0", 4);
  const std::size_t at = file.find(pattern);
  ASSERT_NE(at, std::string::npos) << "no SHA-1 build ID in the test program";
  const std::string id = file.substr(at + pattern.size(), 20);
  EXPECT_EQ(build_hash(), fnv1a_64(id));
  EXPECT_NE(build_hash(), fnv1a_64(file));  // not the whole file any more
}

}  // namespace
}  // namespace weft::app
