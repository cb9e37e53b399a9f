// Outputs that would replace inputs; see input_guard.h.

#include "app/io/input_guard.h"

#include <regex>

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
    if (std::regex_match(name, std::regex(kind.prefix + R"(_\d{4,}\.)" + kind.extension)))
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
    std::string output;
    if (file.parent_path() == folder) output = output_named(file.filename().string(), outputs);
    // A hard link, or a link inside the folder that leads to the input.
    for (const std::string& name : outputs.files)
      if (output.empty() && same_file(dir / name, input)) output = name;
    if (!output.empty())
      throw InputError(input.string() + ": an input of this command, but the output folder " +
                       dir.string() + " is where it writes (or removes an earlier run's) " +
                       output + ": the input would be lost; choose another output folder, or "
                       "move the input out of it");
  }
}

}  // namespace weft::app
