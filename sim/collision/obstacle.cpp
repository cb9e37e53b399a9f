// Vertex–obstacle collisions against analytic shapes (seed 003, "Cloth–Object Collisions":
// a vertex inside an object is "repelled" to the closest point on its surface). See
// obstacle.h for the order in which overlapping obstacles are resolved.

#include "sim/collision/obstacle.h"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace weft::sim {
namespace {

// Gauss–Seidel passes over the obstacles per vertex before the two-obstacle fallback. One pass
// suffices for a single obstacle and for obstacles meeting at a convex corner.
constexpr int max_passes = 4;
constexpr double unit_tolerance = 1e-6;  // how far from unit length a plane normal may be

// The closest point at distance t outside the obstacle: on the offset surface (a sphere of
// radius r + t, or the plane moved by t along its normal).
Vec3 to_offset_surface(const SphereObstacle& s, const Vec3& p, double t) {
  const Vec3 r = p - s.center_m;
  const double length = r.norm();
  const Vec3 direction = length > 0.0 ? Vec3(r / length) : Vec3::UnitZ();
  return s.center_m + (s.radius_m + t) * direction;
}

Vec3 to_offset_surface(const PlaneObstacle& s, const Vec3& p, double t) {
  return p + (t - (p - s.point_m).dot(s.normal)) * s.normal;
}

// Signed distance to each shape, positive outside, m (obstacle_shapes.h for the other three).
double shape_distance(const SphereObstacle& s, const Vec3& p) {
  return (p - s.center_m).norm() - s.radius_m;
}

double shape_distance(const PlaneObstacle& s, const Vec3& p) {
  return (p - s.point_m).dot(s.normal);
}

template <class Shape>
double shape_distance(const Shape& s, const Vec3& p) {
  return signed_distance(s, p);
}

// A box, cylinder or capsule: the closest surface point moved out along its normal.
template <class Shape>
Vec3 to_offset_surface(const Shape& s, const Vec3& p, double t) {
  const SurfacePoint q = closest_surface_point(s, p);
  return q.point_m + t * q.normal;
}

Vec3 to_offset_surface(const Obstacle& o, const Vec3& p, double t) {
  return std::visit([&](const auto& shape) { return to_offset_surface(shape, p, t); }, o);
}

// A circle in space: centre, unit axis (normal of its plane), radius.
struct Circle {
  Vec3 center;
  Vec3 axis;
  double radius;
};

// Where the sphere |x − c| = R meets the plane n·x = h (n unit); none when they do not meet.
std::optional<Circle> sphere_plane_circle(const Vec3& c, double R, const Vec3& n, double h) {
  const double height = n.dot(c) - h;  // signed distance of the centre from the plane
  if (!(std::fabs(height) < R)) return std::nullopt;
  return Circle{c - height * n, n, std::sqrt(R * R - height * height)};
}

Vec3 closest_on_circle(const Circle& k, const Vec3& p) {
  Vec3 w = p - k.center;
  w -= w.dot(k.axis) * k.axis;
  const double length = w.norm();
  // On the axis every circle point is equally near: pick a fixed one (deterministic).
  const Vec3 direction = length > 1e-12 * k.radius ? Vec3(w / length) : k.axis.unitOrthogonal();
  return k.center + k.radius * direction;
}

// The nearest point to p on the curve where the offset surfaces (at distance t) of a and b
// intersect: a circle (sphere–plane, sphere–sphere) or a line (plane–plane). None when they do
// not intersect (disjoint or nested spheres, parallel planes), and none unless both a and b are
// spheres or planes.
std::optional<Vec3> closest_on_offset_intersection(const Obstacle& a, const Obstacle& b,
                                                   const Vec3& p, double t) {
  const auto sphere_or_plane = [](const Obstacle& o) {
    return std::holds_alternative<SphereObstacle>(o) || std::holds_alternative<PlaneObstacle>(o);
  };
  if (!sphere_or_plane(a) || !sphere_or_plane(b)) return std::nullopt;
  const auto* sphere_a = std::get_if<SphereObstacle>(&a);
  const auto* sphere_b = std::get_if<SphereObstacle>(&b);
  const auto* plane_a = std::get_if<PlaneObstacle>(&a);
  const auto* plane_b = std::get_if<PlaneObstacle>(&b);
  const auto offset_height = [t](const PlaneObstacle* s) { return s->normal.dot(s->point_m) + t; };

  std::optional<Circle> circle;
  if (sphere_a && sphere_b) {
    // The circle lies in the radical plane u·x = u·c_a + d_a of the two offset spheres.
    const double Ra = sphere_a->radius_m + t, Rb = sphere_b->radius_m + t;
    const Vec3 between = sphere_b->center_m - sphere_a->center_m;
    const double d = between.norm();
    if (!(d > 0.0)) return std::nullopt;
    const Vec3 u = between / d;
    const double d_a = (d * d + Ra * Ra - Rb * Rb) / (2.0 * d);
    circle = sphere_plane_circle(sphere_a->center_m, Ra, u, u.dot(sphere_a->center_m) + d_a);
  } else if (sphere_a || sphere_b) {
    const SphereObstacle* s = sphere_a ? sphere_a : sphere_b;
    const PlaneObstacle* plane = plane_a ? plane_a : plane_b;
    circle = sphere_plane_circle(s->center_m, s->radius_m + t, plane->normal, offset_height(plane));
  } else {
    // Two planes n1·x = h1, n2·x = h2 meet on the line x0 + s·(n1 × n2).
    const Vec3& n1 = plane_a->normal;
    const Vec3& n2 = plane_b->normal;
    const Vec3 direction = n1.cross(n2);
    const double dd = direction.squaredNorm();
    if (!(dd > 1e-12)) return std::nullopt;
    const Vec3 x0 = (offset_height(plane_a) * n2.cross(direction) +
                     offset_height(plane_b) * direction.cross(n1)) /
                    dd;
    return x0 + ((p - x0).dot(direction) / dd) * direction;
  }
  if (!circle) return std::nullopt;
  return closest_on_circle(*circle, p);
}

// Moves p out of every obstacle's thickness layer; see push_out_of_obstacles in obstacle.h.
void resolve_vertex(const std::vector<Obstacle>& obstacles, double t, Vec3& p) {
  // A projection lands on an offset surface up to rounding: within `rounding` counts as clear.
  const auto rounding = [&] { return 1e-13 * (1.0 + p.lpNorm<Eigen::Infinity>()); };
  bool clear = false;
  for (int pass = 0; pass < max_passes && !clear; ++pass) {
    for (const Obstacle& o : obstacles)
      if (signed_distance(o, p) < t) p = to_offset_surface(o, p, t);
    clear = true;
    for (const Obstacle& o : obstacles) clear = clear && signed_distance(o, p) >= t - rounding();
  }
  if (clear) return;

  // Caught between obstacles: the one it is deepest in, and the nearest of the others.
  std::size_t deepest = 0, nearest = obstacles.size();
  for (std::size_t k = 1; k < obstacles.size(); ++k)
    if (signed_distance(obstacles[k], p) < signed_distance(obstacles[deepest], p)) deepest = k;
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    if (k == deepest) continue;
    if (nearest == obstacles.size() ||
        signed_distance(obstacles[k], p) < signed_distance(obstacles[nearest], p))
      nearest = k;
  }
  if (nearest == obstacles.size()) return;  // unreachable: one obstacle is always resolved
  if (const auto q = closest_on_offset_intersection(obstacles[deepest], obstacles[nearest], p, t))
    p = *q;
}

