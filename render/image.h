#pragma once
// 8-bit RGB images and PNG input/output (stb, through Debian's libstb).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "render/mask.h"

namespace weft::render {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb8& p, const Rgb8& q) { return p.r == q.r && p.g == q.g && p.b == q.b; }
};

// width×height pixels, rows stored top row first, 3 bytes per pixel.
class Image {
 public:
  Image() = default;
  Image(int width, int height, Rgb8 fill = {});

  int width() const { return m_width; }
  int height() const { return m_height; }
  Rgb8 at(int x, int y) const;  // (0, 0) is the top-left pixel
  void set(int x, int y, Rgb8 c);
  std::uint8_t* data() { return m_rgb.data(); }
  const std::uint8_t* data() const { return m_rgb.data(); }

 private:
  int m_width = 0, m_height = 0;
  std::vector<std::uint8_t> m_rgb;
};

// Writes a PNG; throws std::runtime_error naming the path when it cannot.
void write_png(const Image& image, const std::filesystem::path& path);
// An RGBA PNG: the image's colours, alpha 255 where `opaque` is set and 0 elsewhere (straight,
// not premultiplied alpha); the sizes must match.
void write_png(const Image& image, const Mask& opaque, const std::filesystem::path& path);
// An RGBA PNG of the image's colours and `alpha` (one byte per pixel, straight alpha); the
// sizes must match.
void write_png(const Image& image, const std::vector<std::uint8_t>& alpha,
               const std::filesystem::path& path);
// A grey PNG of the mask: 255 where set, 0 elsewhere (mask_from_image reads it back).
void write_png(const Mask& mask, const std::filesystem::path& path);
// Writes a baseline JPEG of the given quality (1…100); throws std::runtime_error naming the path.
void write_jpg(const Image& image, const std::filesystem::path& path, int quality = 95);
// Image files read (PNG, JPG, Radiance .hdr) are at most max_image_file_bytes and
// max_image_pixels (width × height, 8192² — a decoded RGB float map of it is 805 MB): a larger
// file, a device (`/dev/zero`) or a small file claiming a huge image is refused before it is
// decoded.
inline constexpr std::uint64_t max_image_file_bytes = std::uint64_t{256} << 20;
inline constexpr std::uint64_t max_image_pixels = std::uint64_t{1} << 26;

// The bytes of an image file after those checks (stb's header read gives the size); throws
// std::runtime_error "READER: PATH: …" naming what is wrong.
std::string read_image_file(const std::filesystem::path& path, const char* reader);

// Reads a PNG/JPG as RGB; throws std::runtime_error naming the path and stb's reason.
Image read_image(const std::filesystem::path& path);

// The alpha channel of a PNG (one byte per pixel, rows top row first), or an empty vector when
// the file has none (grey, RGB, JPG). Throws as read_image.
std::vector<std::uint8_t> read_alpha(const std::filesystem::path& path);

// Why stb_image just failed to read `path`: its failure reason, or that there is no such file.
std::string stb_read_failure(const std::filesystem::path& path);

}  // namespace weft::render
