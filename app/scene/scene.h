#pragma once
// A scene file, validated and converted to SI units. The format is documented in docs/scene.md.

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/enum_names.h"
#include "app/io/input_error.h"
#include "app/scene/tension_field_scene.h"
#include "render/render_settings.h"
#include "sim/grid.h"
#include "sim/material/material.h"
#include "sim/pin_motion.h"
#include "sim/pins.h"
#include "sim/simulator.h"

namespace weft::app {

struct Scene {
  std::string source;       // file path as given, or "<built-in default scene>"
  std::string name;         // output folder name: the file's stem ("default" for the built-in)
  std::string description;  // what the scene shows and which figure or test it reproduces
  std::string text;         // the scene file's text, copied into the output folder
  // The files the scene reads besides its text (app/scene/scene_inputs.h), resolved.
  std::vector<std::filesystem::path> input_files;

  sim::GridSpec grid;
  // cloth.mesh: the cloth read from a mesh file (app/io/cloth_mesh_file.h); null: the grid above.
  std::shared_ptr<const sim::ClothMesh> mesh;
  sim::Material material;
  std::vector<sim::PinSpec> pins;
  std::vector<sim::PinPath> pin_paths;  // one per pin; empty: the pin stays put
  sim::SimSettings sim;
  // cloth.initial_shape.tension_field: the cloth starts laid onto Conci's folds
  // (app/scene/tension_field_scene.h); none: it starts flat.
  std::optional<TensionFieldShape> tension_field;
  // simulation.dynamics: false shows the initial shape in every frame without simulating.
  bool dynamics = true;

  double fps = 24.0;  // output frames per second of simulated time
  int frames = 72;    // frames written; frame k (1-based) shows time k / fps
  // output.mask: also write mask_0001.png, the cloth's mask (render::Renderer::render_mask);
  // output.alpha: write the frames as RGBA, the background transparent.
  bool write_mask = false, write_alpha = false;
  // simulation.self_collision.crossings: what `weft run` does when a frame of a self-colliding
  // cloth passes through itself (edge–triangle crossings, stats.csv's self_intersections):
  // warn at the end naming the frames, or stop there with the divergence exit code.
  enum class CrossingPolicy { warn, error };

  static constexpr base::EnumNames<CrossingPolicy, 2> crossing_policy_names{
      {{CrossingPolicy::warn, "warn"}, {CrossingPolicy::error, "error"}}};
  CrossingPolicy crossings = CrossingPolicy::warn;

  render::RenderSettings render;
  // render.camera given; without it weft run frames the cloth over the run (app/run/auto_camera.h).
  bool camera_given = true;
  // render.ground.collider: the drawn ground is also a plane obstacle (simulated_settings adds
  // it unless the scene has that plane), so the cloth cannot fall through the floor it is seen on.
  bool ground_collider = true;

  // What the scene allows but a person probably did not mean ("FILE: KEY: what"): a vertex
  // pinned twice, every vertex pinned, a capsule whose ends are one point. The commands print
  // them (load_scene_with, app/scene/scene_patch.h).
  std::vector<std::string> warnings;
};

// Limits on a scene file: its size (a scene reads an endless file such as /dev/zero no further)
// and its number of obstacles (each is tested against every vertex in every step, with no broad
// phase: 1000 spheres by the default scene's 41² cloth take 1.8 s of simulation per 1/24 s
// frame, 10 000 would take half a minute, with the frame progress line as the only sign).
inline constexpr std::size_t max_scene_file_bytes = std::size_t{16} << 20;
inline constexpr std::size_t max_obstacles = 1000;

// Parses and validates scene text; `source` names it in error messages and resolves relative
// paths. Pins are checked against the grid. Throws InputError.
Scene parse_scene(const std::string& text, const std::string& source);
// Reads a scene file; a bare name that is no file here is one of weft's own scenes
// (find_scene, app/scene/data_dir.h: "weft run sphere_drape" from any folder). Throws InputError (a
// missing or unreadable file included; a bare name's message lists weft's scenes).
Scene load_scene(const std::filesystem::path& path);
// The simulator's settings: scene.sim with, when the ground is drawn and a collider
// (Scene::ground_collider), the ground's plane among the obstacles.
sim::SimSettings simulated_settings(const Scene& scene);

// Whether the plane is the rendered ground (settings.ground on, normal +z, at ground_z_m,
// within 1e-9), which the ground already shows.
bool is_rendered_ground(const sim::PlaneObstacle& plane, const render::RenderSettings& settings);

// The scene's cloth mesh: the file's (Scene::mesh) or the grid's (make_grid).
sim::ClothMesh cloth_mesh(const Scene& scene);
// "41x41 vertices" for a grid scene, "812 vertices (panel.obj)" for a mesh file's.
std::string cloth_size_text(const Scene& scene);

// The scene's simulator: grid, pins and their paths, material and settings (simulated_settings).
// A material the model rejects throws InputError naming cloth.material.
std::unique_ptr<sim::Simulator> make_simulator(const Scene& scene);

// --threads N (0: all hardware threads) for the ray tracer, self-collision's candidate search and
// implicit Euler's conjugate gradients; none leaves the scene's own. Never changes a bit of the
// output.
void apply_threads(Scene& scene, std::optional<int> threads);

// The built-in default scene (the text of assets/scenes/default.json, compiled in).
Scene default_scene();
const std::string& default_scene_text();

}  // namespace weft::app
