#include "app/run/run_job.h"

#include "app/run/rest_shape.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <regex>
#include <string>

#include "app/run/auto_camera.h"
#include "app/io/cloth_mesh_states.h"
#include "app/run/frame_mesh.h"
#include "app/run/frame_painter.h"
#include "app/io/npy_file.h"
#include "app/scene/json_reader.h"
#include "app/run/frame_stream.h"
#include "app/run/measure.h"
#include "app/run/obstacle_meshes.h"
#include "app/io/output_files.h"
#include "app/io/input_guard.h"
#include "app/io/progress.h"
#include "app/io/run_checkpoint.h"
#include "app/report/run_report.h"
#include "app/run/renderer_choice.h"
#include "app/run/run_eta.h"
#include "app/run/saved_states.h"
#include "app/scene/scene.h"
#include "app/scene/scene_inputs.h"
#include "app/io/stats_csv.h"
#include "base/check.h"
#include "base/file_read.h"
#include "sim/collision/self_intersection.h"
#include "sim/pins.h"
#include "sim/simulator.h"

namespace weft::app {

namespace {

namespace fs = std::filesystem;

// The cloth's texture beside OBJ and glTF meshes (--export-meshes obj|gltf), which name it.
constexpr const char* texture_file_name = "mesh_texture.png";

// How --export-meshes writes the cloth: the --up axis, the scene's front colour and texture.
MeshExportOptions mesh_export_options(const Scene& scene, const RunOptions& options) {
  MeshExportOptions o;
  o.up = options.up;
  o.base_color = scene.render.front_color;
  const render::ClothTexture& texture = scene.render.cloth_surface.texture;
  if (texture.image && options.export_meshes && *options.export_meshes != MeshFormat::ply) {
    o.texture_uri = texture_file_name;
    o.texture_repeat_m = texture.repeat_m;
    o.texture_mapping = texture.mapping;
  }
  return o;
}

// mesh_0001.obj, ... (--export-meshes), beside frame_0001.png.
std::string mesh_name(int frame, MeshFormat format) {
  return numbered_file_name("mesh", frame, mesh_extension(format));
}

// What weft run writes into its folder: the numbered files of each frame (an earlier run's are
// removed) and the files by name (the point cache's cloth.* among them).
OutputNames run_output_names() {
  return {{"scene.json", "run.txt", "stats.csv", "report.html", checkpoint_file_name,
           texture_file_name, "cloth.obj", "cloth.pc2", "cloth.mdd", "cloth.gltf", "cloth.bin"},
          {{"frame", "png"}, {"mask", "png"}, {"mesh", "(obj|mtl|ply|gltf|bin)"},
           {"state", "npy"}, {cloth_mesh_state_prefix, cloth_mesh_state_extension}}};
}

// Refuses an output folder where the run would replace or remove one of its inputs: the scene
// file (the run writes its copy as scene.json) or a file the scene reads.
void refuse_overwriting_scene_inputs(const fs::path& dir, const Scene& scene) {
  refuse_overwriting_inputs(dir, run_output_names(), scene_files(scene));
}

// Clears the frames (and exported meshes) of an earlier run in the same folder, so that the
// folder holds one run, and writes the scene (with its overrides) and run.txt. Called when the
// first frame is ready: a run that fails before it leaves an earlier run's files as they were.
void prepare_output(std::optional<OutputFolderLock>& lock, const fs::path& dir, const Scene& scene,
                    const RunOptions& options) {
  start_output(lock, dir, run_output_names().numbered,
               {{"scene.json", scene.text},
                {"run.txt", run_record(options.command_line, {{"scene", scene.source}})}});
  std::filesystem::remove(dir / texture_file_name);
  std::filesystem::remove(dir / checkpoint_file_name);  // an earlier run's: --resume must not find it
  if (!mesh_export_options(scene, options).texture_uri.empty())
    render::write_png(*scene.render.cloth_surface.texture.image, dir / texture_file_name);
}

// An explicit step with fast projection jitters when the tolerance is large against the strain
// one step's fall adds to an edge, |g| h² / ℓ: the projection then acts only every few steps, and
// each correction, up to tolerance × ℓ, becomes a velocity of up to tolerance × ℓ / h that nothing
// damps. On the default hang the cloth settled at every tolerance up to 1.4 times that strain and
// never at 2.8 times or more (docs/inextensibility.md, "Explicit integrators"); the warning starts
// at 2. Empty when there is nothing to warn of.
std::string projection_jitter_warning(const Scene& scene, double time_step) {
  const sim::ProjectionSettings& projection = scene.sim.projection;
  if (!sim::is_explicit(scene.sim.integrator) || projection.method != sim::ProjectionMethod::fast_projection || scene.mesh)
    return {};
  const double edge = std::min(scene.grid.size_u_m / static_cast<double>(scene.grid.nu - 1),
                               scene.grid.size_v_m / static_cast<double>(scene.grid.nv - 1));
  const double fall_strain = scene.sim.gravity_m_s2.norm() * time_step * time_step / edge;
  if (projection.tolerance <= 2.0 * fall_strain) return {};
  char text[512];
  std::snprintf(text, sizeof text,
                "simulation.constraints.tolerance %.3g is more than twice the strain one step's "
                "fall adds to an edge (|g| h^2 / edge = %.2g at h = %.3g ms): the projection will act "
                "only every few steps and the cloth may jitter without settling; use a tolerance "
                "of at most %.2g, or implicit_euler",
                projection.tolerance, fall_strain, 1e3 * time_step, fall_strain);
  return text;
}

void print_header(const Scene& scene, const sim::Simulator& simulator,
                  const render::Renderer& renderer, const RunOptions& options) {
  const bool explain = options.explain;
  std::fprintf(
      stderr,
      "weft: %s — %d frame%s at %g fps, %s, time step %.3g ms (critical %.3g ms), "
      "%s\n",
      scene.source.c_str(), scene.frames, scene.frames == 1 ? "" : "s", scene.fps,
      cloth_size_text(scene).c_str(), 1e3 * simulator.time_step(), 1e3 * simulator.critical_time_step(),
      renderer.description().c_str());
  if (sim::is_explicit(scene.sim.integrator) && simulator.time_step() > simulator.critical_time_step())
    std::fprintf(stderr,
                 "weft: warning: the time step %.3g ms exceeds the predicted critical step %.3g ms "
                 "of the explicit integrator: the run will probably diverge (lower "
                 "simulation.time_step or use implicit_euler)\n",
                 1e3 * simulator.time_step(), 1e3 * simulator.critical_time_step());
  // Bending left out of implicit Euler's matrix steps as in symplectic Euler: past its limit
  // the out-of-plane checkerboard grows where no tension steadies it (docs/models.md).
  if (scene.sim.integrator == sim::Integrator::implicit_euler &&
      simulator.time_step() > simulator.explicit_stable_time_step())
    std::fprintf(stderr,
                 "weft: warning: the bending is explicit (simulation.bending_in_step \"%s\") at "
                 "steps of %.3g ms, past its stable %.3g ms: free edges will crumple into a "
                 "saw-tooth (use \"auto\" or \"implicit\")\n",
                 base::enum_name(sim::bending_in_step_names, scene.sim.bending_in_step),
                 1e3 * simulator.time_step(), 1e3 * simulator.explicit_stable_time_step());
  if (const std::string jitter = projection_jitter_warning(scene, simulator.time_step());
      !jitter.empty())
    std::fprintf(stderr, "weft: warning: %s\n", jitter.c_str());
  if (scene.tension_field) {
    const sim::TensionFieldResult folds = sim::solve_tension_field(tension_field_inputs(
        *scene.tension_field, scene.grid, scene.material, scene.sim.gravity_m_s2));
    std::fprintf(stderr, "weft: initial shape: tension-field folds (seed 001): %s\n",
                 folds.message.c_str());
  }
  if (!scene.dynamics && !options.rest)
    std::fprintf(stderr, "weft: simulation.dynamics is false: every frame shows the initial shape\n");
  if (explain) {
    std::printf("weft: the simulation runs, per step:\n");
    for (const std::string& line : simulator.explain()) std::printf("  %s\n", line.c_str());
    std::fflush(stdout);
  }
}

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

// The frame in which a self-colliding cloth passed through itself, when the scene makes that an
// error (simulation.self_collision.crossings): the run ends after writing it.
struct CrossingStop {
  int frame;
  int crossings;
};

// "9–12, 15, 20–48": ascending frame numbers as ranges.
std::string frame_ranges(const std::vector<int>& frames) {
  std::string text;
  for (std::size_t i = 0; i < frames.size();) {
    std::size_t j = i;
    while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
    if (!text.empty()) text += ", ";
    text += std::to_string(frames[i]);
    if (j > i) text += "–" + std::to_string(frames[j]);
    i = j + 1;
  }
  return text;
}

// Renders, writes and records each frame of the stream: frame_NNNN.png, the exported mesh,
// its row of stats.csv, and the progress line. Says to stop the stream after a frame in which
// the cloth passes through itself where the scene makes that an error (crossing_stop()).
//
// A scene without a camera is framed by the cloth's bounding box over the whole run, known only
// when the simulation ends. Its frames are drawn then, from the states the writer keeps in the
// folder meanwhile (state_NNNN.npy and a remeshed cloth's meshes, as --save-states keeps them),
// the way weft render draws saved states: the run is simulated once, and the frames are the
// bytes they would be if drawn as simulated. The writer grows the box frame by frame
// (cloth_box()); draw_kept_frames() draws the frames once the scene's camera is set.
class FrameWriter {
 public:
  FrameWriter(const Scene& scene, const RunOptions& options, const fs::path& dir,
              sim::Simulator& simulator, render::Renderer& renderer)
      : m_scene(scene), m_options(options), m_dir(dir), m_simulator(simulator),
        m_renderer(renderer), m_stats(dir / "stats.csv"), m_draw_later(!scene.camera_given),
        m_keep_states(options.save_states || m_draw_later),
        m_progress(stderr, scene.frames, "frame"), m_initial_x(simulator.state().x) {
    if (m_keep_states && scene.sim.remesh.enabled)
      m_initial_mesh = std::make_unique<sim::ClothMesh>(simulator.mesh());
    if (m_draw_later)
      extend_box(m_cloth_box, m_initial_x);
    else
      m_painter.emplace(scene, renderer, simulator.mesh());
  }

