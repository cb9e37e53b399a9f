#include "analysis/measure/drape_measure.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "base/constants.h"

namespace weft::analysis {

namespace {

bool finite_nonnegative(double v) { return std::isfinite(v) && v >= 0.0; }

// Marks the cells of `mask` whose centres lie inside triangle abc (projected), by the
// crossing rule: on each row of cell centres y = y_c, an edge pq counts when exactly one of
// p, q has y ≤ y_c; the two crossings bound a half-open run [x_left, x_right) of centres.
void fill_triangle(const sim::Vec2& a, const sim::Vec2& b, const sim::Vec2& c, ShadowMask& mask) {
  const double h = mask.cell_m;
  const double y_min = std::min({a.y(), b.y(), c.y()}), y_max = std::max({a.y(), b.y(), c.y()});
  // Rows whose centre y0 + (iy + ½)h lies in [y_min, y_max].
  const int iy_begin = std::max(0, static_cast<int>(std::ceil((y_min - mask.y0_m) / h - 0.5)));
  const int iy_end =
      std::min(mask.ny - 1, static_cast<int>(std::floor((y_max - mask.y0_m) / h - 0.5)));
  const std::array<std::pair<sim::Vec2, sim::Vec2>, 3> edges{{{a, b}, {b, c}, {c, a}}};
  for (int iy = iy_begin; iy <= iy_end; ++iy) {
    const double yc = mask.y0_m + (iy + 0.5) * h;
    double xs[2];
    int found = 0;
    for (const auto& [p, q] : edges) {
      if ((p.y() <= yc) == (q.y() <= yc)) continue;
      if (found < 2) xs[found] = p.x() + (yc - p.y()) * (q.x() - p.x()) / (q.y() - p.y());
      ++found;
    }
    if (found != 2) continue;  // the row passes through a vertex only
    const double x_left = std::min(xs[0], xs[1]), x_right = std::max(xs[0], xs[1]);
    // Centres x0 + (ix + ½)h in [x_left, x_right).
    const int ix_begin =
        std::max(0, static_cast<int>(std::ceil((x_left - mask.x0_m) / h - 0.5)));
    const int ix_end =
        std::min(mask.nx, static_cast<int>(std::ceil((x_right - mask.x0_m) / h - 0.5)));
    std::uint8_t* row = mask.inside.data() + static_cast<std::size_t>(iy) * mask.nx;
    for (int ix = ix_begin; ix < ix_end; ++ix) row[ix] = 1;
  }
}

}  // namespace

long ShadowMask::cell_count() const {
  return static_cast<long>(std::count(inside.begin(), inside.end(), std::uint8_t{1}));
}

ShadowMask rasterize_shadow(const sim::Matrix3X& x, const Triangles& triangles, double cell_m) {
  if (!(std::isfinite(cell_m) && cell_m > 0.0))
    throw std::invalid_argument("rasterize_shadow: the cell size must be finite and > 0, got " +
                                std::to_string(cell_m));
  const sim::Index n = static_cast<sim::Index>(x.rows());
  double x_lo = std::numeric_limits<double>::infinity(), y_lo = x_lo;
  double x_hi = -x_lo, y_hi = -x_lo;
  for (const auto& t : triangles) {
    for (sim::Index v : t) {
      if (v < 0 || v >= n)
        throw std::invalid_argument("rasterize_shadow: vertex index " + std::to_string(v) +
                                    " out of range (" + std::to_string(n) + " positions)");
      if (!x.row(v).allFinite())
        throw std::invalid_argument("rasterize_shadow: vertex " + std::to_string(v) +
                                    " has a non-finite position");
      x_lo = std::min(x_lo, x(v, 0));
      x_hi = std::max(x_hi, x(v, 0));
      y_lo = std::min(y_lo, x(v, 1));
      y_hi = std::max(y_hi, x(v, 1));
    }
  }
  ShadowMask mask;
  mask.cell_m = cell_m;
  if (triangles.empty()) return mask;
  // One spare cell on each side.
  const double nx = std::ceil((x_hi - x_lo) / cell_m) + 2.0;
  const double ny = std::ceil((y_hi - y_lo) / cell_m) + 2.0;
  if (nx * ny > static_cast<double>(max_shadow_cells))
    throw std::invalid_argument("rasterize_shadow: a " + std::to_string(x_hi - x_lo) + " x " +
                                std::to_string(y_hi - y_lo) + " m shadow at a cell of " +
                                std::to_string(cell_m) + " m needs more than " +
                                std::to_string(max_shadow_cells) + " cells; use coarser cells");
  mask.nx = static_cast<int>(nx);
  mask.ny = static_cast<int>(ny);
  mask.x0_m = x_lo - cell_m;
  mask.y0_m = y_lo - cell_m;
  mask.inside.assign(static_cast<std::size_t>(mask.nx) * static_cast<std::size_t>(mask.ny), 0);
  for (const auto& t : triangles) {
    const sim::Vec2 a(x(t[0], 0), x(t[0], 1)), b(x(t[1], 0), x(t[1], 1)), c(x(t[2], 0), x(t[2], 1));
    fill_triangle(a, b, c, mask);
  }
  return mask;
}

double shadow_area_error_bound_m2(double perimeter_m, double cell_m, int boundary_loops) {
  const double r = std::sqrt(2.0) * cell_m;  // a cell's diagonal
  return 2.0 * r * perimeter_m + base::kPi * r * r * boundary_loops;
}

double specimen_rest_area_m2(const sim::ClothMesh& mesh) {
  double area = 0.0;
  for (const auto& q : mesh.quads) {
    const sim::Vec3 d02 = mesh.rest_positions.row(q[2]) - mesh.rest_positions.row(q[0]);
    const sim::Vec3 d13 = mesh.rest_positions.row(q[3]) - mesh.rest_positions.row(q[1]);
    area += 0.5 * d02.cross(d13).norm();
  }
  for (const auto& t : mesh.faces) {  // a mesh without a grid
    const sim::Vec3 d01 = mesh.rest_positions.row(t[1]) - mesh.rest_positions.row(t[0]);
    const sim::Vec3 d02 = mesh.rest_positions.row(t[2]) - mesh.rest_positions.row(t[0]);
    area += 0.5 * d01.cross(d02).norm();
  }
  return area;
}

double drape_coefficient(double shadow_m2, double support_m2, double specimen_m2) {
  if (!finite_nonnegative(shadow_m2) || !finite_nonnegative(support_m2) ||
      !finite_nonnegative(specimen_m2))
    throw std::invalid_argument("drape_coefficient: areas must be finite and >= 0");
  if (!(specimen_m2 > support_m2))
    throw std::invalid_argument("drape_coefficient: the specimen (" + std::to_string(specimen_m2) +
                                " m^2) must be larger than its support (" +
                                std::to_string(support_m2) + " m^2)");
  return (shadow_m2 - support_m2) / (specimen_m2 - support_m2);
}

std::optional<DrapeSupport> find_support(const std::vector<sim::Obstacle>& obstacles,
                                         const sim::Vec3& cloth_center_m) {
  const sim::Vec2 c(cloth_center_m.x(), cloth_center_m.y());
  std::optional<DrapeSupport> best;
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    DrapeSupport s;
    s.obstacle = k;
    bool under = false;
    // std::get_if rather than std::visit: obstacle kinds that cannot be supports need no case.
    if (const auto* cyl = std::get_if<sim::CylinderObstacle>(&obstacles[k])) {
      if (std::abs(std::abs(cyl->axis.z()) - 1.0) > 1e-6) continue;  // tilted
      s.kind = "cylinder";
      s.axis_m = cyl->center_m.head<2>();
      s.top_z_m = cyl->center_m.z() + 0.5 * cyl->height_m;
      s.area_m2 = base::kPi * cyl->radius_m * cyl->radius_m;
      under = (c - s.axis_m).norm() <= cyl->radius_m;
    } else if (const auto* box = std::get_if<sim::BoxObstacle>(&obstacles[k])) {
      s.kind = "box";
      s.axis_m = box->center_m.head<2>();
      s.top_z_m = box->center_m.z() + box->half_size_m.z();
      s.area_m2 = 4.0 * box->half_size_m.x() * box->half_size_m.y();
      const sim::Vec3 d(c.x() - s.axis_m.x(), c.y() - s.axis_m.y(), 0.0);
      under = std::abs(d.dot(sim::box_axis_x(*box))) <= box->half_size_m.x() &&
              std::abs(d.dot(sim::box_axis_y(*box))) <= box->half_size_m.y();
    } else if (const auto* sphere = std::get_if<sim::SphereObstacle>(&obstacles[k])) {
      s.kind = "sphere";
      s.axis_m = sphere->center_m.head<2>();
      s.top_z_m = sphere->center_m.z() + sphere->radius_m;
      s.area_m2 = base::kPi * sphere->radius_m * sphere->radius_m;
      under = (c - s.axis_m).norm() <= sphere->radius_m;
    }
    if (!under || s.top_z_m > cloth_center_m.z()) continue;
    if (!best || s.top_z_m > best->top_z_m) best = s;
  }
  return best;
}

