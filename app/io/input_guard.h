#pragma once
// No output replaces or removes one of the command's own inputs (`weft run DIR/scene.json --out
// DIR`, an obstacle mesh named mesh_0001.obj inside --out, `weft compare DIR/a.png … --out
// DIR`): each command checks its inputs against what it writes before it writes anything.

#include <filesystem>
#include <string>
#include <vector>

#include "app/io/output_files.h"

namespace weft::app {

// What a command writes into its output folder: files by name, and numbered files of the kinds
// it writes and whose earlier run's files it removes.
struct OutputNames {
  std::vector<std::string> files;
  std::vector<NumberedFiles> numbered;
};

// Throws InputError naming the input, the folder and the output when an existing file of
// `inputs` is one that the command would write or remove in `dir` — by any path to it (links
// and `..` resolved). An input elsewhere is left alone (so is another hard link to it in the
// folder: an output is renamed over the name, an earlier file unlinked, the input's file kept).
void refuse_overwriting_inputs(const std::filesystem::path& dir, const OutputNames& outputs,
                               const std::vector<std::filesystem::path>& inputs);

}  // namespace weft::app
