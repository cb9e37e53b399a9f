// Pins and stands as render objects (see support_meshes.h).

#include "app/run/support_meshes.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "base/constants.h"
#include "render/primitives.h"

namespace weft::app {
namespace {

constexpr double held_by_obstacle_m = 0.005;  // a pin this close to an obstacle is held by it
constexpr double neighbour_edges = 1.5;       // pins this many edge lengths apart are neighbours
constexpr double line_tolerance_edges = 0.25;  // off a held edge's segment by at most this
constexpr double pole_max_tilt_deg = 25.0;

// Groups of neighbouring pins (union-find over pairs within `reach`), in order of their first
// member, members in the pins' order: the same groups for the same input, whatever the frame.
std::vector<std::vector<Eigen::Vector3d>> neighbour_groups(const std::vector<Eigen::Vector3d>& p,
                                                           double reach) {
  std::vector<std::size_t> parent(p.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  const auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j)
      if ((p[i] - p[j]).norm() <= reach) parent[std::max(root(i), root(j))] = std::min(root(i), root(j));
  std::vector<std::vector<Eigen::Vector3d>> groups;
  std::vector<std::size_t> group_of(p.size(), p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t r = root(i);
    if (group_of[r] == p.size()) {
      group_of[r] = groups.size();
      groups.emplace_back();
    }
    groups[group_of[r]].push_back(p[i]);
  }
  return groups;
}

// The point of `points` farthest from `from`.
Eigen::Vector3d farthest(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& from) {
  return *std::max_element(points.begin(), points.end(), [&](const auto& a, const auto& b) {
    return (a - from).squaredNorm() < (b - from).squaredNorm();
  });
}

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// A rod along the held edge a–b, reaching down to the ground when it stands nearly upright.
render::RenderMesh rod_mesh(Eigen::Vector3d a, Eigen::Vector3d b, double edge_m,
                            const render::RenderSettings& s) {
  const double radius = std::clamp(0.35 * edge_m, 0.003, 0.012);
  if (a.z() > b.z()) std::swap(a, b);  // a the lower end
  const Eigen::Vector3d along = (b - a).normalized();
  a -= 2.0 * radius * along;
  b += 2.0 * radius * along;
  const double cos_tilt = std::cos(pole_max_tilt_deg * base::kPi / 180.0);
  if (s.ground && along.z() >= cos_tilt && a.z() > s.ground_z_m) {
    a -= ((a.z() - s.ground_z_m) / along.z()) * along;  // the pole meets the ground
    b += 4.0 * radius * along;
  }
  return render::make_capsule_mesh(a, b, radius, 24, 6);
}

// A clip on the pinned point p, its wide side along `across` (horizontal, may be zero).
render::RenderMesh clip_mesh(const Eigen::Vector3d& p, const Eigen::Vector3d& across,
                             double edge_m) {
  const double width = std::clamp(2.5 * edge_m, 0.012, 0.04);
  const double yaw = across.head<2>().squaredNorm() > 0.0 ? std::atan2(across.y(), across.x()) : 0.0;
  const Eigen::Vector3d half(0.5 * width, 0.2 * width, 0.35 * width);
  return render::make_box_mesh(p + Eigen::Vector3d(0.0, 0.0, 0.45 * half.z()), half, yaw);
}

bool held_by_obstacle(const Eigen::Vector3d& p, const std::vector<sim::Obstacle>& obstacles) {
  return std::any_of(obstacles.begin(), obstacles.end(), [&](const sim::Obstacle& o) {
    return sim::signed_distance(o, p) < held_by_obstacle_m;
  });
}

// A stem from the ground up to height `top` under (x, y), with a round foot.
void add_stand(double x, double y, double top, double size_m, const render::RenderSettings& s,
               std::vector<render::RenderObject>& out) {
  const double gap = top - s.ground_z_m;
  const double stem = std::clamp(0.1 * size_m, 0.004, 0.025);
  const double foot_height = std::min(0.01, 0.25 * gap);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  out.push_back({render::make_cylinder_mesh({x, y, s.ground_z_m + 0.5 * gap}, up, stem, gap, 32),
                 s.support_color});
  out.push_back({render::make_cylinder_mesh({x, y, s.ground_z_m + 0.5 * foot_height}, up,
                                            std::max(0.5 * size_m, 3.0 * stem), foot_height, 64),
                 s.support_color});
}

}  // namespace

std::vector<render::RenderObject> pin_support_objects(const std::vector<sim::Index>& pinned,
                                                      const sim::Matrix3X& x, double edge_m,
                                                      const std::vector<sim::Obstacle>& obstacles,
                                                      const render::RenderSettings& settings) {
  std::vector<render::RenderObject> out;
  if (!settings.supports || !(edge_m > 0.0)) return out;
  std::vector<Eigen::Vector3d> points;
  for (sim::Index v : pinned) {
    const Eigen::Vector3d p = x.row(v).transpose();
    if (p.allFinite() && !held_by_obstacle(p, obstacles)) points.push_back(p);
  }
  const auto groups = neighbour_groups(points, neighbour_edges * edge_m);
  for (const auto& group : groups) {
    const Eigen::Vector3d a = farthest(group, group.front()), b = farthest(group, a);
    const bool line = group.size() >= 3 &&
                      std::all_of(group.begin(), group.end(), [&](const Eigen::Vector3d& p) {
                        return distance_to_segment(p, a, b) <= line_tolerance_edges * edge_m;
                      });
    if (line) {
      out.push_back({rod_mesh(a, b, edge_m, settings), settings.support_color});
      continue;
    }
    for (const Eigen::Vector3d& p : group) {
      // The wide side along the line to the nearest other pin: a clip bites the cloth's edge.
      Eigen::Vector3d across = Eigen::Vector3d::Zero();
      double nearest = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& q : points) {
        const double d = (q - p).norm();
        if (d > 0.0 && d < nearest) nearest = d, across = q - p;
      }
      out.push_back({clip_mesh(p, across, edge_m), settings.support_color});
    }
  }
  return out;
}

