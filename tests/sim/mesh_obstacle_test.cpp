// Mesh obstacles: the point–triangle kernel, exact signed distances of a cube mesh against the
// analytic box (faces, edges, vertices; inside and outside), an icosphere against the analytic
// sphere within its sagitta, deterministic ties, and the push-out through obstacle.h.

#include "sim/collision/mesh_obstacle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "sim/collision/obstacle.h"

namespace weft::sim {
namespace {

using Triangles = std::vector<std::array<Index, 3>>;

// The axis-aligned box |x_i| ≤ h_i as 8 vertices and 12 outward triangles.
std::shared_ptr<const MeshSolid> box_mesh(const Vec3& h) {
  Matrix3X v(8, 3);
  for (int i = 0; i < 8; ++i)
    v.row(i) << ((i & 1) ? h.x() : -h.x()), ((i & 2) ? h.y() : -h.y()), ((i & 4) ? h.z() : -h.z());
  const Triangles t = {{0, 2, 3}, {0, 3, 1},   // z−
                       {4, 5, 7}, {4, 7, 6},   // z+
                       {0, 1, 5}, {0, 5, 4},   // y−
                       {2, 6, 7}, {2, 7, 3},   // y+
                       {0, 4, 6}, {0, 6, 2},   // x−
                       {1, 3, 7}, {1, 7, 5}};  // x+
  return std::make_shared<const MeshSolid>(v, t);
}

// assets/meshes/icosphere_3.obj (unit radius), read here with a minimal "v"/"f" reader so that
// the simulation tests need no assimp; scaled to radius_m.
std::shared_ptr<const MeshSolid> icosphere(double radius_m) {
  std::ifstream in(std::string(WEFT_SOURCE_DIR) + "/assets/meshes/icosphere_3.obj");
  EXPECT_TRUE(in.good()) << "cannot open assets/meshes/icosphere_3.obj";
  std::vector<Vec3> vertices;
  Triangles triangles;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      Vec3 p;
      words >> p.x() >> p.y() >> p.z();
      vertices.push_back(radius_m * p);
    } else if (tag == "f") {
      std::array<Index, 3> f;
      words >> f[0] >> f[1] >> f[2];
      triangles.push_back({f[0] - 1, f[1] - 1, f[2] - 1});
    }
  }
  Matrix3X v(static_cast<Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) v.row(static_cast<Index>(i)) = vertices[i];
  return std::make_shared<const MeshSolid>(v, triangles);
}

// The largest gap between a triangle and the sphere through its vertices: r − (distance of
// its plane from the centre), the sagitta of the triangle's circumcircle.
double max_sagitta(const MeshSolid& mesh, double radius_m) {
  double worst = 0.0;
  for (const auto& t : mesh.triangles()) {
    const Vec3 a = mesh.vertices_m().row(t[0]), b = mesh.vertices_m().row(t[1]),
               c = mesh.vertices_m().row(t[2]);
    const Vec3 n = (b - a).cross(c - a).normalized();
    worst = std::max(worst, radius_m - n.dot(a));
  }
  return worst;
}

Vec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return Vec3(normal(rng), normal(rng), normal(rng)).normalized();
}

TEST(ClosestPointOnTriangle, IsInTheTriangleAndNoSampledPointIsNearer) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  const auto random_point = [&] { return Vec3(coordinate(rng), coordinate(rng), coordinate(rng)); };
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 a = random_point(), b = random_point(), c = random_point(), p = 2.0 * random_point();
    const TrianglePoint q = closest_point_on_triangle(p, a, b, c);
    const double d = (p - q.point).norm();
    // q lies in the triangle: its barycentric coordinates are ≥ 0 and sum to 1.
    const Vec3 n = (b - a).cross(c - a);
    const double area2 = n.squaredNorm();
    const double wa = (c - b).cross(q.point - b).dot(n) / area2;
    const double wb = (a - c).cross(q.point - c).dot(n) / area2;
    const double wc = (b - a).cross(q.point - a).dot(n) / area2;
    EXPECT_GT(std::min({wa, wb, wc}), -1e-9) << "trial " << trial;
    EXPECT_NEAR(wa + wb + wc, 1.0, 1e-9);
    // No point of a 40×40 barycentric sampling is nearer.
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; i + j <= 40; ++j) {
        const Vec3 s = a + (i / 40.0) * (b - a) + (j / 40.0) * (c - a);
        ASSERT_LE(d, (p - s).norm() + 1e-12) << "trial " << trial;
      }
  }
}

