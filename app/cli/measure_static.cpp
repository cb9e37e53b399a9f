// weft measure --static: the scene's rest shape solved by the static equilibrium solver from
// one or several imperfection seeds, measured as a drape (app/run/rest_shape.h).

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "app/io/input_guard.h"
#include "app/scene/scene_inputs.h"
#include "app/cli/measure_command.h"
#include "app/io/output_files.h"
#include "app/io/progress.h"
#include "app/io/version.h"
#include "app/run/rest_shape.h"
#include "base/format.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;
using base::format;

std::string static_csv_row(const RestMeasurement& m) {
  std::ostringstream row;
  row.precision(9);
  row << m.seed << ',' << (m.solve.converged ? 1 : 0) << ',' << m.solve.iterations << ','
      << m.solve.factorizations << ',' << m.solve.residual << ',' << m.cpu_s << ',';
  if (m.drape) row << m.drape->drape_coefficient;
  row << ',';
  if (m.drape) row << m.drape->folds;
  row << ',' << m.self_intersections << '\n';
  return row.str();
}

void print_static_table(const Scene& scene, const std::vector<RestMeasurement>& runs) {
  std::vector<double> dc, folds, cpu;
  int converged = 0;
  for (const RestMeasurement& m : runs) {
    converged += m.solve.converged ? 1 : 0;
    cpu.push_back(m.cpu_s);
    if (m.drape) {
      dc.push_back(m.drape->drape_coefficient);
      folds.push_back(m.drape->folds);
    }
  }
  std::printf("weft: %s at rest (static solve, %zu seed%s)\n", scene.source.c_str(), runs.size(),
              runs.size() == 1 ? "" : "s");
  const auto line = [](const char* name, const std::string& value) {
    std::printf("  %-28s %s\n", name, value.c_str());
  };
  line("converged", std::to_string(converged) + " of " + std::to_string(runs.size()) +
                        (converged < static_cast<int>(runs.size()) ? " (see static.csv)" : ""));
  const Spread c = spread_of(cpu);
  line("CPU per solve", format("mean %.2f s", c.mean) + format(" (%.2f", c.min) +
                            format("-%.2f s)", c.max));
  if (dc.empty()) {
    line("drape coefficient, folds", "not measured: no support under the cloth");
    return;
  }
  const Spread d = spread_of(dc), f = spread_of(folds);
  line("drape coefficient", runs.size() == 1 ? format("%.3f", d.mean)
                                             : format("%.3f", d.mean) + format(" +- %.3f", d.sd) +
                                                   format(" (%.3f", d.min) + format("-%.3f)", d.max));
  line("folds", runs.size() == 1 ? format("%.0f", f.mean)
                                 : format("%.2f", f.mean) + format(" +- %.2f", f.sd) +
                                       format(" (%.0f", f.min) + format("-%.0f)", f.max));
  line("self-intersections (seed 1)", std::to_string(runs.front().self_intersections));
}

}  // namespace

int run_measure_static(const MeasureOptions& options) {
  Scene scene = load_scene_with(options.scene, options.overrides);
  apply_threads(scene, options.threads);
  const fs::path dir = options.out.value_or(fs::path("out") / scene.name);
  refuse_overwriting_inputs(dir, {{"static.csv", "measure.txt", "outline.csv"}, {}},
                            scene_files(scene));
  std::string csv = "seed,converged,iterations,factorizations,residual,cpu_s,drape_coefficient,"
                    "folds,self_intersections\n";
  std::vector<RestMeasurement> runs;
  Progress progress(stderr, options.seeds, "seed");
  const unsigned first = scene.sim.statics.seed;
  std::optional<OutputFolderLock> lock;  // from the first seed's result on
  for (int k = 0; k < options.seeds; ++k) {
    const unsigned seed = first + static_cast<unsigned>(k);
    const RestShape rest = solve_rest_shape(scene, seed);  // bad input throws before any write
    runs.push_back(measure_rest_shape(scene, rest, seed));
    if (k == 0) {
      start_output(lock, dir, {}, {{"measure.txt", run_record(options.command_line,
                                                        {{"scene", scene.source}})}});
      if (runs.front().drape)
        write_outline(dir / "outline.csv", *runs.front().drape, analysis::DrapeMeasureSettings{}.folds);
    }
    csv += static_csv_row(runs.back());
    write_text(dir / "static.csv", csv);
    const RestMeasurement& m = runs.back();
    progress.update(k + 1, "seed " + std::to_string(seed) + ": " +
                               (m.solve.converged ? std::to_string(m.solve.iterations) + " iterations"
                                                  : "NOT converged: " + m.solve.stopped) +
                               (m.drape ? format(", DC %.3f", m.drape->drape_coefficient) + ", " +
                                              std::to_string(m.drape->folds) + " folds"
                                        : std::string()));
  }
  progress.finish();
  print_static_table(scene, runs);
  std::printf("weft: wrote static.csv%s to %s (%s)\n", runs.front().drape ? " and outline.csv" : "",
              dir.c_str(), format_duration(progress.elapsed_s()).c_str());
  for (const RestMeasurement& m : runs)
    if (!m.solve.converged) return exit_failure;
  return exit_ok;
}

}  // namespace weft::app
