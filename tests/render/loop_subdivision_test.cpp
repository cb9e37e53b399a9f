// Loop subdivision (render/loop_subdivision.h), against what Loop's scheme must do:
// - counts: one level takes V, E, F to V + E, E' = 2E + 3F, 4F, so the Euler characteristic
//   V − E + F is kept (1 for a sheet, 2 for a sphere);
// - Loop reproduces affine functions: a regular grid laid out by an affine map of its (u, v)
//   stays that map of the (linearly interpolated) UVs at every level, boundary included, and a
//   planar mesh (jittered in its plane) stays in its plane;
// - the masks on a regular (valence-6, β = 1/16) vertex: a unit bump at one vertex gives 10/16
//   at that vertex, 3/8 at the edge points of its edges and 1/8 at the edge points opposite it;
//   its limit position (Loop's limit mask 1/2 centre + 1/12 per neighbour for valence 6) is the
//   same computed from any level;
// - boundaries kept: the boundary of a planar rectangle (uneven spacing, jittered interior)
//   stays on the rectangle's sides, corners do not move, and the boundary does not depend on
//   the interior vertices.

#include "render/loop_subdivision.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "render/primitives.h"

namespace weft::render {
namespace {

using EdgeSet = std::set<std::pair<std::uint32_t, std::uint32_t>>;

EdgeSet edges_of(const RenderMesh& mesh) {
  EdgeSet edges;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
  return edges;
}

// Edges in exactly one triangle.
EdgeSet boundary_edges(const RenderMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++count[std::minmax(t[k], t[(k + 1) % 3])];
  EdgeSet boundary;
  for (const auto& [e, n] : count)
    if (n == 1) boundary.insert(e);
  return boundary;
}

// Deterministic pseudo-random numbers in [−1, 1] (no std::rand: same on every platform).
double jitter(std::uint32_t i, std::uint32_t salt) {
  std::uint32_t h = i * 2654435761u ^ (salt * 40503u + 0x9E3779B9u);
  h ^= h >> 15;
  h *= 2246822519u;
  h ^= h >> 13;
  return (static_cast<double>(h % 20001u) - 10000.0) / 10000.0;
}

TEST(LoopSubdivision, CountsPerLevelKeepEulerCharacteristic) {
  const RenderMesh sheet =
      make_grid_mesh(5, 4, [](double u, double v) { return Eigen::Vector3d(u, v, 0.1 * u * v); });
  const RenderMesh sphere = make_sphere_mesh(Eigen::Vector3d::Zero(), 1.0, 8, 5);
  for (const auto& [mesh, euler] : {std::pair{&sheet, 1}, std::pair{&sphere, 2}}) {
    const std::size_t v0 = mesh->positions.size(), e0 = edges_of(*mesh).size(),
                      f0 = mesh->triangles.size();
    ASSERT_EQ(static_cast<long>(v0) - static_cast<long>(e0) + static_cast<long>(f0), euler);
    std::size_t v = v0, e = e0, f = f0;
    for (int level = 0; level <= max_subdivision_levels; ++level) {
      const RenderMesh out = loop_subdivide(*mesh, level);
      SCOPED_TRACE("level " + std::to_string(level));
      EXPECT_EQ(out.positions.size(), v);
      EXPECT_EQ(out.normals.size(), v);
      EXPECT_EQ(out.triangles.size(), f);
      EXPECT_EQ(edges_of(out).size(), e);
      EXPECT_EQ(static_cast<long>(v) - static_cast<long>(e) + static_cast<long>(f), euler);
      // Next level: V' = V + E, E' = 2E + 3F, F' = 4F.
      const std::size_t next_v = v + e, next_e = 2 * e + 3 * f, next_f = 4 * f;
      v = next_v;
      e = next_e;
      f = next_f;
    }
  }
}

TEST(LoopSubdivision, ReproducesAffineMapsOfARegularGrid) {
  // p = c + A (u, v): a sheared, tilted sheet in 3-D.
  const Eigen::Vector3d c(0.3, -0.2, 1.0), a_u(0.9, 0.2, 0.3), a_v(-0.1, 0.7, 0.5);
  const RenderMesh grid = make_grid_mesh(
      6, 5, [&](double u, double v) { return Eigen::Vector3d(c + u * a_u + v * a_v); });
  const Eigen::Vector3d normal = a_u.cross(a_v).normalized();
  for (int level = 1; level <= max_subdivision_levels; ++level) {
    const RenderMesh out = loop_subdivide(grid, level);
    ASSERT_EQ(out.uvs.size(), out.positions.size());
    double worst = 0.0, worst_normal = 0.0;
    for (std::size_t k = 0; k < out.positions.size(); ++k) {
      const Eigen::Vector3d uv_map = c + out.uvs[k].x() * a_u + out.uvs[k].y() * a_v;
      worst = std::max(worst, (out.positions[k].cast<double>() - uv_map).norm());
      worst_normal = std::max(worst_normal, (out.normals[k].cast<double>() - normal).norm());
    }
    EXPECT_LT(worst, 1e-6) << "level " << level;
    EXPECT_LT(worst_normal, 1e-5) << "level " << level;
  }
}

TEST(LoopSubdivision, PlanarMeshStaysPlanar) {
  // A plane through the origin with normal n, vertices jittered within it.
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.4, 1.0).normalized();
  const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  RenderMesh mesh =
      make_grid_mesh(7, 7, [&](double u, double v) { return Eigen::Vector3d(u * t1 + v * t2); });
  for (std::size_t k = 0; k < mesh.positions.size(); ++k) {
    const auto i = static_cast<std::uint32_t>(k);
    mesh.positions[k] += (0.04 * jitter(i, 1) * t1 + 0.04 * jitter(i, 2) * t2).cast<float>();
  }
  const RenderMesh out = loop_subdivide(mesh, 3);
  double worst = 0.0;
  for (const Eigen::Vector3f& p : out.positions)
    worst = std::max(worst, std::abs(p.cast<double>().dot(n)));
  EXPECT_LT(worst, 1e-6);
}

// The n×n grid over [−2, 2]² (spacing 1 for n = 5) with a bump of height 1 at the middle vertex.
TEST(LoopSubdivision, RegularVertexMasksAndLimitPosition) {
  const int n = 9;  // spacing 0.5; the bump's ring and the next ring are interior, valence 6
  RenderMesh grid = make_grid_mesh(
      n, n, [](double u, double v) { return Eigen::Vector3d(4.0 * u - 2.0, 4.0 * v - 2.0, 0.0); });
  const std::uint32_t centre = (n / 2) * n + n / 2;
  grid.positions[centre].z() = 1.0f;

  const RenderMesh one = loop_subdivide(grid, 1);
  // Old vertex: (1 − 6β) + 0 with β(6) = 1/16.
  EXPECT_NEAR(one.positions[centre].z(), 10.0 / 16.0, 1e-6);
  int on_edge = 0, opposite = 0;
  for (std::size_t k = grid.positions.size(); k < one.positions.size(); ++k) {
    const float z = one.positions[k].z();
    if (std::abs(z - 0.375f) < 1e-6f)
      ++on_edge;
    else if (std::abs(z - 0.125f) < 1e-6f)
      ++opposite;
    else
      EXPECT_NEAR(z, 0.0f, 1e-6f) << "edge point " << k;
  }
  EXPECT_EQ(on_edge, 6);   // the bump's six edges
  EXPECT_EQ(opposite, 6);  // the six edges of its one-ring, each opposite it once

  // Limit position of the centre: 1/2 z + 1/12 Σ neighbours' z, the same at every level, and
  // the centre's own height approaches it.
  const auto limit_height = [&](const RenderMesh& mesh) {
    double sum = 0.0;
    int valence = 0;
    for (const auto& [a, b] : edges_of(mesh)) {
      if (a == centre) sum += mesh.positions[b].z(), ++valence;
      if (b == centre) sum += mesh.positions[a].z(), ++valence;
    }
    EXPECT_EQ(valence, 6);
    return 0.5 * mesh.positions[centre].z() + sum / 12.0;
  };
  const double limit = limit_height(grid);
  EXPECT_NEAR(limit, 0.5, 1e-12);
  double previous_gap = std::abs(1.0 - limit);
  for (int level = 1; level <= max_subdivision_levels; ++level) {
    const RenderMesh out = loop_subdivide(grid, level);
    EXPECT_NEAR(limit_height(out), limit, 1e-6) << "level " << level;
    const double gap = std::abs(out.positions[centre].z() - limit);
    EXPECT_LT(gap, previous_gap) << "level " << level;
    previous_gap = gap;
  }
}

TEST(LoopSubdivision, BoundaryStaysOnARectanglesSidesCornersFixed) {
  // Rectangle [0, 2] × [0, 1], uneven spacing along the sides, interior jittered in the plane.
  const int nu = 6, nv = 5;
  RenderMesh flat = make_grid_mesh(nu, nv, [](double u, double v) {
    return Eigen::Vector3d(2.0 * u * u, v * (0.6 + 0.4 * v), 0.0);
  });
  for (int j = 1; j + 1 < nv; ++j) {
    for (int i = 1; i + 1 < nu; ++i) {
      const auto k = static_cast<std::uint32_t>(j * nu + i);
      flat.positions[k] += Eigen::Vector3f(0.03f * static_cast<float>(jitter(k, 3)),
                                           0.03f * static_cast<float>(jitter(k, 4)), 0.0f);
    }
  }
  // The same boundary with the interior lifted out of the plane.
  RenderMesh lifted = flat;
  for (int j = 1; j + 1 < nv; ++j)
    for (int i = 1; i + 1 < nu; ++i)
      lifted.positions[static_cast<std::size_t>(j * nu + i)].z() = 0.3f;

  const std::vector<std::uint32_t> corners = {0, nu - 1, nu * (nv - 1), nu * nv - 1};
  const EdgeSet boundary0 = boundary_edges(flat);
  for (int level = 1; level <= max_subdivision_levels; ++level) {
    SCOPED_TRACE("level " + std::to_string(level));
    const RenderMesh out = loop_subdivide(flat, level);
    const RenderMesh out_lifted = loop_subdivide(lifted, level);
    for (std::uint32_t c : corners) EXPECT_EQ(out.positions[c], flat.positions[c]);
    const EdgeSet boundary = boundary_edges(out);
    EXPECT_EQ(boundary.size(), boundary0.size() << level);  // each boundary edge split in two
    std::set<std::uint32_t> on_boundary;
    for (const auto& [a, b] : boundary) on_boundary.insert({a, b});
    for (std::uint32_t k : on_boundary) {
      const Eigen::Vector3f& p = out.positions[k];
      const float side = std::min(
          {std::abs(p.x()), std::abs(p.x() - 2.0f), std::abs(p.y()), std::abs(p.y() - 1.0f)});
      EXPECT_LT(side, 1e-6f) << "boundary vertex " << k << " at " << p.transpose();
      EXPECT_LT((out_lifted.positions[k] - p).norm(), 1e-6f) << "boundary vertex " << k;
    }
  }
}

// The wireframe's lines (RenderMesh::edges) follow the surface: a grid's warp
// and weft lines become chains of 2^level sides of subdivided triangles, running from the same
// grid vertex to the same grid vertex through the edge points; a line that is no triangle's
// side is an error.
TEST(LoopSubdivision, WireframeEdgesBecomeSidesOfTheSubdividedTriangles) {
  RenderMesh grid = make_grid_mesh(4, 3, [](double u, double v) {
    return Eigen::Vector3d(u, v, 0.3 * u * u - 0.2 * v);
  });
  for (std::uint32_t j = 0; j < 3; ++j)
    for (std::uint32_t i = 0; i < 4; ++i) {
      if (i + 1 < 4) grid.edges.push_back({j * 4 + i, j * 4 + i + 1});
      if (j + 1 < 3) grid.edges.push_back({j * 4 + i, (j + 1) * 4 + i});
    }
  for (int level = 1; level <= 2; ++level) {
    const RenderMesh out = loop_subdivide(grid, level);
    const int pieces = 1 << level;
    ASSERT_EQ(out.edges.size(), grid.edges.size() * pieces) << "level " << level;
    const EdgeSet sides = edges_of(out);
    for (std::size_t e = 0; e < grid.edges.size(); ++e) {
      // Consecutive pieces chain from the edge's first end to its second.
      EXPECT_EQ(out.edges[e * pieces][0], grid.edges[e][0]);
      EXPECT_EQ(out.edges[e * pieces + pieces - 1][1], grid.edges[e][1]);
      for (int k = 0; k < pieces; ++k) {
        const auto [a, b] = out.edges[e * pieces + k];
        EXPECT_TRUE(sides.count(std::minmax(a, b))) << "level " << level << " edge " << e;
        if (k > 0) {
          EXPECT_EQ(a, out.edges[e * pieces + k - 1][1]);
        }
        // Along a warp or weft line: one material coordinate stays.
        const Eigen::Vector2f d = out.uvs[a] - out.uvs[b];
        EXPECT_TRUE(d.x() == 0.0f || d.y() == 0.0f);
      }
    }
  }
  grid.edges.push_back({0, 5});  // a diagonal (0,0)-(1,1): a triangle side, accepted
  EXPECT_NO_THROW(loop_subdivide(grid, 1));
  grid.edges.push_back({0, 6});  // (0,0)-(2,1): no triangle's side
  EXPECT_THROW(loop_subdivide(grid, 1), std::invalid_argument);
  grid.edges.back() = {0, 12};  // out of range
  EXPECT_THROW(loop_subdivide(grid, 1), std::invalid_argument);
}

TEST(LoopSubdivision, LevelZeroCopiesAndBadLevelsThrow) {
  RenderMesh mesh =
      make_grid_mesh(3, 3, [](double u, double v) { return Eigen::Vector3d(u, v, 0); });
  const RenderMesh same = loop_subdivide(mesh, 0);
  EXPECT_EQ(same.positions, mesh.positions);
  EXPECT_EQ(same.triangles, mesh.triangles);
  EXPECT_THROW(loop_subdivide(mesh, -1), std::invalid_argument);
  EXPECT_THROW(loop_subdivide(mesh, max_subdivision_levels + 1), std::invalid_argument);
  mesh.uvs.pop_back();
  EXPECT_THROW(loop_subdivide(mesh, 1), std::invalid_argument);
}

}  // namespace
}  // namespace weft::render
