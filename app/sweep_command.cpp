// weft sweep: simulate each combination of --set values, compare each final frame with the
// reference run's (analysis/sweep_metrics.h) and report the speed/accuracy trade.

#include "app/sweep_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>
#include <memory>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "app/frame_stream.h"
#include "app/scene.h"
#include "app/scene_patch.h"
#include "app/sweep_plot.h"
#include "app/output_files.h"
#include "analysis/sweep_metrics.h"
#include "render/image.h"
#include "sim/pins.h"
#include "sim/simulator.h"

namespace weft::app {

namespace {

namespace fs = std::filesystem;

// Silhouette masks are kSilhouetteCells × kSilhouetteCells cells over the pair's joint window.
constexpr int kSilhouetteCells = 256;

struct SweepRun {
  std::vector<Setting> settings;
  Scene scene;
  // Results.
  double wall_s = 0.0;  // simulation (advance) wall time, set-up excluded
  long steps = 0;
  double time_step_s = 0.0;  // the step the simulator used
  bool diverged = false;
  std::string failure;      // the divergence message
  sim::ClothMesh mesh;      // its rest shape and material coordinates
  sim::Matrix3X x;          // #V×3 positions at the last frame, metres
  double max_strain = 0.0;  // largest warp/weft strain at any frame end
  // Errors against the reference.
  double rms_error_m = 0.0;
  double silhouette_difference = 0.0;
  bool pareto = false;
};

// Simulates the scene's frames through the frame stream (frame_stream.h), as `weft run` does;
// the wall time is advance()'s only.
void simulate(SweepRun& run) {
  const std::unique_ptr<sim::Simulator> owner = make_simulator(run.scene);
  sim::Simulator& simulator = *owner;
  run.time_step_s = simulator.time_step();
  const FrameStreamEnd end = stream_frames(run.scene, simulator, [&](const Frame& frame) {
    run.wall_s += frame.sim_s;
    run.max_strain = std::max(run.max_strain, simulator.diagnostics().max_strain);
  });
  if (end.divergence) {
    run.diverged = true;
    run.failure = end.divergence->error.what();
  }
  run.steps = simulator.steps_taken();
  run.mesh = simulator.mesh();
  run.x = simulator.state().x;
}

void compare_with_reference(std::vector<SweepRun>& runs, std::size_t reference) {
  const SweepRun& ref = runs[reference];
  const render::Camera& camera = ref.scene.render.camera;
  const OrthoView view = ortho_view(camera.target - camera.eye, camera.up);
  const auto ref_triangles = ref.mesh.triangles();
  for (SweepRun& run : runs) {
    if (run.diverged) continue;
    run.rms_error_m = rms_distance_m(ref.mesh, ref.x, run.mesh, run.x);
    const Window window = joint_window(view, ref.x, run.x);
    run.silhouette_difference = silhouette_difference(
        silhouette(ref_triangles, ref.x, view, window, kSilhouetteCells),
        silhouette(run.mesh.triangles(), run.x, view, window, kSilhouetteCells));
  }
  std::vector<double> time_s, error_m;
  std::vector<bool> finished;
  for (const SweepRun& run : runs) {
    time_s.push_back(run.wall_s);
    error_m.push_back(run.rms_error_m);
    finished.push_back(!run.diverged);
  }
  const std::vector<bool> optimal = pareto_optimal(time_s, error_m, finished);
  for (std::size_t k = 0; k < runs.size(); ++k) runs[k].pareto = optimal[k];
}

// The finished run with the largest wall time, or the user's choice (1-based).
std::size_t choose_reference(const std::vector<SweepRun>& runs, std::optional<int> chosen) {
  if (chosen) {
    const SweepRun& run = runs[static_cast<std::size_t>(*chosen - 1)];
    if (run.diverged)
      throw SceneError("--reference " + std::to_string(*chosen) + ": that run diverged (" +
                       run.failure + "); choose a run that finished");
    return static_cast<std::size_t>(*chosen - 1);
  }
  std::size_t best = runs.size();
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (!runs[k].diverged && (best == runs.size() || runs[k].wall_s > runs[best].wall_s)) best = k;
  }
  return best;
}

// A key's name in labels: its last part ("resolution") when no other key ends the same way.
std::vector<std::string> short_keys(const std::vector<SettingValues>& options) {
  std::vector<std::string> names;
  for (const SettingValues& o : options) names.push_back(o.key.substr(o.key.rfind('.') + 1));
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (std::count(names.begin(), names.end(), names[k]) > 1) names[k] = options[k].key;
  }
  return names;
}

