#include "sim/collision/continuous_collision.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "sim/collision/proximity.h"

namespace weft::sim {
namespace {

double ccd_det(const Vec3& a, const Vec3& b, const Vec3& c) { return a.cross(b).dot(c); }

// Times in [0, 1] worth measuring the distance at, ascending: the roots of f (sign changes
// bisected, values within tol of zero), its critical points inside (0, 1), and 1. Returns −1
// when f is within tol of zero at all of 0, 1 and the critical points: coplanar throughout.
int ccd_candidate_times(const CoplanarityCubic& f, double tol, std::array<double, 8>& times) {
  std::array<double, 4> ends{0.0, 0.0, 0.0, 0.0};
  int n_ends = 0;
  ends[n_ends++] = 0.0;
  // Roots of f′(t) = 3 c3 t² + 2 c2 t + c1 inside (0, 1), ascending.
  const double qa = 3.0 * f.c[3], qb = 2.0 * f.c[2], qc = f.c[1];
  std::array<double, 2> crit{0.0, 0.0};
  int n_crit = 0;
  if (qa != 0.0) {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      // The numerically stable pair of roots.
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      if (q != 0.0) {
        crit[n_crit++] = q / qa;
        crit[n_crit++] = qc / q;
      } else {
        crit[n_crit++] = 0.0;  // qb = disc = 0: a double root at 0
      }
    }
  } else if (qb != 0.0) {
    crit[n_crit++] = -qc / qb;
  }
  std::sort(crit.begin(), crit.begin() + n_crit);
  for (int k = 0; k < n_crit; ++k)
    if (crit[k] > 0.0 && crit[k] < 1.0) ends[n_ends++] = crit[k];
  ends[n_ends++] = 1.0;

  int n = 0;
  const auto is_zero = [&](double value) { return std::abs(value) <= tol; };
  bool coplanar = true;
  for (int k = 0; k < n_ends; ++k) coplanar = coplanar && is_zero(f(ends[k]));
  if (coplanar) return -1;
  for (int k = 0; k < n_ends; ++k) {
    const double t = ends[k];
    const double ft = f(t);
    if (is_zero(ft) || (k > 0 && k + 1 < n_ends) || k + 1 == n_ends) times[n++] = t;
    if (k + 1 == n_ends) break;
    // f is monotone on [t, next]: one sign change at most, bisected.
    double lo = t, hi = ends[k + 1];
    double f_lo = ft;
    const double f_hi = f(hi);
    if (is_zero(f_lo) || is_zero(f_hi) || (f_lo > 0.0) == (f_hi > 0.0)) continue;
    for (int it = 0; it < 60 && hi - lo > 1e-13; ++it) {
      const double mid = 0.5 * (lo + hi);
      const double f_mid = f(mid);
      if ((f_mid > 0.0) == (f_lo > 0.0)) {
        lo = mid;
        f_lo = f_mid;
      } else {
        hi = mid;
      }
    }
    times[n++] = 0.5 * (lo + hi);
  }
  std::sort(times.begin(), times.begin() + n);
  return n;
}

Vec3 ccd_lerp(const Vec3& x0, const Vec3& x1, double t) { return x0 + t * (x1 - x0); }

// For features moving in a common plane: the earliest t ∈ (0, 1] where distance(t) < eta, by
// bisection with the Lipschitz bound |distance′| ≤ speed (the largest relative speed of a
// vertex of one feature against one of the other): an interval whose ends' distances d_a, d_b
// give (d_a + d_b − speed·width)/2 ≥ eta holds no impact. An interval narrower than
// eta/(4·speed) whose bound fails counts as an impact at its end (conservative by eta/8).
template <class Distance>
std::optional<double> ccd_coplanar_search(const Distance& distance, double speed, double eta) {
  struct Span {
    double a, b, da, db;
  };
  // Depth first, one level deeper per split and at most ~40 levels (width 1e-12).
  std::array<Span, 128> stack{};
  std::size_t size = 0;
  stack[size++] = {0.0, 1.0, distance(0.0), distance(1.0)};
  while (size > 0) {
    const Span s = stack[--size];
    if (0.5 * (s.da + s.db - speed * (s.b - s.a)) >= eta) continue;
    if ((s.b - s.a) * speed < 0.25 * eta || s.b - s.a < 1e-12) {
      if (s.a > 0.0 && s.da < eta) return s.a;
      return s.b;
    }
    const double m = 0.5 * (s.a + s.b);
    const double dm = distance(m);
    stack[size++] = {m, s.b, dm, s.db};  // later half below: the earlier is searched first
    stack[size++] = {s.a, m, s.da, dm};
  }
  return std::nullopt;
}

// The largest |(x1_i − x0_i) − (x1_j − x0_j)| for i in `first`, j in `second` (m per step).
template <std::size_t N, std::size_t M>
double ccd_relative_speed(const std::array<Vec3, N>& first, const std::array<Vec3, M>& second) {
  double speed = 0.0;
  for (const Vec3& d : first)
    for (const Vec3& e : second) speed = std::max(speed, (d - e).norm());
  return speed;
}

// The largest length of the relative edges over the step (at least eta): the scale of the
// coplanarity cubic's tolerance, which is a volume.
double ccd_length_scale(const Vec3& u0, const Vec3& du, const Vec3& v0, const Vec3& dv,
                        const Vec3& w0, const Vec3& dw, double eta_m) {
  return std::max({u0.norm(), v0.norm(), w0.norm(), (u0 + du).norm(), (v0 + dv).norm(),
                   (w0 + dw).norm(), eta_m});
}

// Whether a pair stays farther apart than eta all step, by the coplanar search's bound over the
// whole step: d(t) ≥ (d(0) + d(1) − speed)/2. Most pairs of a small step are (neighbours in a
// smooth sheet, whose cubic is nearly zero and would send them to the search), and this costs
// two distances instead of the cubic's roots. The margin keeps rounding in the two distances
// from skipping a pair ccd_first_impact would count.
template <class Distance>
bool ccd_apart_all_step(const Distance& distance, double speed, double eta_m) {
  return 0.5 * (distance(0.0) + distance(1.0) - speed) >= eta_m * (1.0 + 1e-9);
}

// The earliest impact of two features whose coplanarity cubic is f: at the cubic's roots where
// the height over the common plane, |f(t)| / plane_area(t), is below eta and the features' own
// distance(t) is too; or, when they stay coplanar all step (f ≡ 0), by ccd_coplanar_search
// with the bound relative_speed.
template <class Distance, class PlaneArea>
std::optional<double> ccd_first_impact(const CoplanarityCubic& f, double length_m,
                                       const Distance& distance, double relative_speed,
                                       const PlaneArea& plane_area, double eta_m) {
  std::array<double, 8> times{};
  const int n = ccd_candidate_times(f, coplanar_tolerance * length_m * length_m * length_m, times);
  if (n < 0) return ccd_coplanar_search(distance, relative_speed, eta_m);
  for (int k = 0; k < n; ++k) {
    const double t = times[static_cast<std::size_t>(k)];
    if (std::abs(f(t)) > eta_m * plane_area(t)) continue;
    if (distance(t) < eta_m) return t;
  }
  return std::nullopt;
}

}  // namespace

