// Obstacles as render objects (see obstacle_meshes.h).

#include "app/obstacle_meshes.h"

#include <cmath>

#include "render/primitives.h"

namespace weft::app {
namespace {

constexpr double coincidence_tolerance = 1e-9;  // unit normal components and metres

bool is_rendered_ground(const sim::PlaneObstacle& plane, const render::RenderSettings& s) {
  return s.ground && plane.normal.z() >= 1.0 - coincidence_tolerance &&
         std::fabs(plane.normal.dot(plane.point_m) - s.ground_z_m) <= coincidence_tolerance;
}

}  // namespace

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
