#pragma once
// `weft run`: simulate a scene and write its PNG sequence, stats.csv and a copy of the scene.

#include <filesystem>
#include <optional>
#include <string>

#include "app/mesh_export.h"

namespace weft::app {

struct Scene;

struct RunOptions {
  std::optional<std::filesystem::path> scene;  // empty: the built-in default scene
  std::optional<std::filesystem::path> out;    // default: out/<scene name>
  std::optional<int> frames;                   // overrides the scene's output.frames
  std::optional<std::string> size;             // "WxH", overrides render.size
  std::optional<bool> normals_shading;         // overrides render.shading (true: normals)
  std::optional<std::string> renderer;         // "raster" or "raytrace", overrides render.renderer
  std::optional<int> samples;                  // overrides render.raytrace.samples
  std::optional<MeshFormat> export_meshes;     // also write mesh_0001.<ext>, ... (mesh_export.h)
  bool explain = false;                        // print the simulated terms and phase times
  bool report = false;  // also write report.html (frames, plots of strain/energy/time; run_report.h)
  std::string command_line;                    // recorded in run.txt
};

// Exit codes of the weft command.
enum ExitCode : int { exit_ok = 0, exit_bad_input = 1, exit_failure = 2, exit_diverged = 3 };

// Runs the job; bad input throws SceneError before anything is written.
int run_scene(const RunOptions& options);

// Applies the options that override scene settings (frames, size, shading, renderer, samples);
// throws SceneError naming the option. Also used by weft turntable.
void apply_overrides(Scene& scene, const RunOptions& options);

// The --frames option of run, measure and sweep: returns it if it is in 1..100000, else throws
// SceneError naming the option.
int checked_frames_option(int frames);

// Parses "640x480" (each side 16..8192); throws SceneError naming the option.
std::pair<int, int> parse_size(const std::string& text, const std::string& option);

}  // namespace weft::app