CoplanarityCubic coplanarity_cubic(const Vec3& u0, const Vec3& du, const Vec3& v0, const Vec3& dv,
                                   const Vec3& w0, const Vec3& dw) {
  CoplanarityCubic f;
  f.c[0] = ccd_det(u0, v0, w0);
  f.c[1] = ccd_det(du, v0, w0) + ccd_det(u0, dv, w0) + ccd_det(u0, v0, dw);
  f.c[2] = ccd_det(du, dv, w0) + ccd_det(du, v0, dw) + ccd_det(u0, dv, dw);
  f.c[3] = ccd_det(du, dv, dw);
  return f;
}

std::optional<double> vertex_triangle_impact(const Vec3& p0, const Vec3& a0, const Vec3& b0,
                                             const Vec3& c0, const Vec3& p1, const Vec3& a1,
                                             const Vec3& b1, const Vec3& c1, double eta_m) {
  const auto distance = [&](double t) {
    const Vec3 p = ccd_lerp(p0, p1, t), a = ccd_lerp(a0, a1, t), b = ccd_lerp(b0, b1, t),
               c = ccd_lerp(c0, c1, t);
    const Vec3 w = closest_point_on_triangle_weights(p, a, b, c);
    return (p - (w[0] * a + w[1] * b + w[2] * c)).norm();
  };
  const double speed = ccd_relative_speed(std::array<Vec3, 1>{p1 - p0},
                                          std::array<Vec3, 3>{a1 - a0, b1 - b0, c1 - c0});
  if (ccd_apart_all_step(distance, speed, eta_m)) return std::nullopt;
  // Relative to a, so that a translated configuration rounds alike.
  const Vec3 u0 = b0 - a0, v0 = c0 - a0, w0 = p0 - a0;
  const Vec3 du = (b1 - a1) - u0, dv = (c1 - a1) - v0, dw = (p1 - a1) - w0;
  const CoplanarityCubic f = coplanarity_cubic(u0, du, v0, dv, w0, dw);
  // The distance is at least the height over the plane, |f| / |u × v|.
  const auto plane_area = [&](double t) { return (u0 + t * du).cross(v0 + t * dv).norm(); };
  return ccd_first_impact(f, ccd_length_scale(u0, du, v0, dv, w0, dw, eta_m), distance, speed,
                          plane_area, eta_m);
}

std::optional<double> edge_edge_impact(const Vec3& p0, const Vec3& q0, const Vec3& r0,
                                       const Vec3& s0, const Vec3& p1, const Vec3& q1,
                                       const Vec3& r1, const Vec3& s1, double eta_m) {
  const auto distance = [&](double t) {
    const Vec3 p = ccd_lerp(p0, p1, t), q = ccd_lerp(q0, q1, t), r = ccd_lerp(r0, r1, t),
               s = ccd_lerp(s0, s1, t);
    const std::array<double, 2> st = closest_segment_parameters(p, q, r, s);
    return ((p + st[0] * (q - p)) - (r + st[1] * (s - r))).norm();
  };
  const double speed = ccd_relative_speed(std::array<Vec3, 2>{p1 - p0, q1 - q0},
                                          std::array<Vec3, 2>{r1 - r0, s1 - s0});
  if (ccd_apart_all_step(distance, speed, eta_m)) return std::nullopt;
  const Vec3 u0 = q0 - p0, v0 = r0 - p0, w0 = s0 - p0;
  const Vec3 du = (q1 - p1) - u0, dv = (r1 - p1) - v0, dw = (s1 - p1) - w0;
  const CoplanarityCubic f = coplanarity_cubic(u0, du, v0, dv, w0, dw);
  // The distance is at least the lines' distance, |f| / |(q − p) × (s − r)|.
  const auto plane_area = [&](double t) {
    return (u0 + t * du).cross((w0 + t * dw) - (v0 + t * dv)).norm();
  };
  return ccd_first_impact(f, ccd_length_scale(u0, du, v0, dv, w0, dw, eta_m), distance, speed,
                          plane_area, eta_m);
}

}  // namespace weft::sim