bool clear_of_all(const std::vector<Obstacle>& obstacles, double t, const Vec3& p) {
  for (const Obstacle& o : obstacles)
    if (signed_distance(o, p) < t) return false;
  return true;
}

// Coulomb friction for a vertex pushed from `predicted` to p (see obstacle.h): takes back the
// part of its step from `start` tangent to the push, up to friction × the push distance.
void apply_friction(const std::vector<Obstacle>& obstacles, double t, double friction,
                    const Vec3& start, const Vec3& predicted, Vec3& p) {
  const Vec3 push = p - predicted;
  const double depth = push.norm();
  if (!(depth > 0.0)) return;
  const Vec3 n = push / depth;
  Vec3 slide = p - start;
  slide -= slide.dot(n) * n;
  const double length = slide.norm();
  const double limit = friction * depth;
  p -= length <= limit ? slide : Vec3((limit / length) * slide);
  // Convex surfaces bend away from their tangent plane, but a concave corner may not: if the
  // frictional move went back in, resolve again without friction.
  if (!clear_of_all(obstacles, t, p)) resolve_vertex(obstacles, t, p);
}

// Throws "<what> must be finite and > 0, got <value> m" unless it is.
void check_positive(const std::string& what, double value_m) {
  if (!(value_m > 0.0) || !std::isfinite(value_m))
    throw std::invalid_argument(what + " must be finite and > 0, got " + std::to_string(value_m) +
                                " m");
}

