// Image storage and PNG round trips.

#include "render/image.h"

#include <gtest/gtest.h>

#include <stb_image_write.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace weft::render {
namespace {

namespace fs = std::filesystem;

// A fresh, empty directory per test under GoogleTest's temporary directory.
fs::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path dir = fs::path(::testing::TempDir()) / "weft_render_image_test" /
                 (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Every byte differs from its neighbours, so a row swap or channel swap shows.
Image pattern(int width, int height) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.set(x, y,
                Rgb8{static_cast<std::uint8_t>(37 * x + 11 * y),
                     static_cast<std::uint8_t>(255 - 19 * y + 3 * x),
                     static_cast<std::uint8_t>((x * y * 7 + 5) & 0xff)});
    }
  }
  return image;
}

TEST(Image, FillAndAccess) {
  Image image(3, 2, Rgb8{1, 2, 3});
  EXPECT_EQ(image.width(), 3);
  EXPECT_EQ(image.height(), 2);
  EXPECT_EQ(image.at(2, 1), (Rgb8{1, 2, 3}));
  image.set(2, 1, Rgb8{9, 8, 7});
  EXPECT_EQ(image.at(2, 1), (Rgb8{9, 8, 7}));
  // Row-major, top row first, 3 bytes per pixel.
  EXPECT_EQ(image.data()[(1 * 3 + 2) * 3 + 0], 9);
  EXPECT_THROW(image.at(3, 0), std::out_of_range);
  EXPECT_THROW(image.set(0, -1, {}), std::out_of_range);
  EXPECT_THROW(Image(-1, 2), std::invalid_argument);
}

TEST(Image, PngRoundTripIsBitExact) {
  const fs::path path = scratch_dir() / "pattern.png";
  const Image written = pattern(13, 7);  // odd width: rows are not 4-byte aligned
  write_png(written, path);
  EXPECT_FALSE(fs::exists(path.string() + ".tmp")) << "the temporary file must be renamed";

  const Image read = read_image(path);
  ASSERT_EQ(read.width(), written.width());
  ASSERT_EQ(read.height(), written.height());
  for (int y = 0; y < read.height(); ++y) {
    for (int x = 0; x < read.width(); ++x) {
      ASSERT_EQ(read.at(x, y), written.at(x, y)) << "pixel (" << x << ", " << y << ")";
    }
  }
}

// A frame-like image: a vertical gradient backdrop and a shaded disc (smooth areas and an edge,
// as weft's renders have).
Image frame_like(int width, int height) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double dx = x - 0.5 * width, dy = y - 0.55 * height, r = 0.35 * height;
      const double shade = std::max(0.0, 1.0 - (dx * dx + dy * dy) / (r * r));
      const auto v = static_cast<std::uint8_t>(200 + 40 * y / height);
      image.set(x, y, dx * dx + dy * dy < r * r
                          ? Rgb8{static_cast<std::uint8_t>(90 + 150 * shade),
                                 static_cast<std::uint8_t>(30 + 40 * shade),
                                 static_cast<std::uint8_t>(25 + 30 * shade)}
                          : Rgb8{v, v, static_cast<std::uint8_t>(v + 10)});
    }
  }
  return image;
}

// Frames are written with a real deflate (libpng, zlib), the same pixels in
// fewer bytes than stb's own encoder gives.
TEST(Image, WrittenPngsAreSmallerThanStbsForTheSamePixels) {
  const fs::path path = scratch_dir() / "frame.png";
  const Image written = frame_like(320, 240);
  write_png(written, path);
  std::string stb;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<std::size_t>(size));
  };
  ASSERT_NE(stbi_write_png_to_func(append, &stb, written.width(), written.height(), 3,
                                   written.data(), written.width() * 3),
            0);
  const auto ours = fs::file_size(path);
  std::printf("frame-like 320x240: %ju bytes written, %zu by stb's encoder\n",
              static_cast<std::uintmax_t>(ours), stb.size());
  EXPECT_LT(static_cast<double>(ours), 0.9 * static_cast<double>(stb.size()));
  const Image read = read_image(path);
  ASSERT_EQ(read.width(), written.width());
  for (int y = 0; y < read.height(); ++y)
    for (int x = 0; x < read.width(); ++x)
      ASSERT_EQ(read.at(x, y), written.at(x, y)) << "pixel (" << x << ", " << y << ")";
}

TEST(Image, WritePngReplacesAnExistingFile) {
  const fs::path path = scratch_dir() / "twice.png";
  write_png(Image(4, 4, Rgb8{10, 20, 30}), path);
  write_png(Image(2, 3, Rgb8{40, 50, 60}), path);
  const Image read = read_image(path);
  EXPECT_EQ(read.width(), 2);
  EXPECT_EQ(read.height(), 3);
  EXPECT_EQ(read.at(1, 2), (Rgb8{40, 50, 60}));
}

TEST(Image, ReadingAMissingFileNamesThePath) {
  const fs::path path = scratch_dir() / "does_not_exist.png";
  try {
    read_image(path);
    FAIL() << "read_image of a missing file did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(Image, ReadingAFileThatIsNotAnImageNamesThePath) {
  const fs::path path = scratch_dir() / "not_an_image.png";
  write_png(Image(1, 1), path);
  fs::resize_file(path, 20);  // a truncated PNG
  try {
    read_image(path);
    FAIL() << "read_image of a truncated PNG did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(Image, WritingIntoAMissingDirectoryThrowsAndLeavesNothing) {
  const fs::path dir = scratch_dir() / "missing";
  const fs::path path = dir / "image.png";
  try {
    write_png(Image(2, 2), path);
    FAIL() << "write_png into a missing directory did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
}

TEST(Image, WritingAnEmptyImageThrows) {
  const fs::path path = scratch_dir() / "empty.png";
  EXPECT_THROW(write_png(Image(), path), std::runtime_error);
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace weft::render