  StreamControl write(const Frame& frame) {
    const bool remeshed_states = m_initial_mesh != nullptr;  // kept states of a remeshed run
    if (m_rows.empty()) {
      prepare_output(m_lock, m_dir, m_scene, m_options);
      if (m_keep_states)
        write_npy_points(m_dir / numbered_file_name("state", 0, "npy"), m_initial_x);
      if (remeshed_states) write_cloth_mesh_state(m_dir, 0, *m_initial_mesh);
    }
    FrameStats row;
    row.frame = frame.index;
    row.sim_ms = 1e3 * frame.sim_s;
    row.steps = m_simulator.take_step_statistics();
    m_eta.add_simulated(frame.sim_s);  // before drawing: the drawing's ETA counts this frame
    // Every simulated frame's state, for weft render (its camera frames them all) or for drawing
    // the frames when the run ends; with remeshing, the mesh of each frame whose steps remeshed
    // the cloth (cloth_mesh_states.h).
    if (m_keep_states)
      write_npy_points(m_dir / numbered_file_name("state", frame.index, "npy"),
                       m_simulator.state().x);
    // After a resume too: the interrupted run may not have saved states (nor meshes).
    if (remeshed_states && (row.steps.remeshes > 0 || m_resumed_mesh_unsaved))
      write_cloth_mesh_state(m_dir, frame.index, m_simulator.mesh());
    m_resumed_mesh_unsaved = false;
    row.diagnostics = m_simulator.diagnostics();
    // The frame's own mesh: with simulation.remesh it changes from frame to frame, so its
    // triangles and edges are taken anew after each remesh (and only then).
    if (m_triangles.empty() || m_topology_remeshes != m_simulator.remesh_count()) {
      m_triangles = m_simulator.mesh().triangles();
      m_edges = sim::unique_edges(m_triangles);
      m_topology_remeshes = m_simulator.remesh_count();
    }
    row.self_intersections =
        sim::count_edge_triangle_crossings(m_simulator.state().x, m_triangles, m_edges);
    row.vertices = m_simulator.mesh().used_vertex_count();
    add_to_cache();
    if (m_draw_later) {
      extend_box(m_cloth_box, m_simulator.state().x);  // drawn by draw_kept_frames
    } else {
      const auto start = std::chrono::steady_clock::now();
      if (m_options.selection.selects(frame.index, m_scene.frames)) {
        const FrameDrawingReport report(m_renderer, m_progress, m_eta, frame.index - 1, frame.index,
                                        m_scene.frames - frame.index, draws_after(frame.index));
        render_frame(*m_painter, frame.index, m_simulator.state().x, m_simulator.state().time_s);
        m_eta.add_drawn(report.seconds());
      }
      row.render_ms = milliseconds_since(start);
    }
    m_stats.write(row);
    m_rows.push_back(row);
    char detail[128];
    std::snprintf(detail, sizeof detail, "t = %.2f s, max strain %.2f %%%s", row.diagnostics.time_s,
                  100.0 * row.diagnostics.max_strain,
                  row.steps.unconverged_steps ? ", projection missed its tolerance" : "");
    m_progress.update(frame.index, detail,
                      m_eta.seconds_left(m_scene.frames - frame.index, draws_after(frame.index)));
    if (m_scene.sim.self_collision.enabled && row.self_intersections > 0) {
      m_crossing_frames.push_back(frame.index);
      if (m_scene.crossings == Scene::CrossingPolicy::error) {
        m_crossing_stop = CrossingStop{frame.index, row.self_intersections};
        return StreamControl::stop;
      }
    }
    return StreamControl::go_on;
  }
  // Frames still to draw after frame k while simulating (none when they are drawn later).
  int draws_after(int k) const {
    int n = 0;
    if (m_draw_later) return 0;
    for (int j = k + 1; j <= m_scene.frames; ++j) n += m_options.selection.selects(j, m_scene.frames);
    return n;
  }
  // Ends the progress line (unless draw_kept_frames did) and writes the point cache.
  void finish() {
    if (!m_draw_later) m_progress.finish();
    for (const fs::path& path :
         m_cache.write(m_dir / "cloth", m_options.export_cache, m_scene.render.front_color))
      std::fprintf(stderr, "weft: wrote %s (frames 0-%d: the start, then every simulated frame)\n",
                   path.c_str(), m_cache.frame_count() - 1);
  }
  // Goes on after the frames of a checkpoint: their rows and crossings, the folder as it is.
  void resume(const RunCheckpoint& checkpoint) {
    m_lock.emplace(m_dir);
    m_resumed_mesh_unsaved = true;
    m_rows = checkpoint.rows;
    m_crossing_frames = checkpoint.crossing_frames;
    m_stats.restore(m_rows);
    if (m_draw_later) resume_cloth_box(checkpoint.frame);
  }
  // Whether the frames are drawn when the simulation ends (the scene gives no camera).
  bool draws_later() const { return m_draw_later; }
  // The cloth's bounding box over frames 0..k so far (a writer that draws later).
  const Eigen::AlignedBox3d& cloth_box() const { return m_cloth_box; }
  // Draws the selected frames of the run from the kept states with the scene's camera, which
  // must now be final — the PNGs, masks, exported meshes and point cache frames, as a writer
  // with a camera draws them while simulating — fills in their render_ms in stats.csv and
  // removes the kept states unless --save-states asked for them. Does nothing (but end the
  // progress line) when no frame was written.
  void draw_kept_frames() {
    m_progress.finish();
    if (!m_draw_later || m_rows.empty()) return;
    const bool remeshed = m_scene.sim.remesh.enabled;
    // The mesh each frame is drawn on: the scene's, or with remeshing the frame's own, read
    // from the folder as weft render reads it.
    sim::ClothMesh frame_mesh = m_simulator.mesh();
    ClothMeshStates meshes(m_dir, frame_mesh);
    FramePainter painter(m_scene, m_renderer, frame_mesh);
    std::vector<int> selected;
    for (int k = m_first_kept_frame; k <= m_rows.back().frame; ++k)
      if (m_options.selection.selects(k, m_scene.frames)) selected.push_back(k);
    Progress progress(stderr, static_cast<int>(selected.size()), "draw");
    RunEta eta;
    for (std::size_t i = 0; i < selected.size(); ++i) {
      const int k = selected[i];
      const auto start = std::chrono::steady_clock::now();
      if (remeshed) frame_mesh = meshes.at(k);
      const int left = static_cast<int>(selected.size() - i) - 1;
      {
        const FrameDrawingReport report(m_renderer, progress, eta, static_cast<int>(i), k, 0, left);
        render_frame(painter, k, read_state(m_dir, k, frame_mesh.vertex_count()),
                     state_time_s(m_scene, k));
        eta.add_drawn(report.seconds());
      }
      FrameStats& row = m_rows[static_cast<std::size_t>(k - 1)];
      WEFT_CHECK(row.frame == k, "stats.csv's row " + std::to_string(k) + " is of frame " +
                                     std::to_string(row.frame));
      row.render_ms = milliseconds_since(start);
      progress.update(static_cast<int>(i + 1), {}, eta.seconds_left(0, left));
    }
    progress.finish();
    m_stats.rewrite(m_rows);
    if (!m_options.save_states) {
      remove_numbered_files(m_dir, "state", "npy");
      // After the states: a run stopped in between leaves no state without its mesh.
      remove_numbered_files(m_dir, cloth_mesh_state_prefix, cloth_mesh_state_extension);
    }
  }
  // The checkpoint of the frames written so far (the simulator at the last one's end).
  RunCheckpoint checkpoint(int every) const {
    RunCheckpoint c;
    c.frame = static_cast<int>(m_rows.size());
    c.every = every;
    c.scene_source = m_scene.source;
    c.scene_text = m_scene.text;
    c.rows = m_rows;
    c.crossing_frames = m_crossing_frames;
    sim::StateWriter state;
    m_simulator.save_state(state);
    c.simulator_state = state.bytes();
    return c;
  }
  // The frames in which a self-colliding cloth passes through itself, in order.
  const std::vector<int>& crossing_frames() const { return m_crossing_frames; }
  // The frame that ended the run by passing through itself, if one did.
  const std::optional<CrossingStop>& crossing_stop() const { return m_crossing_stop; }
  const std::vector<FrameStats>& rows() const { return m_rows; }
  int frames_drawn() const { return m_frames_drawn; }
  double elapsed_s() const { return m_progress.elapsed_s(); }

