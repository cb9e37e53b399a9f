// Exclusive, atomic file writes; see atomic_file.h.

#include "base/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

namespace weft::base {

namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path, int error) {
  throw std::runtime_error(path.string() + ": cannot " + what + " (" + std::strerror(error) + ")");
}

}  // namespace

ExclusiveFile::ExclusiveFile(std::filesystem::path path) : m_path(std::move(path)) {
  // unlink removes a symbolic link itself, not what it points to; a folder stays (and the
  // open below fails naming it).
  if (::unlink(m_path.c_str()) != 0 && errno != ENOENT && errno != EISDIR && errno != EPERM)
    fail("remove the earlier temporary file", m_path, errno);
  m_fd = ::open(m_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (m_fd < 0) fail("create", m_path, errno);
}

ExclusiveFile::~ExclusiveFile() {
  if (m_fd >= 0) ::close(m_fd);
}

void ExclusiveFile::write(std::string_view bytes) {
  if (m_fd < 0) throw std::logic_error(m_path.string() + ": written after close");
  while (!bytes.empty()) {
    const ssize_t n = ::write(m_fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("write", m_path, n < 0 ? errno : EIO);
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

void ExclusiveFile::close() {
  const int fd = std::exchange(m_fd, -1);
  if (fd >= 0 && ::close(fd) != 0) fail("write", m_path, errno);
}

std::filesystem::path partial_path(const std::filesystem::path& path) {
  return path.string() + ".partial";
}

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(ExclusiveFile&)>& write) {
  const std::filesystem::path partial = partial_path(path);
  try {
    ExclusiveFile file(partial);
    write(file);
    file.close();
    if (std::rename(partial.c_str(), path.c_str()) != 0) fail("write", path, errno);
  } catch (...) {
    // Also a partial file whose creation failed half-way, or a rename refused: none is left.
    struct stat st {};
    if (::lstat(partial.c_str(), &st) == 0 && !S_ISDIR(st.st_mode)) ::unlink(partial.c_str());
    throw;
  }
}

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  write_atomically(path, [&](ExclusiveFile& file) { file.write(bytes); });
}

}  // namespace weft::base
