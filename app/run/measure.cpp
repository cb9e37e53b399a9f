// Measuring a simulated drape frame by frame (analysis/measure/): what `weft measure`, `weft
// run`'s last line and `weft fit` share.

#include "app/run/measure.h"

#include <cmath>
#include <sstream>

#include "app/io/output_files.h"
#include "app/run/frame_stream.h"
#include "base/format.h"
#include "sim/collision/self_intersection.h"
#include "analysis/measure/settle.h"

namespace weft::app {

namespace fs = std::filesystem;
using base::format;

std::string support_name(const analysis::DrapeSupport& s) {
  return "the " + s.kind + " obstacles[" + std::to_string(s.obstacle) + "]";
}

void write_outline(const fs::path& path, const analysis::DrapeShape& drape,
                   const analysis::FoldCountSettings& folds) {
  std::ostringstream out;
  out << "theta_deg,radius_m,smoothed_radius_m\n";
  const std::vector<double> smooth =
      analysis::circular_moving_average(drape.radii_m, folds.smoothing_bins);
  const int bins = static_cast<int>(drape.radii_m.size());
  out.precision(9);
  for (int k = 0; k < bins; ++k)
    out << 360.0 * (k + 0.5) / bins << ',' << drape.radii_m[static_cast<std::size_t>(k)] << ','
        << smooth[static_cast<std::size_t>(k)] << '\n';
  write_text(path, out.str());
}

sim::Vec3 cloth_center_m(const sim::ClothMesh& mesh) {
  sim::Vec3 sum = sim::Vec3::Zero();
  int used = 0;
  for (sim::Index v = 0; v < mesh.vertex_count(); ++v) {
    if (!mesh.is_used(v)) continue;
    sum += mesh.start().row(v).transpose();  // a mesh cloth's rest shape is its flat pattern
    ++used;
  }
  return used ? sim::Vec3(sum / used) : sum;
}

std::optional<analysis::DrapeSupport> scene_support(const Scene& scene, const sim::ClothMesh& mesh,
                                               bool require_drape) {
  const sim::Vec3 c = cloth_center_m(mesh);
  std::optional<analysis::DrapeSupport> support = analysis::find_support(scene.sim.obstacles, c);
  char where[96];
  std::snprintf(where, sizeof where, "(%.3g, %.3g, %.3g) m", c.x(), c.y(), c.z());
  if (!support && require_drape)
    throw InputError(scene.source + ": obstacles: --drape needs a support under the cloth centre " +
                     where + " to measure the drape coefficient and folds: a cylinder with a "
                     "vertical axis, a box or a sphere whose top is below it; found none");
  const double specimen_m2 = analysis::specimen_rest_area_m2(mesh);
  if (support && !(specimen_m2 > support->area_m2))
    throw InputError(scene.source + ": cloth: the specimen (" + format("%.4g", specimen_m2) +
                     " m^2) is no larger than its support, " + support_name(*support) + " (" +
                     format("%.4g", support->area_m2) + " m^2): no overhang to measure");
  return support;
}

bool settled_for(const std::vector<MeasureRow>& rows, double threshold, double hold_s) {
  if (rows.empty() || rows.back().max_speed_m_s >= threshold) return false;
  double below_since_s = rows.front().time_s;
  for (const MeasureRow& r : rows)
    if (r.max_speed_m_s >= threshold) below_since_s = r.time_s;
  return rows.back().time_s - below_since_s >= hold_s;
}

SceneMeasurement measure_scene(const Scene& scene, sim::Simulator& simulator, bool require_drape,
                               const std::function<void(const MeasureRow&)>& on_frame,
                               bool stop_when_settled) {
  SceneMeasurement m;
  const sim::ClothMesh& mesh = simulator.mesh();
  m.support = scene_support(scene, mesh, require_drape);
  m.specimen_m2 = analysis::specimen_rest_area_m2(mesh);
  const analysis::DrapeMeasureSettings settings;

  const auto record = [&](int frame, double time_s) {
    MeasureRow row;
    row.frame = frame;
    const sim::Diagnostics d = simulator.diagnostics();
    row.time_s = time_s;
    row.kinetic_energy_J = d.kinetic_energy_J;
    row.max_speed_m_s = d.max_speed_m_s;
    if (m.support) {
      // The frame's own triangles: with simulation.remesh the mesh changes between frames.
      m.final_drape =
          analysis::measure_drape(mesh, mesh.triangles(), simulator.state().x, *m.support, settings);
      row.drape_coefficient = m.final_drape->drape_coefficient;
      row.folds = m.final_drape->folds;
    }
    m.rows.push_back(row);
    if (on_frame) on_frame(row);
  };
  record(0, simulator.state().time_s);
  const FrameStreamEnd end = stream_frames(scene, simulator, [&](const Frame& frame) {
    record(frame.index, frame.time_s);
    return stop_when_settled && settled_for(m.rows, m.settle_threshold_m_s, settled_hold_s)
               ? StreamControl::stop
               : StreamControl::go_on;
  });
  if (end.divergence) throw end.divergence->error;
  if (hangs_as_curtain(scene)) m.curtain = analysis::count_curtain_folds(mesh, simulator.state().x);
  std::vector<double> time_s, speed_m_s;
  for (const MeasureRow& r : m.rows) {
    time_s.push_back(r.time_s);
    speed_m_s.push_back(r.max_speed_m_s);
  }
  m.settle_time_s = analysis::settle_time_s(time_s, speed_m_s, m.settle_threshold_m_s);
  const auto triangles = mesh.triangles();
  m.self_intersections = sim::count_edge_triangle_crossings(simulator.state().x, triangles,
                                                            sim::unique_edges(triangles));
  return m;
}

bool hangs_as_curtain(const Scene& scene) {
  const sim::Vec3 g = scene.sim.gravity_m_s2;
  if (!(g.norm() > 0.0) || scene.grid.weft_axis.normalized().dot(g.normalized()) < 1.0 - 1e-9)
    return false;
  if (scene.mesh && !scene.mesh->has_grid()) return false;  // its folds are counted on the grid
  const sim::ClothMesh mesh = cloth_mesh(scene);
  if (!mesh.has_grid()) return false;  // a disc with a smooth edge
  const std::vector<sim::Index> pinned = sim::resolve_pins(scene.pins, mesh);
  const auto is_pinned = [&](sim::Index v) {
    return std::binary_search(pinned.begin(), pinned.end(), v);
  };
  return is_pinned(mesh.index(0, 0)) && is_pinned(mesh.index(mesh.nu - 1, 0));
}

std::optional<std::string> drape_summary(const Scene& scene, const sim::Simulator& simulator) {
  if (hangs_as_curtain(scene))
    return std::to_string(analysis::count_curtain_folds(simulator.mesh(), simulator.state().x).folds) +
           " curtain folds (bulges down the centre column)";
  const auto support = analysis::find_support(scene.sim.obstacles, cloth_center_m(simulator.mesh()));
  const double specimen_m2 = analysis::specimen_rest_area_m2(simulator.mesh());
  if (!support || !(specimen_m2 > support->area_m2)) return std::nullopt;
  const analysis::DrapeShape d = analysis::measure_drape(simulator.mesh(), simulator.mesh().triangles(),
                                               simulator.state().x, *support);
  return format("drape coefficient %.3f, ", d.drape_coefficient) + std::to_string(d.folds) +
         " folds over " + support_name(*support);
}

}  // namespace weft::app
