// Outputs that would replace inputs; see input_guard.h.

#include "app/io/input_guard.h"

#include "app/io/input_error.h"

namespace weft::app {

namespace fs = std::filesystem;

namespace {

// The file's path with every link and `..` resolved; empty when it does not exist.
fs::path resolved(const fs::path& path) {
  std::error_code error;
  fs::path out = fs::canonical(path, error);
  return error ? fs::path() : out;
}

// Which output of `outputs` the file `name` in the output folder is, or "".
std::string output_named(const std::string& name, const OutputNames& outputs) {
  for (const std::string& file : outputs.files)
    if (name == file) return file;
  for (const NumberedFiles& kind : outputs.numbered)
    if (std::regex_match(name, numbered_file_pattern(kind)))
      return kind.prefix + "_NNNN." + kind.extension;
  return "";
}

}  // namespace

void refuse_overwriting_inputs(const fs::path& dir, const OutputNames& outputs,
                               const std::vector<fs::path>& inputs) {
  const fs::path folder = resolved(dir);
  if (folder.empty()) return;  // no folder yet: nothing of it can be an input
  for (const fs::path& input : inputs) {
    const fs::path file = resolved(input);
    if (file.empty()) continue;
    // Outputs are renamed over their names and earlier files unlinked, so only the input's own
    // name (links resolved) matters: another hard link to it in the folder loses nothing.
    const std::string output =
        file.parent_path() == folder ? output_named(file.filename().string(), outputs) : "";
    if (!output.empty())
      throw InputError(input.string() + ": an input of this command, but the output folder " +
                       dir.string() + " is where it writes (or removes an earlier run's) " +
                       output + ": the input would be lost; choose another output folder, or "
                       "move the input out of it");
  }
}

}  // namespace weft::app
