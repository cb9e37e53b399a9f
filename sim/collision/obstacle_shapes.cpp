// Signed distances and closest surface points of the box, cylinder and capsule obstacles.
// The box and the cylinder use the standard exact distance to an axis-aligned box (the
// cylinder as the 2-D box 0 ≤ r ≤ R, |z| ≤ H/2 in its radial–axial half-plane): outside, the
// length of the part of (|p| − h) that is positive; inside, minus the distance to the nearest
// face (Quilez, "Distance functions", the sdBox and sdCappedCylinder derivations).

#include "sim/collision/obstacle_shapes.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace weft::sim {
namespace {

// The box's local coordinates of p: components along its x, y, z axes from its centre.
Vec3 to_box_local(const BoxObstacle& box, const Vec3& p) {
  const Vec3 d = p - box.center_m;
  return {d.dot(box_axis_x(box)), d.dot(box_axis_y(box)), d.z()};
}

Vec3 from_box_local(const BoxObstacle& box, const Vec3& local) {
  return box.center_m + local.x() * box_axis_x(box) + local.y() * box_axis_y(box) +
         local.z() * Vec3::UnitZ();
}

// A point of the cylinder's half-plane: axial coordinate z, distance r from the axis, and the
// unit radial direction (fixed, orthogonal to the axis, when p is on the axis).
struct AxialCoordinates {
  double z;
  double r;
  Vec3 radial;
};

AxialCoordinates to_axial(const CylinderObstacle& c, const Vec3& p) {
  const Vec3 d = p - c.center_m;
  const double z = d.dot(c.axis);
  const Vec3 w = d - z * c.axis;
  const double r = w.norm();
  return {z, r, r > 0.0 ? Vec3(w / r) : Vec3(c.axis.unitOrthogonal())};
}

// The nearest point of the capsule's axis segment to p.
Vec3 closest_on_segment(const CapsuleObstacle& c, const Vec3& p) {
  const Vec3 ab = c.b_m - c.a_m;
  const double ll = ab.squaredNorm();
  if (!(ll > 0.0)) return c.a_m;
  const double s = std::clamp((p - c.a_m).dot(ab) / ll, 0.0, 1.0);
  return c.a_m + s * ab;
}

// Outside a convex body whose nearest point to p is q: the unit vector from q to p. None when
// p is outside only by rounding (q = p): the caller then treats p as on the nearest face.
std::optional<SurfacePoint> outside(const Vec3& q, const Vec3& p) {
  const Vec3 d = p - q;
  const double length = d.norm();
  if (!(length > 0.0)) return std::nullopt;
  return SurfacePoint{q, d / length};
}

}  // namespace

Vec3 box_axis_x(const BoxObstacle& box) {
  return {std::cos(box.yaw_rad), std::sin(box.yaw_rad), 0.0};
}

Vec3 box_axis_y(const BoxObstacle& box) {
  return {-std::sin(box.yaw_rad), std::cos(box.yaw_rad), 0.0};
}

double signed_distance(const BoxObstacle& box, const Vec3& p) {
  const Vec3 q = to_box_local(box, p).cwiseAbs() - box.half_size_m;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

double signed_distance(const CylinderObstacle& c, const Vec3& p) {
  const AxialCoordinates a = to_axial(c, p);
  const double dr = a.r - c.radius_m, dz = std::fabs(a.z) - 0.5 * c.height_m;
  return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0)) + std::min(std::max(dr, dz), 0.0);
}

double signed_distance(const CapsuleObstacle& c, const Vec3& p) {
  return (p - closest_on_segment(c, p)).norm() - c.radius_m;
}

SurfacePoint closest_surface_point(const BoxObstacle& box, const Vec3& p) {
  const Vec3 local = to_box_local(box, p);
  const Vec3& h = box.half_size_m;
  const Vec3 clamped = local.cwiseMax(-h).cwiseMin(h);
  if (clamped != local)
    if (const auto q = outside(from_box_local(box, clamped), p)) return *q;
  // Inside or on the surface: out through the nearest face.
  int face = 0;
  for (int i = 1; i < 3; ++i)
    if (h[i] - std::fabs(local[i]) < h[face] - std::fabs(local[face])) face = i;
  const double sign = local[face] >= 0.0 ? 1.0 : -1.0;
  Vec3 on_face = local;
  on_face[face] = sign * h[face];
  Vec3 local_normal = Vec3::Zero();
  local_normal[face] = sign;
  const Vec3 normal = local_normal.x() * box_axis_x(box) + local_normal.y() * box_axis_y(box) +
                      local_normal.z() * Vec3::UnitZ();
  return {from_box_local(box, on_face), normal};
}

SurfacePoint closest_surface_point(const CylinderObstacle& c, const Vec3& p) {
  const AxialCoordinates a = to_axial(c, p);
  const double half_height = 0.5 * c.height_m;
  const double r = std::min(a.r, c.radius_m);
  const double z = std::clamp(a.z, -half_height, half_height);
  const auto at = [&](double zz, double rr) {
    return Vec3(c.center_m + zz * c.axis + rr * a.radial);
  };
  if (r != a.r || z != a.z)
    if (const auto q = outside(at(z, r), p)) return *q;
  // Inside or on the surface: the side if strictly nearer than the nearer cap.
  const double sign = a.z >= 0.0 ? 1.0 : -1.0;
  if (c.radius_m - a.r < half_height - std::fabs(a.z)) return {at(a.z, c.radius_m), a.radial};
  return {at(sign * half_height, a.r), sign * c.axis};
}

SurfacePoint closest_surface_point(const CapsuleObstacle& c, const Vec3& p) {
  const Vec3 s = closest_on_segment(c, p);
  const Vec3 d = p - s;
  const double length = d.norm();
  Vec3 direction;
  if (length > 0.0) {
    direction = d / length;
  } else {
    const Vec3 ab = c.b_m - c.a_m;
    direction = ab.squaredNorm() > 0.0 ? Vec3(ab.normalized().unitOrthogonal()) : Vec3::UnitZ();
  }
  return {s + c.radius_m * direction, direction};
}

}  // namespace weft::sim