std::string label(const SweepRun& run, const std::vector<std::string>& keys) {
  std::string text;
  for (std::size_t k = 0; k < keys.size(); ++k)
    text += (k ? " " : "") + keys[k] + "=" + run.settings[k].value;
  return text;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string number(const char* format, double v) {
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

void write_csv(const fs::path& path, const std::vector<SettingValues>& options,
               const std::vector<SweepRun>& runs, std::size_t reference) {
  std::ostringstream out;
  out << "run";
  for (const SettingValues& o : options) out << "," << csv_field(o.key);
  out << ",wall_time_s,steps,time_step_s,rms_error_m,max_strain,silhouette_difference,diverged,"
         "pareto,reference\n";
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const SweepRun& r = runs[k];
    out << k + 1;
    for (const Setting& s : r.settings) out << "," << csv_field(s.value);
    out << "," << number("%.6g", r.wall_s) << "," << r.steps << ","
        << number("%.6g", r.time_step_s);
    if (r.diverged) {
      out << ",,,";  // no errors for a run without a last frame
    } else {
      out << "," << number("%.6g", r.rms_error_m) << "," << number("%.6g", r.max_strain) << ","
          << number("%.6g", r.silhouette_difference);
    }
    out << "," << r.diverged << "," << r.pareto << "," << (k == reference) << "\n";
  }
  write_text(path, out.str());
}

// The table on stdout, columns padded to their widest cell.
void print_table(const std::vector<SettingValues>& options, const std::vector<SweepRun>& runs,
                 std::size_t reference) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> header{"run"};
  for (const SettingValues& o : options) header.push_back(o.key);
  for (const char* h : {"wall s", "steps", "rms error m", "max strain", "silhouette", "note"})
    header.push_back(h);
  rows.push_back(header);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const SweepRun& r = runs[k];
    std::vector<std::string> row{std::to_string(k + 1)};
    for (const Setting& s : r.settings) row.push_back(s.value);
    row.push_back(number("%.3g", r.wall_s));
    row.push_back(std::to_string(r.steps));
    row.push_back(r.diverged ? "-" : number("%.3g", r.rms_error_m));
    row.push_back(r.diverged ? "-" : number("%.3g %%", 100.0 * r.max_strain));
    row.push_back(r.diverged ? "-" : number("%.3f", r.silhouette_difference));
    row.push_back(r.diverged       ? "diverged"
                  : k == reference ? "reference, Pareto"
                  : r.pareto       ? "Pareto"
                                   : "");
    rows.push_back(row);
  }
  std::vector<std::size_t> width(header.size(), 0);
  for (const auto& row : rows)
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c)
      line += row[c] + std::string(c + 1 < row.size() ? width[c] - row[c].size() + 2 : 0, ' ');
    while (!line.empty() && line.back() == ' ') line.pop_back();
    std::printf("%s\n", line.c_str());
  }
}

}  // namespace

