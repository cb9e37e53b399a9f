// Image storage and PNG input/output. PNGs are read by stb and written by libpng, whose zlib
// deflate makes the default scene's frames 36 % smaller than stb's own encoder did, with the
// same pixels (docs/benchmarks.md). stb's implementation is compiled into Debian's
// libstb (linked through PkgConfig::STB); only its declarations are included here, so no
// STB_*_IMPLEMENTATION is defined anywhere in weft.

#include "render/image.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>

// libstb's include directory comes from an imported target, so it is a system include and its
// headers' warnings do not reach weft's warning flags.
#include <stb_image.h>
#include <stb_image_write.h>
#include <png.h>

#include "base/atomic_file.h"
#include "base/file_read.h"

namespace weft::render {

namespace {

std::string quoted(const std::filesystem::path& path) {
  return "'" + path.string() + "'";
}

// A file's bytes as stb_image takes them (read_image_file has capped their size far below 2³¹).
const stbi_uc* stb_bytes(const std::string& bytes) {
  return reinterpret_cast<const stbi_uc*>(bytes.data());
}
int stb_size(const std::string& bytes) { return static_cast<int>(bytes.size()); }

void check_inside(const Image& image, int x, int y) {
  if (x < 0 || y < 0 || x >= image.width() || y >= image.height()) {
    throw std::out_of_range("Image: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") outside a " + std::to_string(image.width()) + "x" +
                            std::to_string(image.height()) + " image");
  }
}

// stbi_write_png_to_func callback: appends the encoded bytes to a std::string.
void append_bytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                             static_cast<std::size_t>(size));
}

}  // namespace

Image::Image(int width, int height, Rgb8 fill) : m_width(width), m_height(height) {
  if (width < 0 || height < 0) {
    throw std::invalid_argument("Image: negative size " + std::to_string(width) + "x" +
                                std::to_string(height));
  }
  m_rgb.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  for (std::size_t i = 0; i < m_rgb.size(); i += 3) {
    m_rgb[i] = fill.r;
    m_rgb[i + 1] = fill.g;
    m_rgb[i + 2] = fill.b;
  }
}

Rgb8 Image::at(int x, int y) const {
  check_inside(*this, x, y);
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(m_width) +
                         static_cast<std::size_t>(x)) *
                        3;
  return {m_rgb[i], m_rgb[i + 1], m_rgb[i + 2]};
}

void Image::set(int x, int y, Rgb8 c) {
  check_inside(*this, x, y);
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(m_width) +
                         static_cast<std::size_t>(x)) *
                        3;
  m_rgb[i] = c.r;
  m_rgb[i + 1] = c.g;
  m_rgb[i + 2] = c.b;
}

namespace {

// Writes encoded image bytes to PATH.partial, created exclusively, and renames them over
// PATH, so an interrupted run never leaves a half image and a link planted at the partial
// name cannot redirect the write; a failed write (a full disk) leaves no partial file.
void write_encoded(const std::string& encoded, const std::filesystem::path& path) {
  try {
    base::write_file_atomically(path, encoded);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("write_png: ") + e.what());
  }
}

// Encodes width × height pixels of `channels` bytes each (rows top first) and writes them.
void write_png_bytes(int width, int height, int channels, const std::uint8_t* data,
                     const std::filesystem::path& path) {
  if (width <= 0 || height <= 0) {
    throw std::runtime_error("write_png: cannot write an empty " + std::to_string(width) + "x" +
                             std::to_string(height) + " image to " + quoted(path));
  }
  // Encode in memory first (libpng's simplified API: its size, then the bytes), so an encoder
  // failure leaves no file at all.
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(width);
  png.height = static_cast<png_uint_32>(height);
  png.format = channels == 1   ? PNG_FORMAT_GRAY
               : channels == 2 ? PNG_FORMAT_GA
               : channels == 3 ? PNG_FORMAT_RGB
                               : PNG_FORMAT_RGBA;
  const png_int_32 stride = width * channels;
  png_alloc_size_t size = 0;
  std::string encoded;
  bool ok = png_image_write_to_memory(&png, nullptr, &size, 0, data, stride, nullptr) != 0;
  if (ok) {
    encoded.resize(size);
    ok = png_image_write_to_memory(&png, encoded.data(), &size, 0, data, stride, nullptr) != 0;
    encoded.resize(size);
  }
  if (!ok || encoded.empty()) {
    const std::string reason = png.message[0] ? std::string(": ") + png.message : "";
    png_image_free(&png);
    throw std::runtime_error("write_png: PNG encoding failed for " + quoted(path) + reason);
  }
  write_encoded(encoded, path);
}

}  // namespace

void write_png(const Image& image, const std::filesystem::path& path) {
  write_png_bytes(image.width(), image.height(), 3, image.data(), path);
}

