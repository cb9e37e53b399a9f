#include "app/scene/scene_bounds.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "app/io/input_error.h"
#include "base/format.h"

namespace weft::app {

namespace {

std::string number(double value) { return base::format("%.3g", value); }

// The cloth's used vertices: total mass, area, and the farthest from the origin.
struct ClothExtent {
  double mass_kg = 0.0, area_m2 = 0.0, radius_m = 0.0, diagonal_m = 0.0;
};

ClothExtent cloth_extent(const sim::Simulator& simulator) {
  ClothExtent e;
  const sim::ClothMesh& mesh = simulator.mesh();
  const sim::Matrix3X& x = simulator.state().x;
  Eigen::AlignedBox3d box;
  for (sim::Index i = 0; i < x.rows(); ++i) {
    if (!mesh.is_used(i)) continue;
    e.mass_kg += simulator.masses_kg()[i];
    e.area_m2 += mesh.vertex_area_m2[i];
    e.radius_m = std::max(e.radius_m, x.row(i).norm());
    box.extend(x.row(i).transpose());
  }
  e.diagonal_m = box.isEmpty() ? 0.0 : box.diagonal().norm();
  return e;
}

void check_energy_scale(const Scene& scene, const ClothExtent& e) {
  const sim::SimSettings& s = scene.sim;
  const double g = s.gravity_m_s2.norm();
  const double reach_m = e.radius_m + e.diagonal_m;
  // Per kg of cloth: the gravity energy within the reach, and the kinetic energy at max_speed.
  const double per_kg = g * reach_m + 0.5 * s.max_speed_m_s * s.max_speed_m_s;
  const double energy_J = e.mass_kg * per_kg;
  if (!(energy_J <= max_energy_scale_J))
    throw InputError(
        scene.source + ": cloth.material.density: " + number(scene.material.density_kg_m2) +
        " kg/m^2 gives the cloth (" + number(e.area_m2) + " m^2) a mass of " + number(e.mass_kg) +
        " kg and energies up to " + number(energy_J) + " J (gravity " + number(g) +
        " m/s^2 over " + number(reach_m) + " m, speeds up to simulation.max_speed), more than " +
        number(max_energy_scale_J) +
        " J, beyond what the simulation can add up; expected at most " +
        number(max_energy_scale_J / (per_kg * e.area_m2)) + " kg/m^2");
  const sim::Material& m = scene.material;
  const std::pair<const char*, double> stiffnesses[] = {{"stretch_warp", m.stretch_warp_N_m},
                                                        {"stretch_weft", m.stretch_weft_N_m},
                                                        {"shear", m.shear_N_m}};
  const double per_stiffness = 0.5 * e.area_m2 * s.max_strain * s.max_strain;
  for (const auto& [key, k] : stiffnesses)
    if (!(k * per_stiffness <= max_energy_scale_J))
      throw InputError(scene.source + ": cloth.material." + key + ": " + number(k) +
                       " N/m gives an elastic energy up to " + number(k * per_stiffness) +
                       " J at simulation.max_strain over the cloth's " + number(e.area_m2) +
                       " m^2, more than " + number(max_energy_scale_J) +
                       " J, beyond what the simulation can add up; expected at most " +
                       number(max_energy_scale_J / per_stiffness) + " N/m");
}

void check_remesh_size(const Scene& scene, const ClothExtent& e) {
  const sim::RemeshSettings& r = scene.sim.remesh;
  if (!r.enabled) return;
  const double vertices = uniform_mesh_vertices(e.area_m2, r.h_min_m);
  if (vertices <= static_cast<double>(r.max_vertices)) return;
  const double finest_m = r.h_min_m * std::sqrt(vertices / static_cast<double>(r.max_vertices));
  throw InputError(scene.source + ": simulation.remesh.h_min: " + number(r.h_min_m) +
                   " m would make the cloth (" + number(e.area_m2) + " m^2) a mesh of about " +
                   number(vertices) + " vertices where it is all refined (a drape's folds "
                   "refine most of it), more than simulation.remesh.max_vertices (" +
                   std::to_string(r.max_vertices) + "); expected an h_min of at least " +
                   number(finest_m) + " m for this cloth, or a larger max_vertices (at most " +
                   std::to_string(max_remesh_vertices) + ")");
}

}  // namespace

double uniform_mesh_vertices(double area_m2, double h_m) {
  return area_m2 / (std::sqrt(3.0) / 2.0 * h_m * h_m);
}

void check_scene_bounds(const Scene& scene, const sim::Simulator& simulator) {
  const ClothExtent extent = cloth_extent(simulator);
  check_energy_scale(scene, extent);
  check_remesh_size(scene, extent);
}

}  // namespace weft::app
