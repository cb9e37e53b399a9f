#pragma once
// The files a scene reads besides its own text: the cloth's mesh (cloth.mesh), mesh obstacles
// (obstacles[i].mesh.file), the cloth's texture (render.texture.file) and the environment map
// (render.environment.file). Each is named relative to the scene file (or absolute). Commands
// keep these from being overwritten by their outputs (app/io/input_guard.h), and checkpoints
// hash their bytes, so that a resume with a changed file is refused (app/io/run_checkpoint.h).

#include <filesystem>
#include <string>
#include <vector>

#include "app/scene/json_reader.h"

namespace weft::app {

// A file named in the scene file `scene_file`: relative to its folder unless absolute.
std::filesystem::path scene_relative(const std::string& scene_file,
                                     const std::filesystem::path& file);

struct Scene;

// The scene's own file (none for the built-in scene) and every file it reads: what no output of
// a command that reads the scene may replace.
std::vector<std::filesystem::path> scene_files(const Scene& scene);

// The files of the keys above that the parsed scene `document` names, resolved, in the order
// listed there; a key of another type is skipped (the scene reader reports it).
std::vector<std::filesystem::path> scene_input_files(const Json& document,
                                                     const std::string& scene_file);

}  // namespace weft::app
