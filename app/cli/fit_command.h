#pragma once
// `weft fit FIT.json`: estimate the material parameters a fit file names so that the settled
// simulation matches its target — measured numbers, a point cloud or a photo
// (app/fit/fit_spec.h for the file, docs/photos.md "Fitting a material: weft fit").

#include <filesystem>
#include <optional>
#include <string>

#include "app/cli/command.h"

namespace weft::app {

struct FitOptions {
  std::filesystem::path spec;                // the fit file
  std::optional<std::filesystem::path> out;  // default: out/<fit file stem>
  std::optional<int> max_evaluations;        // overrides optimizer.max_evaluations
  std::optional<int> profile_points;         // overrides profile.points (0: no profile)
  std::optional<int> threads;                // --threads (command.h)
  std::string command_line;
};

// Runs the fit and writes its outputs (app/fit/fit_report.h); bad input throws InputError before
// anything is written.
int run_fit_command(const FitOptions& options);

Command register_fit(CLI::App& app, const std::string& command_line);

}  // namespace weft::app
