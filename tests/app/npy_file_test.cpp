// app/io/npy_file.h: .npy arrays read strictly, written back, and every bad file named.
#include "app/io/npy_file.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace weft::app {
namespace {

namespace fs = std::filesystem;

fs::path temp_file(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "weft_npy_test";
  fs::create_directories(dir);
  return dir / name;
}

// A version-1.0 file with this header dict and these data bytes, padded as NumPy pads it.
fs::path npy_with(const std::string& name, const std::string& dict, const std::string& data) {
  std::string header = dict;
  header += std::string((64 - (10 + header.size() + 1) % 64) % 64, ' ') + "\n";
  const fs::path path = temp_file(name);
  std::ofstream out(path, std::ios::binary);
  out.write("\x93NUMPY\x01\x00", 8);
  out.put(static_cast<char>(header.size() & 0xff));
  out.put(static_cast<char>(header.size() >> 8));
  out << header << data;
  return path;
}

std::string floats(std::initializer_list<float> values) {
  std::string bytes;
  for (const float v : values) bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  return bytes;
}

void expect_error(const fs::path& path, const std::string& expected) {
  try {
    read_npy_points(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const NpyError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(NpyFile, WrittenPointsReadBackExactly) {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> p(4, 3);
  p << 0.1, -0.2, 1.25, 1e-9, 3.0, -7.5, 0.0, 0.3333333333333333, 2.0, -1.0, 1.0, 1e6;
  const fs::path path = temp_file("points.npy");
  write_npy_points(path, p);
  EXPECT_EQ(fs::file_size(path) % 16, 0u);  // 64-byte header, then 4·3·8 bytes
  const auto q = read_npy_points(path);
  ASSERT_EQ(q.rows(), 4);
  EXPECT_EQ((q - p).cwiseAbs().maxCoeff(), 0.0);
}

TEST(NpyFile, ReadsFloat32InCOrder) {
  const fs::path path = npy_with("f4.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }",
                                 floats({1, 2, 3, 4, 5, 6}));
  const auto q = read_npy_points(path);
  ASSERT_EQ(q.rows(), 2);
  EXPECT_EQ(q(0, 2), 3.0);
  EXPECT_EQ(q(1, 0), 4.0);
  const NpyArray a = read_npy(path);
  EXPECT_EQ(a.shape, (std::vector<std::int64_t>{2, 3}));
}

TEST(NpyFile, BadFilesAreNamedWithWhatWasExpected) {
  expect_error(temp_file("missing.npy"), "cannot read a .npy file");
  {
    std::ofstream(temp_file("text.npy")) << "x,y,z\n1,2,3\n";
    expect_error(temp_file("text.npy"), "magic string");
  }
  expect_error(npy_with("int.npy", "{'descr': '<i8', 'fortran_order': False, 'shape': (1, 3), }",
                        std::string(24, '\0')),
               "got dtype '<i8'");
  expect_error(npy_with("fortran.npy", "{'descr': '<f4', 'fortran_order': True, 'shape': (1, 3), }",
                        floats({1, 2, 3})),
               "Fortran order");
  expect_error(npy_with("shape.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (3,), }",
                        floats({1, 2, 3})),
               "got shape (3)");
  expect_error(npy_with("short.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }",
                        floats({1, 2, 3})),
               "expected 24 bytes of data");
  expect_error(npy_with("nan.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (1, 3), }",
                        floats({1, std::numeric_limits<float>::quiet_NaN(), 3})),
               "point 0 has a non-finite");
}

// A shape whose element count overflows used to wrap round to the data's size, or end in
// std::bad_alloc naming no file; /dev/zero was read for gigabytes.
TEST(NpyFile, AHugeShapeOrADeviceIsRefusedNamingTheFile) {
  expect_error(npy_with("huge.npy",
                        "{'descr': '<f8', 'fortran_order': False, 'shape': (2305843009213693952, 3), }",
                        std::string(48, '\0')),
               "its shape (2305843009213693952, 3) needs more bytes than a size holds");
  expect_error(npy_with("wraps.npy",
                        "{'descr': '<f8', 'fortran_order': False, 'shape': (6148914691236517206, 3), }",
                        std::string(16, '\0')),
               "(the element count overflows)");
  expect_error("/dev/zero", "cannot read a .npy file (not a regular file");
}

}  // namespace
}  // namespace weft::app
