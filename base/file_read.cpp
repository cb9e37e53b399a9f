// Whole-file reads with a size limit; see file_read.h.

#include "base/file_read.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace weft::base {

namespace {

std::string too_large(const std::filesystem::path& path, std::uint64_t max_bytes,
                      const std::string& what, const std::string& size) {
  const std::string limit = max_bytes >= (1u << 20) ? std::to_string(max_bytes >> 20) + " MiB"
                                                     : std::to_string(max_bytes) + " bytes";
  return path.string() + ": " + what + " is at most " + limit + " (the limit), this file " + size;
}

}  // namespace

std::string read_file_capped(const std::filesystem::path& path, std::uint64_t max_bytes,
                             const std::string& what) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw FileReadError(path.string() + ": cannot read " + what + " (" + std::strerror(errno) + ")");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || S_ISDIR(st.st_mode) || S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode))
    throw FileReadError(path.string() + ": cannot read " + what +
                        " (not a regular file: a folder or a device)");
  if (S_ISREG(st.st_mode) && static_cast<std::uint64_t>(st.st_size) > max_bytes)
    throw FileReadError(too_large(path, max_bytes, what, "has " + std::to_string(st.st_size) + " bytes"));
  std::string bytes;
  if (S_ISREG(st.st_mode)) bytes.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw FileReadError(path.string() + ": cannot read " + what + " (" + std::strerror(errno) + ")");
    if (n == 0) return bytes;
    bytes.append(buffer, static_cast<std::size_t>(n));
    if (bytes.size() > max_bytes)  // a pipe, or a file that grew: stop, do not read on
      throw FileReadError(too_large(path, max_bytes, what, "goes on beyond it"));
  }
}

}  // namespace weft::base