void check_unit(const std::string& what, const Vec3& v) {
  const double length = v.norm();
  if (!(std::fabs(length - 1.0) <= unit_tolerance))
    throw std::invalid_argument(what + " must be a unit vector, got length " +
                                std::to_string(length));
}

void check_arguments(const std::vector<Obstacle>& obstacles, double thickness_m,
                     const Eigen::VectorXd& inv_mass, const Matrix3X& x) {
  if (inv_mass.size() != x.rows()) {
    throw std::invalid_argument("push_out_of_obstacles: " + std::to_string(inv_mass.size()) +
                                " inverse masses for " + std::to_string(x.rows()) + " vertices");
  }
  if (!(thickness_m >= 0.0) || !std::isfinite(thickness_m)) {
    throw std::invalid_argument("push_out_of_obstacles: thickness must be finite and >= 0, got " +
                                std::to_string(thickness_m) + " m");
  }
  check_obstacles(obstacles);
}

// Every push_out_of_obstacles overload; x_start is null without friction, step_motions null or
// empty when no obstacle moves.
// `vertices`: those to check, or null for all.
int push_out(const std::vector<Obstacle>& obstacles, double thickness_m,
             const Eigen::VectorXd& inv_mass, const Matrix3X* x_start, double friction,
             const std::vector<RigidPose>* step_motions, const std::vector<Index>* vertices,
             Matrix3X& x) {
  int moved = 0;
  if (obstacles.empty()) return moved;
  const auto count = static_cast<Index>(vertices ? vertices->size() : static_cast<std::size_t>(x.rows()));
  for (Index k = 0; k < count; ++k) {
    const Index i = vertices ? (*vertices)[static_cast<std::size_t>(k)] : k;
    if (!(inv_mass[i] > 0.0)) continue;  // pinned
    const Vec3 predicted = x.row(i).transpose();
    if (clear_of_all(obstacles, thickness_m, predicted)) continue;  // left exactly as it was
    Vec3 p = predicted;
    resolve_vertex(obstacles, thickness_m, p);
    if (x_start && friction > 0.0) {
      Vec3 start = x_start->row(i).transpose();
      if (step_motions && !step_motions->empty()) {  // friction against the moving surface
        const std::size_t contact = obstacles.size() > 1 ? nearest_obstacle(obstacles, p) : 0;
        start = (*step_motions)[contact].apply(start);
      }
      apply_friction(obstacles, thickness_m, friction, start, predicted, p);
    }
    if (p != predicted) {
      x.row(i) = p.transpose();
      ++moved;
    }
  }
  return moved;
}

}  // namespace

double signed_distance(const Obstacle& obstacle, const Vec3& p) {
  return std::visit([&](const auto& shape) { return shape_distance(shape, p); }, obstacle);
}

std::size_t nearest_obstacle(const std::vector<Obstacle>& obstacles, const Vec3& p) {
  std::size_t nearest = 0;
  double nearest_m = signed_distance(obstacles[0], p);
  for (std::size_t k = 1; k < obstacles.size(); ++k) {
    const double d = signed_distance(obstacles[k], p);
    if (d < nearest_m) {
      nearest_m = d;
      nearest = k;
    }
  }
  return nearest;
}

Vec3 outward_normal(const Obstacle& obstacle, const Vec3& p) {
  if (const auto* s = std::get_if<SphereObstacle>(&obstacle)) {
    const Vec3 r = p - s->center_m;
    const double length = r.norm();
    return length > 0.0 ? Vec3(r / length) : Vec3::UnitZ();  // as to_offset_surface
  }
  if (const auto* plane = std::get_if<PlaneObstacle>(&obstacle)) return plane->normal;
  return std::visit(
      [&](const auto& shape) -> Vec3 {
        using Shape = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<Shape, SphereObstacle> || std::is_same_v<Shape, PlaneObstacle>)
          return Vec3::UnitZ();  // handled above
        else
          return closest_surface_point(shape, p).normal;
      },
      obstacle);
}

