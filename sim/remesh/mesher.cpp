#include "sim/remesh/mesher.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "base/check.h"
#include "sim/remesh/mesh_topology.h"
#include "sim/remesh/point_locator.h"

namespace weft::sim::remesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
struct OldVertex {
  Index index = -1;  // the old vertex this CGAL vertex is, or −1 for a Steiner point
};
using VertexBase =
    CGAL::Triangulation_vertex_base_with_info_2<OldVertex, Kernel,
                                                CGAL::Delaunay_mesh_vertex_base_2<Kernel>>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;
using Point = Cdt::Point;

// Sizing and shape criteria in the form CGAL's Delaunay_mesher_2 asks of its Criteria: a
// Quality ordered so that the worst face is refined first, and an Is_bad functor.
class SizeFieldCriteria {
 public:
  // (squared sine of the smallest angle, squared longest edge / squared target size)
  struct Quality {
    double sine2 = 0.0, size_ratio2 = 0.0;
    // a < b: a is refined first. Oversized faces first, the most oversized first; then the
    // flattest.
    bool operator<(const Quality& other) const {
      const bool big = size_ratio2 > 1.0, other_big = other.size_ratio2 > 1.0;
      if (big != other_big) return big;
      if (big) return size_ratio2 > other.size_ratio2;
      return sine2 < other.sine2;
    }
  };

  class Is_bad {
   public:
    Is_bad(double sine2_bound, const SizeFunction* size)
        : m_sine2_bound(sine2_bound), m_size(size) {}

    CGAL::Mesh_2::Face_badness operator()(const Quality& q) const {
      if (q.size_ratio2 > 1.0) return CGAL::Mesh_2::IMPERATIVELY_BAD;
      return q.sine2 < m_sine2_bound ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }

    CGAL::Mesh_2::Face_badness operator()(const Cdt::Face_handle& face, Quality& q) const {
      const Point& a = face->vertex(0)->point();
      const Point& b = face->vertex(1)->point();
      const Point& c = face->vertex(2)->point();
      std::array<double, 3> len2{CGAL::to_double(CGAL::squared_distance(b, c)),
                                 CGAL::to_double(CGAL::squared_distance(c, a)),
                                 CGAL::to_double(CGAL::squared_distance(a, b))};
      std::sort(len2.begin(), len2.end());
      const Vec2 centroid((a.x() + b.x() + c.x()) / 3.0, (a.y() + b.y() + c.y()) / 3.0);
      const double h = (*m_size)(centroid);
      q.size_ratio2 = len2[2] / (h * h);
      // (2·area)² / (longest² · middle²) = sin² of the smallest angle.
      const double area2 = 2.0 * CGAL::to_double(CGAL::area(a, b, c));
      q.sine2 = area2 * area2 / (len2[2] * len2[1]);
      return (*this)(q);
    }

   private:
    double m_sine2_bound;
    const SizeFunction* m_size;
  };

  SizeFieldCriteria(double sine2_bound, const SizeFunction* size)
      : m_sine2_bound(sine2_bound), m_size(size) {}
  Is_bad is_bad_object() const { return Is_bad(m_sine2_bound, m_size); }

 private:
  double m_sine2_bound;
  const SizeFunction* m_size;
};

void check_params(const MesherParams& params) {
  if (!(params.min_angle_deg > 0.0 && params.min_angle_deg <= 20.7))
    throw std::invalid_argument("remesh: min_angle = " + std::to_string(params.min_angle_deg) +
                                "°, expected (0, 20.7]° (Delaunay refinement's termination "
                                "bound)");
  if (params.max_vertices < 3)
    throw std::invalid_argument("remesh: max_vertices = " + std::to_string(params.max_vertices) +
                                ", expected at least 3");
}

// A size function that checks what it returns.
SizeFunction checked(const SizeFunction& size) {
  return [&size](const Vec2& p) {
    const double h = size(p);
    if (!(std::isfinite(h) && h > 0.0))
      throw std::invalid_argument("remesh: the size field is " + std::to_string(h) + " m at (" +
                                  std::to_string(p.x()) + ", " + std::to_string(p.y()) +
                                  "), expected a positive length");
    return h;
  };
}

// The old vertices the new mesh keeps, ascending: those of the boundary and the pins.
std::vector<Index> vertices_to_keep(const std::vector<std::array<Index, 2>>& boundary,
                                    const std::vector<Index>& keep, Index old_count) {
  std::vector<Index> kept;
  for (const auto& e : boundary) kept.insert(kept.end(), e.begin(), e.end());
  for (Index k : keep) {
    if (k < 0 || k >= old_count)
      throw std::invalid_argument("remesh: pinned vertex " + std::to_string(k) +
                                  " is not a vertex of the mesh (" + std::to_string(old_count) +
                                  " vertices)");
    kept.push_back(k);
  }
  std::sort(kept.begin(), kept.end());
  kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
  return kept;
}

