#pragma once
// How far one simulated cloth is from another (weft sweep's errors against its reference run),
// and which runs are Pareto-optimal. Pure functions of meshes and positions.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "sim/grid.h"
#include "sim/types.h"

namespace weft::analysis {

// The reference cloth's position at material point uv = (u, v) metres: bilinear interpolation
// of `x` (#V×3, metres) over the warp/weft grid `mesh` (its material coordinates are a regular
// grid from (0, 0) to the cloth's size). uv outside the cloth is clamped to its edge.
sim::Vec3 position_at_material_point(const sim::ClothMesh& mesh, const sim::Matrix3X& x,
                                     const sim::Vec2& uv);

// Root-mean-square distance, metres, between the run's vertices and the reference's cloth at
// the same material points: sqrt(mean over the run's vertices i of
// |x_i − X_ref(uv_i)|²), X_ref interpolated bilinearly. Grids of different resolutions compare;
// both cloths should have the same size.
double rms_distance_m(const sim::ClothMesh& reference_mesh, const sim::Matrix3X& reference_x,
                      const sim::ClothMesh& mesh, const sim::Matrix3X& x);

// A binary image: width × height cells, row-major from the top.
struct Mask {
  int width = 0, height = 0;
  std::vector<bool> cells;
  bool at(int column, int row) const { return cells[static_cast<std::size_t>(row * width + column)]; }
  long count() const;
};

// An orthographic view: a point p lands at (p·right, p·up) on the image plane, metres. `right`
// and `up` are orthonormal; the view direction is up × right.
struct OrthoView {
  sim::Vec3 right{1.0, 0.0, 0.0};
  sim::Vec3 up{0.0, 1.0, 0.0};
};
// Looking along `view_direction` (need not be unit) with `up_hint` pointing up on the image
// (e.g. a camera's target − eye and up). They must not be parallel.
OrthoView ortho_view(const sim::Vec3& view_direction, const sim::Vec3& up_hint);

// A square window on the image plane: [u0, u0 + side] × [v0, v0 + side], metres.
struct Window {
  double u0 = 0.0, v0 = 0.0, side_m = 1.0;
};
// The smallest square window holding both point sets' projections, centred on their joint
// bounding box and grown by `margin` (a fraction of its side) on each side.
Window joint_window(const OrthoView& view, const sim::Matrix3X& a, const sim::Matrix3X& b,
                    double margin = 0.02);

// The silhouette of the triangles (indices into x, #V×3 metres) seen through `view`: cell
// (c, r) of an n × n mask is set when its centre, (u0 + (c + ½) side/n, v0 + side − (r + ½)
// side/n), lies in a projected triangle (edges included). Front and back faces alike.
Mask silhouette(const std::vector<std::array<sim::Index, 3>>& triangles, const sim::Matrix3X& x,
                const OrthoView& view, const Window& window, int n);

// |A xor B| / |A or B|: 0 for equal silhouettes, 1 for disjoint ones (0 when both are empty).
// The masks must have the same size.
double silhouette_difference(const Mask& a, const Mask& b);

// Whether each run is Pareto-optimal among the runs marked eligible: no other eligible run is
// at least as good in both time and error and better in one. Ineligible runs are never optimal.
std::vector<bool> pareto_optimal(const std::vector<double>& time_s,
                                 const std::vector<double>& error,
                                 const std::vector<bool>& eligible);

}  // namespace weft::analysis