int run_sweep(const SweepOptions& options) {
  Scene base = load_scene_with(options.scene, options.overrides);
  apply_threads(base, options.threads);
  if (options.set.empty())
    throw SceneError("--set: expected at least one KEY=V1,V2,... to sweep over");
  std::vector<SettingValues> values;
  for (const std::string& text : options.set) values.push_back(parse_set_option(text));

  // Every combination is read (and so checked) before any is simulated.
  std::vector<SweepRun> runs;
  for (std::vector<Setting>& settings : setting_grid(values)) {
    SweepRun run;
    run.scene = patched_scene(base, settings);
    apply_threads(run.scene, options.threads);
    run.settings = std::move(settings);
    runs.push_back(std::move(run));
  }
  if (options.reference &&
      (*options.reference < 1 || *options.reference > static_cast<int>(runs.size())))
    throw SceneError("--reference: expected a run number in 1.." + std::to_string(runs.size()) +
                     ", got " + std::to_string(*options.reference));

  const std::vector<std::string> keys = short_keys(values);
  std::fprintf(stderr, "weft sweep: %s, %zu runs of %d frames each\n", base.source.c_str(),
               runs.size(), runs.front().scene.frames);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    SweepRun& run = runs[k];
    simulate(run);
    std::fprintf(stderr, "weft sweep: run %zu/%zu %s: %.3g s, %ld steps of %.3g ms%s%s\n", k + 1,
                 runs.size(), label(run, keys).c_str(), run.wall_s, run.steps,
                 1e3 * run.time_step_s, run.diverged ? ", diverged: " : "", run.failure.c_str());
  }

  const std::size_t reference = choose_reference(runs, options.reference);
  if (reference < runs.size()) compare_with_reference(runs, reference);

  const fs::path dir = options.out.value_or(fs::path("out") / ("sweep-" + base.name));
  start_output(dir, {}, {{"scene.json", base.text},
                         {"run.txt", run_record(options.command_line, {{"scene", base.source}})}});
  write_csv(dir / "sweep.csv", values, runs, reference);
  std::vector<PlotRun> plot_runs;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const SweepRun& r = runs[k];
    plot_runs.push_back(
        {r.wall_s, r.rms_error_m, label(r, keys), r.pareto, k == reference, r.diverged});
  }
  chart::write_png(sweep_chart(plot_runs, "weft sweep: " + base.name + ", error vs time"),
                   dir / "sweep.png");

  print_table(values, runs, reference);
  if (reference == runs.size()) {
    std::printf("weft sweep: every run diverged; nothing to compare (see %s)\n",
                (dir / "sweep.csv").c_str());
    return exit_diverged;
  }
  std::printf("weft sweep: errors against run %zu (%s), %s\n", reference + 1,
              label(runs[reference], keys).c_str(),
              options.reference ? "chosen with --reference" : "the slowest run that finished");
  std::printf("weft sweep: Pareto-optimal settings, fastest first:\n");
  std::vector<std::size_t> front;
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (runs[k].pareto) front.push_back(k);
  std::sort(front.begin(), front.end(),
            [&](std::size_t a, std::size_t b) { return runs[a].wall_s < runs[b].wall_s; });
  for (std::size_t k : front) {
    std::printf("  run %zu: %s (%.3g s, RMS error %.3g m)\n", k + 1,
                describe(runs[k].settings).c_str(), runs[k].wall_s, runs[k].rms_error_m);
  }
  std::printf("weft sweep: wrote %s and %s\n", (dir / "sweep.csv").c_str(),
              (dir / "sweep.png").c_str());
  return exit_ok;
}

Command register_sweep(CLI::App& app, const std::string& command_line) {
  const auto o = std::make_shared<SweepOptions>();
  o->command_line = command_line;
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Run a scene over a grid of settings; write sweep.csv and sweep.png (error vs wall time)");
  cmd->add_option("scene", o->scene, "Scene file; the built-in default scene if omitted");
  cmd->add_option("--set", o->set,
                  "KEY=V1,V2,...: scene key (dotted path, e.g. cloth.resolution) and the values to "
                  "try (JSON, or plain text such as 1 ms); repeat for a grid of every combination")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--out", o->out, "Output folder (default: out/sweep-<scene name>)");
  add_override_option(*cmd, "--frames", "output.frames", o->overrides,
                      "Frames to simulate in every run (overrides output.frames)", "INT");
  add_threads_option(*cmd, o->threads);
  cmd->add_option("--reference", o->reference,
                  "Run number (row of sweep.csv) the errors are measured against (default: the "
                  "finished run with the largest wall time, taken as the most accurate)");
  return {cmd, [o] { return run_sweep(*o); }};
}

}  // namespace weft::app
