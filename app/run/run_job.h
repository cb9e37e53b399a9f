#pragma once
// The job of `weft run` (and of each scene of `weft gallery`): simulate a scene and write its
// PNG sequence, stats.csv and a copy of the scene. The command line: app/cli/run_command.h.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/io/exit_code.h"
#include "app/io/mesh_export.h"
#include "app/io/point_cache.h"
#include "app/scene/scene_patch.h"

namespace weft::app {

// Every `every`-th frame from `first` to `last`, and `last` itself: --every 24 over 96 frames
// is 1, 25, 49, 73 and 96 (the last frame, the cloth at rest, used to be left out).
inline bool every_nth_selects(int frame, int first, int last, int every) {
  return frame >= first && frame <= last && ((frame - first) % every == 0 || frame == last);
}
inline std::vector<int> every_nth_frames(int first, int last, int every) {
  std::vector<int> frames;
  for (int k = first; k <= last; ++k)
    if (every_nth_selects(k, first, last, every)) frames.push_back(k);
  return frames;
}

// Which frames weft run renders and writes (every frame is simulated and has its stats.csv row):
// --start, --end, --every N (with the last of the range), --last.
struct FrameSelection {
  int start = 1;
  std::optional<int> end;  // none: the last frame
  int every = 1;
  bool last_only = false;  // --last: only the final frame
  bool selects(int frame, int frames) const {
    if (last_only) return frame == frames;
    return every_nth_selects(frame, start, end.value_or(frames), every);
  }
};

struct RunOptions {
  std::optional<std::filesystem::path> scene;  // empty: the built-in default scene
  std::optional<std::filesystem::path> out;    // default: out/<scene name>
  // Scene patches, in order: --set KEY=VALUE and the options that override one key (--frames,
  // --size, --shading, --renderer, --samples). The copied scene.json holds them.
  std::vector<Setting> overrides;
  std::optional<int> threads;                  // --threads (apply_threads, app/scene/scene.h)
  std::optional<MeshFormat> export_meshes;     // also write mesh_0001.<ext>, ... (mesh_export.h)
  std::vector<CacheFormat> export_cache;       // also write cloth.obj + cloth.pc2/.mdd/.gltf (point_cache.h)
  UpAxis up = UpAxis::y;                       // --up: the exported OBJ/PLY's up axis
  FrameSelection selection;                    // the frames rendered and written
  bool explain = false;                        // print the simulated terms and phase times
  bool report = false;  // also write report.html (frames, plots of strain/energy/time; run_report.h)
  std::string command_line;                    // recorded in run.txt
  // --checkpoint-every K: write out/checkpoint.weft after every K-th frame (0: never; a run
  // resumed goes on with the checkpoint's K unless given). --resume DIR: go on from DIR's
  // checkpoint, writing into DIR (app/io/run_checkpoint.h, docs/checkpoints.md).
  std::optional<int> checkpoint_every;
  std::optional<std::filesystem::path> resume;
  // --save-states: state_NNNN.npy per simulated frame, kept for weft render. A scene without a
  // camera writes them anyway, to draw its frames when the simulation ends, and then removes them.
  bool save_states = false;
  // --rest: one frame, the scene's rest shape found by the static equilibrium solver instead of
  // its motion (app/run/rest_shape.h); stats.csv's row and the summary say how the solve went.
  bool rest = false;
};

// Runs the job; bad input throws InputError before anything is written.
int run_scene(const RunOptions& options);

}  // namespace weft::app