std::vector<double> outline_radii(const ShadowMask& shadow, const sim::Vec2& center_m, int bins) {
  if (bins < 3)
    throw std::invalid_argument("outline_radii: expected at least 3 angular bins, got " +
                                std::to_string(bins));
  std::vector<double> radius(static_cast<std::size_t>(bins), 0.0);
  for (int iy = 0; iy < shadow.ny; ++iy) {
    for (int ix = 0; ix < shadow.nx; ++ix) {
      if (!shadow.inside[static_cast<std::size_t>(iy) * shadow.nx + ix]) continue;
      const sim::Vec2 d = shadow.cell_center_m(ix, iy) - center_m;
      double theta = std::atan2(d.y(), d.x());
      if (theta < 0.0) theta += 2.0 * base::kPi;
      const int k = std::min(bins - 1, static_cast<int>(theta / (2.0 * base::kPi) * bins));
      radius[static_cast<std::size_t>(k)] = std::max(radius[static_cast<std::size_t>(k)], d.norm());
    }
  }
  return radius;
}

std::vector<double> circular_moving_average(const std::vector<double>& values, int window) {
  const int n = static_cast<int>(values.size());
  if (window < 1 || window % 2 == 0 || window > n)
    throw std::invalid_argument("circular_moving_average: the window must be odd, >= 1 and at "
                                "most the signal's length " + std::to_string(n) + ", got " +
                                std::to_string(window));
  const int half = window / 2;
  std::vector<double> out(values.size());
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int d = -half; d <= half; ++d) sum += values[static_cast<std::size_t>(((i + d) % n + n) % n)];
    out[static_cast<std::size_t>(i)] = sum / window;
  }
  return out;
}

