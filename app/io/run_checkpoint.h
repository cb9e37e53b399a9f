#pragma once
// weft run's checkpoints (--checkpoint-every K, --resume DIR; docs/checkpoints.md): one file,
// DIR/checkpoint.weft, replaced atomically every K frames, holding what a run needs to go on
// from the frame after it with the same bits as a run that never stopped — the scene it belongs
// to (its text and where it was read from), the simulator's state between two steps
// (Simulator::save_state), the frames' stats.csv rows so far and the frames the cloth crossed
// itself in — behind a header with a hash of the weft executable and of the scene text. A
// checkpoint of another build or scene is refused with an error that says which.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "app/io/stats_csv.h"

namespace weft::app {

inline constexpr const char* checkpoint_file_name = "checkpoint.weft";
// A checkpoint is read only up to this size (a 256² cloth's is about 10 MB): a larger file or a
// device (`weft run --resume /dev/zero`) is refused at once.
inline constexpr std::uint64_t max_checkpoint_bytes = std::uint64_t{1} << 30;

struct RunCheckpoint {
  int frame = 0;             // frames 1..frame were simulated (and written if selected)
  int every = 0;             // the run's --checkpoint-every
  std::string scene_source;  // Scene::source: names it and resolves its relative paths
  std::string scene_text;    // Scene::text, overrides included
  std::vector<FrameStats> rows;     // stats.csv rows of frames 1..frame
  std::vector<int> crossing_frames;  // frames in which the cloth passed through itself
  std::string simulator_state;      // Simulator::save_state's bytes
};

// FNV-1a (64 bits) of some bytes; and the identity of the running executable: FNV-1a of the
// GNU build ID the linker wrote into it (a SHA-1 of the linked output, so a rebuild that changes
// any byte of weft changes it), or of the whole file /proc/self/exe where there is none. Computed
// once. The build ID is read from memory: hashing the file took 1.5 s at every start of the
// sanitized weft (132 MB), 20 s of CI per checkpoint test.
std::uint64_t fnv1a_64(const std::string& bytes);
std::uint64_t build_hash();

// Writes dir/checkpoint.weft atomically (app/io/output_files.h). Throws std::runtime_error naming
// the path when it cannot.
void write_checkpoint(const std::filesystem::path& dir, const RunCheckpoint& checkpoint);
// Reads dir/checkpoint.weft (dir may also name the file itself). Throws InputError naming the
// path when it is missing, not a checkpoint, truncated, or written by another build of weft.
RunCheckpoint read_checkpoint(const std::filesystem::path& dir);

}  // namespace weft::app
