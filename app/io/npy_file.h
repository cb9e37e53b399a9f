#pragma once
// NumPy .npy files (format versions 1.0, 2.0 and 3.0), read strictly: a little- or big-endian
// float32/float64 array in C order, e.g. a point cloud of N×3 coordinates. Anything else — a
// missing or short file, a bad magic string or header, Fortran order, an integer, complex or
// object dtype, a shape that does not match — is an error naming the file and what was
// expected. The header is the Python dict literal NumPy writes,
// {'descr': '<f8', 'fortran_order': False, 'shape': (N, 3), }, padded with spaces to a
// multiple of 64 bytes and ended by '\n' (numpy.lib.format, "The .npy format").

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace weft::app {

// Bad .npy input; what() reads "FILE: what was expected (got …)".
class NpyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct NpyArray {
  std::vector<std::int64_t> shape;  // e.g. {N, 3}; {} for a scalar
  std::vector<double> values;       // C order (last index fastest), converted to double
};

// Reads a float32 or float64 array of any shape. Throws NpyError.
NpyArray read_npy(const std::filesystem::path& path);
// The same from a file's bytes; `path` names it in errors (tests/fuzz reads bytes).
NpyArray parse_npy(const std::string& bytes, const std::filesystem::path& path);

// A .npy file is read only up to this size (44 M points of float64): a larger file or a device
// (`/dev/zero`) is an NpyError naming it at once.
inline constexpr std::uint64_t max_npy_bytes = std::uint64_t{1} << 30;

// Reads an N×3 float array (N ≥ 1) of finite values, e.g. points in metres, as #N×3 rows.
// Throws NpyError naming the file for another shape or a non-finite value (its row).
Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> read_npy_points(
    const std::filesystem::path& path);

// Writes rows×3 float64 values as a version 1.0 .npy file (little-endian, C order), e.g. a
// synthetic point cloud, atomically and exclusively (base::write_file_atomically). Throws
// std::runtime_error naming the path when it cannot.
void write_npy_points(const std::filesystem::path& path,
                      const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& points);

}  // namespace weft::app