TEST(ClosestPointOnTriangle, NamesTheVertexEdgeOrFaceItLiesOn) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_EQ(closest_point_on_triangle({-1, -1, 1}, a, b, c).feature, TriangleFeature::vertex_a);
  EXPECT_EQ(closest_point_on_triangle({2, -0.5, 1}, a, b, c).feature, TriangleFeature::vertex_b);
  EXPECT_EQ(closest_point_on_triangle({-0.5, 2, 1}, a, b, c).feature, TriangleFeature::vertex_c);
  EXPECT_EQ(closest_point_on_triangle({0.5, -1, 1}, a, b, c).feature, TriangleFeature::edge_ab);
  EXPECT_EQ(closest_point_on_triangle({1, 1, 1}, a, b, c).feature, TriangleFeature::edge_bc);
  EXPECT_EQ(closest_point_on_triangle({-1, 0.5, 1}, a, b, c).feature, TriangleFeature::edge_ca);
  const TrianglePoint face = closest_point_on_triangle({0.2, 0.3, -2}, a, b, c);
  EXPECT_EQ(face.feature, TriangleFeature::face);
  EXPECT_TRUE(face.point.isApprox(Vec3(0.2, 0.3, 0.0)));
  // A degenerate (collinear) triangle: the nearest point of its segment.
  const TrianglePoint line = closest_point_on_triangle({0.5, 1, 0}, a, b, Vec3(2, 0, 0));
  EXPECT_TRUE(line.point.isApprox(Vec3(0.5, 0, 0)));
}

// Points around a box: near faces, edges and corners, inside and outside, at several scales.
std::vector<Vec3> probe_points(const Vec3& h, std::mt19937& rng) {
  std::vector<Vec3> points;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < 400; ++k) {
    const double reach = k % 4 == 0 ? 0.5 : k % 4 == 1 ? 1.05 : k % 4 == 2 ? 1.5 : 4.0;
    points.push_back(reach * Vec3(unit(rng) * h.x(), unit(rng) * h.y(), unit(rng) * h.z()));
  }
  // Exactly in a corner's, an edge's and a face's region, and on the medial surface inside.
  points.push_back(h + Vec3(0.01, 0.02, 0.03));
  points.push_back(Vec3(0.3 * h.x(), h.y() + 0.01, h.z() + 0.02));
  points.push_back(Vec3(0.1 * h.x(), 0.2 * h.y(), h.z() + 0.05));
  points.push_back(Vec3(h.x() - 0.01, h.y() - 0.01, 0.0));  // equally near the x+ and y+ faces
  points.push_back(Vec3(h.x() - 0.01, h.y() - 0.01, h.z() - 0.01));
  points.push_back(h);  // on the corner
  points.push_back(Vec3::Zero());
  return points;
}

// A cube mesh is the box: its signed distance is the box's exactly, at faces, edges and
// corners, inside and outside (the pseudonormal gets the sign right at every feature).
TEST(MeshObstacle, CubeMeshSignedDistanceIsTheBoxsExactly) {
  const Vec3 h(0.1, 0.07, 0.05);
  const auto cube = box_mesh(h);
  EXPECT_EQ(cube->border_edge_count(), 0);
  EXPECT_EQ(cube->non_manifold_edge_count(), 0);
  const BoxObstacle box{Vec3::Zero(), h, 0.0};
  std::mt19937 rng(11);
  for (const Vec3& p : probe_points(h, rng)) {
    const MeshPoint q = cube->closest_point(p);
    ASSERT_NEAR(q.signed_distance_m, signed_distance(box, p), 1e-14) << p.transpose();
    // The closest point and its normal give p back: point + distance · normal = p.
    EXPECT_TRUE((q.point_m + q.signed_distance_m * q.normal - p).norm() < 1e-14) << p.transpose();
    EXPECT_NEAR(q.normal.norm(), 1.0, 1e-12);
    if (signed_distance(box, p) > 0.0) {  // outside the closest point is unique
      const SurfacePoint s = closest_surface_point(box, p);
      EXPECT_LT((q.point_m - s.point_m).norm(), 1e-14) << p.transpose();
    }
  }
}

