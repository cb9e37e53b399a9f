#include "app/run_command.h"

#include <cstdio>
#include <fstream>
#include <regex>
#include <stdexcept>

#include "app/output_files.h"
#include "app/frame_mesh.h"
#include "app/measure_command.h"
#include "app/obstacle_meshes.h"
#include "app/progress.h"
#include "app/run_report.h"
#include "app/renderer_choice.h"
#include "app/scene.h"
#include "app/stats_csv.h"
#include "app/version.h"
#include "sim/collision/self_intersection.h"
#include "sim/pins.h"
#include "sim/simulator.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

std::string frame_name(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", frame);
  return name;
}

// mesh_0001.obj, ... (--export-meshes), beside frame_0001.png.
std::string mesh_name(int frame, MeshFormat format) {
  char name[32];
  std::snprintf(name, sizeof name, "mesh_%04d.%s", frame, mesh_extension(format));
  return name;
}

// Removes the frames (and exported meshes) of an earlier run in the same folder, so that the
// folder holds one run.
int remove_old_frames(const fs::path& dir) {
  return remove_numbered_files(dir, "frame", "png") +
         remove_numbered_files(dir, "mesh", "(obj|ply|gltf|bin)");
}

}  // namespace

void apply_overrides(Scene& scene, const RunOptions& options) {
  if (options.frames) scene.frames = checked_frames_option(*options.frames);
  if (options.size)
    std::tie(scene.render.width, scene.render.height) = parse_size(*options.size, "--size");
  if (options.normals_shading)
    scene.render.shading =
        *options.normals_shading ? render::Shading::normals : render::Shading::lit;
  if (options.renderer) {
    try {
      scene.render.renderer = render::renderer_from_name(*options.renderer, "--renderer");
    } catch (const std::invalid_argument& e) {
      throw SceneError(e.what());
    }
  }
  if (options.samples) {
    if (*options.samples < 1 || *options.samples > 65536)
      throw SceneError("--samples: expected an integer in 1..65536, got " +
                       std::to_string(*options.samples));
    scene.render.raytrace.samples_per_pixel = *options.samples;
  }
}

int checked_frames_option(int frames) {
  if (frames < 1 || frames > 100000)
    throw SceneError("--frames: expected an integer in 1..100000, got " + std::to_string(frames));
  return frames;
}

std::pair<int, int> parse_size(const std::string& text, const std::string& option) {
  static const std::regex pattern(R"((\d{1,5})x(\d{1,5}))");
  std::smatch m;
  if (std::regex_match(text, m, pattern)) {
    const int w = std::stoi(m[1]), h = std::stoi(m[2]);
    if (w >= 16 && w <= 8192 && h >= 16 && h <= 8192) return {w, h};
  }
  throw SceneError(option +
                   ": expected WIDTHxHEIGHT with each side in 16..8192 (e.g. 640x480), got '" +
                   text + "'");
}

namespace {

// "weft: time per phase: integrate 61 % (2.1 s), project 37 % (1.3 s), ..." — phases that ran.
void print_phase_shares(const sim::PhaseTimers& timers) {
  const double total = timers.total_seconds();
  if (total <= 0.0) return;
  std::string text;
  for (int p = 0; p < static_cast<int>(sim::Phase::count); ++p) {
    const double s = timers.seconds(static_cast<sim::Phase>(p));
    if (s <= 0.0) continue;
    char part[96];
    std::snprintf(part, sizeof part, "%s%s %.0f %% (%s)", text.empty() ? "" : ", ",
                  std::string(sim::phase_names[static_cast<std::size_t>(p)]).c_str(),
                  100.0 * s / total, format_duration(s).c_str());
    text += part;
  }
  std::printf("weft: time per phase: %s\n", text.c_str());
}

}  // namespace