std::vector<int> find_peaks(const std::vector<double>& values, double min_prominence) {
  const int n = static_cast<int>(values.size());
  std::vector<int> peaks;
  if (n < 3) return peaks;
  // Start the walk at a lowest sample: then every peak lies strictly inside [1, n), and the
  // walks to either side stop at the latest when they reach it (index 0, or n ≡ 0), beyond
  // which no lower col can be found.
  const int start = static_cast<int>(std::min_element(values.begin(), values.end()) - values.begin());
  std::vector<double> a(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) a[static_cast<std::size_t>(i)] = values[static_cast<std::size_t>((start + i) % n)];
  for (int i = 1; i < n;) {
    if (!(a[i] > a[i - 1])) {
      ++i;
      continue;
    }
    int j = i;  // the run of samples equal to a[i]
    while (j + 1 < n && a[j + 1] == a[i]) ++j;
    if (a[j + 1] < a[i]) {
      double left_col = a[i - 1], right_col = a[j + 1];
      for (int k = i - 1; k >= 0 && a[k] <= a[i]; --k) left_col = std::min(left_col, a[k]);
      for (int k = j + 1; k <= n && a[k] <= a[i]; ++k) right_col = std::min(right_col, a[k]);
      if (a[i] - std::max(left_col, right_col) >= min_prominence)
        peaks.push_back((start + (i + j) / 2) % n);
    }
    i = j + 1;
  }
  std::sort(peaks.begin(), peaks.end());
  return peaks;
}

int count_peaks(const std::vector<double>& values, double min_prominence) {
  return static_cast<int>(find_peaks(values, min_prominence).size());
}

std::vector<int> fold_crests(const std::vector<double>& radii_m, const FoldCountSettings& settings) {
  const std::vector<double> smooth = circular_moving_average(radii_m, settings.smoothing_bins);
  const auto [lo, hi] = std::minmax_element(smooth.begin(), smooth.end());
  const double threshold =
      std::max(settings.prominence_fraction * (*hi - *lo), settings.min_prominence_m);
  return find_peaks(smooth, threshold);
}

int count_folds(const std::vector<double>& radii_m, const FoldCountSettings& settings) {
  return static_cast<int>(fold_crests(radii_m, settings).size());
}

DrapeShape measure_shadow(const ShadowMask& shadow, const sim::Vec2& axis_m, double support_m2,
                          double specimen_m2, const DrapeMeasureSettings& settings) {
  DrapeShape shape;
  shape.cell_m = shadow.cell_m;
  shape.shadow_m2 = shadow.area_m2();
  shape.drape_coefficient = drape_coefficient(shape.shadow_m2, support_m2, specimen_m2);
  shape.radii_m = outline_radii(shadow, axis_m, settings.outline_bins);
  FoldCountSettings folds = settings.folds;
  folds.min_prominence_m = std::max(folds.min_prominence_m, 2.0 * shape.cell_m);
  shape.crests = fold_crests(shape.radii_m, folds);
  shape.folds = static_cast<int>(shape.crests.size());
  return shape;
}

DrapeShape measure_drape(const sim::ClothMesh& mesh, const Triangles& triangles,
                         const sim::Matrix3X& x, const DrapeSupport& support,
                         const DrapeMeasureSettings& settings) {
  const double specimen_m2 = specimen_rest_area_m2(mesh);
  double cell_m = settings.cell_fraction * std::sqrt(specimen_m2);
  // Coarser cells when the shadow spreads wide: at most 4096 along its longer side (plus the
  // margin), about 17 million cells, under max_shadow_cells.
  double extent_m = 0.0;
  if (!triangles.empty()) {
    sim::Vec2 lo = sim::Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const auto& t : triangles)
      for (sim::Index v : t)
        if (v >= 0 && v < x.rows()) {
          lo = lo.cwiseMin(x.row(v).head<2>().transpose());
          hi = hi.cwiseMax(x.row(v).head<2>().transpose());
        }
    extent_m = (hi - lo).maxCoeff();
  }
  if (std::isfinite(extent_m)) cell_m = std::max(cell_m, extent_m / 4096.0);
  return measure_shadow(rasterize_shadow(x, triangles, cell_m), support.axis_m, support.area_m2,
                        specimen_m2, settings);
}

}  // namespace weft::analysis
