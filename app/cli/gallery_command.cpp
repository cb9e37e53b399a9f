// weft gallery (see gallery_command.h): each scene is run with weft run into a scratch folder
// inside the gallery, its last frame copied and its contact sheet drawn, then the scratch
// folder removed.

#include "app/cli/gallery_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "app/scene/data_dir.h"
#include "app/scene/json_reader.h"
#include "app/io/output_files.h"
#include "app/io/progress.h"
#include "app/run/run_job.h"
#include "app/report/run_report.h"
#include "app/scene/scene.h"
#include "app/cluster/slurm_job.h"
#include "app/cluster/slurm_resources.h"
#include "base/atomic_file.h"
#include "base/timer.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

struct GalleryEntry {
  std::string name;         // file stem
  fs::path path;            // scene file
  std::string description;  // empty when the scene could not be read
  std::string commands;     // the commands that reproduce the images
  std::string error;        // empty: rendered
};

std::vector<fs::path> scene_files(const fs::path& dir) {
  if (!fs::is_directory(dir))
    throw InputError("--scenes: " + dir.string() + " is not a folder (expected a folder of scene "
                     "files, e.g. assets/scenes)");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw InputError("--scenes: no *.json scene files in " + dir.string());
  return files;
}

// The files named by --only, in folder order; an unknown name lists the known ones.
std::vector<fs::path> selected(const std::vector<fs::path>& files,
                               const std::vector<std::string>& only) {
  if (only.empty()) return files;
  std::vector<fs::path> out;
  for (const std::string& name : only) {
    const auto it = std::find_if(files.begin(), files.end(),
                                 [&](const fs::path& f) { return f.stem().string() == name; });
    if (it == files.end()) {
      std::string known;
      for (const fs::path& f : files) known += (known.empty() ? "" : ", ") + f.stem().string();
      throw InputError("--only: no scene '" + name + "' (known: " + known + ")");
    }
    out.push_back(*it);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::string quoted_if_needed(const std::string& s) {
  return s.find_first_of(" \t'\"$") == std::string::npos ? s : "'" + s + "'";
}

// The scene in weft run's command line: weft's own scenes by their names (find_scene), which any
// folder reproduces.
std::string scene_argument(const GalleryEntry& entry, const GalleryOptions& options) {
  return options.scenes ? quoted_if_needed(entry.path.string()) : quoted_if_needed(entry.name);
}

std::string frames_argument(int frames, const Scene& scene) {
  return frames != scene.frames ? " --frames " + std::to_string(frames) : "";
}

// Reads the entry's scene and fills its description and the commands that reproduce it.
Scene describe_scene(GalleryEntry& entry, const GalleryOptions& options) {
  Scene scene = load_scene(entry.path);
  entry.description = scene.description;
  const int frames = scaled_frames(scene.frames, options.frames_scale);
  const std::string scene_arg = scene_argument(entry, options);
  const std::string frames_arg = frames_argument(frames, scene);
  const std::string run_out = "out/" + entry.name;
  std::ostringstream commands;
  commands << "weft run " << scene_arg << frames_arg << " --out " << run_out << "\n"
           << "# " << entry.name << ".png is " << run_out << "/" << frame_file_name(frames)
           << "; both images at once:\n"
           << "weft gallery "
           << (options.scenes ? "--scenes " + quoted_if_needed(options.scenes->string()) + " " : "")
           << "--only " << entry.name;
  if (options.frames_scale != 1.0) {
    char scale[32];
    std::snprintf(scale, sizeof scale, "%g", options.frames_scale);
    commands << " --frames-scale " << scale;
  }
  commands << " --out " << quoted_if_needed(options.out.string());
  entry.commands = commands.str();
  return scene;
}

// Runs one scene; fills the entry's description and commands, or throws.
void render_scene(GalleryEntry& entry, const GalleryOptions& options) {
  const Scene scene = describe_scene(entry, options);
  const int frames = scaled_frames(scene.frames, options.frames_scale);
  const fs::path scratch = options.out / (".frames_" + entry.name);
  const std::string scene_arg = scene_argument(entry, options);
  const std::string frames_arg = frames_argument(frames, scene);
  RunOptions run;
  run.scene = entry.path;
  run.out = scratch;
  if (frames != scene.frames)
    run.overrides.push_back({"output.frames", std::to_string(frames), frames_arg.substr(1)});
  run.threads = options.threads;
  run.command_line = "weft run " + scene_arg + frames_arg;
  const int code = run_scene(run);
  if (code != exit_ok) {
    fs::remove_all(scratch);
    throw std::runtime_error("weft run stopped with exit code " + std::to_string(code));
  }
  std::ifstream frame(scratch / frame_file_name(frames), std::ios::binary);
  const std::string png((std::istreambuf_iterator<char>(frame)), std::istreambuf_iterator<char>());
  if (!frame) throw std::runtime_error((scratch / frame_file_name(frames)).string() + ": cannot read");
  base::write_file_atomically(options.out / (entry.name + ".png"), png);
  render::write_png(frame_contact_sheet(scratch, evenly_spaced_frames(frames, report_sheet_frames),
                                        scene.fps),
                    options.out / (entry.name + "_sheet.png"));
  fs::remove_all(scratch);
}

std::string readme(const std::vector<GalleryEntry>& entries, const GalleryOptions& options) {
  std::ostringstream md;
  md << "# Gallery\n\n"
     << (options.scenes ? "Every scene of `" + options.scenes->string() + "`"
                        : std::string("Every one of weft's own scenes"))
     << " rendered by `weft gallery`: the final frame, a contact sheet of frames evenly spaced "
        "in time, and the commands that reproduce them. Runs are deterministic: the same command "
        "and build give the same bytes.\n\n```sh\n"
     << options.command_line << "\n```\n";
  if (options.frames_scale != 1.0)
    md << "\nEach scene ran for --frames-scale " << options.frames_scale
       << " of its frames: the final frames are not the scenes' rest states.\n";
  for (const GalleryEntry& e : entries) {
    md << "\n## " << e.name << "\n\n";
    if (!e.description.empty()) md << e.description << "\n\n";
    if (!e.error.empty()) {
      md << "**Failed:** " << e.error << "\n";
      continue;
    }
    md << "| final frame (`" << e.name << ".png`) | contact sheet (`" << e.name
       << "_sheet.png`) |\n|---|---|\n| ![](" << e.name << ".png) | ![](" << e.name
       << "_sheet.png) |\n\n```sh\n" << e.commands << "\n```\n";
  }
  return md.str();
}

}  // namespace

int scaled_frames(int frames, double scale) {
  return std::max(1, static_cast<int>(std::lround(frames * scale)));
}

namespace {

GalleryEntry entry_for(const fs::path& file) {
  GalleryEntry entry;
  entry.path = file;
  entry.name = file.stem().string();
  return entry;
}

// README.md and the summary, from the local run or the collect job; the exit code.
int finish_gallery(const std::vector<GalleryEntry>& entries, const GalleryOptions& options,
                   const std::string& how) {
  fs::create_directories(options.out);  // when no scene got as far as its first frame
  write_text(options.out / "README.md", readme(entries, options));
  std::vector<std::string> failed;
  for (const GalleryEntry& e : entries)
    if (!e.error.empty()) failed.push_back(e.name + " (" + e.error + ")");
  const int n = static_cast<int>(entries.size());
  std::printf("weft gallery: %d of %d scenes rendered into %s (README.md; %s)\n",
              n - static_cast<int>(failed.size()), n, options.out.c_str(), how.c_str());
  if (failed.empty()) return exit_ok;
  // stdout too: the collect job's log is where a Slurm user looks.
  std::printf("weft gallery: %zu failed:\n", failed.size());
  for (const std::string& f : failed) std::printf("  %s\n", f.c_str());
  std::fflush(stdout);
  std::fprintf(stderr, "weft gallery: %zu failed:\n", failed.size());
  for (const std::string& f : failed) std::fprintf(stderr, "  %s\n", f.c_str());
  return exit_failure;
}

std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

fs::path result_file(const GalleryOptions& options, const std::string& name) {
  return options.out / "slurm" / "results" / (name + ".txt");
}

// The command line of a task (--only NAME --task) or the collect job (--collect), run in the
// folder it was submitted from (#SBATCH --chdir), so that README.md names the same paths.
std::vector<std::string> gallery_argv(const GalleryOptions& options,
                                      const std::vector<std::string>& only,
                                      const std::string& mode) {
  std::vector<std::string> argv{fs::read_symlink("/proc/self/exe").string(), "gallery"};
  if (options.scenes) argv.insert(argv.end(), {"--scenes", options.scenes->string()});
  char scale[32];
  std::snprintf(scale, sizeof scale, "%.17g", options.frames_scale);
  argv.insert(argv.end(), {"--out", options.out.string(), "--frames-scale", scale});
  if (options.threads) argv.insert(argv.end(), {"--threads", std::to_string(*options.threads)});
  std::string names;
  for (const std::string& name : only) names += (names.empty() ? "" : ",") + name;
  if (!names.empty()) argv.insert(argv.end(), {"--only", names});
  argv.push_back(mode);
  return argv;
}

int submit_gallery(const GalleryOptions& options, const std::vector<fs::path>& files) {
  const fs::path slurm_dir = fs::absolute(options.out / "slurm");
  SlurmArray array;
  array.job_name = "weft-gallery";
  array.log_dir = slurm_dir;
  array.chdir = fs::current_path();
  std::vector<TaskWork> works;
  for (const fs::path& file : files) {
    Scene scene = load_scene(file);
    scene.frames = scaled_frames(scene.frames, options.frames_scale);
    works.push_back(scene_work(scene, true));
    array.tasks.push_back(gallery_argv(options, {file.stem().string()}, "--task"));
  }
  array.resources = estimate_resources(works, options.threads.value_or(1));
  SlurmJob collect;
  collect.job_name = "weft-gallery-collect";
  collect.argv = gallery_argv(options, options.only, "--collect");
  collect.log = slurm_dir / "weft-gallery-collect.log";
  collect.chdir = array.chdir;
  collect.resources = estimate_resources({TaskWork{}}, 1);
  check_slurm_scripts(array, collect);
  fs::remove_all(slurm_dir / "results");  // an earlier submission's
  record_submission(options.out, options.command_line);
  submit_array_and_collect(array, slurm_dir / "gallery.sbatch", collect,
                           slurm_dir / "collect.sbatch", options.dry_run);
  return exit_ok;
}

// The collect job: each scene's outcome from the result its task left.
void collect_scene(GalleryEntry& entry, std::size_t k, const GalleryOptions& options) {
  const fs::path slurm_dir = fs::absolute(options.out / "slurm");
  const std::string again =
      "; its log: " + (slurm_dir / ("weft-gallery_" + std::to_string(k) + ".log")).string() +
      "; resubmit it alone with sbatch --array=" + std::to_string(k) + " " +
      (slurm_dir / "gallery.sbatch").string() + ", then sbatch " +
      (slurm_dir / "collect.sbatch").string();
  describe_scene(entry, options);
  std::ifstream in(result_file(options, entry.name));
  std::string line;
  if (!in || !std::getline(in, line)) {
    entry.error = "no result (its task did not finish)" + again;
  } else if (line != "rendered") {
    entry.error = (line.rfind("failed: ", 0) == 0 ? line.substr(8) : line) + again;
  }
}

}  // namespace

int run_gallery(const GalleryOptions& options) {
  if (!(options.frames_scale > 0.0 && options.frames_scale <= 10.0))
    throw InputError("--frames-scale: expected a number in (0, 10], e.g. 0.25, got " +
                     std::to_string(options.frames_scale));
  const std::vector<fs::path> files =
      selected(scene_files(options.scenes.value_or(data_dir() / "scenes")), options.only);
  if (options.slurm) return submit_gallery(options, files);

  std::vector<GalleryEntry> entries;
  const int n = static_cast<int>(files.size());
  if (options.collect) {
    for (int k = 0; k < n; ++k) {
      entries.push_back(entry_for(files[static_cast<std::size_t>(k)]));
      try {
        collect_scene(entries.back(), static_cast<std::size_t>(k + 1), options);
      } catch (const std::exception& e) {
        entries.back().error = e.what();
      }
    }
    GalleryOptions as_submitted = options;
    as_submitted.command_line = submitted_command_line(options.out, options.command_line);
    return finish_gallery(entries, as_submitted, "merged from the Slurm tasks' results");
  }

  const base::Stopwatch watch;
  int failures = 0;
  for (int k = 0; k < n; ++k) {
    GalleryEntry entry = entry_for(files[static_cast<std::size_t>(k)]);
    std::fprintf(stderr, "weft gallery: scene %d/%d: %s\n", k + 1, n, entry.name.c_str());
    try {
      render_scene(entry, options);
    } catch (const std::exception& e) {
      entry.error = e.what();
      ++failures;
      std::fprintf(stderr, "weft gallery: %s failed: %s\n", entry.name.c_str(), e.what());
    }
    if (options.task) {  // for the collect job; its README.md is the collect job's
      fs::create_directories(result_file(options, entry.name).parent_path());
      write_text(result_file(options, entry.name),
                 entry.error.empty() ? "rendered\n" : "failed: " + one_line(entry.error) + "\n");
    }
    entries.push_back(std::move(entry));
  }
  if (options.task) return failures ? exit_failure : exit_ok;
  return finish_gallery(entries, options, format_duration(watch.seconds()));
}

Command register_gallery(CLI::App& app, const std::string& command_line) {
  const auto o = std::make_shared<GalleryOptions>();
  o->command_line = command_line;
  CLI::App* cmd = app.add_subcommand(
      "gallery", "Render every scene (weft's own) into out/gallery: <scene>.png (final frame), "
                 "<scene>_sheet.png (contact sheet), README.md with the commands");
  cmd->add_option("--scenes", o->scenes,
                  "Folder of scene files (default: weft's own scenes, assets/scenes in the "
                  "source tree, PREFIX/share/weft/scenes installed)");
  cmd->add_option("--out", o->out,
                  "Output folder (default: out/gallery; the repository's gallery/ only if given)");
  check_range(cmd->add_option("--frames-scale", o->frames_scale,
                              "Run each scene for this fraction of its frames, e.g. 0.25 for a "
                              "quick look"),
              Range::gt(0.0).le(10.0));
  cmd->add_option_function<std::string>(
      "--only",
      [o](const std::string& text) {
        std::stringstream names(text);
        for (std::string name; std::getline(names, name, ',');)
          if (!name.empty()) o->only.push_back(name);
      },
      "Comma-separated scene names (file stems) to render");
  add_threads_option(*cmd, o->threads);
  CLI::Option* slurm = add_slurm_flags(
      *cmd, o->slurm, o->dry_run,
      "Write OUT/slurm/gallery.sbatch (a Slurm job array, one task per scene) and "
      "OUT/slurm/collect.sbatch (writes README.md after them) and submit both with sbatch");
  // What the Slurm scripts run (in a group of their own: CLI11 names a hidden option nowhere,
  // not even in its errors).
  CLI::Option* task = cmd->add_flag("--task", o->task, "Render the scenes, leave their results")
                          ->group("Run by the --slurm scripts")
                          ->excludes(slurm);
  cmd->add_flag("--collect", o->collect, "Write README.md from the tasks' results")
      ->group("Run by the --slurm scripts")
      ->excludes(slurm)
      ->excludes(task);
  return {cmd, [o] { return run_gallery(*o); }};
}

}  // namespace weft::app
