#pragma once
// The fit-spec file of `weft fit` (docs/photos.md, "Fitting a material"): the
// scene to fit, the material parameters to estimate, the target and how to settle, optimise
// and profile. Strict like a scene file: every key read through app/scene/json_reader.h, an unknown
// key or a bad value is a InputError naming the file and key path.
//
//   {"description": "…", "scene": "strip.json",           (relative to the fit file)
//    "set": {"render.size": [548, 323]},                  (optional scene patches)
//    "parameters": [{"name": "bend", "start": "0.05 N*m", "min": "0.005 N*m", "max": "1 N*m"}],
//    "target": {"measured": {"overhang": "20 cm", "drop": "9 cm"}}
//            | {"point_cloud": {"file": "cloud.npy"}}
//            | {"photo": {"image": "p.png", "mask": "m.png", "metric": "chamfer", "mm_per_px": 0.11}}
//            | {"drape_photos": {"images": ["a.png", "b.png"], "mm_per_px": 0.5, "specimen": "30 cm",
//                                "support": "18 cm"}}       (app/fit/drape_photos_target.h)
//    "settle": {…}, "optimizer": {…}, "profile": {…}}

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "base/enum_names.h"
#include "app/fit/chamfer_3d.h"
#include "app/fit/drape_photos_target.h"
#include "app/scene/scene.h"
#include "app/scene/scene_patch.h"
#include "app/scene/units.h"
#include "render/image.h"
#include "render/photo_compare/photo_compare.h"

namespace weft::app {

// A material parameter the fit estimates, in SI units. The optimiser works on log10 of it.
struct FitParameter {
  std::string name;               // "bend", "bend_warp", "bend_weft", "shear", "density", "friction"
  std::vector<std::string> keys;  // the scene keys it sets ("bend": bend_warp and bend_weft)
  std::string unit;               // its SI unit, for tables: "N*m", "N/m", "kg/m^2", ""
  double start = 0.0, min = 0.0, max = 0.0;  // 0 < min ≤ start ≤ max
};

// The names fit parameters may have, in the order errors list them.
const std::vector<std::string>& fit_parameter_names();

// Numbers measured on the settled cloth, each optional (at least one given). The objective is
// Σ ((simulated − target) / target)² over those given.
struct MeasuredTarget {
  // A cantilever: clamp = the mean of the pinned vertices, tip = the mean of the grid edge
  // farthest from it (at rest); overhang = the horizontal distance from clamp to tip, drop = how
  // far the tip is below the clamp (along gravity), m.
  std::optional<double> overhang_m, drop_m;
  // A drape over a support (analysis/measure/drape_measure.h, as `weft measure` measures it).
  std::optional<double> drape_coefficient;
  // A real number ≥ 1: the mean node count of several specimens, e.g. 7.5.
  std::optional<double> folds;
};

// A point cloud in the scene's frame, metres (.npy, N×3; app/io/npy_file.h). Objective: the
// symmetric mean Chamfer distance between the cloth's vertices and the points, mm.
struct PointCloudTarget {
  std::filesystem::path file;
  Points points;
};

enum class PhotoMetric { chamfer, iou };
inline constexpr base::EnumNames<PhotoMetric, 2> photo_metric_names{
    {{PhotoMetric::chamfer, "chamfer"}, {PhotoMetric::iou, "iou"}}};

// A photo seen through the scene's camera (render.camera and render.size, which must match the
// photo's size): its silhouette (the mask if given, else render/photo_compare's segmentation)
// against the settled cloth's. Objective: the outline Chamfer distance, px, or 1 − IoU.
struct PhotoTarget {
  std::filesystem::path image_path;
  std::optional<std::filesystem::path> mask_path;
  render::Image photo;
  render::Mask mask;
  PhotoMetric metric = PhotoMetric::chamfer;
  std::optional<double> mm_per_px;  // the photo's scale, for distances in mm
};

using FitTarget = std::variant<MeasuredTarget, PointCloudTarget, PhotoTarget, DrapePhotosTarget>;

// The settle to rest of each evaluation. static (the default): the static equilibrium solver
// (app/run/rest_shape.h) with the scene's simulation.static settings — each evaluation a
// deterministic function of the parameters. dynamic_relaxation (the scene's integrator is
// replaced) until ‖R‖/‖Mg‖ ≤ tolerance, or no vertex moved more than still_m over the last
// check_every iterations (a drape on a support keeps a residual: its contact forces are not
// part of R), or max_iterations: for scenes a static solve cannot take (constraints, air).
enum class SettleMethod { static_solve, dynamic_relaxation };
inline constexpr base::EnumNames<SettleMethod, 2> settle_method_names{
    {{SettleMethod::static_solve, "static"}, {SettleMethod::dynamic_relaxation, "dynamic_relaxation"}}};

struct SettleSettings {
  SettleMethod method = SettleMethod::static_solve;
  // static: each evaluation solved from this many imperfection seeds (simulation.static.seed
  // and the next ones), its objective and measures their means.
  int seeds = 1;
  double tolerance = 1e-4;
  double still_m = 1e-7;
  long check_every = 100;
  long max_iterations = 200000;
};

enum class FitMethod { bobyqa, nelder_mead };
inline constexpr base::EnumNames<FitMethod, 2> fit_method_names{
    {{FitMethod::bobyqa, "bobyqa"}, {FitMethod::nelder_mead, "nelder_mead"}}};

struct OptimizerSettings {
  FitMethod method = FitMethod::bobyqa;
  int max_evaluations = 60;
  double initial_step = 0.1;   // log10 units: a first step of ×1.26
  double x_tolerance = 1e-3;   // log10 units: stop when a step changes every parameter < 0.23 %
};

// The objective profile along each parameter around the optimum: `points` values on each side,
// out to ×/÷ (1 + span); the sensitivity band is where the objective stays ≤ optimum + band.
struct ProfileSettings {
  int points = 3;
  double span = 0.2;
  std::optional<double> band;  // objective units; default per target (docs/photos.md)
};

struct FitSpec {
  std::string source;       // the fit file as given
  std::string name;         // its stem: the output folder out/<name>
  std::string description;
  Scene base;               // the scene with "set" applied
  std::vector<Setting> set; // the "set" patches, kept for the fitted scene file
  std::vector<FitParameter> parameters;
  FitTarget target;
  SettleSettings settle;
  OptimizerSettings optimizer;
  ProfileSettings profile;
  // --threads (not in the file): applied to every evaluation's scene and to the renderer's.
  std::optional<int> threads;
};

// The default sensitivity band of a target: measured 1e-4 (a 1 % rms misfit), point cloud
// 0.5 mm, photo Chamfer 0.5 px, photo 1 − IoU 0.01, drape photos 1 (one unit of one part).
double default_band(const FitTarget& target);
// "outline Chamfer [px]", "1 − IoU", "3D Chamfer [mm]", "Σ relative misfit²",
// "drape photos misfit".
std::string objective_label(const FitTarget& target);

// A file named in the fit file `fit_file`: relative to the fit file's folder unless absolute.
std::filesystem::path fit_file_path(const std::string& fit_file, const std::string& file);

FitSpec parse_fit_spec(const std::string& text, const std::string& source);
FitSpec load_fit_spec(const std::filesystem::path& path);

}  // namespace weft::app