void write_png(const Image& image, const std::vector<std::uint8_t>& alpha,
               const std::filesystem::path& path) {
  const std::size_t n = static_cast<std::size_t>(image.width()) * image.height();
  if (alpha.size() != n) {
    throw std::invalid_argument("write_png: " + std::to_string(alpha.size()) +
                                " alpha values for the " + std::to_string(image.width()) + "x" +
                                std::to_string(image.height()) + " image (" + quoted(path) + ")");
  }
  std::vector<std::uint8_t> rgba(4 * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) rgba[4 * i + c] = image.data()[3 * i + c];
    rgba[4 * i + 3] = alpha[i];
  }
  write_png_bytes(image.width(), image.height(), 4, rgba.data(), path);
}

void write_png(const Image& image, const Mask& opaque, const std::filesystem::path& path) {
  if (opaque.width != image.width() || opaque.height != image.height()) {
    throw std::invalid_argument("write_png: the alpha mask is " + std::to_string(opaque.width) +
                                "x" + std::to_string(opaque.height) + " but the image is " +
                                std::to_string(image.width()) + "x" +
                                std::to_string(image.height()) + " (" + quoted(path) + ")");
  }
  std::vector<std::uint8_t> alpha(opaque.in.size());
  for (std::size_t i = 0; i < alpha.size(); ++i) alpha[i] = opaque.in[i] ? 255 : 0;
  write_png(image, alpha, path);
}

void write_png(const Mask& mask, const std::filesystem::path& path) {
  std::vector<std::uint8_t> grey(mask.in.size());
  for (std::size_t i = 0; i < grey.size(); ++i) grey[i] = mask.in[i] ? 255 : 0;
  write_png_bytes(mask.width, mask.height, 1, grey.data(), path);
}

void write_jpg(const Image& image, const std::filesystem::path& path, int quality) {
  if (image.width() <= 0 || image.height() <= 0)
    throw std::runtime_error("write_jpg: cannot write an empty image to " + quoted(path));
  std::string encoded;
  if (!stbi_write_jpg_to_func(append_bytes, &encoded, image.width(), image.height(), 3,
                              image.data(), quality) ||
      encoded.empty())
    throw std::runtime_error("write_jpg: JPEG encoding failed for " + quoted(path));
  write_encoded(encoded, path);
}

std::string stb_read_failure(const std::filesystem::path& path) {
  const char* reason = stbi_failure_reason();
  std::string why = reason ? reason : "unknown reason";
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) why = "no such file (" + why + ")";
  return why;
}

std::string read_image_file(const std::filesystem::path& path, const char* reader) {
  std::string bytes;
  try {
    bytes = base::read_file_capped(path, max_image_file_bytes, "an image file");
  } catch (const base::FileReadError& e) {
    throw std::runtime_error(std::string(reader) + ": " + e.what());
  }
  int width = 0, height = 0, channels = 0;
  if (stbi_info_from_memory(stb_bytes(bytes), stb_size(bytes), &width, &height, &channels) &&
      static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) > max_image_pixels)
    throw std::runtime_error(std::string(reader) + ": " + quoted(path) + ": a " +
                             std::to_string(width) + "x" + std::to_string(height) +
                             " image, more than " + std::to_string(max_image_pixels) +
                             " pixels (the limit)");
  return bytes;
}

Image read_image(const std::filesystem::path& path) {
  const std::string bytes = read_image_file(path, "read_image");
  int width = 0, height = 0, channels_in_file = 0;
  // 3 requested channels: stb converts grey/grey-alpha/RGBA to RGB; rows come top row first.
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(stb_bytes(bytes), stb_size(bytes), &width, &height,
                            &channels_in_file, 3),
      stbi_image_free);
  if (!pixels)
    throw std::runtime_error("read_image: cannot read " + quoted(path) + ": " + stb_read_failure(path));
  Image image(width, height);
  std::memcpy(image.data(), pixels.get(),
              static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  return image;
}

std::vector<std::uint8_t> read_alpha(const std::filesystem::path& path) {
  const std::string bytes = read_image_file(path, "read_alpha");
  int width = 0, height = 0, channels_in_file = 0;
  if (!stbi_info_from_memory(stb_bytes(bytes), stb_size(bytes), &width, &height, &channels_in_file))
    throw std::runtime_error("read_alpha: cannot read " + quoted(path) + ": " + stb_read_failure(path));
  if (channels_in_file != 2 && channels_in_file != 4) return {};  // grey or RGB: no alpha
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(stb_bytes(bytes), stb_size(bytes), &width, &height,
                            &channels_in_file, 4),
      stbi_image_free);
  if (!pixels)
    throw std::runtime_error("read_alpha: cannot read " + quoted(path) + ": " + stb_read_failure(path));
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<std::uint8_t> alpha(n);
  for (std::size_t i = 0; i < n; ++i) alpha[i] = pixels.get()[4 * i + 3];
  return alpha;
}

}  // namespace weft::render
