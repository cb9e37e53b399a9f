// weft fit (see fit_command.h).

#include "app/cli/fit_command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <variant>
#include <vector>

#include "app/fit/fit_report.h"
#include "app/io/input_guard.h"
#include "app/io/output_lock.h"
#include "app/scene/scene_inputs.h"
#include "app/scene/json_reader.h"
#include "app/io/progress.h"
#include "app/cli/options.h"

namespace weft::app {

namespace fs = std::filesystem;

namespace {

// The files a fit reads: the fit file, its scene's files, a point cloud or a photo and its mask
// (drape photos are read by name from their own folder).
std::vector<fs::path> fit_inputs(const FitSpec& spec, const fs::path& fit_file) {
  std::vector<fs::path> inputs = scene_files(spec.base);
  inputs.push_back(fit_file);
  if (const auto* cloud = std::get_if<PointCloudTarget>(&spec.target)) inputs.push_back(cloud->file);
  if (const auto* photo = std::get_if<PhotoTarget>(&spec.target)) {
    inputs.push_back(photo->image_path);
    if (photo->mask_path) inputs.push_back(*photo->mask_path);
  }
  return inputs;
}

// What weft fit writes into its folder (app/fit/fit_report.h, drape_photos_report.h).
const OutputNames fit_outputs = {
    {"fit.csv", "report.html", "fit_result.json", "fitted_scene.json", "fit.txt",
     "convergence.png", "profile.png", "photo.png", "fitted_render.png", "overlay.png",
     "comparison.png", "drape_photos.png", "outline_spectra.png"},
    {}};

}  // namespace

int run_fit_command(const FitOptions& options) {
  FitSpec spec = load_fit_spec(options.spec);
  if (options.max_evaluations) spec.optimizer.max_evaluations = *options.max_evaluations;
  if (options.profile_points) spec.profile.points = *options.profile_points;
  spec.threads = options.threads;
  apply_threads(spec.base, options.threads);  // the renderer is made from the base scene's
  FitProblem problem(spec);
  problem.scene_at(std::vector<double>(spec.parameters.size(), 1.0));  // rejects a bad key early
  std::vector<double> start;
  for (const FitParameter& p : spec.parameters) start.push_back(p.start);
  problem.scene_at(start);

  const fs::path dir = options.out.value_or(fs::path("out") / spec.name);
  refuse_overwriting_inputs(dir, fit_outputs, fit_inputs(spec, options.spec));
  const OutputFolderLock lock(dir);  // creates the folder
  FitLog log(dir / "fit.csv", spec);
  std::fprintf(stderr, "weft: fitting %s to %s (%s) — %zu parameter(s), up to %d evaluations\n",
               spec.base.source.c_str(), spec.source.c_str(), objective_label(spec.target).c_str(),
               spec.parameters.size(), spec.optimizer.max_evaluations);
  const auto on_evaluation = [&](const Evaluation& e, int number, FitPhase phase) {
    log.write(e, number, phase);
    const std::string measures = e.measures.empty() ? "" : " " + describe_measures(e);
    std::fprintf(stderr, "fit %s %3d  %s  objective %.6g%s  (%s, %ld iterations%s)%s\n",
                 phase == FitPhase::optimise ? "eval" : "prof", number,
                 describe_values(spec, e.values).c_str(), e.objective, measures.c_str(),
                 format_duration(e.seconds).c_str(), e.iterations, e.settled ? "" : ", NOT settled",
                 e.failure.empty() ? "" : (" diverged: " + e.failure).c_str());
  };
  const FitResult result = run_fit(problem, on_evaluation);
  // A target no evaluation could be compared with (a point cloud at 1e300 m), or a scene that
  // diverged at every evaluation, used to end with exit 0, reporting the start as the fit.
  if (!result.best.failure.empty())
    throw InputError(spec.source + ": target: none of the " +
                     std::to_string(result.evaluations.size()) +
                     " evaluations gave a finite objective (the best: " + result.best.failure +
                     "; is the target in the scene's units and frame?); nothing was fitted "
                     "(fit.csv lists them)");
  const FitOutputs outputs = write_fit_outputs(dir, problem, result, options.command_line);

  std::printf("weft: fit %s: %s after %zu evaluations (%s)\n", spec.name.c_str(),
              describe_values(spec, result.best.values).c_str(), result.evaluations.size(),
              result.stop_reason.c_str());
  for (std::size_t i = 0; i < result.profiles.size(); ++i) {
    const FittedParameter& f = result.fitted[i];
    std::printf("  %s band %s%.4g … %s%.4g %s (objective ≤ optimum + %.3g)\n",
                spec.parameters[i].name.c_str(), f.low_open ? "≤ " : "", f.band_low,
                f.high_open ? "≥ " : "", f.band_high, spec.parameters[i].unit.c_str(), result.band);
  }
  std::printf("  objective (%s) %.6g", objective_label(spec.target).c_str(), result.best.objective);
  for (const auto& [name, value] : result.best.measures) std::printf(", %s %.4g", name.c_str(), value);
  std::printf("\n");
  if (outputs.drape_check)
    for (const DrapePhotoComparison& c : outputs.drape_check->images)
      std::printf("  %s\n", describe_comparison(c, outputs.drape_check->fitted).c_str());
  std::printf("weft: wrote %s\n", outputs.report.c_str());
  return exit_ok;
}

Command register_fit(CLI::App& app, const std::string& command_line) {
  const auto o = std::make_shared<FitOptions>();
  o->command_line = command_line;
  CLI::App* cmd = app.add_subcommand(
      "fit", "Fit material parameters so that the settled cloth matches measured numbers, a "
             "point cloud or a photo (NLopt); write fit.csv, plots, fitted_scene.json and "
             "report.html (docs/photos.md)");
  cmd->add_option("fit", o->spec, "Fit file (JSON: scene, parameters, target)")->required();
  cmd->add_option("--out", o->out, "Output folder (default: out/<fit file name>)");
  check_range(cmd->add_option("--max-evaluations", o->max_evaluations,
                              "Overrides optimizer.max_evaluations"),
              Range::closed(1, 1e6));
  check_range(cmd->add_option("--profile-points", o->profile_points,
                              "Overrides profile.points (0: no profile)"),
              Range::closed(0, 1000));
  add_threads_option(*cmd, o->threads);
  return {cmd, [o] { return run_fit_command(*o); }};
}

}  // namespace weft::app
