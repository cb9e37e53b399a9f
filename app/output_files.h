#pragma once
// Writing into an output folder, shared by the commands: a text file, and clearing the
// numbered files (frame_0001.png, mesh_0001.obj, turntable_0001.png, …) an earlier run left.

#include <filesystem>
#include <string>

namespace weft::app {

// Writes `text` to `path`; throws std::runtime_error naming the path when it cannot.
void write_text(const std::filesystem::path& path, const std::string& text);

// Removes the files in `dir` named <prefix>_<4 or more digits>.<extension> (extension a
// regular expression such as "png" or "(obj|ply|gltf|bin)"); returns how many.
int remove_numbered_files(const std::filesystem::path& dir, const std::string& prefix,
                          const std::string& extension);

}  // namespace weft::app
