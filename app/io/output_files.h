#pragma once
// Writing into an output folder, shared by the commands: a text file, and clearing the
// numbered files (frame_0001.png, mesh_0001.obj, turntable_0001.png, …) an earlier run left.
// Every file is written whole (NAME.partial, then renamed), and a command touches its folder
// only when its first output is ready (start_output), so a command that fails before leaves an
// earlier run's files as they were (docs/reliability.md).

#include <filesystem>
#include <functional>
#include <optional>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "app/io/output_lock.h"

namespace weft::app {

// Writes `text` to `path` atomically (base::write_file_atomically: to PATH.partial, created
// exclusively, then renamed: a reader sees the old file or the whole new one, never a part, and
// a link planted at the partial name is not followed); throws std::runtime_error naming the
// path when it cannot, leaving no partial file. render::write_png does the same for images.
// A .csv file's cells must be finite numbers where they are numbers (require_finite_csv,
// app/io/finite_outputs.h): a non-finite one throws before anything is written.
void write_text(const std::filesystem::path& path, const std::string& text);

// Writes `path` atomically for a writer that opens files itself (ffmpeg, assimp): a fresh
// folder PATH.partial/ is made (mkdir, so by this process alone, mode 0700: nobody else can
// place a link in it), `write` makes the file PATH.partial/NAME (NAME: path's file name) and
// any companions beside it (an OBJ's .mtl, a glTF's .bin), which are then moved beside `path`,
// companions first, NAME last; the folder is removed. A throwing `write` leaves `path` as it
// was and removes the folder. Throws std::runtime_error naming the path when a move fails.
void write_through_folder(const std::filesystem::path& path,
                          const std::function<void(const std::filesystem::path&)>& write);

// Numbered files of one kind, e.g. {"frame", "png"} for frame_0001.png (remove_numbered_files).
struct NumberedFiles {
  std::string prefix;
  std::string extension;  // a regular expression: "png", "(obj|mtl|ply|gltf|bin)"
};

// What a command writes first into its output folder, when its first output is ready: creates
// `dir`, locks it (into `lock`, unless it holds the lock already; the command keeps it to its
// end: another command writing there is refused, app/io/output_lock.h), removes the numbered
// files of an earlier run (saying on stderr how many), so that the folder holds one run, and
// writes each {name, text} of `files` (the run's record: run.txt, scene.json, …). Until then
// the command leaves the folder alone.
void start_output(std::optional<OutputFolderLock>& lock, const std::filesystem::path& dir,
                  const std::vector<NumberedFiles>& earlier,
                  const std::vector<std::pair<std::string, std::string>>& files);

// The record of how an output folder was made (run.txt, turntable.txt, measure.txt, …):
// "weft VERSION", "command: COMMAND_LINE" and one "KEY: VALUE" line per input.
std::string run_record(const std::string& command_line,
                       const std::vector<std::pair<std::string, std::string>>& inputs);

// Whether two paths name the same file (the same file twice, through links or `..`), e.g. an
// output that would overwrite an input. A path that does not exist is the same as no other.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// The path's extension in lower case, with its dot: ".png" for "A.PNG", "" for none.
std::string lower_extension(const std::filesystem::path& path);

// The names of that kind, <prefix>_<4 or more digits>.<extension>, as a regular expression.
std::regex numbered_file_pattern(const NumberedFiles& kind);

// Removes the files in `dir` named <prefix>_<4 or more digits>.<extension> (extension a
// regular expression such as "png" or "(obj|ply|gltf|bin)"); returns how many.
int remove_numbered_files(const std::filesystem::path& dir, const std::string& prefix,
                          const std::string& extension);

// frame_0001.png, mask_0001.png, state_0001.npy, mesh_0001.obj …: PREFIX_NNNN.EXTENSION.
std::string numbered_file_name(const char* prefix, int frame, const char* extension);

}  // namespace weft::app
