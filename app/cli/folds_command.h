#pragma once
// `weft folds`: the tension-field folds of a suspended cloth (seed 001, sim/folds/): prints Q,
// n, z_max, the amplitudes a_i, L′ and whether L′ met the tolerance, as text or JSON; renders
// the folded membrane; draws the predicted wrinkle lines on a photo. docs/folds.md.

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "sim/folds/fold_geometry.h"
#include "sim/folds/tension_field.h"
#include "sim/grid.h"

namespace weft::app {

struct FoldsOptions {
  sim::TensionFieldInputs inputs;              // SI units (the flags are converted by main)
  bool json = false;                           // --json: one JSON object on stdout
  std::optional<std::filesystem::path> out;    // --out DIR: render DIR/folds.png
  std::optional<std::filesystem::path> overlay;  // --overlay PHOTO
  std::optional<std::string> supports;         // --supports x1,y1,x2,y2 (pixels)
  std::optional<double> bottom_px;             // --bottom y
  std::optional<std::string> size;             // --size WxH of folds.png (default 640x480)
  sim::MembraneShape shape = sim::MembraneShape::rectangle;
  sim::FoldInterpolation interpolation = sim::FoldInterpolation::cosine;
  std::string command_line;
};

// The command-line flags of an input quantity: "t" → "--t/--t-mm", … (TensionFieldInputError::field).
std::string folds_flag(const std::string& field);

// The result as JSON: the inputs (SI), span_m, Q, Q_given, critical_stress_Pa, n, z_max_m,
// amplitudes_m, boundary_length_m, relative_error, status, converged, message.
nlohmann::json folds_json(const sim::TensionFieldInputs& inputs,
                          const sim::TensionFieldResult& result);

// The folded membrane on a grid of about 1 cm cells (at least 2×2 vertices), placed with its
// supports' midpoint at top_center_m: world #V×3 positions and the grid they belong to.
struct FoldedMembrane {
  sim::ClothMesh mesh;
  sim::Matrix3X x;
};
FoldedMembrane folded_membrane(const sim::FoldPattern& pattern, sim::MembraneShape shape,
                               const sim::Vec3& top_center_m);

// Runs the job; bad input throws InputError (naming the flag) before anything is written. The
// overlay goes to DIR/folds_overlay.png, DIR from --out or out/folds.
int run_folds(const FoldsOptions& options);


// Adds `weft folds` to the command line.
Command register_folds(CLI::App& app, const std::string& command_line);

}  // namespace weft::app
