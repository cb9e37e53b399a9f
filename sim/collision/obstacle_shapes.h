#pragma once
// Solid analytic obstacles beyond the sphere and the plane: a box (a pedestal), a finite
// cylinder (a Cusick support disc is a short one) and a capsule. Each comes with two pure
// functions: its exact signed distance and its closest surface point with the outward normal
// there, from which the push-out of obstacle.h moves a vertex to the offset surface
// point + thickness·normal. All three are convex, so for a point outside, the closest surface
// point is unique and the normal is (p − point)/|p − point|: the gradient of the signed
// distance. Inside, the closest point is on the nearest face (box), on the side or a cap
// (cylinder), or radially out from the axis segment (capsule); where two faces are equally near
// (the medial surface, where the gradient is undefined) the first in the order stated wins.

#include "sim/types.h"

namespace weft::sim {

// A rectangular box: |local_i| ≤ half_size_m_i with local = Rz(−yaw)(p − center), i.e. an
// axis-aligned box turned by yaw_rad about the vertical (+z) axis through its centre.
struct BoxObstacle {
  Vec3 center_m{0.0, 0.0, 0.0};
  Vec3 half_size_m{0.05, 0.05, 0.05};  // half extents along its local x, y, z, m (all > 0)
  double yaw_rad = 0.0;                // rotation about +z, counter-clockwise seen from above
};

// A solid finite circular cylinder: points within radius_m of the axis line through center_m
// and within height_m/2 of center_m along the axis. center_m is the middle of the cylinder
// (half-way between the two caps), not the centre of its base.
struct CylinderObstacle {
  Vec3 center_m{0.0, 0.0, 0.0};
  Vec3 axis{0.0, 0.0, 1.0};  // unit
  double radius_m = 0.09;
  double height_m = 0.01;  // full length along the axis, cap to cap
};

// All points within radius_m of the segment a_m–b_m (a_m = b_m gives a sphere).
struct CapsuleObstacle {
  Vec3 a_m{0.0, 0.0, 0.0};
  Vec3 b_m{0.0, 0.0, 0.1};
  double radius_m = 0.05;
};

// The surface point nearest a query point and the outward unit normal of the surface there.
struct SurfacePoint {
  Vec3 point_m;
  Vec3 normal;
};

// Exact signed distance from p (m) to the surface, positive outside, m.
double signed_distance(const BoxObstacle& box, const Vec3& p);
double signed_distance(const CylinderObstacle& cylinder, const Vec3& p);
double signed_distance(const CapsuleObstacle& capsule, const Vec3& p);

// The closest surface point to p and the outward normal there. Outside, the normal is the unit
// vector from that point to p (at an edge or corner of the box or a rim of the cylinder it is
// the bisecting direction towards p). Inside or on the surface: the box's nearest face (ties:
// x before y before z faces, + before −); the cylinder's side when it is nearer than the
// nearer cap (ties to the cap), else that cap (+axis cap when exactly mid-height); the capsule
// radially out from its axis segment. Where the direction is undefined (p on the axis of a
// cylinder with the side nearest, or on the capsule's segment) the normal is a fixed unit
// vector orthogonal to the axis (Vec3::unitOrthogonal), or +z for a capsule with a_m = b_m.
SurfacePoint closest_surface_point(const BoxObstacle& box, const Vec3& p);
SurfacePoint closest_surface_point(const CylinderObstacle& cylinder, const Vec3& p);
SurfacePoint closest_surface_point(const CapsuleObstacle& capsule, const Vec3& p);

// The box's local x and y axes in world coordinates: (cos yaw, sin yaw, 0), (−sin yaw, cos yaw, 0).
Vec3 box_axis_x(const BoxObstacle& box);
Vec3 box_axis_y(const BoxObstacle& box);

}  // namespace weft::sim
