// weft measure: simulate a scene frame by frame as `weft run` does, without rendering, and
// measure its settle time and drape (analysis/measure/); docs/measure.md.

#include "app/cli/measure_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "app/io/input_guard.h"
#include "app/scene/scene_inputs.h"
#include "app/run/drape_photo.h"
#include "app/run/frame_stream.h"
#include "app/scene/json_reader.h"
#include "app/io/output_files.h"
#include "app/io/progress.h"
#include "app/scene/units.h"
#include "app/io/version.h"
#include "base/format.h"
#include "sim/collision/self_intersection.h"
#include "analysis/measure/settle.h"

namespace weft::app {

namespace {

namespace fs = std::filesystem;

using base::format;

// measure.csv, rewritten whole (app/io/output_files.h) with each simulated frame's row.
class MeasureCsv {
 public:
  explicit MeasureCsv(const fs::path& path)
      : m_path(path), m_text("frame,time_s,kinetic_energy_J,max_speed_m_s,drape_coefficient,folds\n") {}
  void add(const MeasureRow& r) {
    std::ostringstream row;
    row.precision(9);
    row << r.frame << ',' << r.time_s << ',' << r.kinetic_energy_J << ',' << r.max_speed_m_s
        << ',';
    if (r.drape_coefficient) row << *r.drape_coefficient;
    row << ',';
    if (r.folds) row << *r.folds;
    m_text += row.str() + '\n';
  }
  void save() const { write_text(m_path, m_text); }

