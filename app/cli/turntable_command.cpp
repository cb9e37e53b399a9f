// weft turntable (see turntable_command.h): load a scene and simulate it to its last frame
// without writing anything (or load a mesh file), then render the orbit.

#include "app/cli/turntable_command.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <regex>

#include <CLI/CLI.hpp>

#include "app/io/input_guard.h"
#include "app/scene/scene_inputs.h"
#include "app/scene/json_reader.h"
#include "app/io/output_files.h"
#include "app/report/contact_sheet.h"
#include "app/scene/data_dir.h"
#include "app/io/ffmpeg_video.h"
#include "app/run/frame_mesh.h"
#include "app/io/frame_png.h"
#include "app/run/frame_stream.h"
#include "app/io/mesh_file.h"
#include "app/run/frame_painter.h"
#include "app/io/progress.h"
#include "app/run/renderer_choice.h"
#include "base/timer.h"
#include "app/scene/scene.h"
#include "base/constants.h"
#include "sim/simulator.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;
constexpr int max_turntable_frames = 3600;
constexpr int contact_sheet_max_width_px = 960;  // thumbnails shrink to keep the sheet this wide

// What is rendered at every angle: the cloth (or mesh) and the obstacles.
struct Subject {
  std::string name;  // for the default output folder
  std::string text;  // the scene file's text ("" for a mesh)
  render::RenderSettings settings;
  bool alpha = false;  // output.alpha: RGBA frames
  render::RenderMesh mesh;
  std::vector<render::RenderObject> objects;
  std::unique_ptr<render::Renderer> renderer;  // made from `settings`
  std::vector<fs::path> inputs;  // the mesh file, or the scene's files
};

bool is_mesh_file(const fs::path& path) {
  static const char* const extensions[] = {".obj", ".ply", ".stl", ".gltf", ".glb", ".fbx"};
  const std::string ext = lower_extension(path);
  return std::find(std::begin(extensions), std::end(extensions), ext) != std::end(extensions);
}

std::string frame_name(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "turntable_%04d.png", frame);
  return name;
}

void check_options(const TurntableOptions& o) {
  if (o.frames < 1 || o.frames > max_turntable_frames)
    throw InputError("--frames: expected an integer in 1.." +
                     std::to_string(max_turntable_frames) + " (images around the orbit), got " +
                     std::to_string(o.frames));
  if (o.orbit.elevation_deg && !(std::fabs(*o.orbit.elevation_deg) < 90.0))
    throw InputError("--elevation-deg: expected degrees strictly between -90 and 90, got " +
                     std::to_string(*o.orbit.elevation_deg));
  if (!(o.orbit.distance_scale > 0.0) || !std::isfinite(o.orbit.distance_scale))
    throw InputError("--distance-scale: expected a finite factor > 0, got " +
                     std::to_string(o.orbit.distance_scale));
  if (!fs::exists(o.input))
    throw InputError(o.input.string() + ": no such file (expected a scene .json or a mesh file)");
  if (lower_extension(o.input) != ".json" && !is_mesh_file(o.input))
    throw InputError(o.input.string() +
                     ": expected a scene (.json) or a mesh file (.obj, .ply, .stl, .gltf, .glb, "
                     ".fbx)");
  if (o.up && lower_extension(o.input) == ".json")
    throw InputError("--up: only for a mesh file (a scene is in weft's own z-up frame), got " +
                     o.input.string());
  const std::string ext = lower_extension(o.input);
  if (o.up == UpAxis::z && (ext == ".gltf" || ext == ".glb"))
    throw InputError("--up z: " + o.input.string() +
                     " is a glTF, which is y-up by definition (leave --up out)");
}

// A mesh file's vertex in weft's z-up frame: a y-up file's (x, y, z) is weft's (x, −z, y), the
// inverse of the turn the exporter writes (mesh_export.h).
Eigen::Vector3f weft_frame(const Eigen::Vector3d& p, UpAxis up) {
  const Eigen::Vector3d q = up == UpAxis::y ? Eigen::Vector3d(p.x(), -p.z(), p.y()) : p;
  return q.cast<float>();
}

Subject scene_subject(const TurntableOptions& o) {
  Scene scene = load_scene_with(o.input, o.overrides);
  apply_threads(scene, o.threads);
  const std::unique_ptr<sim::Simulator> simulator = make_simulator(scene);
  Subject s;
  s.inputs = scene_files(scene);
  // A renderer that cannot start fails before the simulation time is spent.
  s.renderer = make_chosen_renderer(scene.render);

  std::fprintf(stderr, "weft: %s — simulating %d frames at %g fps to t = %.3g s, %s\n",
               scene.source.c_str(), scene.frames, scene.fps, scene.frames / scene.fps,
               cloth_size_text(scene).c_str());
  // The frame stream of weft run, so the last frame is the one weft run writes.
  Progress progress(stderr, scene.frames, "simulate");
  const FrameStreamEnd end = stream_frames(scene, *simulator, [&](const Frame& frame) {
    char detail[64];
    std::snprintf(detail, sizeof detail, "t = %.2f s", frame.time_s);
    progress.update(frame.index, detail);
    return StreamControl::go_on;
  });
  progress.finish();
  if (end.divergence) throw end.divergence->error;

  s.name = scene.name;
  s.text = scene.text;
  s.settings = scene.render;
  s.alpha = scene.write_alpha;
  s.mesh = to_render_mesh(simulator->mesh(), simulator->state().x);
  // What weft run draws beside the cloth: obstacles, stands, clips and rods.
  s.objects = FramePainter(scene, *s.renderer, simulator->mesh())
                  .objects(simulator->state().x, simulator->state().time_s);
  return s;
}