// Posed (turned about z and moved), the mesh is the box with that yaw and centre.
TEST(MeshObstacle, PosedCubeIsTheYawedBox) {
  const Vec3 h(0.1, 0.07, 0.05);
  const MeshObstacle mesh{box_mesh(h), RigidPose{Vec3(0.3, -0.2, 0.5), 0.6}};
  const BoxObstacle box{Vec3(0.3, -0.2, 0.5), h, 0.6};
  std::mt19937 rng(12);
  for (const Vec3& local : probe_points(h, rng)) {
    const Vec3 p = mesh.pose.apply(local);
    ASSERT_NEAR(signed_distance(mesh, p), signed_distance(box, p), 1e-12) << p.transpose();
    const SurfacePoint m = closest_surface_point(mesh, p);
    const double d = signed_distance(mesh, p);
    EXPECT_LT((m.point_m + d * m.normal - p).norm(), 1e-12);
  }
}

// A prism whose cross-section is a 20° wedge: outside its sharp edge, p − q may point against
// the normal of one of the two faces there, so a face normal would call p inside. The edge's
// pseudonormal (the sum of both) gets it right, whichever triangle wins the tie.
TEST(MeshObstacle, SharpEdgeSignComesFromTheEdgePseudonormal) {
  const double w = 0.18;  // half the base: tip angle 2·atan(0.18) = 20.4°
  Matrix3X v(6, 3);
  v << 1, 0, 0, 0, -w, 0, 0, w, 0, 1, 0, 1, 0, -w, 1, 0, w, 1;
  // The lower face (the tip's −y side) first, so that it wins ties at the tip edge.
  const MeshSolid wedge(v, {{1, 0, 3}, {1, 3, 4}, {0, 2, 5}, {0, 5, 3}, {2, 1, 4}, {2, 4, 5},
                            {3, 5, 4}, {0, 1, 2}});
  EXPECT_EQ(wedge.border_edge_count(), 0);
  const Vec3 lower_normal = Vec3(w, -1, 0).normalized();
  const Vec3 upper_normal = Vec3(w, 1, 0).normalized();
  const Vec3 u(0.5, std::sqrt(0.75), 0.0);  // 60° from the bisector: in the tip edge's region
  ASSERT_LT(u.dot(lower_normal), -0.5);     // a face normal would get the sign wrong
  ASSERT_GT(u.dot(upper_normal), 0.0);
  for (double z : {0.3, 0.5, 0.7}) {
    const Vec3 tip(1, 0, z);
    const MeshPoint q = wedge.closest_point(tip + 0.1 * u);
    EXPECT_NEAR(q.signed_distance_m, 0.1, 1e-12) << "z = " << z;
    EXPECT_LT((q.point_m - tip).norm(), 1e-12);
    // Inside, just behind the tip: minus the distance to the nearer (upper, by symmetry equal)
    // face.
    EXPECT_NEAR(wedge.signed_distance(Vec3(0.9, 0.0, z)), -0.1 * upper_normal.x(), 1e-12);
  }
}

// The icosphere's faces lie between the sphere of radius r and the concentric sphere r − s (s
// the sagitta): its solid is inside the ball and contains the ball shrunk by s, so its signed
// distance is at least the sphere's and at most the sphere's + s, everywhere.
TEST(MeshObstacle, IcosphereSignedDistanceIsTheSpheresWithinTheSagitta) {
  const double r = 0.05;
  const auto sphere_mesh = icosphere(r);
  EXPECT_EQ(sphere_mesh->border_edge_count(), 0);
  const double s = max_sagitta(*sphere_mesh, r);
  std::printf("icosphere r = 5 cm: %zu triangles, sagitta %.4f mm\n",
              sphere_mesh->triangles().size(), 1e3 * s);
  EXPECT_LT(s, 0.5e-3);  // the asset's promise: below 0.5 mm at r = 5 cm
  EXPECT_GT(s, 0.0);
  std::mt19937 rng(5);
  for (double radius : {0.0, 0.01, 0.04, 0.0495, 0.05, 0.0505, 0.06, 0.2, 5.0}) {
    for (int k = 0; k < 60; ++k) {
      const Vec3 p = radius * random_direction(rng);
      const double exact = p.norm() - r;
      const double d = sphere_mesh->signed_distance(p);
      ASSERT_GE(d, exact - 1e-12) << "at |p| = " << radius;
      ASSERT_LE(d, exact + s + 1e-12) << "at |p| = " << radius;
    }
  }
}

