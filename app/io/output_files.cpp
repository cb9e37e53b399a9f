// Output-folder helpers; see output_files.h.

#include "app/io/output_files.h"

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <regex>
#include <stdexcept>

#include "app/io/finite_outputs.h"
#include "app/io/version.h"
#include "base/atomic_file.h"

namespace weft::app {

namespace fs = std::filesystem;

void write_through_folder(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  const fs::path folder = base::partial_path(path);
  std::error_code ignored;
  fs::remove_all(folder, ignored);  // a killed run's; a link there is removed, not followed
  if (::mkdir(folder.c_str(), 0700) != 0)
    throw std::runtime_error(folder.string() + ": cannot create (" + std::strerror(errno) + ")");
  try {
    write(folder / path.filename());
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.path().filename() != path.filename())
        fs::rename(entry.path(), path.parent_path() / entry.path().filename());
    fs::rename(folder / path.filename(), path);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(folder, ignored);
    throw std::runtime_error(path.string() + ": cannot write (" + e.code().message() + ")");
  } catch (...) {
    fs::remove_all(folder, ignored);
    throw;
  }
  fs::remove(folder, ignored);
}

void write_text(const fs::path& path, const std::string& text) {
  if (lower_extension(path) == ".csv") require_finite_csv(path.string(), text);
  base::write_file_atomically(path, text);
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code error;
  return fs::equivalent(a, b, error) && !error;
}

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::regex numbered_file_pattern(const NumberedFiles& kind) {
  return std::regex(kind.prefix + R"(_\d{4,}\.)" + kind.extension);
}

int remove_numbered_files(const fs::path& dir, const std::string& prefix,
                          const std::string& extension) {
  const std::regex pattern = numbered_file_pattern({prefix, extension});
  int removed = 0;
  for (const auto& entry : fs::directory_iterator(dir))
    if (std::regex_match(entry.path().filename().string(), pattern) && fs::remove(entry.path()))
      ++removed;
  return removed;
}

void start_output(std::optional<OutputFolderLock>& lock, const fs::path& dir,
                  const std::vector<NumberedFiles>& earlier,
                  const std::vector<std::pair<std::string, std::string>>& files) {
  if (!lock) lock.emplace(dir);  // creates the folder
  int removed = 0;
  for (const NumberedFiles& kind : earlier)
    removed += remove_numbered_files(dir, kind.prefix, kind.extension);
  if (removed)
    std::fprintf(stderr, "weft: replaced %d files of an earlier run in %s\n", removed,
                 dir.c_str());
  for (const auto& [name, text] : files) write_text(dir / name, text);
}

std::string run_record(const std::string& command_line,
                       const std::vector<std::pair<std::string, std::string>>& inputs) {
  std::string text = "weft " + std::string(version()) + "\ncommand: " + command_line + "\n";
  for (const auto& [key, value] : inputs) text += key + ": " + value + "\n";
  return text;
}

std::string numbered_file_name(const char* prefix, int frame, const char* extension) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%04d.%s", prefix, frame, extension);
  return name;
}

}  // namespace weft::app
