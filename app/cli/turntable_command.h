#pragma once
// `weft turntable SCENE|MESH`: the camera orbits the final drape of a scene (or a mesh file) and
// writes turntable_0001.png, ..., contact_sheet.png and, with ffmpeg, turntable.mp4 and
// turntable.gif (camera path in app/run/orbit_camera.h).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "app/io/mesh_export.h"
#include "app/cli/options.h"
#include "app/run/orbit_camera.h"

namespace weft::app {

struct TurntableOptions {
  std::filesystem::path input;               // a scene (.json) or a mesh file (mesh_file.h)
  std::optional<std::filesystem::path> out;  // default: out/<input stem>_turntable
  int frames = 36;                           // images around the orbit, 1..3600
  // Scene patches (command.h): --set, --size, --renderer, --shading, --samples, and
  // --sim-frames (output.frames: a scene is simulated to that frame). A mesh file is drawn with
  // the default scene's render settings, patched the same way.
  std::vector<Setting> overrides;
  std::optional<int> threads;                // --threads (command.h)
  OrbitSettings orbit;                       // --elevation-deg, --distance-scale
  double video_fps = 12.0;                   // of turntable.mp4/.gif: 36 frames take 3 s
  // --up: the mesh file's up axis (a mesh input only). y (the default: weft's own OBJ/PLY
  // exports, Blender, glTF) is turned into weft's z-up frame, (x, y, z) ↦ (x, −z, y); z keeps
  // the file's coordinates. A glTF/GLB is y-up by definition: --up z is refused for it.
  std::optional<UpAxis> up;
  std::string command_line;                  // recorded in turntable.txt
};

// Adds `weft turntable` to the command line.
Command register_turntable(CLI::App& app, const std::string& command_line);

// Runs the job. Bad input (missing or unknown file, bad option) throws InputError before
// anything is written; returns exit_diverged when the scene's simulation diverges (nothing
// written) and exit_failure when ffmpeg fails (the PNGs and contact sheet are kept).
int run_turntable(const TurntableOptions& options);

// The camera that shows a mesh whose bounding box is [lo, hi] whole, looking at its centre
// from the direction of `direction` (eye − target of the default camera), with the field of
// view fov_y_deg and an image aspect width/height: the bounding sphere fills about 85 % of the
// narrower field of view. Near and far planes scale with the distance.
render::Camera framing_camera(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                              const Eigen::Vector3d& direction, double fov_y_deg, double aspect);

}  // namespace weft::app
