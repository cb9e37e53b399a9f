#pragma once
// Writing into an output folder, shared by the commands: a text file, and clearing the
// numbered files (frame_0001.png, mesh_0001.obj, turntable_0001.png, …) an earlier run left.

#include <filesystem>
#include <string>

namespace weft::app {

// Writes `text` to `path` atomically (to PATH.partial, then renamed: a reader sees the old file
// or the whole new one, never a part); throws std::runtime_error naming the path when it
// cannot. render::write_png does the same for images.
void write_text(const std::filesystem::path& path, const std::string& text);

// Whether two paths name the same file (the same file twice, through links or `..`), e.g. an
// output that would overwrite an input. A path that does not exist is the same as no other.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// The path's extension in lower case, with its dot: ".png" for "A.PNG", "" for none.
std::string lower_extension(const std::filesystem::path& path);

// Removes the files in `dir` named <prefix>_<4 or more digits>.<extension> (extension a
// regular expression such as "png" or "(obj|ply|gltf|bin)"); returns how many.
int remove_numbered_files(const std::filesystem::path& dir, const std::string& prefix,
                          const std::string& extension);

}  // namespace weft::app
