#pragma once
// Self-contacts as linear inequality constraints for a step: the rows that the
// projection with contacts (sim/constraints/contact_projection.h) solves together with the
// inextensibility constraints, so that no projection can push one layer of cloth through
// another.
//
// At the start of a step, every pair of the cloth's features that can come within the contact
// distance during the step — swept boxes from the start positions x_start to the predicted
// positions x_end, grown by a slack for what the projection adds — gives one row, with its side
// taken from x_start, where the cloth does not pass through itself:
//
//  - vertex–triangle: a vertex over the face of a triangle at x_start (its projection onto the
//    triangle's plane inside the triangle grown by over_face_margin), with the barycentric
//    weights w of that projection
//    and the unit normal n of the triangle at x_start, turned toward the vertex;
//  - edge–edge: two edges sharing no vertex whose closest points at x_start are inside both,
//    with their parameters s, u and n the unit vector from the point on f to the point on e.
//
// Each row is g(x) = n · Σ_k w_k x_k ≥ distance, w and n fixed for the step (vertex: w = 1,
// triangle corners: −barycentric; edge e: 1 − s, s; edge f: u − 1, −u). g is linear in x, so
// if it holds at the step's start and end it holds all along the straight path between: the
// vertex stays on its side of the plane through the triangle's material point, the edges on
// their sides of each other. Pairs closer at rest than the contact distance plus
// `neighbourhood_edges` mean rest edges get no row, as in self_collision.h. Deterministic:
// rows are ordered by (vertex, triangle) then (edge, edge).

#include <array>
#include <vector>

#include "sim/grid.h"
#include "sim/types.h"

namespace weft::sim {

struct SelfContactRow {
  std::array<Index, 4> v;
  std::array<double, 4> w;
  Vec3 n;
  // g(x) = n · Σ_k w_k x_k.
  double gap(const Matrix3X& x) const {
    Vec3 p = Vec3::Zero();
    for (int k = 0; k < 4; ++k) p += w[static_cast<std::size_t>(k)] * x.row(v[static_cast<std::size_t>(k)]).transpose();
    return n.dot(p);
  }
  // How far the row is inside as a contact: min(0, g − distance), but 0 when the pair's two
  // material points (Σ w x on each side) are farther apart than the depth plus lateral_m: the
  // pair slid apart during the step, and its plane no longer stands for the cloth between.
  double violation(const Matrix3X& x, double distance_m, double lateral_m) const {
    Vec3 p = Vec3::Zero();
    for (std::size_t k = 0; k < 4; ++k) p += w[k] * x.row(v[k]).transpose();
    const double c = n.dot(p) - distance_m;
    return c < 0.0 && p.norm() <= distance_m - c + lateral_m ? c : 0.0;
  }
};

class SelfContactRows {
 public:
  // Throws std::invalid_argument unless distance_m is finite > 0 and neighbourhood_edges in 0..4.
  SelfContactRows(const ClothMesh& mesh, double distance_m, double neighbourhood_edges);

  // The rows of a step from x_start to (about) x_end: pairs whose boxes swept between the two
  // and grown by slack_m + distance come within reach. Rows whose four vertices are all pinned
  // (inv_mass 0) are left out.
  void gather(const Matrix3X& x_start, const Matrix3X& x_end, const Eigen::VectorXd& inv_mass,
              double slack_m);
  const std::vector<SelfContactRow>& rows() const { return m_rows; }
  double distance_m() const { return m_distance_m; }
  double mean_edge_m() const { return m_mean_edge_m; }
  // The most negative violation() over the rows at x, with lateral_m() (0 without rows).
  double worst_violation(const Matrix3X& x) const;
  // Rows whose material points slid apart by more than this count as no contact: half a mean
  // rest edge.
  double lateral_m() const { return 0.5 * m_mean_edge_m; }

  // A vertex counts as over a triangle when its projection's barycentric weights are all above
  // −this: the triangle grown a little, so that a vertex over the gap between two triangles
  // that meet at an angle (on the convex side) is over both.
  static constexpr double over_face_margin = 0.1;

 private:
  double m_distance_m;
  double m_exclusion_m;  // pairs closer than this at rest get no row
  double m_mean_edge_m;
  Matrix3X m_rest;
  std::vector<std::array<Index, 3>> m_triangles;
  std::vector<std::array<Index, 2>> m_edges;
  std::vector<Index> m_vertices;  // the vertices of some triangle, ascending
  std::vector<SelfContactRow> m_rows;
};

}  // namespace weft::sim
