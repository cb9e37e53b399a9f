#pragma once
// Videos from a PNG sequence with the `ffmpeg` program, when it is installed (weft turntable).

#include <filesystem>
#include <optional>
#include <string>

namespace weft::app {

// The first executable file named `program` in the directories of $PATH, or none.
std::optional<std::filesystem::path> find_on_path(const std::string& program);

// What ffmpeg made of a sequence.
struct VideoResult {
  bool ok = false;
  std::string message;  // on failure: which file and ffmpeg's exit status
};

// Encodes the PNGs `pattern` (a printf pattern such as DIR/turntable_%04d.png, numbered from 1)
// at `fps` frames per second into `output`: an H.264 .mp4 (yuv420p, sides padded to even) or a
// looping .gif (with a palette made from the frames), by the extension. Runs `ffmpeg` (found
// on $PATH, the executable given) without a shell and waits for it; ffmpeg's own messages
// go to stderr. The video is written to OUTPUT.partial and renamed: never a part of one.
VideoResult encode_video(const std::filesystem::path& ffmpeg, const std::filesystem::path& pattern,
                         double fps, const std::filesystem::path& output);

}  // namespace weft::app
