#pragma once
// A lock on an output folder, so that two weft commands never write into one folder at once
// (the second would remove the first's frames as an earlier run's, and the first then fail).

#include <filesystem>

namespace weft::app {

// The lock file's name inside an output folder.
inline constexpr const char* output_lock_file_name = ".weft-lock";

// An exclusive flock(2) on DIR/.weft-lock, held while the object lives (the system drops it
// when the process ends, however it ends: a killed run leaves no stale lock, only the empty
// file). Creates DIR when needed.
class OutputFolderLock {
 public:
  // Throws InputError "DIR: another weft command is writing into this folder …" when another
  // process (or another lock in this one) holds it, std::runtime_error naming the file when it
  // cannot be made.
  explicit OutputFolderLock(const std::filesystem::path& dir);
  OutputFolderLock(OutputFolderLock&& other) noexcept;
  OutputFolderLock& operator=(OutputFolderLock&&) = delete;
  OutputFolderLock(const OutputFolderLock&) = delete;
  ~OutputFolderLock();

 private:
  int m_fd = -1;
};

}  // namespace weft::app