// The constrained Delaunay triangulation of the kept vertices with the boundary edges as
// constraints; handle: each kept vertex's CGAL vertex.
void triangulate_kept_vertices(const Matrix2X& material, const std::vector<Index>& kept,
                               const std::vector<std::array<Index, 2>>& boundary, Cdt& cdt,
                               std::map<Index, Cdt::Vertex_handle>& handle) {
  for (Index k : kept) {
    const Cdt::Vertex_handle vh = cdt.insert(Point(material(k, 0), material(k, 1)));
    if (vh->info().index >= 0)
      throw std::invalid_argument("remesh input: vertices " + std::to_string(vh->info().index) +
                                  " and " + std::to_string(k) +
                                  " have the same material coordinates");
    vh->info().index = k;
    handle[k] = vh;
  }
  for (const auto& e : boundary) cdt.insert_constraint(handle.at(e[0]), handle.at(e[1]));
  if (static_cast<Index>(cdt.number_of_vertices()) != static_cast<Index>(kept.size()))
    throw std::invalid_argument(
        "remesh input: a boundary edge passes through another kept vertex (the boundary "
        "touches itself)");
}

// The domain: faces whose centroid lies in the old mesh. Each face of the constrained
// triangulation of the boundary lies wholly inside or wholly outside, so its centroid decides.
void mark_old_mesh_domain(const Matrix2X& material, const Triangles& triangles, Cdt& cdt) {
  const PointLocator old_locator(material, triangles);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    const Point& a = f->vertex(0)->point();
    const Point& b = f->vertex(1)->point();
    const Point& c = f->vertex(2)->point();
    f->set_in_domain(
        old_locator.contains(Vec2((a.x() + b.x() + c.x()) / 3.0, (a.y() + b.y() + c.y()) / 3.0)));
  }
}

// Delaunay refinement of the domain until every face meets the size field and the smallest
// angle; throws beyond params.max_vertices.
void refine_to_size_field(Cdt& cdt, const SizeFunction& size, const MesherParams& params) {
  const SizeFunction checked_size = checked(size);
  const double rad = params.min_angle_deg * 3.14159265358979323846 / 180.0;
  const SizeFieldCriteria criteria(std::sin(rad) * std::sin(rad), &checked_size);
  CGAL::Delaunay_mesher_2<Cdt, SizeFieldCriteria> mesher(cdt, criteria);
  mesher.init(/*domain_specified=*/true);
  while (!mesher.is_refinement_done()) {
    mesher.step_by_step_refine_mesh();
    if (static_cast<Index>(cdt.number_of_vertices()) > params.max_vertices)
      throw std::invalid_argument("remesh: the size field asks for more than " +
                                  std::to_string(params.max_vertices) +
                                  " vertices (max_vertices); raise h_min");
  }
}

// The new mesh: the domain's faces, oriented like the old mesh (old_sign), over the kept
// vertices first in old-index order, then the new ones in CGAL's order.
MeshResult mesh_of_domain(const Cdt& cdt, const std::vector<Index>& kept,
                          const std::map<Index, Cdt::Vertex_handle>& handle, int old_sign) {
  MeshResult result;
  std::map<Cdt::Vertex_handle, Index> new_index;
  std::vector<Cdt::Vertex_handle> order;
  for (Index k : kept) order.push_back(handle.at(k));
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
    if (v->info().index < 0) order.push_back(v);
  std::vector<std::array<Cdt::Vertex_handle, 3>> faces;
  std::vector<char> used(order.size(), 0);
  for (size_t i = 0; i < order.size(); ++i) new_index[order[i]] = static_cast<Index>(i);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->is_in_domain()) {
      faces.push_back({f->vertex(0), f->vertex(1), f->vertex(2)});
      for (int k = 0; k < 3; ++k) used[static_cast<size_t>(new_index.at(f->vertex(k)))] = 1;
    }
  // Vertices of no domain face (none expected: kept vertices lie on the domain and Steiner
  // points are inserted in it) are dropped.
  std::vector<Index> compact(order.size(), -1);
  Index count = 0;
  for (size_t i = 0; i < order.size(); ++i)
    if (used[i]) compact[i] = count++;
  result.material.resize(count, 2);
  result.new_to_old.resize(static_cast<size_t>(count));
  for (size_t i = 0; i < order.size(); ++i) {
    if (!used[i]) continue;
    const Index j = compact[i];
    result.material(j, 0) = order[i]->point().x();
    result.material(j, 1) = order[i]->point().y();
    result.new_to_old[static_cast<size_t>(j)] = order[i]->info().index;
  }
  result.triangles.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t t = 0; t < faces.size(); ++t) {
    // CGAL's faces are counter-clockwise; keep the old mesh's orientation.
    std::array<Index, 3> idx;
    for (int k = 0; k < 3; ++k) idx[k] = compact[static_cast<size_t>(new_index.at(faces[t][k]))];
    if (old_sign < 0) std::swap(idx[1], idx[2]);
    result.triangles.row(static_cast<Eigen::Index>(t)) << idx[0], idx[1], idx[2];
  }
  return result;
}

}  // namespace

MeshResult mesh_domain(const Matrix2X& material, const Triangles& triangles,
                       const std::vector<Index>& keep, const SizeFunction& size,
                       const MesherParams& params) {
  check_mesh(material, triangles, "remesh input");
  check_params(params);
  const int old_sign = orientation(material, triangles);
  const auto boundary = boundary_edges(triangles);
  const std::vector<Index> kept =
      vertices_to_keep(boundary, keep, static_cast<Index>(material.rows()));
  Cdt cdt;
  std::map<Index, Cdt::Vertex_handle> handle;
  triangulate_kept_vertices(material, kept, boundary, cdt, handle);
  mark_old_mesh_domain(material, triangles, cdt);
  refine_to_size_field(cdt, size, params);
  return mesh_of_domain(cdt, kept, handle, old_sign);
}

}  // namespace weft::sim::remesh
