// Output-folder helpers; see output_files.h.

#include "app/output_files.h"

#include <fstream>
#include <cctype>
#include <regex>
#include <stdexcept>

namespace weft::app {

namespace fs = std::filesystem;

void write_text(const fs::path& path, const std::string& text) {
  const fs::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial);
    out << text;
    out.flush();
    if (!out) throw std::runtime_error(path.string() + ": cannot write");
  }
  std::error_code error;
  fs::rename(partial, path, error);
  if (error) throw std::runtime_error(path.string() + ": cannot write (" + error.message() + ")");
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

int remove_numbered_files(const fs::path& dir, const std::string& prefix,
                          const std::string& extension) {
  const std::regex pattern(prefix + R"(_\d{4,}\.)" + extension);
  int removed = 0;
  for (const auto& entry : fs::directory_iterator(dir))
    if (std::regex_match(entry.path().filename().string(), pattern) && fs::remove(entry.path()))
      ++removed;
  return removed;
}

}  // namespace weft::app
