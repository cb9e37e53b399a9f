// The files a scene reads; see scene_inputs.h.

#include "app/scene/scene_inputs.h"

#include "app/scene/scene.h"

namespace weft::app {

namespace fs = std::filesystem;

fs::path scene_relative(const std::string& scene_file, const fs::path& file) {
  return file.is_absolute() ? file : fs::path(scene_file).parent_path() / file;
}

std::vector<fs::path> scene_files(const Scene& scene) {
  std::vector<fs::path> files = scene.input_files;
  if (std::filesystem::exists(scene.source)) files.emplace_back(scene.source);  // not "<built-in …>"
  return files;
}

namespace {

// document[a][b]…: a string value, or nullptr.
const std::string* string_at(const Json& object, std::initializer_list<const char*> keys) {
  const Json* at = &object;
  for (const char* key : keys) {
    if (!at->is_object() || !at->contains(key)) return nullptr;
    at = &at->at(key);
  }
  return at->is_string() ? at->get_ptr<const std::string*>() : nullptr;
}

}  // namespace

std::vector<fs::path> scene_input_files(const Json& document, const std::string& scene_file) {
  std::vector<fs::path> files;
  const auto add = [&](const std::string* file) {
    if (file) files.push_back(scene_relative(scene_file, *file));
  };
  add(string_at(document, {"cloth", "mesh"}));
  if (document.is_object() && document.contains("obstacles") && document["obstacles"].is_array())
    for (const Json& obstacle : document["obstacles"]) add(string_at(obstacle, {"mesh", "file"}));
  add(string_at(document, {"render", "texture", "file"}));
  add(string_at(document, {"render", "weave", "file"}));
  add(string_at(document, {"render", "environment", "file"}));
  return files;
}

}  // namespace weft::app
