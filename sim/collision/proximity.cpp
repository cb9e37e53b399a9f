#include "sim/collision/proximity.h"

#include <algorithm>

namespace weft::sim {
namespace {

double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }

// Nearest point of segment ab to p, as the parameter along it.
double closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = ab.squaredNorm();
  return length2 > 0.0 ? clamp01((p - a).dot(ab) / length2) : 0.0;
}

}  // namespace

Vec3 closest_point_on_triangle_weights(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};  // vertex a
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};  // vertex b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {  // edge ab
    const double v = d1 / (d1 - d3);
    return {1.0 - v, v, 0.0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};  // vertex c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {  // edge ac
    const double w = d2 / (d2 - d6);
    return {1.0 - w, 0.0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {  // edge bc
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - w, w};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {
    // Degenerate: the nearest point of the longest edge.
    const double lab = ab.squaredNorm(), lac = ac.squaredNorm(), lbc = (c - b).squaredNorm();
    if (lab >= lac && lab >= lbc) {
      const double v = closest_on_segment(p, a, b);
      return {1.0 - v, v, 0.0};
    }
    if (lac >= lbc) {
      const double w = closest_on_segment(p, a, c);
      return {1.0 - w, 0.0, w};
    }
    const double w = closest_on_segment(p, b, c);
    return {0.0, 1.0 - w, w};
  }
  const double v = vb / sum, w = vc / sum;  // face
  return {1.0 - v - w, v, w};
}

std::array<double, 2> closest_segment_parameters(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                                 const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  if (!(a > 0.0) && !(e > 0.0)) return {0.0, 0.0};
  if (!(a > 0.0)) return {0.0, clamp01(f / e)};
  const double c = d1.dot(r);
  if (!(e > 0.0)) return {clamp01(-c / a), 0.0};
  const double b = d1.dot(d2);
  const double denominator = a * e - b * b;  // ≥ 0; 0 when parallel
  // Parallel: start from s = 0 (any s gives the same distance before clamping t).
  double s = denominator > 1e-14 * a * e ? clamp01((b * f - c * e) / denominator) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = clamp01(-c / a);
  } else if (t > 1.0) {
    t = 1.0;
    s = clamp01((b - c) / a);
  }
  return {s, t};
}

}  // namespace weft::sim
