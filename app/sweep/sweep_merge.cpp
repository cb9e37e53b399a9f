// weft sweep's merge (see sweep_merge.h): errors against the reference run
// (analysis/sweep_metrics.h), the Pareto front, sweep.csv, sweep.png and the table.

#include "app/sweep/sweep_merge.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <sstream>

#include "analysis/sweep_metrics.h"
#include "app/io/exit_code.h"
#include "app/run/frame_stream.h"
#include "app/io/output_files.h"
#include "app/sweep/sweep_plot.h"
#include "sim/simulator.h"

namespace weft::app {

namespace fs = std::filesystem;

void simulate(SweepRun& run) {
  const std::unique_ptr<sim::Simulator> owner = make_simulator(run.scene);
  sim::Simulator& simulator = *owner;
  run.time_step_s = simulator.time_step();
  const FrameStreamEnd end = stream_frames(run.scene, simulator, [&](const Frame& frame) {
    run.wall_s += frame.sim_s;
    run.max_strain = std::max(run.max_strain, simulator.diagnostics().max_strain);
    return StreamControl::go_on;
  });
  if (end.divergence) {
    run.diverged = true;
    run.failure = end.divergence->error.what();
  }
  run.steps = simulator.steps_taken();
  run.mesh = simulator.mesh();
  run.x = simulator.state().x;
}

namespace {

bool finished(const SweepRun& run) { return !run.diverged && !run.failed; }

// Silhouette masks are kSilhouetteCells × kSilhouetteCells cells over the pair's joint window.
constexpr int kSilhouetteCells = 256;


void compare_with_reference(std::vector<SweepRun>& runs, std::size_t reference) {
  const SweepRun& ref = runs[reference];
  const render::Camera& camera = ref.scene.render.camera;
  const analysis::OrthoView view = analysis::ortho_view(camera.target - camera.eye, camera.up);
  const auto ref_triangles = ref.mesh.triangles();
  for (SweepRun& run : runs) {
    if (!finished(run)) continue;
    run.rms_error_m = analysis::rms_distance_m(ref.mesh, ref.x, run.mesh, run.x);
    const analysis::Window window = analysis::joint_window(view, ref.x, run.x);
    run.silhouette_difference = analysis::silhouette_difference(
        analysis::silhouette(ref_triangles, ref.x, view, window, kSilhouetteCells),
        analysis::silhouette(run.mesh.triangles(), run.x, view, window, kSilhouetteCells));
  }
  std::vector<double> time_s, error_m;
  std::vector<bool> finished;
  for (const SweepRun& run : runs) {
    time_s.push_back(run.wall_s);
    error_m.push_back(run.rms_error_m);
    finished.push_back(app::finished(run));
  }
  const std::vector<bool> optimal = analysis::pareto_optimal(time_s, error_m, finished);
  for (std::size_t k = 0; k < runs.size(); ++k) runs[k].pareto = optimal[k];
}

// Whether run a is taken as more accurate than run b by the reference rule: more cloth vertices
// (the finer mesh), then more steps (the smaller step over the same frames). Never by time: the
// slowest run used to be taken, which depends on the machine's load, and was not always the
// most accurate (implicit Euler's long step damps the motion).
bool finer(const SweepRun& a, const SweepRun& b) {
  const long va = a.mesh.used_vertex_count(), vb = b.mesh.used_vertex_count();
  if (va != vb) return va > vb;
  return a.steps > b.steps;
}

// The finest finished run (finer(); the first of equals), or the user's choice (1-based).
std::size_t choose_reference(const std::vector<SweepRun>& runs, std::optional<int> chosen) {
  if (chosen) {
    const SweepRun& run = runs[static_cast<std::size_t>(*chosen - 1)];
    if (!finished(run))
      throw InputError("--reference " + std::to_string(*chosen) + ": that run " +
                       (run.failed ? "failed" : "diverged") + " (" +
                       run.failure + "); choose a run that finished");
    return static_cast<std::size_t>(*chosen - 1);
  }
  std::size_t best = runs.size();
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (finished(runs[k]) && (best == runs.size() || finer(runs[k], runs[best]))) best = k;
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
         "pareto,reference,failed\n";
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const SweepRun& r = runs[k];
    out << k + 1;
    for (const Setting& s : r.settings) out << "," << csv_field(s.value);
    if (r.failed) {
      out << ",,,,,,," << r.diverged << "," << r.pareto << "," << (k == reference) << ",1\n";
      continue;  // no result at all
    }
    out << "," << number("%.6g", r.wall_s) << "," << r.steps << ","
        << number("%.6g", r.time_step_s);
    if (r.diverged) {
      out << ",,,";  // no errors for a run without a last frame
    } else {
      out << "," << number("%.6g", r.rms_error_m) << "," << number("%.6g", r.max_strain) << ","
          << number("%.6g", r.silhouette_difference);
    }
    out << "," << r.diverged << "," << r.pareto << "," << (k == reference) << ",0\n";
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
    row.push_back(r.failed ? "-" : number("%.3g", r.wall_s));
    row.push_back(r.failed ? "-" : std::to_string(r.steps));
    row.push_back(!finished(r) ? "-" : number("%.3g", r.rms_error_m));
    row.push_back(!finished(r) ? "-" : number("%.3g %%", 100.0 * r.max_strain));
    row.push_back(!finished(r) ? "-" : number("%.3f", r.silhouette_difference));
    row.push_back(r.failed         ? "failed"
                  : r.diverged     ? "diverged"
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

std::string sweep_label(const SweepRun& run, const std::vector<SettingValues>& values) {
  return label(run, short_keys(values));
}

int merge_sweep(std::vector<SweepRun>& runs, const SweepMerge& m) {
  const Scene& base = *m.base;
  const std::vector<std::string> keys = short_keys(m.values);
  const std::size_t reference = choose_reference(runs, m.reference);
  if (reference < runs.size()) compare_with_reference(runs, reference);

  const fs::path& dir = m.dir;
  std::optional<OutputFolderLock> lock;
  start_output(lock, dir, {}, {{"scene.json", base.text},
                         {"run.txt", run_record(m.command_line, {{"scene", base.source}})}});
  write_csv(dir / "sweep.csv", m.values, runs, reference);
  std::vector<PlotRun> plot_runs;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const SweepRun& r = runs[k];
    plot_runs.push_back({r.wall_s, r.rms_error_m, label(r, keys), r.pareto, k == reference,
                         r.diverged, r.failed});
  }
  chart::write_png(sweep_chart(plot_runs, "weft sweep: " + base.name + ", error vs time"),
                   dir / "sweep.png");

  print_table(m.values, runs, reference);
  std::vector<std::size_t> failed;
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (runs[k].failed) failed.push_back(k);
  for (std::size_t k : failed)
    std::printf("weft sweep: run %zu (%s) failed: %s\n", k + 1, describe(runs[k].settings).c_str(),
                runs[k].failure.c_str());
  if (reference == runs.size()) {
    std::printf("weft sweep: %s; nothing to compare (see %s)\n",
                failed.empty() ? "every run diverged" : "no run finished", (dir / "sweep.csv").c_str());
    return failed.empty() ? exit_diverged : exit_failure;
  }
  std::printf("weft sweep: errors against run %zu (%s), %s\n", reference + 1,
              label(runs[reference], keys).c_str(),
              m.reference ? "chosen with --reference"
                          : "the finest run that finished: most vertices, then most steps");
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
  std::printf("weft sweep: wrote %s and %s%s\n", (dir / "sweep.csv").c_str(),
              (dir / "sweep.png").c_str(),
              failed.empty() ? "" : (", without the " + std::to_string(failed.size()) +
                                     " failed run" + (failed.size() == 1 ? "" : "s")).c_str());
  return failed.empty() ? exit_ok : exit_failure;
}

}  // namespace weft::app
