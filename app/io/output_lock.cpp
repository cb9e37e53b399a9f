// Output folder locks; see output_lock.h.

#include "app/io/output_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "app/io/input_error.h"

namespace weft::app {

namespace fs = std::filesystem;

OutputFolderLock::OutputFolderLock(const fs::path& dir) {
  fs::create_directories(dir);
  const fs::path file = dir / output_lock_file_name;
  // O_NOFOLLOW: a link planted at the name cannot make weft create or lock another file.
  m_fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (m_fd < 0)
    throw std::runtime_error(file.string() + ": cannot open the output folder's lock file (" +
                             std::strerror(errno) + ")");
  if (::flock(m_fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(m_fd);
    m_fd = -1;
    if (error == EWOULDBLOCK)
      throw InputError(dir.string() + ": another weft command is writing into this folder (it "
                       "holds the lock " + file.string() + "); wait until it ends, or choose "
                       "another output folder");
    throw std::runtime_error(file.string() + ": cannot lock (" + std::strerror(error) + ")");
  }
}

OutputFolderLock::OutputFolderLock(OutputFolderLock&& other) noexcept
    : m_fd(std::exchange(other.m_fd, -1)) {}

OutputFolderLock::~OutputFolderLock() {
  if (m_fd >= 0) ::close(m_fd);  // closing the last descriptor releases the lock
}

}  // namespace weft::app