void check_obstacles(const std::vector<Obstacle>& obstacles) {
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const std::string name = "obstacle " + std::to_string(k) + ": ";
    if (const auto* s = std::get_if<SphereObstacle>(&obstacles[k])) {
      if (!s->center_m.allFinite())
        throw std::invalid_argument(name + "sphere centre must be finite");
      check_positive(name + "sphere radius", s->radius_m);
    } else if (const auto* plane = std::get_if<PlaneObstacle>(&obstacles[k])) {
      if (!plane->point_m.allFinite())
        throw std::invalid_argument(name + "plane point must be finite");
      check_unit(name + "plane normal", plane->normal);
    } else if (const auto* box = std::get_if<BoxObstacle>(&obstacles[k])) {
      if (!box->center_m.allFinite())
        throw std::invalid_argument(name + "box centre must be finite");
      for (int i = 0; i < 3; ++i)
        check_positive(name + "box half size " + "xyz"[i], box -> half_size_m[i]);
      if (!std::isfinite(box->yaw_rad))
        throw std::invalid_argument(name + "box yaw must be finite");
    } else if (const auto* c = std::get_if<CylinderObstacle>(&obstacles[k])) {
      if (!c->center_m.allFinite())
        throw std::invalid_argument(name + "cylinder centre must be finite");
      check_unit(name + "cylinder axis", c->axis);
      check_positive(name + "cylinder radius", c->radius_m);
      check_positive(name + "cylinder height", c->height_m);
    } else if (const auto* capsule = std::get_if<CapsuleObstacle>(&obstacles[k])) {
      if (!capsule->a_m.allFinite() || !capsule->b_m.allFinite())
        throw std::invalid_argument(name + "capsule endpoints must be finite");
      check_positive(name + "capsule radius", capsule->radius_m);
    } else {
      const auto& mesh = std::get<MeshObstacle>(obstacles[k]);
      if (!mesh.solid) throw std::invalid_argument(name + "mesh has no solid");
      if (!mesh.pose.translation_m.allFinite() || !std::isfinite(mesh.pose.yaw_rad))
        throw std::invalid_argument(name + "mesh pose must be finite");
    }
  }
}

int push_out_of_obstacles(const std::vector<Obstacle>& obstacles, double thickness_m,
                          const Eigen::VectorXd& inv_mass, Matrix3X& x) {
  check_arguments(obstacles, thickness_m, inv_mass, x);
  return push_out(obstacles, thickness_m, inv_mass, nullptr, 0.0, nullptr, nullptr, x);
}

int push_out_of_obstacles(const std::vector<Obstacle>& obstacles, double thickness_m,
                          const Eigen::VectorXd& inv_mass, const std::vector<Index>& vertices,
                          Matrix3X& x) {
  check_arguments(obstacles, thickness_m, inv_mass, x);
  for (const Index v : vertices)
    if (v < 0 || v >= x.rows())
      throw std::invalid_argument("push_out_of_obstacles: vertex " + std::to_string(v) +
                                  " is not one of the " + std::to_string(x.rows()) + " vertices");
  return push_out(obstacles, thickness_m, inv_mass, nullptr, 0.0, nullptr, &vertices, x);
}

int push_out_of_obstacles(const std::vector<Obstacle>& obstacles, double thickness_m,
                          const Eigen::VectorXd& inv_mass, const Matrix3X& x_start, double friction,
                          Matrix3X& x) {
  return push_out_of_obstacles(obstacles, {}, thickness_m, inv_mass, x_start, friction, x);
}

int push_out_of_obstacles(const std::vector<Obstacle>& obstacles,
                          const std::vector<RigidPose>& step_motions, double thickness_m,
                          const Eigen::VectorXd& inv_mass, const Matrix3X& x_start, double friction,
                          Matrix3X& x) {
  check_arguments(obstacles, thickness_m, inv_mass, x);
  if (!step_motions.empty() && step_motions.size() != obstacles.size()) {
    throw std::invalid_argument("push_out_of_obstacles: " + std::to_string(step_motions.size()) +
                                " step motions for " + std::to_string(obstacles.size()) +
                                " obstacles");
  }
  if (x_start.rows() != x.rows()) {
    throw std::invalid_argument("push_out_of_obstacles: " + std::to_string(x_start.rows()) +
                                " start positions for " + std::to_string(x.rows()) + " vertices");
  }
  if (!(friction >= 0.0) || !std::isfinite(friction)) {
    throw std::invalid_argument("push_out_of_obstacles: friction must be finite and >= 0, got " +
                                std::to_string(friction));
  }
  return push_out(obstacles, thickness_m, inv_mass, &x_start, friction, &step_motions, nullptr, x);
}

}  // namespace weft::sim