Subject mesh_subject(const TurntableOptions& o) {
  TriangleMesh file;
  try {
    file = load_triangle_mesh(o.input);
  } catch (const MeshFileError& e) {
    throw InputError(e.what());
  }
  Subject s;
  s.name = o.input.stem().string();
  s.inputs = {o.input};
  Scene defaults = load_scene_with(std::nullopt, o.overrides);  // the default render settings
  apply_threads(defaults, o.threads);
  s.settings = defaults.render;
  s.alpha = defaults.write_alpha;
  const UpAxis up = o.up.value_or(UpAxis::y);
  for (Eigen::Index v = 0; v < file.vertices.rows(); ++v)
    s.mesh.positions.push_back(weft_frame(file.vertices.row(v).transpose(), up));
  for (const auto& t : file.triangles)
    s.mesh.triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                                static_cast<std::uint32_t>(t[2])});
  try {
    render::validate(s.mesh, o.input.string());
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  render::compute_vertex_normals(s.mesh);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Eigen::Vector3f& p : s.mesh.positions) {
    lo = lo.cwiseMin(p.cast<double>());
    hi = hi.cwiseMax(p.cast<double>());
  }
  const render::Camera& c = s.settings.camera;
  s.settings.camera = framing_camera(lo, hi, c.eye - c.target, c.fov_y_deg,
                                     static_cast<double>(s.settings.width) / s.settings.height);
  // The mesh stands on the ground.
  s.settings.ground_z_m = lo.z();
  s.settings.ground_half_size_m = 5.0 * std::max((hi - lo).norm(), 1e-3);
  s.renderer = make_chosen_renderer(s.settings);
  return s;
}

Eigen::Vector3d bounding_box_center(const render::RenderMesh& mesh) {
  Eigen::Vector3f lo = mesh.positions.front(), hi = lo;
  for (const Eigen::Vector3f& p : mesh.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (0.5f * (lo + hi)).cast<double>();
}

std::string angle_label(double azimuth_deg) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g deg", azimuth_deg);
  return text;
}

}  // namespace

render::Camera framing_camera(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                              const Eigen::Vector3d& direction, double fov_y_deg, double aspect) {
  const double radius_m = std::max(0.5 * (hi - lo).norm(), 1e-6);
  const double half_fov_y = 0.5 * fov_y_deg * base::kPi / 180.0;
  const double half_fov_x = std::atan(std::tan(half_fov_y) * aspect);
  const double half_fov = std::min(half_fov_y, half_fov_x);
  const double distance_m = radius_m / (0.85 * std::sin(half_fov));
  render::Camera camera;
  camera.fov_y_deg = fov_y_deg;
  camera.target = 0.5 * (lo + hi);
  camera.eye = camera.target + direction.normalized() * distance_m;
  camera.up = Eigen::Vector3d::UnitZ();
  camera.near_m = 0.01 * distance_m;
  camera.far_m = 100.0 * distance_m;
  return camera;
}

