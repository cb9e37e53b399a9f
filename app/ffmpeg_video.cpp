// Videos through ffmpeg (see ffmpeg_video.h).

#include "app/ffmpeg_video.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

extern char** environ;

namespace weft::app {

std::optional<std::filesystem::path> find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  const std::string dirs = path;
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = dirs.substr(start, end - start);
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / program;
    std::error_code error;
    if (std::filesystem::is_regular_file(candidate, error) &&
        ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
    start = end + 1;
  }
  return std::nullopt;
}

VideoResult encode_video(const std::filesystem::path& ffmpeg, const std::filesystem::path& pattern,
                         double fps, const std::filesystem::path& output) {
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", fps);
  std::vector<std::string> args = {ffmpeg.string(), "-nostdin", "-y", "-loglevel", "error",
                                    "-framerate", rate, "-start_number", "1",
                                    "-i", pattern.string()};
  if (output.extension() == ".gif") {
    // One palette for the whole sequence, made from its own colours.
    args.insert(args.end(), {"-filter_complex",
                             "[0:v]split[a][b];[a]palettegen[p];[b][p]paletteuse", "-loop", "0"});
  } else {
    args.insert(args.end(), {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264",
                             "-pix_fmt", "yuv420p"});
  }
  args.push_back(output.string());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  VideoResult result;
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, ffmpeg.c_str(), nullptr, nullptr, argv.data(), environ);
  if (spawned != 0) {
    result.message = output.string() + ": cannot start " + ffmpeg.string() + ": " +
                     std::strerror(spawned);
    return result;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      result.message = output.string() + ": lost track of ffmpeg: " + std::strerror(errno);
      return result;
    }
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    result.ok = true;
  } else if (WIFEXITED(status)) {
    result.message = output.string() + ": ffmpeg failed with exit status " +
                     std::to_string(WEXITSTATUS(status));
  } else {
    result.message = output.string() + ": ffmpeg was stopped by a signal";
  }
  return result;
}

}  // namespace weft::app
