// NumPy .npy reading and writing (see npy_file.h).

#include "app/io/npy_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "base/atomic_file.h"
#include "base/file_read.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

bool native_big_endian() {
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 0;
}

[[noreturn]] void fail(const fs::path& path, const std::string& what) {
  throw NpyError(path.string() + ": " + what);
}

std::string file_bytes(const fs::path& path) {
  try {
    return base::read_file_capped(path, max_npy_bytes, "a .npy file");
  } catch (const base::FileReadError& e) {
    throw NpyError(e.what());
  }
}

std::uint32_t little_endian(const std::string& bytes, std::size_t at, int count) {
  std::uint32_t v = 0;
  for (int k = count - 1; k >= 0; --k)
    v = (v << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(k)]);
  return v;
}

// The text after "'key':" in the header dict, trimmed of leading spaces.
std::string header_value(const fs::path& path, const std::string& header, const std::string& key) {
  const std::size_t k = header.find("'" + key + "'");
  if (k == std::string::npos) fail(path, "the header has no '" + key + "' (header: " + header + ")");
  std::size_t at = header.find(':', k);
  if (at == std::string::npos) fail(path, "malformed header: " + header);
  ++at;
  while (at < header.size() && header[at] == ' ') ++at;
  return header.substr(at);
}

struct Dtype {
  bool big_endian = false;
  int bytes = 8;
};

Dtype parse_descr(const fs::path& path, const std::string& header) {
  const std::string v = header_value(path, header, "descr");
  const std::size_t end = v.find('\'', 1);
  if (v.empty() || v[0] != '\'' || end == std::string::npos) fail(path, "malformed 'descr'");
  const std::string descr = v.substr(1, end - 1);
  if (descr == "<f8" || descr == "<f4" || descr == ">f8" || descr == ">f4" || descr == "=f8" ||
      descr == "=f4")
    return {descr[0] == '>', descr[2] == '8' ? 8 : 4};
  fail(path, "expected a float64 or float32 array ('<f8', '<f4', '>f8', '>f4'), got dtype '" +
                 descr + "'");
}

std::vector<std::int64_t> parse_shape(const fs::path& path, const std::string& header) {
  const std::string v = header_value(path, header, "shape");
  const std::size_t close = v.find(')');
  if (v.empty() || v[0] != '(' || close == std::string::npos) fail(path, "malformed 'shape'");
  std::vector<std::int64_t> shape;
  std::stringstream items(v.substr(1, close - 1));
  std::string item;
  while (std::getline(items, item, ',')) {
    const std::size_t first = item.find_first_not_of(' ');
    if (first == std::string::npos) continue;  // the trailing comma of (N,)
    char* end = nullptr;
    const long long n = std::strtoll(item.c_str() + first, &end, 10);
    if (end == item.c_str() + first || n < 0) fail(path, "malformed 'shape' entry '" + item + "'");
    shape.push_back(n);
  }
  return shape;
}

// "(2, 3)".
std::string shape_text(const std::vector<std::int64_t>& shape) {
  std::string text = "(";
  for (std::size_t k = 0; k < shape.size(); ++k) text += (k ? ", " : "") + std::to_string(shape[k]);
  return text + ")";
}

double element(const std::string& bytes, std::size_t at, const Dtype& d) {
  unsigned char raw[8];
  std::memcpy(raw, bytes.data() + at, static_cast<std::size_t>(d.bytes));
  if (d.big_endian != native_big_endian())
    for (int k = 0; k < d.bytes / 2; ++k) std::swap(raw[k], raw[d.bytes - 1 - k]);
  if (d.bytes == 8) {
    double v;
    std::memcpy(&v, raw, 8);
    return v;
  }
  float v;
  std::memcpy(&v, raw, 4);
  return v;
}

}  // namespace

NpyArray read_npy(const fs::path& path) { return parse_npy(file_bytes(path), path); }

NpyArray parse_npy(const std::string& bytes, const fs::path& path) {
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0)
    fail(path, "not a .npy file (expected the magic string \\x93NUMPY at the start)");
  const int major = static_cast<unsigned char>(bytes[6]);
  if (major < 1 || major > 3)
    fail(path, "unsupported .npy format version " + std::to_string(major) + " (expected 1, 2 or 3)");
  const int length_bytes = major == 1 ? 2 : 4;
  const std::size_t header_start = 8 + static_cast<std::size_t>(length_bytes);
  if (bytes.size() < header_start) fail(path, "the file ends inside its header");
  const std::size_t header_length = little_endian(bytes, 8, length_bytes);
  if (bytes.size() < header_start + header_length) fail(path, "the file ends inside its header");
  const std::string header = bytes.substr(header_start, header_length);
  if (header_value(path, header, "fortran_order").rfind("False", 0) != 0)
    fail(path, "expected 'fortran_order': False (C order), got Fortran order");
  const Dtype dtype = parse_descr(path, header);
  NpyArray array;
  array.shape = parse_shape(path, header);
  const std::size_t data_start = header_start + header_length;
  const std::size_t data_bytes = bytes.size() - data_start;
  // The element count and its bytes, each product checked: a shape of 2⁶¹ × 3 used to wrap
  // round (to the data's size, or to std::bad_alloc naming no file).
  std::size_t count = 1, expected = 0;
  for (const std::int64_t n : array.shape)
    if (__builtin_mul_overflow(count, static_cast<std::size_t>(n), &count))
      fail(path, "its shape " + shape_text(array.shape) + " has more elements than a size holds "
                 "(the element count overflows)");
  if (__builtin_mul_overflow(count, static_cast<std::size_t>(dtype.bytes), &expected))
    fail(path, "its shape " + shape_text(array.shape) + " needs more bytes than a size holds "
               "(the byte count overflows)");
  if (data_bytes != expected)
    fail(path, "expected " + std::to_string(expected) + " bytes of data for its shape " +
                   shape_text(array.shape) + ", got " + std::to_string(data_bytes));
  array.values.resize(count);
  for (std::size_t i = 0; i < count; ++i)
    array.values[i] = element(bytes, data_start + i * static_cast<std::size_t>(dtype.bytes), dtype);
  return array;
}

Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> read_npy_points(const fs::path& path) {
  const NpyArray a = read_npy(path);
  if (a.shape.size() != 2 || a.shape[1] != 3 || a.shape[0] < 1)
    fail(path, "expected an N×3 array of points (N ≥ 1), got shape " + shape_text(a.shape));
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> points(a.shape[0], 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double v = a.values[static_cast<std::size_t>(3 * i + c)];
      if (!std::isfinite(v))
        fail(path, "point " + std::to_string(i) + " has a non-finite coordinate");
      points(i, c) = v;
    }
  return points;
}

void write_npy_points(const fs::path& path,
                      const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& points) {
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" +
                       std::to_string(points.rows()) + ", 3), }";
  const std::size_t unpadded = 10 + header.size() + 1;
  header += std::string((64 - unpadded % 64) % 64, ' ') + "\n";
  std::string out("\x93NUMPY\x01\x00", 8);
  const auto n = static_cast<std::uint16_t>(header.size());
  out += static_cast<char>(n & 0xff);
  out += static_cast<char>(n >> 8);
  out += header;
  out.reserve(out.size() + 24 * static_cast<std::size_t>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double v = points(i, c);
      char raw[8];
      std::memcpy(raw, &v, 8);
      if (native_big_endian()) std::reverse(raw, raw + 8);
      out.append(raw, 8);
    }
  base::write_file_atomically(path, out);
}

}  // namespace weft::app