int run_turntable(const TurntableOptions& given) {
  const base::Stopwatch total;  // the simulation of a scene, rendering and encoding
  TurntableOptions options = given;
  options.input = find_scene(given.input);  // a bare name: one of weft's scenes
  check_options(options);
  const bool is_scene = lower_extension(options.input) == ".json";
  Subject subject;
  try {
    subject = is_scene ? scene_subject(options) : mesh_subject(options);
  } catch (const sim::DivergenceError& e) {
    std::fprintf(stderr, "weft: error: %s: the simulation diverged: %s; nothing written\n",
                 options.input.c_str(), e.what());
    return exit_diverged;
  }
  render::Renderer& renderer = *subject.renderer;
  const Eigen::Vector3d center = bounding_box_center(subject.mesh);
  const render::Camera base = subject.settings.camera;

  // The output folder is touched when the first image is ready (start_output).
  const fs::path dir = options.out.value_or(fs::path("out") / (subject.name + "_turntable"));
  refuse_overwriting_inputs(dir,
                            {{"turntable.txt", "scene.json", "contact_sheet.png", "turntable.mp4",
                              "turntable.gif"},
                             {{"turntable", "png"}}},
                            subject.inputs);
  std::vector<std::pair<std::string, std::string>> records = {
      {"turntable.txt", run_record(options.command_line, {{"input", options.input.string()}})}};
  if (is_scene) records.emplace_back("scene.json", subject.text);

  const int n = options.frames;
  std::fprintf(stderr,
               "weft: turntable of %s — %d frame%s around (%.3g, %.3g, %.3g) m, %dx%d, %s\n",
               options.input.c_str(), n, n == 1 ? "" : "s", center.x(), center.y(), center.z(),
               subject.settings.width, subject.settings.height, renderer.description().c_str());
  const int columns = contact_sheet_columns(n, subject.settings.width, subject.settings.height);
  const int thumb_width = std::min(subject.settings.width,
                                   std::max(16, contact_sheet_max_width_px / columns - 8));
  std::vector<render::Image> thumbnails;
  std::vector<std::string> labels;
  Progress progress(stderr, n, "frame");
  std::optional<OutputFolderLock> lock;  // from the first image on
  for (int i = 0; i < n; ++i) {
    render::RenderSettings settings = subject.settings;
    settings.camera = orbit_camera(base, center, i, n, options.orbit);
    const render::Image image = render_frame_png(
        renderer, subject.mesh, settings, subject.objects, subject.alpha, dir / frame_name(i + 1),
        [&] { if (i == 0) start_output(lock, dir, {{"turntable", "png"}}, records); });
    thumbnails.push_back(thumbnail(image, thumb_width));
    labels.push_back(angle_label(orbit_azimuth_deg(i, n)));
    progress.update(i + 1, "azimuth " + labels.back());
  }
  progress.finish();
  render::write_png(contact_sheet(thumbnails, labels, columns), dir / "contact_sheet.png");

  int status = exit_ok;
  if (const auto ffmpeg = find_on_path("ffmpeg")) {
    for (const char* name : {"turntable.mp4", "turntable.gif"}) {
      const VideoResult video =
          encode_video(*ffmpeg, dir / "turntable_%04d.png", options.video_fps, dir / name);
      if (!video.ok) {
        std::fprintf(stderr, "weft: error: %s\n", video.message.c_str());
        status = exit_failure;
      }
    }
    if (status == exit_ok)
      std::printf("weft: wrote %d frames, contact_sheet.png, turntable.mp4 and turntable.gif to "
                  "%s (%s in all, simulation included)\n",
                  n, dir.c_str(), format_duration(total.seconds()).c_str());
  } else {
    std::printf("weft: ffmpeg not found: wrote PNGs and the contact sheet only; apt-get install "
                "ffmpeg for mp4/gif\n");
    std::printf("weft: wrote %d frames and contact_sheet.png to %s (%s in all, simulation "
                "included)\n",
                n, dir.c_str(), format_duration(total.seconds()).c_str());
  }
  return status;
}

Command register_turntable(CLI::App& app, const std::string& command_line) {
  const auto o = std::make_shared<TurntableOptions>();
  o->command_line = command_line;
  CLI::App* cmd = app.add_subcommand(
      "turntable", "Orbit the camera around a scene's final drape (or a mesh file): write "
                   "turntable_0001.png, ..., contact_sheet.png, and turntable.mp4/.gif with ffmpeg");
  cmd->add_option("input", o->input,
                  "Scene file (.json; simulated to its last frame first) or mesh file "
                  "(.obj, .ply, .stl, .gltf, .glb, .fbx)")
      ->required();
  check_range(cmd->add_option("--frames", o->frames,
                              "Images N around the orbit (default 36): turntable_0001.png at "
                              "azimuth 0 (the camera's own direction), image k at 360*(k-1)/N "
                              "degrees"),
              Range::closed(1, max_turntable_frames));
  check_range(cmd->add_option("--video-fps", o->video_fps,
                              "Frame rate of turntable.mp4 and .gif (default 12: 36 images take 3 s)"),
              Range::gt(0.0).le(240.0));
  cmd->add_option("--out", o->out, "Output folder (default: out/<input name>_turntable)");
  add_set_option(*cmd, o->overrides);
  add_size_option(*cmd, o->overrides, "Image size WIDTHxHEIGHT (overrides render.size)");
  add_render_options(*cmd, o->overrides);
  add_threads_option(*cmd, o->threads);
  check_range(cmd->add_option("--elevation-deg", o->orbit.elevation_deg,
                              "Camera elevation above the cloth centre, degrees (default: the "
                              "scene camera's)"),
              Range::gt(-90.0).lt(90.0));
  check_range(cmd->add_option("--distance-scale", o->orbit.distance_scale,
                              "Factor on the scene camera's distance to its target (default 1)"),
              Range::gt(0.0).le(1e3));
  cmd->add_option_function<std::string>(
      "--up", [o](const std::string& text) { o->up = parse_up_axis(text, "--up"); },
      "A mesh file's up axis: y (default; weft's own OBJ/PLY/glTF exports, Blender) or z "
      "(weft run --up z exports, many STL/CAD files); a glTF is always y-up");
  add_override_option(*cmd, "--sim-frames", "output.frames", o->overrides,
                      "Simulate to this frame instead of output.frames", "INT");
  return {cmd, [o] { return run_turntable(*o); }};
}

}  // namespace weft::app
