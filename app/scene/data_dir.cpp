// Where weft's assets are (see data_dir.h). The build passes three folders (app/CMakeLists.txt):
// WEFT_BIN_TO_DATA, the install data folder relative to the install bin folder
// ("../share/weft"); WEFT_BUILD_DIR and WEFT_SOURCE_ASSETS, the build folder that holds the
// uninstalled binary and the source tree's assets/; WEFT_INSTALL_DATA, the configured prefix's
// data folder.

#include "app/scene/data_dir.h"

#include <algorithm>
#include <cstdlib>
#include <system_error>
#include <vector>

#include "app/io/input_error.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

bool has_scenes(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir / "scenes", ec);
}

// The running binary's folder, symlinks resolved; empty when /proc is not there.
fs::path binary_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

bool same_folder(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return !a.empty() && fs::equivalent(a, b, ec);
}

}  // namespace

fs::path data_dir() {
  if (const char* env = std::getenv("WEFT_DATA_DIR"); env && *env) {
    if (!has_scenes(env))
      throw InputError(std::string("WEFT_DATA_DIR=") + env +
                       ": no scenes/ folder there (expected weft's data folder, e.g. "
                       "PREFIX/share/weft or the source tree's assets/)");
    return env;
  }
  const fs::path bin = binary_dir();
  std::vector<fs::path> tried;
  if (!bin.empty()) {
    const fs::path installed = (bin / WEFT_BIN_TO_DATA).lexically_normal();
    if (has_scenes(installed)) return installed;
    tried.push_back(installed);
    if (same_folder(bin, WEFT_BUILD_DIR) && has_scenes(WEFT_SOURCE_ASSETS))
      return WEFT_SOURCE_ASSETS;
  }
  if (has_scenes(WEFT_INSTALL_DATA)) return WEFT_INSTALL_DATA;
  tried.push_back(WEFT_INSTALL_DATA);
  std::string places;
  for (const fs::path& p : tried) places += (places.empty() ? "" : ", ") + p.string();
  throw InputError("cannot find weft's scenes folder (looked in " + places +
                   "); install weft with cmake --install, or set WEFT_DATA_DIR");
}

fs::path find_scene(const fs::path& given) {
  std::error_code ec;
  if (given.empty() || fs::exists(given, ec) || given.has_parent_path()) return given;
  fs::path dir;
  try {
    dir = data_dir() / "scenes";
  } catch (const InputError&) {
    return given;
  }
  for (const fs::path& candidate :
       {dir / given, dir / (given.string() + (given.extension() == ".json" ? "" : ".json"))})
    if (fs::is_regular_file(candidate, ec)) return candidate;
  return given;
}

std::string known_scene_names() {
  const fs::path dir = data_dir() / "scenes";
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".json") names.push_back(it->path().stem().string());
  std::sort(names.begin(), names.end());
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

}  // namespace weft::app
