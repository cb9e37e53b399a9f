#pragma once
// What `weft fit` writes into its output folder (docs/photos.md):
//   fit.csv            one row per evaluation: phase, parameter values, objective, measures,
//                      settle iterations and residual, seconds
//   fit_result.json    the fitted values with their sensitivity bands, the objective and measures
//   fitted_scene.json  the scene with the fitted values (run it with `weft run`)
//   convergence.png    the objective per evaluation and the best so far
//   profile.png        the objective along each parameter around the optimum, with the band
//   photo.png, fitted_render.png, overlay.png, comparison.png   photo targets: the photo, the fitted cloth
//                      through the scene's camera, both silhouettes' outlines on the photo, and
//                      the three side by side with the numbers
//   drape_photos.png, outline_spectra.png   drape_photos targets (app/fit/drape_photos_report.h)
//   report.html        all of it on one page

#include <filesystem>
#include <fstream>
#include <string>

#include "app/fit/drape_photos_report.h"
#include "app/fit/fit_optimizer.h"
#include "base/atomic_file.h"

namespace weft::app {

// Appends one evaluation per row to fit.csv, flushed after each row (a fit stopped early keeps
// its log).
class FitLog {
 public:
  FitLog(const std::filesystem::path& path, const FitSpec& spec);
  void write(const Evaluation& e, int number, FitPhase phase);

 private:
  base::ExclusiveFile m_file;  // created anew: a link planted at fit.csv is not followed
};

// "bend=0.1234 N*m" for each parameter.
std::string describe_values(const FitSpec& spec, const std::vector<double>& values);
// "drape_coefficient 0.4586 folds 8 …": an evaluation's measures, 4 digits each.
std::string describe_measures(const Evaluation& e);

struct FitOutputs {
  std::filesystem::path report;                 // report.html
  std::optional<FittedDrapeCheck> drape_check;  // drape_photos targets: the fitted drape against
                                                // every image (none if every evaluation diverged)
};

// Writes everything after fit.csv into `dir` (see above).
FitOutputs write_fit_outputs(const std::filesystem::path& dir, FitProblem& problem,
                             const FitResult& result, const std::string& command_line);

}  // namespace weft::app