std::vector<render::RenderObject> stand_objects(const std::vector<sim::Obstacle>& obstacles,
                                                const render::RenderSettings& settings) {
  std::vector<render::RenderObject> out;
  if (!settings.supports || !settings.ground) return out;
  constexpr double min_gap_m = 0.001;
  for (const sim::Obstacle& obstacle : obstacles) {
    if (const auto* sphere = std::get_if<sim::SphereObstacle>(&obstacle)) {
      const Eigen::Vector3d& c = sphere->center_m;
      const double bottom = c.z() - sphere->radius_m;
      // The stem reaches a little into the sphere, so that no gap shows at its bottom.
      if (bottom - settings.ground_z_m > min_gap_m)
        add_stand(c.x(), c.y(), bottom + 0.2 * sphere->radius_m, sphere->radius_m, settings, out);
    } else if (const auto* disc = std::get_if<sim::CylinderObstacle>(&obstacle)) {
      const Eigen::Vector3d& c = disc->center_m;
      const double bottom = c.z() - 0.5 * disc->height_m;
      if (std::abs(disc->axis.z()) > 0.999 && bottom - settings.ground_z_m > min_gap_m)
        add_stand(c.x(), c.y(), bottom, disc->radius_m, settings, out);
    }
  }
  return out;
}

double median_rest_edge_m(const sim::ClothMesh& mesh) {
  std::vector<double> lengths;
  for (const auto& t : mesh.triangles()) {
    for (int k = 0; k < 3; ++k)
      lengths.push_back((mesh.rest_positions.row(t[k]) - mesh.rest_positions.row(t[(k + 1) % 3])).norm());
  }
  if (lengths.empty()) return 0.0;
  auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  return *middle;
}

}  // namespace weft::app
