#pragma once
// Writing a file so that neither a reader nor another user of a shared folder can see or steer
// a part of it. The bytes go to a temporary file PATH.partial beside it, created by this
// process alone — whatever was at that name (a killed run's leftover, or a symbolic link
// planted to redirect the write) is unlinked first, never followed, and the file is opened with
// O_CREAT|O_EXCL|O_NOFOLLOW — then renamed over PATH once complete. On any error (a full disk,
// a closed folder) the partial file is removed and nothing at PATH changes.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string_view>

namespace weft::base {

// A file created exclusively for writing (see above). Errors are std::runtime_error naming the
// path and the system's reason ("No space left on device").
class ExclusiveFile {
 public:
  // Unlinks what is at `path` (a file or a link, not a folder) and creates the file anew.
  explicit ExclusiveFile(std::filesystem::path path);
  ExclusiveFile(const ExclusiveFile&) = delete;
  ExclusiveFile& operator=(const ExclusiveFile&) = delete;
  ~ExclusiveFile();  // closes the file if close() was not called; errors are then lost

  void write(std::string_view bytes);
  // Closes the file, throwing if the system reports an error writing it out.
  void close();
  const std::filesystem::path& path() const { return m_path; }

 private:
  std::filesystem::path m_path;
  int m_fd = -1;
};

// PATH.partial, the temporary name of `path`.
std::filesystem::path partial_path(const std::filesystem::path& path);

// Writes `path` atomically: `write` fills an ExclusiveFile at PATH.partial, which is closed and
// renamed over `path`; if anything throws, the partial file is removed and the error rethrown.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(ExclusiveFile&)>& write);

// The same with the whole content at once.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace weft::base
