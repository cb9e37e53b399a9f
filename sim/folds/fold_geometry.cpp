// Wrinkle lines, folded fibres and the folded grid of a tension-field solution (fold_geometry.h).

#include "sim/folds/fold_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "base/constants.h"

namespace weft::sim {

namespace {

// Pieces per strip when walking a half-cosine strip by arc length: the chord error of 32
// pieces is below 1e-3 of the strip's z change.
constexpr int kCosinePieces = 32;

double column_cosine(const FoldPattern& p, double x_m) {
  return std::max(0.0, std::cos(base::kPi * x_m / p.span_m));
}

// The strip from wrinkle line k (upper) to line k − 1 at a column with cosine c.
struct Strip {
  double depth0, depth1, z0, z1;
};

Strip strip(const FoldPattern& p, int k, double c) {
  const double a_upper = p.amplitudes_m[static_cast<std::size_t>(k)];
  const double a_lower = p.amplitudes_m[static_cast<std::size_t>(k - 1)];
  return {a_upper * c, a_lower * c, wrinkle_sign(k) * p.z_max_m * c,
          wrinkle_sign(k - 1) * p.z_max_m * c};
}

FoldPoint on_strip(const FoldPattern& p, const Strip& s, double x_m, double t) {
  const double blend =
      p.interpolation == FoldInterpolation::linear ? t : 0.5 * (1.0 - std::cos(base::kPi * t));
  return {x_m, s.depth0 + (s.depth1 - s.depth0) * t, s.z0 + (s.z1 - s.z0) * blend};
}

struct Walk {
  FoldPoint point;
  double remaining_m = 0.0;  // arc length left beyond line 0 (0 if the point is on the lines)
  double length_m = 0.0;     // arc length walked along the lines
};

// Walks s_m along the fibre from the top line down to line 0 (or the whole fibre for s = ∞).
Walk walk(const FoldPattern& p, double x_m, double s_m) {
  const double c = column_cosine(p, x_m);
  const int n = p.top_line();
  const int pieces = p.interpolation == FoldInterpolation::linear ? 1 : kCosinePieces;
  Walk w;
  if (n < 0) {  // no wrinkles: the fibre hangs straight down in the plane
    w.point = {x_m, 0.0, 0.0};
    w.remaining_m = s_m;
    return w;
  }
  double remaining = s_m;
  for (int k = n; k >= 1; --k) {
    const Strip s = strip(p, k, c);
    FoldPoint a = on_strip(p, s, x_m, 0.0);
    for (int j = 1; j <= pieces; ++j) {
      const double t = static_cast<double>(j) / pieces;
      const FoldPoint b = on_strip(p, s, x_m, t);
      const double piece = std::hypot(b.depth_m - a.depth_m, b.z_m - a.z_m);
      if (remaining <= piece) {
        const double within = piece > 0.0 ? remaining / piece : 0.0;
        w.point = on_strip(p, s, x_m, (j - 1 + within) / pieces);
        w.length_m += remaining;
        return w;
      }
      remaining -= piece;
      w.length_m += piece;
      a = b;
    }
  }
  w.point = {x_m, p.amplitudes_m[0] * c, wrinkle_z_m(p, 0, x_m)};
  w.remaining_m = remaining;
  return w;
}

}  // namespace

FoldPattern make_fold_pattern(const TensionFieldInputs& inputs, const TensionFieldResult& result,
                              FoldInterpolation interpolation) {
  validate(inputs);
  if (std::abs(result.span_m - inputs.span_m()) > 1e-12 * inputs.width_m)
    throw std::invalid_argument("make_fold_pattern: the result's span l = " +
                                std::to_string(result.span_m) + " m is not the inputs' L - d = " +
                                std::to_string(inputs.span_m()) + " m");
  FoldPattern p;
  p.span_m = result.span_m;
  p.width_m = inputs.width_m;
  p.height_m = inputs.height_m;
  p.amplitudes_m = result.amplitudes_m;
  p.z_max_m = result.z_max_m;
  p.interpolation = interpolation;
  return p;
}

double wrinkle_depth_m(const FoldPattern& p, int i, double x_m) {
  return p.amplitudes_m.at(static_cast<std::size_t>(i)) * column_cosine(p, x_m);
}

double wrinkle_z_m(const FoldPattern& p, int i, double x_m) {
  return wrinkle_sign(i) * p.z_max_m * column_cosine(p, x_m);
}

FoldPoint fibre_point(const FoldPattern& p, double x_m, double s_m) {
  const Walk w = walk(p, x_m, std::max(0.0, s_m));
  FoldPoint point = w.point;
  if (w.remaining_m > 0.0 && p.top_line() >= 0) {
    // Below line 0 a rectangle hangs straight down; fibre_point of a cosine membrane stops there.
    point.depth_m += w.remaining_m;
  } else if (p.top_line() < 0) {
    point.depth_m = w.remaining_m;
  }
  return point;
}

double fibre_length_m(const FoldPattern& p, double x_m) {
  if (p.top_line() < 0) return 0.0;
  return walk(p, x_m, std::numeric_limits<double>::infinity()).length_m;
}

Matrix3X fold_rest_positions(const FoldPattern& p, const Matrix3X& rest, const Vec3& top_center_m,
                             MembraneShape shape) {
  if (!(p.span_m > 0.0 && p.width_m > 0.0 && p.height_m > 0.0))
    throw std::invalid_argument("fold_rest_positions: the pattern needs l, L, h > 0");
  const double margin = 1e-9 * std::max(p.width_m, p.height_m);
  const double gather = p.span_m / p.width_m;
  Matrix3X out(rest.rows(), 3);
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const Vec3 r = rest.row(v).transpose();
    const std::string which = "fold_rest_positions: vertex " + std::to_string(v);
    if (!r.allFinite()) throw std::invalid_argument(which + " has a non-finite position");
    const double across = r.x() - top_center_m.x();
    const double depth = top_center_m.z() - r.z();
    if (std::abs(across) > 0.5 * p.width_m + margin || depth < -margin)
      throw std::invalid_argument(
          which + " at (" + std::to_string(r.x()) + ", " + std::to_string(r.y()) + ", " +
          std::to_string(r.z()) + ") m lies outside the flat membrane: expected |x - x_c| <= L/2 = " +
          std::to_string(0.5 * p.width_m) + " m and z <= the top edge's " +
          std::to_string(top_center_m.z()) + " m");
    const double x = std::clamp(across * gather, -0.5 * p.span_m, 0.5 * p.span_m);
    const double s = std::max(depth, 0.0);
    const FoldPoint f =
        shape == MembraneShape::rectangle || p.top_line() < 0
            ? fibre_point(p, x, s)
            : fibre_point(p, x, std::min(s / p.height_m, 1.0) * fibre_length_m(p, x));
    out.row(v) << top_center_m.x() + x, r.y() - f.z_m, top_center_m.z() - f.depth_m;
  }
  return out;
}

std::vector<FoldLine> fold_lines(const FoldPattern& p, int samples) {
  if (samples < 2)
    throw std::invalid_argument("fold_lines: need at least 2 samples per line, got " +
                                std::to_string(samples));
  std::vector<FoldLine> lines;
  for (int i = 0; i <= p.top_line(); ++i) {
    FoldLine line;
    line.index = i;
    line.sign = wrinkle_sign(i);
    for (int k = 0; k < samples; ++k) {
      const double x = p.span_m * (static_cast<double>(k) / (samples - 1) - 0.5);
      line.points.emplace_back(x, wrinkle_depth_m(p, i, x));
    }
    lines.push_back(std::move(line));
  }
  return lines;
}

}  // namespace weft::sim
