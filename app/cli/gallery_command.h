#pragma once
// weft gallery: render every scene of a folder (weft's own scenes by default) into one folder — per scene the
// final frame (<scene>.png), a contact sheet (<scene>_sheet.png) and the command that
// reproduces them — and write its README.md with a section per scene. A scene that fails is
// reported and the others still run.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "app/cli/options.h"

namespace weft::app {

struct GalleryOptions {
  // Every *.json in it, in name order; none: weft's own scenes (data_dir()/scenes, app/scene/data_dir.h),
  // named by their bare names in README.md's commands (weft run NAME works from any folder).
  std::optional<std::filesystem::path> scenes;
  std::filesystem::path out = "out/gallery";       // the repository's gallery/ only if asked
  double frames_scale = 1.0;       // each scene's output.frames × this (rounded, at least 1)
  std::vector<std::string> only;   // scene names (file stems) to render; empty: all
  std::optional<int> threads;      // --threads (command.h), passed to every run
  std::string command_line;        // recorded in README.md
  // Slurm (docs/cluster.md): --slurm writes OUT/slurm/gallery.sbatch, an array of one task per
  // scene, and OUT/slurm/collect.sbatch, which writes README.md after them; the tasks run the
  // --task (render the --only scenes, leave OUT/slurm/results/<scene>.txt), the collect
  // job --collect.
  bool slurm = false;
  bool dry_run = false;
  bool task = false;
  bool collect = false;
};

// Frames of a scene of `frames` frames under --frames-scale: round(frames × scale), at least 1.
int scaled_frames(int frames, double scale);

// Adds `weft gallery` to the command line.
Command register_gallery(CLI::App& app, const std::string& command_line);

// Returns exit_ok when every scene rendered, exit_failure (listing the failed scenes on stderr)
// otherwise. Bad options (missing folder, unknown --only name, scale out of range) throw
// InputError before anything is rendered.
int run_gallery(const GalleryOptions& options);

}  // namespace weft::app
