#pragma once
// Reading a whole input file with a size limit, so that a huge file or a device that never ends
// (`/dev/zero`) is refused at once instead of filling memory: a device or folder is refused
// before any byte is read, a regular file larger than the limit by its size, and whatever else
// (a pipe) as soon as more than the limit has come.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace weft::base {

// The file cannot be read, or is larger than allowed. what(): "PATH: …" with the reason.
class FileReadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The file's bytes. `what` names the kind of file for the message ("a checkpoint"): "PATH: a
// checkpoint is at most 1024 MiB (the limit), this file has N bytes".
std::string read_file_capped(const std::filesystem::path& path, std::uint64_t max_bytes,
                             const std::string& what);

}  // namespace weft::base
