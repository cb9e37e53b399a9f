#pragma once
// Continuous collision detection: whether two mesh features moving linearly over a
// step, from their start to their end positions, touch on the way — a vertex through a
// triangle, or an edge through an edge. The failsafe of self-collision (impact_zones.h) asks
// this of every nearby pair of the step's motion.
//
// Each vertex moves along a straight line, x(t) = x0 + t (x1 − x0), t ∈ [0, 1]. A vertex p
// meets triangle abc, or edge pq meets edge rs, only when the four points are coplanar:
// f(t) = det[b − a, c − a, p − a] (resp. det[q − p, r − p, s − p]) = 0, a cubic in t (Provot
// 1997, "Collision and self-collision handling in cloth model dedicated to design garments";
// Bridson et al. 2002, §4). Conservative: the cubic's real roots in [0, 1] (bracketed by the
// interval ends and the roots of f′, then bisected), its critical points, values within
// coplanar_tolerance·L³ of zero at those points (L the pair's longest extent over the step)
// and t = 1 are all tried; at each such time the features' distance is measured, and a
// distance below `eta` (a thickness, m) is an impact. So near misses within eta count,
// grazing coplanar motion counts where the features come within eta, and a pair that ends
// within eta counts at t = 1. The start (t = 0) counts only as a root of f. Before all
// this, a pair whose distance is at least eta all step by the Lipschitz bound — d(t) ≥
// (d(0) + d(1) − S)/2, S the largest relative displacement of a vertex of one feature against
// one of the other — is no impact without solving the cubic.

#include <optional>

#include "sim/types.h"

namespace weft::sim {

// Relative tolerance on the coplanarity cubic: |f| ≤ tol·L³ counts as zero.
inline constexpr double coplanar_tolerance = 1e-12;

// The cubic f(t) = det[u0 + t du, v0 + t dv, w0 + t dw] as coefficients c[0] + c[1] t + c[2] t²
// + c[3] t³.
struct CoplanarityCubic {
  double c[4] = {0.0, 0.0, 0.0, 0.0};
  double operator()(double t) const { return ((c[3] * t + c[2]) * t + c[1]) * t + c[0]; }
};
CoplanarityCubic coplanarity_cubic(const Vec3& u0, const Vec3& du, const Vec3& v0, const Vec3& dv,
                                   const Vec3& w0, const Vec3& dw);

// The earliest time t ∈ [0, 1] at which vertex p comes within eta_m of triangle abc, moving
// from (p0, a0, b0, c0) to (p1, a1, b1, c1), or none (rule above).
std::optional<double> vertex_triangle_impact(const Vec3& p0, const Vec3& a0, const Vec3& b0,
                                             const Vec3& c0, const Vec3& p1, const Vec3& a1,
                                             const Vec3& b1, const Vec3& c1, double eta_m);

// The earliest time at which segment pq comes within eta_m of segment rs, likewise.
std::optional<double> edge_edge_impact(const Vec3& p0, const Vec3& q0, const Vec3& r0,
                                       const Vec3& s0, const Vec3& p1, const Vec3& q1,
                                       const Vec3& r1, const Vec3& s1, double eta_m);

}  // namespace weft::sim
