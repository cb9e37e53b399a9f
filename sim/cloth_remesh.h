#pragma once
// Adaptive remeshing of a simulated cloth (docs/remeshing.md): the bridge
// between a ClothMesh with its state and the array-based remeshing step of sim/remesh/remesh.h.
// The new mesh covers the same material domain, graded by the curvature of the current
// positions; its boundary vertices and the kept vertices (pins) are the old ones, at the same
// material point, with their positions, velocities and start positions copied bit for bit;
// every other per-vertex array is interpolated in material coordinates. Simulator::remesh_now()
// rebuilds everything made from the mesh on the result.

#include <string>
#include <vector>

#include "sim/grid.h"
#include "sim/sim_settings.h"
#include "sim/types.h"

namespace weft::sim {

struct RemeshedCloth {
  ClothMesh mesh;        // a triangle mesh (no grid), source and orientation kept
  Matrix3X x, v;         // #V_new×3 positions and velocities
  Matrix3X initial_x;    // #V_new×3 the start positions moving pins are offset from
  std::vector<Index> old_to_new;  // #V_old: the new index of a kept old vertex, or −1
};

// Throws std::invalid_argument "simulation.remesh: …" naming what the combination lacks when
// settings.remesh is enabled and the cloth or settings cannot be remeshed: a warp/weft grid
// (its models run on quads), the mass-spring model (its springs on triangle edges depend on
// the triangulation), RFT (its bending patches may be degenerate on a Delaunay mesh), an explicit integrator (its step is fixed from the first mesh's critical
// step), constraints (projection) or the adaptive step, a build without CGAL.
void check_remesh_settings(const ClothMesh& mesh, const SimSettings& settings);

// Seed 002's criterion on the cloth at positions x (#V×3): max over triangles of |κ| h² (metres;
// sim/remesh/size_field.h remesh_indicator, triangles already at h_min left out).
double cloth_remesh_indicator_m(const ClothMesh& mesh, const Matrix3X& x,
                                const RemeshSettings& settings);

// Both criteria at once (one curvature fit): seed 002's indicator as cloth_remesh_indicator_m,
// and the refinement excess (sim/remesh/size_field.h refinement_excess) for coarsening.
struct ClothRemeshCriteria {
  double indicator_m = 0.0;
  double excess = 0.0;
};
ClothRemeshCriteria cloth_remesh_criteria(const ClothMesh& mesh, const Matrix3X& x,
                                          const RemeshSettings& settings);

// One remeshing step: the cloth at positions x and velocities v (#V×3), with initial_x (#V×3)
// carried along and `keep` (pins) kept. Throws std::invalid_argument from the remesher (a size
// field asking for more than settings.max_vertices vertices, ...).
RemeshedCloth remesh_cloth(const ClothMesh& mesh, const Matrix3X& x, const Matrix3X& v,
                           const Matrix3X& initial_x, const std::vector<Index>& keep,
                           const RemeshSettings& settings);

}  // namespace weft::sim
