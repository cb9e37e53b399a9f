// Obstacles as render objects (see obstacle_meshes.h).

#include "app/run/obstacle_meshes.h"

#include <cmath>

#include "app/scene/scene.h"
#include "base/constants.h"
#include "render/primitives.h"

namespace weft::app {
namespace {

constexpr double coincidence_tolerance = 1e-9;  // unit normal components and metres

// A mesh obstacle's triangles in the world, each with its own three corners (see the header).
render::RenderMesh make_obstacle_mesh(const sim::MeshObstacle& mesh) {
  const sim::Matrix3X& vertices = mesh.solid->vertices_m();
  const auto& triangles = mesh.solid->triangles();
  const double cos_crease = std::cos(mesh_crease_angle_deg * base::kPi / 180.0);
  std::vector<Eigen::Vector3d> world(static_cast<std::size_t>(vertices.rows()));
  for (std::size_t i = 0; i < world.size(); ++i)
    world[i] = mesh.pose.apply(vertices.row(static_cast<Eigen::Index>(i)).transpose());
  std::vector<Eigen::Vector3d> area_normal(triangles.size());  // |n| = twice the area
  std::vector<std::vector<std::size_t>> around(world.size());  // triangles at each vertex
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const auto& t = triangles[f];
    area_normal[f] = (world[t[1]] - world[t[0]]).cross(world[t[2]] - world[t[0]]);
    for (sim::Index v : t) around[v].push_back(f);
  }
  render::RenderMesh out;
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Eigen::Vector3d own = area_normal[f].normalized();
    const auto first = static_cast<std::uint32_t>(out.positions.size());
    for (sim::Index v : triangles[f]) {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      for (std::size_t g : around[v])
        if (area_normal[g].normalized().dot(own) >= cos_crease) n += area_normal[g];
      out.positions.push_back(world[v].cast<float>());
      out.normals.push_back((n.squaredNorm() > 0.0 ? n.normalized() : own).cast<float>());
    }
    out.triangles.push_back({first, first + 1, first + 2});
  }
  return out;
}

}  // namespace

std::vector<render::RenderObject> obstacle_render_objects(
    const std::vector<sim::Obstacle>& obstacles, const std::vector<sim::ObstacleMotion>& motions,
    double time_s, const render::RenderSettings& settings) {
  return obstacle_render_objects(sim::posed_obstacles(obstacles, motions, time_s), settings);
}

std::vector<render::RenderObject> obstacle_render_objects(
    const std::vector<sim::Obstacle>& obstacles, const render::RenderSettings& settings) {
  std::vector<render::RenderObject> objects;
  for (const sim::Obstacle& obstacle : obstacles) {
    if (const auto* sphere = std::get_if<sim::SphereObstacle>(&obstacle)) {
      objects.push_back(
          {render::make_sphere_mesh(sphere->center_m, sphere->radius_m), settings.obstacle_color});
      continue;
    }
    if (const auto* box = std::get_if<sim::BoxObstacle>(&obstacle)) {
      objects.push_back({render::make_box_mesh(box->center_m, box->half_size_m, box->yaw_rad),
                         settings.obstacle_color});
      continue;
    }
    if (const auto* c = std::get_if<sim::CylinderObstacle>(&obstacle)) {
      objects.push_back({render::make_cylinder_mesh(c->center_m, c->axis, c->radius_m, c->height_m),
                         settings.obstacle_color});
      continue;
    }
    if (const auto* c = std::get_if<sim::CapsuleObstacle>(&obstacle)) {
      objects.push_back(
          {render::make_capsule_mesh(c->a_m, c->b_m, c->radius_m), settings.obstacle_color});
      continue;
    }
    if (const auto* mesh = std::get_if<sim::MeshObstacle>(&obstacle)) {
      objects.push_back({make_obstacle_mesh(*mesh), settings.obstacle_color});
      continue;
    }
    const auto& plane = std::get<sim::PlaneObstacle>(obstacle);
    if (is_rendered_ground(plane, settings)) continue;
    const Eigen::Vector3d n = plane.normal.normalized();
    const Eigen::Vector3d& target = settings.camera.target;
    const Eigen::Vector3d centre = target - (target - plane.point_m).dot(n) * n;
    objects.push_back(
        {render::make_square_patch(centre, n, plane_patch_half_size_m), settings.obstacle_color});
  }
  return objects;
}

}  // namespace weft::app