 private:
  fs::path m_path;
  std::string m_text;  // the header and every row so far
};

// The table on stdout: one "name  value" line per measurement.
void print_table(const Scene& scene, const SceneMeasurement& m) {
  const MeasureRow& last = m.rows.back();
  std::vector<std::pair<std::string, std::string>> lines;
  const std::string threshold = format("%.3g cm/s", 100.0 * m.settle_threshold_m_s);
  lines.emplace_back("settle time (max speed < " + threshold + ")",
                     m.settle_time_s ? format("%.2f s", *m.settle_time_s)
                                     : format("not settled by t = %.2f s", last.time_s));
  if (m.final_drape) {
    const analysis::DrapeShape& d = *m.final_drape;
    lines.emplace_back("drape coefficient", format("%.3f", d.drape_coefficient));
    lines.emplace_back("folds", std::to_string(d.folds));
    lines.emplace_back("shadow area", format("%.1f cm^2", 1e4 * d.shadow_m2) +
                                          format(" (raster cell %.2g mm)", 1e3 * d.cell_m));
    lines.emplace_back("support", support_name(*m.support) +
                                      format(", %.1f cm^2", 1e4 * m.support->area_m2) +
                                      format(" at (%.3g", m.support->axis_m.x()) +
                                      format(", %.3g) m", m.support->axis_m.y()));
    lines.emplace_back("specimen area", format("%.1f cm^2", 1e4 * m.specimen_m2));
  } else {
    lines.emplace_back("drape coefficient, folds", "not measured: no support under the cloth");
  }
  if (m.curtain)
    lines.emplace_back("curtain folds (bulges down the centre)",
                       std::to_string(m.curtain->folds) +
                           format(" (hysteresis %.3g mm)", 1e3 * m.curtain->min_prominence_m));
  lines.emplace_back("max speed at the end", format("%.3g mm/s", 1e3 * last.max_speed_m_s));
  lines.emplace_back("self-intersections at the end", std::to_string(m.self_intersections));
  std::size_t width = 0;
  for (const auto& [name, value] : lines) width = std::max(width, name.size());
  std::printf("weft: %s at t = %.2f s (%d frames)\n", scene.source.c_str(), last.time_s,
              last.frame);
  for (const auto& [name, value] : lines)
    std::printf("  %s%s  %s\n", name.c_str(), std::string(width - name.size(), ' ').c_str(),
                value.c_str());
}

}  // namespace

int run_measure(const MeasureOptions& options) {
  Scene scene = load_scene_with(options.scene, options.overrides);
  apply_threads(scene, options.threads);
  if (options.until_settled_max_s) {
    scene.frames = static_cast<int>(std::ceil(*options.until_settled_max_s * scene.fps - 1e-9));
    // Shorter than a frame used to simulate nothing and report "settle time 0.00 s".
    if (scene.frames < 1)
      throw InputError("--until-settled: " + format("%g", *options.until_settled_max_s) +
                       " s is shorter than one frame of the scene (1/" + format("%g", scene.fps) +
                       " s); nothing would be simulated");
  }
  // Everything that can reject the input happens before the output folder is touched.
  const std::unique_ptr<sim::Simulator> simulator = make_simulator(scene);
  const std::optional<analysis::DrapeSupport> support =
      scene_support(scene, simulator->mesh(), options.require_drape);

  // The output folder is touched when the first frame is measured (start_output).
  const fs::path dir = options.out.value_or(fs::path("out") / scene.name);
  refuse_overwriting_inputs(dir, {{"measure.csv", "measure.txt", "outline.csv"}, {}},
                            scene_files(scene));
  MeasureCsv csv(dir / "measure.csv");
  std::fprintf(stderr,
               "weft: measuring %s — %d frames at %g fps, %s, time step %.3g ms, %s\n",
               scene.source.c_str(), scene.frames, scene.fps, cloth_size_text(scene).c_str(),
               1e3 * simulator->time_step(),
               support ? ("drape over " + support_name(*support)).c_str()
                       : "no support under the cloth: settle time only");
  Progress progress(stderr, scene.frames, "frame");
  SceneMeasurement m;
  int measured = 0;  // the last frame in measure.csv
  std::optional<OutputFolderLock> lock;  // from the first frame on
  try {
    m = measure_scene(scene, *simulator, options.require_drape, [&](const MeasureRow& row) {
      csv.add(row);
      if (row.frame == 0) return;
      if (row.frame == 1)
        start_output(lock, dir, {}, {{"measure.txt", run_record(options.command_line,
                                                          {{"scene", scene.source}})}});
      csv.save();
      measured = row.frame;
      std::string detail = format("t = %.2f s", row.time_s) +
                           format(", max speed %.3g m/s", row.max_speed_m_s);
      if (row.drape_coefficient)
        detail += format(", DC %.3f", *row.drape_coefficient) + ", " +
                  std::to_string(*row.folds) + " folds";
      progress.update(row.frame, detail);
    }, options.until_settled_max_s.has_value());
  } catch (const sim::DivergenceError& e) {
    progress.finish();
    std::fprintf(stderr, "weft: error: %s\n", e.what());
    if (measured > 0)
      std::fprintf(stderr, "weft: measure.csv up to the last finished frame is in %s\n",
                   dir.c_str());
    else
      std::fprintf(stderr, "weft: no frame was finished; %s is as it was\n", dir.c_str());
    return exit_diverged;
  }
  progress.finish();
  if (m.final_drape) {
    write_outline(dir / "outline.csv", *m.final_drape, analysis::DrapeMeasureSettings{}.folds);
  }
  print_table(scene, m);
  std::printf("weft: wrote measure.csv%s to %s (%s)\n", m.final_drape ? " and outline.csv" : "",
              dir.c_str(), format_duration(progress.elapsed_s()).c_str());
  return exit_ok;
}

namespace {

// --photo and its setup (app/run/drape_photo.h); none of the scene options apply to a photo.
void add_photo_options(CLI::App& cmd, MeasurePhotoOptions& p, std::string& center) {
  CLI::Option* photo = cmd.add_option(
      "--photo", p.photo,
      "Top-view photo or silhouette of a Cusick drape to measure instead of a scene "
      "(docs/measure.md); needs --disc-mm, --specimen-mm and --mm-per-px or --disc-px");
  for (const char* name :
       {"scene", "--set", "--frames", "--threads", "--drape", "--until-settled", "--static"})
    photo->excludes(cmd.get_option(name));
  const auto needs_photo = [&](CLI::Option* o) { o->needs(photo); };
  needs_photo(cmd.add_option("--mask-photo", p.mask,
                             "Mask of the photo (white = cloth) instead of segmenting it"));
  const Range positive = Range::gt(0.0).le(1e5);  // mm or pixels
  needs_photo(check_range(
      cmd.add_option("--mm-per-px", p.setup.mm_per_px, "Photo scale, mm per pixel"), positive));
  needs_photo(check_range(cmd.add_option("--disc-px", p.setup.disc_px,
                                         "Support disc's diameter in the photo, pixels (sets the "
                                         "scale)"),
                          positive));
  needs_photo(check_range(
      cmd.add_option("--disc-mm", p.setup.disc_mm, "Support disc's diameter, mm"), positive));
  needs_photo(check_range(cmd.add_option("--specimen-mm", p.setup.specimen_mm,
                                         "Flat circular specimen's diameter, mm"),
                          positive));
  needs_photo(cmd.add_option("--center-px", center,
                             "Disc centre in the photo, X,Y pixels (default: the silhouette's "
                             "centroid)"));
}

// --until-settled's MAX: a time in (0, 600] s; a bare number is seconds.
double until_settled_limit(const std::string& text) {
  double t = 0.0;
  try {
    t = text.empty() ? 30.0 : parse_quantity(text.find_first_not_of("0123456789.eE+-") ==
                                                     std::string::npos
                                                 ? text + " s"
                                                 : text,
                                             Quantity::time);
  } catch (const UnitError& e) {
    throw InputError("--until-settled: " + std::string(e.what()));
  }
  if (!(t > 0.0 && t <= 600.0))
    throw InputError("--until-settled: expected a time in (0, 600] s, got '" + text + "'");
  return t;
}

std::optional<sim::Vec2> parse_center(const std::string& text) {
  if (text.empty()) return std::nullopt;
  double x = 0.0, y = 0.0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf%c", &x, &y, &tail) != 2 || !std::isfinite(x) ||
      !std::isfinite(y))
    throw InputError("--center-px: expected X,Y in pixels (e.g. 412.5,300), got '" + text + "'");
  return sim::Vec2(x, y);
}

}  // namespace

