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
#include <string_view>
#include <vector>

#include "app/io/stats_csv.h"

namespace weft::app {

inline constexpr const char* checkpoint_file_name = "checkpoint.weft";
// A checkpoint is read only up to this size (a 256² cloth's is about 10 MB): a larger file or a
// device (`weft run --resume /dev/zero`) is refused at once.
inline constexpr std::uint64_t max_checkpoint_bytes = std::uint64_t{1} << 30;

// An input file a run read (its mesh, obstacles, texture, environment map: Scene::input_files)
// and FNV-1a of its bytes, so that a resume with another file is refused.
struct InputFileHash {
  std::string path;  // as the scene resolved it, relative to the working directory or absolute
  std::uint64_t hash = 0;
};

// At most this many input files are read from a checkpoint (a scene has at most 1000 obstacles).
inline constexpr std::uint64_t max_scene_inputs = 4096;

struct RunCheckpoint {
  int frame = 0;             // frames 1..frame were simulated (and written if selected)
  int every = 0;             // the run's --checkpoint-every
  std::string scene_source;  // Scene::source: names it and resolves its relative paths
  std::string scene_text;    // Scene::text, overrides included
  std::vector<InputFileHash> inputs;  // the scene's input files when the run started
  std::vector<FrameStats> rows;     // stats.csv rows of frames 1..frame
  std::vector<int> crossing_frames;  // frames in which the cloth passed through itself
  std::string simulator_state;      // Simulator::save_state's bytes
};

// FNV-1a (64 bits) of some bytes; and the identity of the running executable: FNV-1a of the
// GNU build ID the linker wrote into it (a SHA-1 of the linked output, so a rebuild that changes
// any byte of weft changes it), or of the whole file /proc/self/exe where there is none. Computed
// once. The build ID is read from memory: hashing the file took 1.5 s at every start of the
// sanitized weft (132 MB), 20 s of CI per checkpoint test.
std::uint64_t fnv1a_64(std::string_view bytes);
std::uint64_t build_hash();

// Writes dir/checkpoint.weft atomically (app/io/output_files.h). Throws std::runtime_error naming
// the path when it cannot.
void write_checkpoint(const std::filesystem::path& dir, const RunCheckpoint& checkpoint);
// Reads dir/checkpoint.weft (dir may also name the file itself). Throws InputError naming the
// path when it is missing, larger than max_checkpoint_bytes, not a checkpoint, written by another
// build of weft, or damaged: its payload (every byte after the header) must have the hash the
// header holds, so a changed byte anywhere is refused, not resumed.
RunCheckpoint read_checkpoint(const std::filesystem::path& dir);

// The same from a checkpoint's bytes; `name` names it in errors (tests/fuzz reads bytes).
RunCheckpoint parse_checkpoint(const std::string& bytes, const std::string& name);
// The header a checkpoint of this build with this scene hash and payload begins with.
std::string checkpoint_header(std::uint64_t scene_hash, std::string_view payload);

// The files and the hashes of their bytes. Throws InputError naming a file that cannot be read.
std::vector<InputFileHash> hash_input_files(const std::vector<std::filesystem::path>& files);

// Throws InputError naming the file when one of `files` (the resumed scene's input files, as
// resolved now) is not, byte for byte, the one the checkpointed run read.
void check_input_files(const RunCheckpoint& checkpoint,
                       const std::vector<std::filesystem::path>& files,
                       const std::string& checkpoint_name);

}  // namespace weft::app