int run_scene(const RunOptions& options) {
  Scene scene = options.scene ? load_scene(*options.scene) : default_scene();
  apply_overrides(scene, options);

  // Everything that can reject the input happens before the output folder is touched.
  const std::unique_ptr<sim::Simulator> simulator = make_simulator(scene);
  const std::unique_ptr<render::Renderer> renderer = make_chosen_renderer(scene.render);

  const fs::path dir = options.out.value_or(fs::path("out") / scene.name);
  fs::create_directories(dir);
  if (const int removed = remove_old_frames(dir))
    std::fprintf(stderr, "weft: replaced %d frames of an earlier run in %s\n", removed,
                 dir.c_str());
  write_text(dir / "scene.json", scene.text);
  write_text(dir / "run.txt", "weft " + std::string(version()) + "\ncommand: " +
                                  options.command_line + "\nscene: " + scene.source + "\n");
  StatsCsv stats(dir / "stats.csv");

  const double frame_dt = 1.0 / scene.fps;
  std::fprintf(
      stderr,
      "weft: %s — %d frames at %g fps, %dx%d vertices, time step %.3g ms (critical %.3g ms), %s\n",
      scene.source.c_str(), scene.frames, scene.fps, scene.grid.nu, scene.grid.nv,
      1e3 * simulator->time_step(), 1e3 * simulator->critical_time_step(),
      renderer->description().c_str());
  if (scene.tension_field) {
    const sim::TensionFieldResult folds = sim::solve_tension_field(tension_field_inputs(
        *scene.tension_field, scene.grid, scene.material, scene.sim.gravity_m_s2));
    std::fprintf(stderr, "weft: initial shape: tension-field folds (seed 001): %s\n",
                 folds.message.c_str());
  }
  if (!scene.dynamics)
    std::fprintf(stderr, "weft: simulation.dynamics is false: every frame shows the initial shape\n");
  if (options.explain) {
    std::printf("weft: the simulation runs, per step:\n");
    for (const std::string& line : simulator->explain()) std::printf("  %s\n", line.c_str());
    std::fflush(stdout);
  }
  // Moving obstacles are drawn where they are at each frame's time.
  const bool obstacles_move = sim::any_moves(scene.sim.obstacle_motions);
  std::vector<render::RenderObject> obstacle_objects =
      obstacle_render_objects(scene.sim.obstacles, scene.render);
  const auto cloth_triangles = simulator->mesh().triangles();
  const auto cloth_edges = sim::unique_edges(cloth_triangles);
  Progress progress(stderr, scene.frames, "frame");
  double sim_ms_total = 0.0, render_ms_total = 0.0;
  long unconverged_total = 0, steps_total = 0;
  std::vector<FrameStats> rows;  // for --report
  for (int frame = 1; frame <= scene.frames; ++frame) {
    FrameStats row;
    row.frame = frame;
    auto start = std::chrono::steady_clock::now();
    try {
      if (scene.dynamics) simulator->advance(frame * frame_dt - simulator->state().time_s);
    } catch (const sim::DivergenceError& e) {
      progress.finish();
      std::fprintf(stderr, "weft: error: frame %d: %s\n", frame, e.what());
      if (frame > 1)
        std::fprintf(stderr, "weft: kept frames 1..%d and stats.csv in %s\n", frame - 1,
                     dir.c_str());
      else
        std::fprintf(stderr, "weft: no frame was finished; stats.csv is in %s\n", dir.c_str());
      if (options.report && !rows.empty())
        std::printf("weft: report of the frames written: %s\n",
                    write_run_report(dir, scene, options.command_line, rows).c_str());
      return exit_diverged;
    }
    row.sim_ms = ms_since(start);
    row.steps = simulator->take_step_statistics();
    row.diagnostics = simulator->diagnostics();
    row.self_intersections = sim::count_edge_triangle_crossings(simulator->state().x,
                                                                cloth_triangles, cloth_edges);

    start = std::chrono::steady_clock::now();
    if (obstacles_move) {
      obstacle_objects = obstacle_render_objects(scene.sim.obstacles, scene.sim.obstacle_motions,
                                                 simulator->state().time_s, scene.render);
    }
    const render::RenderMesh cloth = to_render_mesh(simulator->mesh(), simulator->state().x);
    const render::Image image = renderer->render(cloth, scene.render, obstacle_objects);
    render::write_png(image, dir / frame_name(frame));
    if (options.export_meshes)
      export_mesh(cloth, *options.export_meshes, dir / mesh_name(frame, *options.export_meshes));
    row.render_ms = ms_since(start);
    stats.write(row);
    if (options.report) rows.push_back(row);

    sim_ms_total += row.sim_ms;
    unconverged_total += row.steps.unconverged_steps;
    steps_total += row.steps.steps;
    render_ms_total += row.render_ms;
    char detail[128];
    std::snprintf(detail, sizeof detail, "t = %.2f s, max strain %.2f %%%s", row.diagnostics.time_s,
                  100.0 * row.diagnostics.max_strain,
                  row.steps.unconverged_steps ? ", projection missed its tolerance" : "");
    progress.update(frame, detail);
  }
  progress.finish();
  if (unconverged_total > 0)
    std::fprintf(
        stderr,
        "weft: warning: the constraint projection missed its tolerance in %ld of %ld steps "
        "(see unconverged_steps in stats.csv)\n",
        unconverged_total, steps_total);
  if (options.explain) print_phase_shares(simulator->timers());
  std::printf("weft: wrote %d frames to %s (simulation %s, rendering %s, total %s)\n", scene.frames,
              dir.c_str(), format_duration(sim_ms_total / 1e3).c_str(),
              format_duration(render_ms_total / 1e3).c_str(),
              format_duration(progress.elapsed_s()).c_str());
  if (options.report)
    std::printf("weft: report: %s\n",
                write_run_report(dir, scene, options.command_line, rows).c_str());
  if (const auto drape = drape_summary(scene, *simulator))
    std::printf("weft: last frame: %s (weft measure: settle time, outline)\n", drape->c_str());
  return exit_ok;
}

}  // namespace weft::app