Command register_measure(CLI::App& app, const std::string& command_line) {
  const auto o = std::make_shared<MeasureOptions>();
  const auto p = std::make_shared<MeasurePhotoOptions>();
  const auto center = std::make_shared<std::string>();
  o->command_line = command_line;
  p->command_line = command_line;
  CLI::App* cmd = app.add_subcommand(
      "measure", "Simulate a scene without rendering, or read a top-view photo of a drape "
                 "(--photo); print settle time, drape coefficient and folds; write measure.csv "
                 "and outline.csv (docs/measure.md)");
  cmd->add_option("scene", o->scene, "Scene file; the built-in default scene if omitted");
  cmd->add_option("--out", o->out, "Output folder (default: out/<scene or photo name>)");
  add_set_option(*cmd, o->overrides);
  add_override_option(*cmd, "--frames", "output.frames", o->overrides,
                      "Frames to simulate (overrides output.frames)", "INT");
  add_threads_option(*cmd, o->threads);
  cmd->add_option_function<std::string>(
         "--until-settled",
         [o](const std::string& text) {
           o->until_settled_max_s = until_settled_limit(text);
         },
         "Simulate until the max speed has stayed below 1 cm/s for 1 s, at most MAX of simulated "
         "time (default 30 s; a time such as '20 s'), instead of output.frames")
      ->expected(0, 1)
      ->default_str("30 s")
      ->excludes(cmd->get_option("--frames"));
  cmd->add_flag("--drape", o->require_drape,
                "Require the drape measures: an error if no obstacle supports the cloth centre");
  CLI::Option* statics =
      cmd->add_flag("--static", o->static_solve,
                    "Solve the rest shape by the static equilibrium solver instead of "
                    "simulating the motion (docs/measure.md, \"Static solves\")")
          ->excludes(cmd->get_option("--until-settled"))
          ->excludes(cmd->get_option("--frames"));
  check_range(cmd->add_option("--seeds", o->seeds,
                              "With --static: solve from this many imperfection seeds (1..N) "
                              "and report the spread of DC and folds (default 1)"),
              Range::closed(1, 1000))
      ->needs(statics);
  add_photo_options(*cmd, *p, *center);
  return {cmd, [o, p, center, cmd] {
            if (cmd->count("--photo") == 0)
              return o->static_solve ? run_measure_static(*o) : run_measure(*o);
            p->out = o->out;
            p->setup.center_px = parse_center(*center);
            return run_measure_photo(*p);
          }};
}

}  // namespace weft::app
