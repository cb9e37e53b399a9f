// Videos through ffmpeg (see ffmpeg_video.h).

#include "app/io/ffmpeg_video.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "app/io/output_files.h"

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

namespace {

// Runs ffmpeg on `args` and waits for it; throws std::runtime_error "OUTPUT: <why>" when it
// cannot start or does not succeed.
void run_ffmpeg(const std::filesystem::path& ffmpeg, std::vector<std::string> args,
                const std::filesystem::path& output) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, ffmpeg.c_str(), nullptr, nullptr, argv.data(), environ);
  if (spawned != 0)
    throw std::runtime_error(output.string() + ": cannot start " + ffmpeg.string() + ": " +
                             std::strerror(spawned));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      throw std::runtime_error(output.string() + ": lost track of ffmpeg: " +
                               std::strerror(errno));
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
    throw std::runtime_error(output.string() + ": ffmpeg failed with exit status " +
                             std::to_string(WEXITSTATUS(status)));
  if (!WIFEXITED(status))
    throw std::runtime_error(output.string() + ": ffmpeg was stopped by a signal");
}

}  // namespace

VideoResult encode_video(const std::filesystem::path& ffmpeg, const std::filesystem::path& pattern,
                         double fps, const std::filesystem::path& output) {
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", fps);
  std::vector<std::string> args = {ffmpeg.string(), "-nostdin", "-y", "-loglevel", "error",
                                    "-framerate", rate, "-start_number", "1",
                                    "-i", pattern.string()};
  const bool gif = output.extension() == ".gif";
  if (gif) {
    // One palette for the whole sequence, made from its own colours.
    args.insert(args.end(), {"-filter_complex",
                             "[0:v]split[a][b];[a]palettegen[p];[b][p]paletteuse", "-loop", "0"});
  } else {
    args.insert(args.end(), {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264",
                             "-pix_fmt", "yuv420p"});
  }
  // Written to OUTPUT.partial, whose extension ffmpeg cannot read the format from.
  args.insert(args.end(), {"-f", gif ? "gif" : "mp4"});
  VideoResult result;
  try {
    write_through_folder(output, [&](const std::filesystem::path& partial) {
      args.push_back(partial.string());
      run_ffmpeg(ffmpeg, args, output);
    });
    result.ok = true;
  } catch (const std::runtime_error& e) {
    result.message = e.what();
  }
  return result;
}

}  // namespace weft::app
