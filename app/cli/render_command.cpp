#include "app/cli/render_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <regex>

#include "app/io/input_guard.h"
#include "app/scene/scene_inputs.h"
#include "app/run/auto_camera.h"
#include "app/io/cloth_mesh_states.h"
#include "app/run/frame_painter.h"
#include "app/scene/json_reader.h"
#include "app/io/progress.h"
#include "app/run/run_eta.h"
#include "app/run/renderer_choice.h"
#include "app/run/run_job.h"
#include "app/run/saved_states.h"
#include "app/scene/scene.h"
#include "app/cluster/slurm_job.h"
#include "app/cluster/slurm_resources.h"

namespace weft::app {

namespace fs = std::filesystem;

std::pair<int, int> parse_frame_range(const std::string& text, int frames) {
  static const std::regex pattern(R"((\d{1,6})(?:-(\d{1,6}))?)");
  std::smatch m;
  if (std::regex_match(text, m, pattern)) {
    const int first = std::stoi(m[1]), last = m[2].matched ? std::stoi(m[2]) : first;
    if (1 <= first && first <= last && last <= frames) return {first, last};
  }
  throw InputError("--frames: expected A-B or A with 1 <= A <= B <= " + std::to_string(frames) +
                   " (the scene's frames), got '" + text + "'");
}

namespace {

// The frames in `tasks` contiguous parts, as weft render command lines of their own.
int submit_render(const RenderOptions& options, const Scene& scene, Eigen::Index vertices,
                  const std::vector<int>& selected, const fs::path& out) {
  SlurmArray array;
  array.job_name = "weft-render";
  array.log_dir = fs::absolute(out / "slurm");
  const std::size_t tasks = std::min<std::size_t>(static_cast<std::size_t>(options.tasks), selected.size());
  TaskWork work = drawing_work(scene, static_cast<long>((selected.size() + tasks - 1) / tasks));
  work.vertices = static_cast<long>(vertices);
  array.resources = estimate_resources({work}, options.threads.value_or(1));
  for (std::size_t t = 0; t < tasks; ++t) {
    const std::size_t begin = selected.size() * t / tasks, end = selected.size() * (t + 1) / tasks;
    std::vector<std::string> argv{fs::read_symlink("/proc/self/exe").string(), "render",
                                  fs::absolute(options.states).string(), "--frames",
                                  std::to_string(selected[begin]) + "-" + std::to_string(selected[end - 1]),
                                  "--every", std::to_string(options.every),
                                  "--out", fs::absolute(out).string(),
                                  "--threads", std::to_string(array.resources.cpus)};
    if (options.scene) argv.insert(argv.end(), {"--scene", fs::absolute(*options.scene).string()});
    for (const Setting& s : options.overrides) argv.insert(argv.end(), {"--set", s.key + "=" + s.value});
    array.tasks.push_back(argv);
  }
  const fs::path script = out / "slurm" / "render.sbatch";
  const std::string submitted = write_slurm_array(array, script, options.dry_run);
  std::fprintf(stderr, "weft: wrote %s: %zu array tasks for %zu frames%s\n", script.c_str(), tasks,
               selected.size(), options.dry_run ? " (not submitted: --dry-run)" : "");
  if (options.dry_run) std::printf("%s", slurm_array_script(array).c_str());
  else std::printf("%s", submitted.c_str());
  return exit_ok;
}

}  // namespace

int run_render(const RenderOptions& options) {
  for (const Setting& s : options.overrides)
    if (s.key.rfind("render.", 0) != 0 && s.key != "output.alpha" && s.key != "output.mask")
      throw InputError((s.option.empty() ? "--set " + s.key : s.option) +
                       ": weft render draws saved states: only render.* keys, output.alpha and "
                       "output.mask may change");
  const fs::path scene_path = options.scene.value_or(options.states / "scene.json");
  Scene scene = load_scene_with(scene_path, options.overrides);
  apply_threads(scene, options.threads);
  const auto [first, last] = options.frames.empty()
                                 ? std::pair<int, int>{1, scene.frames}
                                 : parse_frame_range(options.frames, scene.frames);
  // The cloth's mesh as weft run makes it; no step is taken. A remeshed run's frames each have
  // the mesh saved beside their states (app/io/cloth_mesh_states.h), drawn through `frame_mesh`.
  const std::unique_ptr<sim::Simulator> simulator = make_simulator(scene);
  const sim::ClothMesh& mesh = simulator->mesh();
  const bool remeshed = scene.sim.remesh.enabled;
  ClothMeshStates meshes(options.states, mesh);
  sim::ClothMesh frame_mesh = mesh;
  const auto vertices_of = [&](int k) {
    return remeshed ? meshes.at(k).vertex_count() : mesh.vertex_count();
  };
  const std::vector<int> selected = every_nth_frames(first, last, options.every);
  // Not DIR itself: its frames are the run's own (weft run's preview, or the frames it drew),
  // which a render with other settings used to overwrite.
  const fs::path out = options.out.value_or(options.states / default_render_folder);
  refuse_overwriting_inputs(out, {{}, {{"frame", "png"}, {"mask", "png"}}}, scene_files(scene));
  if (options.slurm) return submit_render(options, scene, mesh.vertex_count(), selected, out);
  // Each state file is read once: without a camera every frame's, for weft run's framing (the
  // cloth over frames 0..N), keeping the selected ones; otherwise only the selected ones.
  std::vector<sim::Matrix3X> states(selected.size());
  const auto selected_index = [&](int k) {
    const auto at = std::lower_bound(selected.begin(), selected.end(), k);
    return at != selected.end() && *at == k ? static_cast<std::size_t>(at - selected.begin())
                                            : selected.size();
  };
  if (!scene.camera_given) {
    Eigen::AlignedBox3d box;
    for (int k = 0; k <= scene.frames; ++k) {
      sim::Matrix3X x = read_state(options.states, k, vertices_of(k));
      extend_box(box, x);
      if (const std::size_t i = selected_index(k); i < selected.size()) states[i] = std::move(x);
    }
    frame_cloth_if_no_camera(scene, box);
  } else {
    for (std::size_t i = 0; i < selected.size(); ++i)
      states[i] = read_state(options.states, selected[i], vertices_of(selected[i]));
  }
  const std::unique_ptr<render::Renderer> renderer = make_chosen_renderer(scene.render);
  fs::create_directories(out);
  FramePainter painter(scene, *renderer, frame_mesh);
  Progress progress(stderr, static_cast<int>(selected.size()), "frame");
  RunEta eta;
  for (std::size_t i = 0; i < selected.size(); ++i) {
    if (remeshed) frame_mesh = meshes.at(selected[i]);
    const int left = static_cast<int>(selected.size() - i) - 1;
    const FrameDrawingReport report(*renderer, progress, eta, static_cast<int>(i), selected[i], 0, left);
    painter.paint(selected[i], states[i], state_time_s(scene, selected[i]), out);
    eta.add_drawn(report.seconds());
    progress.update(static_cast<int>(i + 1), {}, eta.seconds_left(0, left));
  }
  progress.finish();
  std::fprintf(stderr, "weft: rendered %zu frame%s (%d–%d every %d) from %s into %s\n",
               selected.size(), selected.size() == 1 ? "" : "s", first, last, options.every,
               options.states.c_str(), out.c_str());
  return exit_ok;
}

Command register_render(CLI::App& app, const std::string&) {
  const auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Draw frames of a run from the states weft run --save-states wrote, without simulating");
  cmd->add_option("states", o->states, "The run's output folder (state_0000.npy, ..., scene.json)")
      ->required();
  cmd->add_option("--scene", o->scene,
                  "The run's scene file (default: DIR/scene.json; give the original where the "
                  "scene names files by relative paths)");
  cmd->add_option("--out", o->out, "Output folder (default: DIR/render, beside the states; DIR's "
                                    "own frames are the run's)");
  cmd->add_option("--frames", o->frames, "Frames to draw, A-B or A (default: all)")->type_name("A-B");
  check_range(cmd->add_option("--every", o->every, "Draw every Nth frame from A, and B"),
              Range::closed(1, 100000));
  add_set_option(*cmd, o->overrides);
  add_size_option(*cmd, o->overrides, "Image size WIDTHxHEIGHT (overrides render.size)");
  add_render_options(*cmd, o->overrides);
  add_threads_option(*cmd, o->threads);
  CLI::Option* slurm = add_slurm_flags(
      *cmd, o->slurm, o->dry_run,
      "Write OUT/slurm/render.sbatch, a Slurm job array drawing the frames in --tasks parts, "
      "and submit it with sbatch (--threads N: CPUs per task, default 1)");
  check_range(cmd->add_option("--tasks", o->tasks, "Array tasks for --slurm (default 4)"),
              Range::closed(1, 100000))
      ->needs(slurm);
  return {cmd, [o] { return run_render(*o); }};
}

}  // namespace weft::app
