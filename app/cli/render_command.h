#pragma once
// `weft render DIR`: draws frames of a run from the cloth states `weft run --save-states` wrote
// into DIR (state_0000.npy … state_NNNN.npy), without simulating: a chosen range (--frames A-B,
// --every N), with render settings that may differ from the run's (--size, --renderer,
// --samples, --set render.*), so that simulation (sequential) and rendering (one task per frame
// range) can run apart (docs/checkpoints.md). The frames are drawn by the one frame painter of
// weft run (app/run/frame_painter.h): with the run's render settings they are the same bytes.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "app/cli/options.h"

namespace weft::app {

// The default output folder inside the run's folder: `weft render DIR` writes DIR/render/.
inline constexpr const char* default_render_folder = "render";

struct RenderOptions {
  std::filesystem::path states;              // the run's output folder
  std::optional<std::filesystem::path> scene;  // default: states/scene.json
  std::optional<std::filesystem::path> out;    // default: states/render (default_render_folder)
  std::string frames;                        // "A-B" or "A"; empty: every frame of the scene
  int every = 1;                             // every Nth frame from A, and B
  std::vector<Setting> overrides;            // render.*, output.alpha and output.mask only
  std::optional<int> threads;
  // --slurm: write OUT/slurm/render.sbatch, a job array of `tasks` tasks each drawing one
  // contiguous part of the frames (app/cluster/slurm_job.h), and submit it unless dry_run.
  bool slurm = false;
  int tasks = 4;
  bool dry_run = false;
};

Command register_render(CLI::App& app, const std::string& command_line);

// Throws InputError (bad option, missing or mismatched state file) before writing anything.
int run_render(const RenderOptions& options);

// "100-199" or "7" → {first, last}, each within 1..frames. Throws InputError naming --frames.
std::pair<int, int> parse_frame_range(const std::string& text, int frames);

}  // namespace weft::app