 private:
  static double milliseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  }

  // Draws frame `index` (the cloth at x, the obstacles at time_s) and writes its exports.
  void render_frame(FramePainter& painter, int index, const sim::Matrix3X& x, double time_s) {
    const render::RenderMesh cloth = painter.paint(index, x, time_s, m_dir);
    ++m_frames_drawn;
    if (const auto format = m_options.export_meshes)
      export_mesh(cloth, *format, m_dir / mesh_name(index, *format),
                  mesh_export_options(m_scene, m_options));
  }

  // --export-cache: the frame just simulated, after frame 0 (the start) when it is the first;
  // every simulated frame, whichever are drawn (--every), so that sample k is frame k.
  void add_to_cache() {
    if (m_options.export_cache.empty()) return;
    if (m_cache.frame_count() == 0)
      m_cache.add(to_render_mesh(m_simulator.mesh(), m_initial_x), state_time_s(m_scene, 0));
    m_cache.add(to_render_mesh(m_simulator.mesh(), m_simulator.state().x),
                m_simulator.state().time_s);
  }

  // The box of frames 0..k of a run resumed from the checkpoint of frame k. An interrupted run
  // leaves the states of its frames in the folder, undrawn: the box is theirs, and they are
  // drawn with the rest. A run that ended drew its frames and removed their states: frames 1..k
  // are simulated again for the box alone, and only the frames after k are drawn anew.
  void resume_cloth_box(int k) {
    m_cloth_box.setEmpty();
    bool kept = !m_scene.sim.remesh.enabled ||
                fs::exists(m_dir / numbered_file_name(cloth_mesh_state_prefix, 0,
                                                      cloth_mesh_state_extension));
    for (int j = 0; j <= k && kept; ++j)
      kept = fs::exists(m_dir / numbered_file_name("state", j, "npy"));
    if (kept) {
      for (int j = 0; j <= k; ++j)
        extend_box(m_cloth_box, read_npy_points(m_dir / numbered_file_name("state", j, "npy")));
      return;
    }
    std::fprintf(stderr,
                 "weft: the states of frames 0..%d are not in %s (a run removes them once it has "
                 "drawn its frames): simulating frames 1..%d again for the camera\n",
                 k, m_dir.c_str(), k);
    m_cloth_box = cloth_bounds_over_frames(m_scene, k);
    m_first_kept_frame = k + 1;
  }