// Whatever order the BVH visits the triangles in, the result is the brute-force minimum of
// (distance, triangle index): the centre of a cube is equally near all twelve triangles.
TEST(MeshObstacle, ClosestTriangleIsTheBruteForceMinimumWithTiesToTheLowestIndex) {
  const auto sphere_mesh = icosphere(1.0);
  const auto cube = box_mesh(Vec3(1, 1, 1));
  std::mt19937 rng(3);
  for (const auto& mesh : {sphere_mesh, cube}) {
    for (int k = 0; k < 300; ++k) {
      // Many points on symmetry planes and vertex directions, where ties are common.
      Vec3 p = (0.5 + 0.01 * (k % 150)) * random_direction(rng);
      if (k % 3 == 0) p = mesh->vertices_m().row(k % mesh->vertices_m().rows()).transpose() * 1.3;
      if (k % 5 == 0) p.y() = 0.0;
      if (k == 0) p = Vec3::Zero();  // the centre
      double best = std::numeric_limits<double>::infinity();
      Index best_triangle = -1;
      for (std::size_t f = 0; f < mesh->triangles().size(); ++f) {
        const auto& t = mesh->triangles()[f];
        const double d2 =
            (p - closest_point_on_triangle(p, mesh->vertices_m().row(t[0]).transpose(),
                                           mesh->vertices_m().row(t[1]).transpose(),
                                           mesh->vertices_m().row(t[2]).transpose())
                     .point)
                .squaredNorm();
        if (d2 < best) {
          best = d2;
          best_triangle = static_cast<Index>(f);
        }
      }
      const MeshPoint q = mesh->closest_point(p);
      ASSERT_EQ(q.triangle, best_triangle) << p.transpose();
      ASSERT_EQ(std::abs(q.signed_distance_m), std::sqrt(best));
    }
  }
}

// Through push_out_of_obstacles a cube mesh moves vertices exactly as the box does.
TEST(MeshObstacle, PushOutMatchesTheBox) {
  const Vec3 h(0.1, 0.1, 0.02);
  const std::vector<Obstacle> mesh{MeshObstacle{box_mesh(h), RigidPose{Vec3(0, 0, 0.3), 0.2}}};
  const std::vector<Obstacle> box{BoxObstacle{Vec3(0, 0, 0.3), h, 0.2}};
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  Matrix3X x(300, 3);
  for (Index i = 0; i < x.rows(); ++i) x.row(i) << u(rng), u(rng), 0.3 + 0.3 * u(rng);
  const Eigen::VectorXd inv_mass = Eigen::VectorXd::Ones(x.rows());
  Matrix3X by_mesh = x, by_box = x;
  const int moved = push_out_of_obstacles(mesh, 0.002, inv_mass, by_mesh);
  EXPECT_EQ(moved, push_out_of_obstacles(box, 0.002, inv_mass, by_box));
  EXPECT_GT(moved, 20);
  EXPECT_LT((by_mesh - by_box).cwiseAbs().maxCoeff(), 1e-12);
  for (Index i = 0; i < x.rows(); ++i)
    EXPECT_GE(signed_distance(mesh[0], by_mesh.row(i).transpose()), 0.002 - 1e-12);
}

// An open mesh (one triangle) still gives exact distances; its back is "inside" (the header's
// warning), and its three edges are border edges.
TEST(MeshObstacle, OpenMeshHasBorderEdgesAndAOneSidedSign) {
  Matrix3X v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  const MeshSolid triangle(v, {{0, 1, 2}});
  EXPECT_EQ(triangle.border_edge_count(), 3);
  EXPECT_DOUBLE_EQ(triangle.signed_distance(Vec3(0.2, 0.2, 0.5)), 0.5);
  EXPECT_DOUBLE_EQ(triangle.signed_distance(Vec3(0.2, 0.2, -0.5)), -0.5);
  EXPECT_DOUBLE_EQ(triangle.signed_distance(Vec3(-3, 0.5, 4)), 5.0);  // beside its edge
}

TEST(MeshObstacle, BadMeshesThrowSayingWhatIsWrong) {
  const auto message = [](Matrix3X v, Triangles t) -> std::string {
    try {
      MeshSolid mesh(std::move(v), std::move(t));
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no error";
  };
  Matrix3X v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  EXPECT_NE(message(v, {}).find("no triangles"), std::string::npos);
  EXPECT_NE(message(v, {{0, 1, 3}}).find("triangle 0 has vertex index 3, outside 0..2"),
            std::string::npos);
  EXPECT_NE(message(v, {{0, 1, 2}, {0, 1, 1}}).find("triangle 1 repeats a vertex"),
            std::string::npos);
  Matrix3X bad = v;
  bad(1, 2) = std::nan("");
  EXPECT_NE(message(bad, {{0, 1, 2}}).find("vertex 1 is not finite"), std::string::npos);
  EXPECT_THROW(check_obstacles({MeshObstacle{}}), std::invalid_argument);  // no solid
}

}  // namespace
}  // namespace weft::sim
