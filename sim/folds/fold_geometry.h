#pragma once
// The folded shape of a suspended membrane from its tension-field solution (seed 001 §5.1,
// §5.3; tension_field.h): the wrinkle lines y_i = (a0/Q^i) cos(πx/l) (eqs. 5–6), the
// out-of-plane displacement ±z_max cos(πx/l) alternating from one line to the next (eq. 4), and
// a flat grid of vertices laid onto that shape.
//
// The fold frame: x across the membrane from the midpoint between the supports, x ∈ [−l/2, l/2];
// depth downwards from the supports' line (the paper's y); z out of the membrane's plane, along
// which wrinkle line 0 (the lowest) bulges: line i has z = (−1)^i z_max cos(πx/l), so even lines
// are "positive" folds and odd lines "negative" ones (seed 001 Figs 6–7).
//
// Between consecutive wrinkle lines depth varies linearly and z either linearly (the paper's
// "varies linearly on any strip", whose fibres have exactly eq. (9)'s length at x = 0) or as a
// half cosine, z_a + (z_b − z_a)(1 − cos πt)/2 (smooth across the lines: no crease; the fibre is
// then slightly longer than eq. (9) assumes, so a rectangle's bottom ends a little higher).
//
// Vertical fibres are inextensible: a point at rest depth s below the top edge goes to arc
// length s along the folded fibre of its column. The fibre starts on the top wrinkle line n
// (the upper boundary of eq. 8), runs through lines n−1 … 0 and below line 0 (the lower corners
// of a rectangle) hangs straight down, keeping line 0's z. At the supports (x = ±l/2) every
// line meets the supports' line and the fibre hangs straight down from the support.
// Horizontally the flat width L is gathered uniformly into the span l.

#include <vector>

#include "base/enum_names.h"
#include "sim/folds/tension_field.h"
#include "sim/types.h"

namespace weft::sim {

enum class FoldInterpolation { linear, cosine };

inline constexpr base::EnumNames<FoldInterpolation, 2> fold_interpolation_names{
    {{FoldInterpolation::cosine, "cosine"}, {FoldInterpolation::linear, "linear"}}};

// rectangle: the membrane is h tall everywhere (a curtain); cosine: the membrane between the
// top wrinkle line and line 0 — the shape for which the wrinkle-line solution is exact.
enum class MembraneShape { rectangle, cosine };

inline constexpr base::EnumNames<MembraneShape, 2> membrane_shape_names{
    {{MembraneShape::rectangle, "rectangle"}, {MembraneShape::cosine, "cosine"}}};

struct FoldPattern {
  double span_m = 0.0;               // l, > 0
  double width_m = 0.0;              // L: the flat width, gathered into l
  double height_m = 0.0;             // h
  std::vector<double> amplitudes_m;  // a_0 … a_n; empty: no wrinkles, the membrane hangs flat
  double z_max_m = 0.0;
  FoldInterpolation interpolation = FoldInterpolation::cosine;

  int top_line() const { return static_cast<int>(amplitudes_m.size()) - 1; }  // n; −1 if none
};

// The pattern of a solution (any status; no_wrinkling gives no lines). Throws std::invalid_argument
// if the result does not belong to the inputs (span mismatch).
FoldPattern make_fold_pattern(const TensionFieldInputs& inputs, const TensionFieldResult& result,
                              FoldInterpolation interpolation = FoldInterpolation::cosine);

// +1 for even i (positive folds, towards +z), −1 for odd i.
inline int wrinkle_sign(int i) { return i % 2 == 0 ? 1 : -1; }

// Depth of wrinkle line i at x: a_i cos(πx/l) (eq. 6), m; cos clamped to ≥ 0 beyond ±l/2.
double wrinkle_depth_m(const FoldPattern& pattern, int i, double x_m);
// Out-of-plane displacement of wrinkle line i at x: (−1)^i z_max cos(πx/l) (eq. 4), m.
double wrinkle_z_m(const FoldPattern& pattern, int i, double x_m);

// A point of the folded membrane in the fold frame, m.
struct FoldPoint {
  double x_m = 0.0, depth_m = 0.0, z_m = 0.0;
};

// The point at arc length s_m ≥ 0 along the folded fibre of column x_m (|x| ≤ l/2); beyond
// line 0 (s > fibre_length_m) the fibre continues straight down, as a rectangle's corners do.
FoldPoint fibre_point(const FoldPattern& pattern, double x_m, double s_m);
// The folded fibre's length from the top line n to line 0 at x, m (0 at the supports).
double fibre_length_m(const FoldPattern& pattern, double x_m);

// Lays a flat membrane onto the folds, in world coordinates (z up, gravity along −z). rest:
// #V×3 positions, m, of the flat membrane in a vertical plane: warp across along +x, weft
// downwards along −z, its top edge's midpoint at top_center_m (the midpoint between the
// supports), so x − x_c ∈ [−L/2, L/2] and the rest depth s = z_c − z ∈ [0, h]. The folded
// point: x = x_c + (x − x_c)·l/L, z = z_c − depth, y = y − z_fold (positive folds bulge towards
// −y, the side the default camera looks from). A rectangle maps rest depth s to arc length s;
// a cosine membrane maps s to the fraction s/h of its fibre (a rest grid h tall). Returns #V×3.
// Throws std::invalid_argument naming the first vertex outside the flat membrane (beyond a
// 1e-9 relative margin) or with a non-finite position.
Matrix3X fold_rest_positions(const FoldPattern& pattern, const Matrix3X& rest,
                             const Vec3& top_center_m,
                             MembraneShape shape = MembraneShape::rectangle);

// A wrinkle line for drawing: `samples` points (x, depth) in the fold frame from x = −l/2 to
// l/2, m. sign: +1 positive fold, −1 negative (wrinkle_sign).
struct FoldLine {
  int index = 0;
  int sign = 1;
  std::vector<Vec2> points;
};

// Lines 0 … n. Throws std::invalid_argument for samples < 2.
std::vector<FoldLine> fold_lines(const FoldPattern& pattern, int samples = 97);

}  // namespace weft::sim