  const Scene& m_scene;
  const RunOptions& m_options;
  std::optional<OutputFolderLock> m_lock;  // taken at the first frame, or on resuming
  int m_frames_drawn = 0;                  // by this process: a resumed run draws only some
  fs::path m_dir;
  sim::Simulator& m_simulator;
  render::Renderer& m_renderer;
  StatsCsv m_stats;
  bool m_draw_later;   // no camera: the frames are drawn when the simulation ends
  bool m_keep_states;  // state_NNNN.npy (and remeshed meshes): --save-states, or to draw later
  // Draws the simulator's mesh as it is at each frame (a writer that draws as it simulates).
  std::optional<FramePainter> m_painter;
  Eigen::AlignedBox3d m_cloth_box;  // the cloth over frames 0..k so far (drawing later)
  int m_first_kept_frame = 1;       // the first frame whose state is kept (drawing later)
  // The current mesh's triangles and edges (crossings), of the mesh after this many remeshes.
  std::vector<std::array<sim::Index, 3>> m_triangles;
  std::vector<std::array<sim::Index, 2>> m_edges;
  long m_topology_remeshes = 0;
  Progress m_progress;
  RunEta m_eta;  // the time left on m_progress's line
  std::vector<FrameStats> m_rows;
  PointCache m_cache;  // --export-cache: the frames so far
  std::vector<int> m_crossing_frames;
  std::optional<CrossingStop> m_crossing_stop;
  sim::Matrix3X m_initial_x;  // frame 0's state (--save-states)
  std::unique_ptr<sim::ClothMesh> m_initial_mesh;  // and its mesh, with simulation.remesh
  bool m_resumed_mesh_unsaved = false;  // resumed: the mesh goes with the first frame's state
};

// Says where the run stopped and what it kept; writes the report of the frames written.
int report_divergence(const FrameDivergence& d, const fs::path& dir, const Scene& scene,
                      const RunOptions& options, const std::vector<FrameStats>& rows) {
  std::fprintf(stderr, "weft: error: frame %d: %s\n", d.frame, d.error.what());
  if (d.frame > 1)
    std::fprintf(stderr, "weft: kept frames 1..%d and stats.csv in %s\n", d.frame - 1,
                 dir.c_str());
  else
    std::fprintf(stderr, "weft: no frame was finished; %s is as it was\n", dir.c_str());
  if (options.report && !rows.empty())
    std::printf("weft: report of the frames written: %s\n",
                write_run_report(dir, scene, options.command_line, rows).c_str());
  return exit_diverged;
}

// Fast projection after a fixed implicit step misses its tolerance where the step is long for
// the mesh: its prediction then lies far from the constraints (the 256² hang at 1/120 s missed
// in 11 of 240 steps; the adaptive step chose about 1/276 s there and missed none, at 0.28 of
// the CPU time: docs/benchmarks.md, "256² converged"). Empty when that is not the case.
std::string shorter_step_advice(const Scene& scene) {
  if (scene.sim.integrator != sim::Integrator::implicit_euler || scene.sim.time_step.is_adaptive() ||
      scene.sim.projection.method != sim::ProjectionMethod::fast_projection)
    return {};
  return "; \"time_step\": \"adaptive\" shortens the steps where the projection needs it";
}

void print_summary(const Scene& scene, const RunOptions& options, const fs::path& dir,
                   const sim::Simulator& simulator, const FrameWriter& writer) {
  double sim_ms = 0.0, render_ms = 0.0;
  long unconverged = 0, steps = 0;
  for (const FrameStats& row : writer.rows()) {
    sim_ms += row.sim_ms;
    render_ms += row.render_ms;
    unconverged += row.steps.unconverged_steps;
    steps += row.steps.steps;
  }
  if (unconverged > 0)
    std::fprintf(
        stderr,
        "weft: warning: the constraint projection missed its tolerance in %ld of %ld steps "
        "(see unconverged_steps in stats.csv)%s\n",
        unconverged, steps, shorter_step_advice(scene).c_str());
  if (const std::vector<int>& crossed = writer.crossing_frames(); !crossed.empty()) {
    int most = 0;
    for (const FrameStats& row : writer.rows()) most = std::max(most, row.self_intersections);
    std::fprintf(stderr,
                 "weft: warning: the cloth passes through itself despite self-collision in %zu of "
                 "%zu frames (%s; up to %d edge–triangle crossings: self_intersections in "
                 "stats.csv)\n",
                 crossed.size(), writer.rows().size(), frame_ranges(crossed).c_str(), most);
  }
  if (options.explain) print_phase_shares(simulator.timers());
  // The frames this process drew (a resumed run said it wrote the interrupted run's too).
  const int written = writer.frames_drawn();
  std::fprintf(stderr, "weft: wrote %d frame%s to %s (simulation %s, rendering %s, total %s)\n",
              written, written == 1 ? "" : "s",
              dir.c_str(), format_duration(sim_ms / 1e3).c_str(),
              format_duration(render_ms / 1e3).c_str(), format_duration(writer.elapsed_s()).c_str());
  if (options.report)
    std::printf("weft: report: %s\n",
                write_run_report(dir, scene, options.command_line, writer.rows()).c_str());
  if (const auto drape = drape_summary(scene, simulator))
    std::printf("weft: last frame: %s (weft measure: settle time, outline)\n", drape->c_str());
}

// The folder of --resume DIR or --resume DIR/checkpoint.weft ("." for a bare checkpoint.weft,
// which used to be named "" in the messages).
fs::path resume_folder(const fs::path& resume) {
  if (fs::is_directory(resume)) return resume;
  return resume.has_parent_path() ? resume.parent_path() : fs::path(".");
}

// The scene of a checkpoint; a scene (and overrides) given with --resume must be the same, and
// so must the folder's scene.json (a checkpoint of another run copied in would mix two scenes'
// frames) and every file the scene reads.
Scene resumed_scene(const RunCheckpoint& checkpoint, const RunOptions& options) {
  const fs::path record = resume_folder(*options.resume) / "scene.json";
  if (fs::exists(record) &&
      base::read_file_capped(record, max_scene_file_bytes, "a scene file") != checkpoint.scene_text)
    throw InputError("--resume " + options.resume->string() + ": the checkpoint's scene is not " +
                     record.string() + ", the scene of the run in that folder (a checkpoint of "
                     "another run?); resume a checkpoint in its own run's folder");
  Scene scene = parse_scene(checkpoint.scene_text, checkpoint.scene_source);
  if (options.scene || !options.overrides.empty()) {
    const Scene given = load_scene_with(options.scene, options.overrides);
    if (given.text != scene.text)
      throw InputError("--resume " + options.resume->string() + ": the checkpoint belongs to " +
                       "another scene (" + checkpoint.scene_source + " with the overrides in its "
                       "scene.json, hash " + std::to_string(fnv1a_64(scene.text)) + "; given: " +
                       given.source + ", hash " + std::to_string(fnv1a_64(given.text)) +
                       "); give no scene to go on with the checkpoint's");
  }
  check_input_files(checkpoint, scene.input_files, options.resume->string());
  return scene;
}

// What rejects the run's options against its scene (and a checkpoint), before anything runs.
void check_run_input(const Scene& scene, const RunOptions& options,
                     const std::optional<RunCheckpoint>& resumed, int every) {
  if ((every > 0 || resumed) && !options.export_cache.empty())
    throw InputError("--export-cache: not with --checkpoint-every or --resume (the point cache "
                     "holds every frame and is not checkpointed; export meshes per frame with "
                     "--export-meshes)");
  // A point cache holds one mesh's vertices (docs/remeshing.md); checkpoints and saved states
  // hold each frame's mesh (docs/checkpoints.md).
  if (scene.sim.remesh.enabled && !options.export_cache.empty())
    throw InputError("--export-cache: not with simulation.remesh (" + scene.source +
                     "): a remeshed cloth's vertices change from frame to frame, and a point "
                     "cache holds one mesh's; export each frame's mesh with --export-meshes");
  if (resumed && resumed->frame >= scene.frames)
    throw InputError("--resume " + options.resume->string() + ": the checkpoint is of frame " +
                     std::to_string(resumed->frame) + ", the scene's last: nothing to resume");
  const FrameSelection& f = options.selection;
  if (!f.last_only && (f.start > scene.frames || f.end.value_or(scene.frames) < f.start))
    throw InputError("--start/--end: expected 1 <= start <= end <= " +
                     std::to_string(scene.frames) + " (the scene's frames), got start " +
                     std::to_string(f.start) + ", end " + std::to_string(f.end.value_or(scene.frames)));
}

// The scene's simulator, at the checkpoint's state when resumed.
// --rest: the scene's simulator holding its rest shape; says how the solve went.
std::unique_ptr<sim::Simulator> rest_simulator(const Scene& scene, bool& converged) {
  RestShape rest = solve_rest_shape(scene);
  converged = rest.solve.converged;
  std::fprintf(stderr, "weft: rest shape: static solve %s after %d Newton iterations "
                       "(residual %.2g of the weight, %d vertices on obstacles, %.2f s CPU)\n",
               converged ? "converged" : ("NOT converged (" + rest.solve.stopped + ")").c_str(),
               rest.solve.iterations, rest.solve.residual, rest.solve.contacts, rest.cpu_s);
  return std::move(rest.simulator);
}

std::unique_ptr<sim::Simulator> simulator_for(const Scene& scene,
                                              const std::optional<RunCheckpoint>& resumed,
                                              const RunOptions& options) {
  std::unique_ptr<sim::Simulator> simulator = make_simulator(scene);
  if (resumed) {
    sim::StateReader state(resumed->simulator_state, options.resume->string());
    try {
      simulator->restore_state(state);
    } catch (const sim::StateArchiveError& e) {
      throw InputError(std::string(e.what()) + " (a damaged checkpoint)");
    }
  }
  return simulator;
}

// A scene without a camera: frames the cloth's box over the run the writer kept (frames 0..N,
// or up to a divergence) and draws the kept frames. The camera frames the cloth over frames
// 0..N whatever the crossings policy, so that a run a crossing stopped draws its frames as a
// run that went on would: the rest of that run is simulated for the box alone.
void draw_with_the_automatic_camera(Scene& scene, sim::Simulator& simulator, FrameWriter& writer,
                                    const FrameStreamEnd& end) {
  Eigen::AlignedBox3d box = writer.cloth_box();
  if (writer.crossing_stop())
    (void)stream_frames(
        scene, simulator,
        [&](const Frame& frame) {
          extend_box(box, frame.simulator.state().x);
          return StreamControl::go_on;
        },
        end.frames + 1);
  frame_cloth_if_no_camera(scene, box);
  writer.draw_kept_frames();
}

// Says where a crossing stopped the run and what it kept.
int report_crossing_stop(const CrossingStop& stop, const fs::path& dir) {
  std::fprintf(stderr,
               "weft: error: frame %d: the cloth passes through itself (%d edge–triangle "
               "crossings; simulation.self_collision.crossings is \"error\")\n"
               "weft: kept what frames 1..%d wrote and stats.csv in %s\n",
               stop.frame, stop.crossings, stop.frame, dir.c_str());
  return exit_diverged;
}

}  // namespace

