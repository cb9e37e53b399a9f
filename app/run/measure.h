#pragma once
// A simulated drape measured frame by frame — the settle time, the drape coefficient, the
// outline r(θ) and the fold count (analysis/measure/, docs/measure.md) — for `weft measure`,
// `weft run`'s last line and `weft fit`.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/scene/scene.h"
#include "analysis/measure/curtain_folds.h"
#include "analysis/measure/drape_measure.h"
#include "analysis/measure/settle.h"
#include "sim/simulator.h"

namespace weft::app {

// One row of measure.csv: the state at the end of a frame (frame 0: the start).
struct MeasureRow {
  int frame = 0;
  double time_s = 0.0;
  double kinetic_energy_J = 0.0;
  double max_speed_m_s = 0.0;
  std::optional<double> drape_coefficient;  // with a support only
  std::optional<int> folds;
};

struct SceneMeasurement {
  std::optional<analysis::DrapeSupport> support;  // none: a hang, only the settle time is measured
  double specimen_m2 = 0.0;                  // the cloth's rest area
  std::vector<MeasureRow> rows;              // frames 0..N
  double settle_threshold_m_s = analysis::settle_speed_threshold_m_s;
  std::optional<double> settle_time_s;       // none: still moving at the end
  std::optional<analysis::DrapeShape> final_drape;  // at the last frame, with a support
  int self_intersections = 0;                // edge–triangle crossings at the last frame
  std::optional<analysis::CurtainFolds> curtain;   // at the last frame, for a curtain (hangs_as_curtain)
};

// Whether the cloth hangs as a curtain: weft along gravity (its top edge at v = 0) and both
// top corners pinned — the folds are then counted down its centre column (analysis/measure/curtain_folds.h).
bool hangs_as_curtain(const Scene& scene);

// The cloth centre a support is looked for under: the mean start position of the used vertices
// (ClothMesh::start(): a grid's rest positions; a mesh cloth's placement, not its flat pattern).
sim::Vec3 cloth_center_m(const sim::ClothMesh& mesh);

// The scene's drape support (analysis::find_support under cloth_center_m), or none. With
// require_drape, none is a InputError naming the scene file; so is a specimen no larger than
// its support.
std::optional<analysis::DrapeSupport> scene_support(const Scene& scene, const sim::ClothMesh& mesh,
                                               bool require_drape);

// How long the max speed must have stayed below the settle threshold for --until-settled to
// stop: 1 s of simulated time (a slow swing crosses 1 cm/s at its turning points, briefly).
inline constexpr double settled_hold_s = 1.0;

// Whether the rows' max speed has stayed below `threshold` for the last `hold_s` seconds.
bool settled_for(const std::vector<MeasureRow>& rows, double threshold, double hold_s);

// Simulates every frame of the scene on `simulator` (made by make_simulator(scene)) through the
// frame stream (frame_stream.h) and measures it; on_frame, if given, sees each row as it is
// made. With stop_when_settled the stream ends at the first frame where settled_for(rows,
// threshold, settled_hold_s). Throws sim::DivergenceError (the rows so far are lost; on_frame
// has seen them), InputError as scene_support.
SceneMeasurement measure_scene(const Scene& scene, sim::Simulator& simulator, bool require_drape,
                               const std::function<void(const MeasureRow&)>& on_frame = {},
                               bool stop_when_settled = false);

// "drape coefficient 0.62, 9 folds over the cylinder obstacles[0]" for the simulator's current
// positions, or none when the scene has no support. For `weft run`'s last line.
std::optional<std::string> drape_summary(const Scene& scene, const sim::Simulator& simulator);

// Writes outline.csv: theta_deg, radius_m and smoothed_radius_m (smoothed as `folds` says),
// one row per bin of drape.radii_m.
void write_outline(const std::filesystem::path& path, const analysis::DrapeShape& drape,
                   const analysis::FoldCountSettings& folds);

// "the cylinder obstacles[0]": the support as the scene names it.
std::string support_name(const analysis::DrapeSupport& support);

}  // namespace weft::app
