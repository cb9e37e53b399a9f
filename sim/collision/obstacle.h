#pragma once
// Rigid obstacles the cloth cannot enter, as analytic shapes. Response (seed 003's "repel"):
// a vertex found inside an obstacle, or closer than the cloth thickness to its surface, is
// moved to the closest surface point offset by the thickness; the step's velocity update
// v = (x_{n+1} − x_n)/h then removes its approaching normal velocity. Frictionless, or with
// Coulomb friction through the overload that also takes the step's start positions.

#include <variant>
#include <vector>

#include "sim/collision/mesh_obstacle.h"
#include "sim/collision/obstacle_shapes.h"
#include "sim/types.h"

namespace weft::sim {

struct SphereObstacle {
  Vec3 center_m{0.0, 0.0, 0.0};
  double radius_m = 0.1;
};

// The solid half-space behind a plane: points p with (p − point)·normal < 0 are inside.
struct PlaneObstacle {
  Vec3 point_m{0.0, 0.0, 0.0};
  Vec3 normal{0.0, 0.0, 1.0};  // unit
};

// Box, cylinder and capsule: sim/collision/obstacle_shapes.h; triangle meshes:
// sim/collision/mesh_obstacle.h.
using Obstacle = std::variant<SphereObstacle, PlaneObstacle, BoxObstacle, CylinderObstacle,
                              CapsuleObstacle, MeshObstacle>;

// Signed distance from p to the obstacle's surface, positive outside, metres.
double signed_distance(const Obstacle& obstacle, const Vec3& p);

// The index of the obstacle nearest to p by signed distance (the first of equally near ones):
// the one a pushed-out vertex at p rests on. `obstacles` must not be empty.
std::size_t nearest_obstacle(const std::vector<Obstacle>& obstacles, const Vec3& p);

// The unit normal out of the obstacle's surface at its point closest to p: the direction the
// push-out moves p (from a sphere's centre, a plane's normal, closest_surface_point's normal).
Vec3 outward_normal(const Obstacle& obstacle, const Vec3& p);

// Throws std::invalid_argument naming the obstacle ("obstacle 1: …") unless every sphere has a
// finite centre and a finite radius > 0, every plane a finite point and a unit normal (±1e-6),
// every box a finite centre, half sizes finite and > 0 and a finite yaw, every cylinder a
// finite centre, a unit axis (±1e-6), a radius and a height finite and > 0, every capsule
// finite endpoints and a radius finite and > 0, and every mesh a solid (not null) and a finite
// pose (the solid checked its own mesh). push_out_of_obstacles checks this itself;
// callers may check earlier.
void check_obstacles(const std::vector<Obstacle>& obstacles);

// Moves every vertex with inv_mass > 0 that lies closer than thickness_m to (or inside) any
// obstacle out to distance thickness_m from its surface. Returns how many vertices moved.
//
// x: #V×3 positions, m; inv_mass: #V, 0 for pinned vertices (never moved). A vertex at
// distance ≥ thickness_m from every obstacle is left bit-for-bit as it was.
// Order: for each vertex, the obstacles are applied in list order, in up to 4 passes, until
// it is clear of all (up to rounding). A sphere's closest surface point is along the ray from
// its centre (a vertex exactly at the centre goes out along +z); a plane's along its normal;
// a box's, cylinder's, capsule's or mesh's is closest_surface_point (obstacle_shapes.h,
// mesh_obstacle.h), offset along the normal there.
// Where two obstacles meet in a concave wedge (a sphere resting on the ground plane) those
// alternating moves only creep towards the way out, so a vertex still not clear after the
// passes goes to the nearest point of the curve where the offset surfaces (at thickness_m) of
// the obstacle it is deepest in and the nearest other one intersect: clear of both. Three or
// more obstacles overlapping at one place are resolved only that far; and if those offset
// surfaces do not intersect (e.g. facing planes closer than 2·thickness_m) the vertex stays
// where the passes left it, clear of the last obstacle in the list that it was inside.
// Throws std::invalid_argument for sizes that disagree, a thickness that is negative or not
// finite, or a bad obstacle (check_obstacles).
int push_out_of_obstacles(const std::vector<Obstacle>& obstacles, double thickness_m,
                          const Eigen::VectorXd& inv_mass, Matrix3X& x);

// As above, for the listed vertices only (the others are not looked at): e.g. the ones a
// later correction moved. Throws std::invalid_argument as above, and for an index out of range.
int push_out_of_obstacles(const std::vector<Obstacle>& obstacles, double thickness_m,
                          const Eigen::VectorXd& inv_mass, const std::vector<Index>& vertices,
                          Matrix3X& x);

// As above, with Coulomb friction against the obstacles, position-based (Macklin et al. 2014,
// "Unified particle physics for real-time applications", §6.1). x_start: #V×3 positions at
// the start of the step, m. A vertex pushed out by a distance d along n has its displacement
// over the step tangent to n, (x − x_start) minus its n part, removed when it is at most
// friction·d (static friction: the vertex sticks) and otherwise shortened by friction·d
// (kinetic). Through the step's velocity update v = (x_{n+1} − x_n)/h that is a tangential
// velocity change of at most friction times the normal one: Coulomb's law with coefficient
// `friction` (≥ 0; 0 gives exactly the frictionless push-out). Vertices not pushed out are not
// touched, so a vertex resting exactly at the thickness slides freely for that step.
// Throws std::invalid_argument as above, and for a friction that is negative or not finite or
// an x_start of another size.
int push_out_of_obstacles(const std::vector<Obstacle>& obstacles, double thickness_m,
                          const Eigen::VectorXd& inv_mass, const Matrix3X& x_start, double friction,
                          Matrix3X& x);

// As above, for obstacles that move over the step (obstacle_motion.h): `obstacles` are posed
// at the end of the step and step_motions[k] carries a point fixed to obstacle k from where it
// was at the start of the step to where it is at the end (empty: none moves). Friction then
// acts on the displacement relative to the surface: a vertex pushed out has its start position
// first carried by the motion of the obstacle it ends nearest to (the first in the list among
// equally near ones), so a cloth resting on a moving plate is carried along with it (static
// friction) or dragged at most friction × the push-out distance per step (kinetic).
// Throws std::invalid_argument as above, and for a step_motions of another size, not empty.
int push_out_of_obstacles(const std::vector<Obstacle>& obstacles,
                          const std::vector<RigidPose>& step_motions, double thickness_m,
                          const Eigen::VectorXd& inv_mass, const Matrix3X& x_start, double friction,
                          Matrix3X& x);

}  // namespace weft::sim