int run_scene(const RunOptions& options) {
  std::optional<RunCheckpoint> resumed;
  if (options.resume) resumed = read_checkpoint(*options.resume);
  Scene scene = resumed ? resumed_scene(*resumed, options)
                        : load_scene_with(options.scene, options.overrides);
  const int every = options.checkpoint_every.value_or(resumed ? resumed->every : 0);
  check_run_input(scene, options, resumed, every);
  // The input files as read now, bound to each checkpoint (a resume with others is refused).
  const std::vector<InputFileHash> inputs =
      every > 0 ? hash_input_files(scene.input_files) : std::vector<InputFileHash>{};
  apply_threads(scene, options.threads);
  if (options.rest) {  // one frame showing the solved shape, nothing simulated in time
    scene.frames = 1;
    scene.dynamics = false;
  }
  // Everything that can reject the input happens before the output folder is touched.
  bool rest_converged = true;
  const std::unique_ptr<sim::Simulator> simulator =
      options.rest ? rest_simulator(scene, rest_converged) : simulator_for(scene, resumed, options);
  const std::unique_ptr<render::Renderer> renderer = make_chosen_renderer(scene.render);
  if (!scene.camera_given)
    std::fprintf(stderr, "weft: the scene gives no render.camera: framing the cloth's bounding box "
                         "over the run (the frames are drawn when the simulation ends)\n");

  const fs::path dir = options.resume ? resume_folder(*options.resume)
                                       : options.out.value_or(fs::path("out") / scene.name);
  refuse_overwriting_scene_inputs(dir, scene);
  print_header(scene, *simulator, *renderer, options);
  FrameWriter writer(scene, options, dir, *simulator, *renderer);
  if (resumed) {
    std::fprintf(stderr, "weft: resuming from the checkpoint of frame %d in %s\n", resumed->frame,
                 dir.c_str());
    writer.resume(*resumed);
  }
  const FrameStreamEnd end = stream_frames(
      scene, *simulator,
      [&](const Frame& frame) {
        if (writer.write(frame) == StreamControl::stop) return StreamControl::stop;
        if (every > 0 && frame.index % every == 0 && frame.index < scene.frames) {
          RunCheckpoint checkpoint = writer.checkpoint(every);
          checkpoint.inputs = inputs;
          write_checkpoint(dir, checkpoint);
        }
        return StreamControl::go_on;
      },
      resumed ? resumed->frame + 1 : 1);
  if (writer.draws_later()) draw_with_the_automatic_camera(scene, *simulator, writer, end);
  writer.finish();
  if (const std::optional<CrossingStop>& stop = writer.crossing_stop())
    return report_crossing_stop(*stop, dir);
  if (end.divergence) return report_divergence(*end.divergence, dir, scene, options, writer.rows());
  print_summary(scene, options, dir, *simulator, writer);
  return rest_converged ? exit_ok : exit_failure;
}

}  // namespace weft::app
