// Drape measurements (analysis/measure): the shadow area of analytic shapes within the stated raster
// bound (also at ×1e-3 and ×1e3), a fold counted once, the fold count of star outlines
// r(θ) = R(1 + a cos kθ) for k = 6..12, DC = 0 for an overhang hanging straight down and 1 for
// a flat sheet, the support rule, and the settle time of damped motions.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "base/constants.h"
#include "sim/grid.h"
#include "analysis/measure/drape_measure.h"
#include "analysis/measure/settle.h"

namespace weft::analysis {
namespace {

struct Mesh {
  sim::Matrix3X x;
  Triangles triangles;
};

// A star-shaped polygon about `center` at height z as a triangle fan: vertex 0 the centre,
// then `n` rim points at θ_k = 2πk/n with radius r(θ_k).
template <class Radius>
Mesh fan(const sim::Vec2& center, int n, Radius r, double z = 0.2) {
  Mesh m;
  m.x.resize(n + 1, 3);
  m.x.row(0) << center.x(), center.y(), z;
  for (int k = 0; k < n; ++k) {
    const double theta = 2.0 * base::kPi * k / n;
    m.x.row(k + 1) << center.x() + r(theta) * std::cos(theta),
        center.y() + r(theta) * std::sin(theta), z;
    m.triangles.push_back({0, k + 1, (k + 1) % n + 1});
  }
  return m;
}

// The exact area of the fan's polygon (shoelace).
double polygon_area(const Mesh& m) {
  double twice = 0.0;
  for (const auto& t : m.triangles) {
    const sim::Vec3 a = m.x.row(t[1]) - m.x.row(t[0]), b = m.x.row(t[2]) - m.x.row(t[0]);
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

TEST(ShadowArea, FlatDiscWithinTheStatedBoundAtEveryScale) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    const double radius = 0.1 * scale, cell = radius / 200.0;
    const Mesh disc = fan(
        sim::Vec2(0.31, -0.17) * scale, 4096, [&](double) { return radius; }, 0.2 * scale);
    const double exact = polygon_area(disc);
    ASSERT_NEAR(exact, base::kPi * radius * radius, 1e-6 * exact);  // the polygon is the circle
    const ShadowMask shadow = rasterize_shadow(disc.x, disc.triangles, cell);
    const double bound = shadow_area_error_bound_m2(2.0 * base::kPi * radius, cell);
    EXPECT_NEAR(shadow.area_m2(), exact, bound) << "scale " << scale;
    EXPECT_LT(bound, 0.03 * exact);  // the bound is a useful one at 200 cells per radius
  }
}

TEST(ShadowArea, ErrorShrinksWithTheCell) {
  const Mesh disc = fan(sim::Vec2(0.0, 0.0), 4096, [](double) { return 0.1; });
  const double exact = polygon_area(disc);
  for (double cell : {4e-3, 1e-3, 2.5e-4}) {
    const double error = std::abs(rasterize_shadow(disc.x, disc.triangles, cell).area_m2() - exact);
    EXPECT_LE(error, shadow_area_error_bound_m2(2.0 * base::kPi * 0.1, cell)) << "cell " << cell;
  }
}

// A square sheet turned 30° about z (so its edges are not aligned with the cells).
Mesh turned_square(double side_m, double z_m, sim::Index n = 21) {
  sim::GridSpec spec;
  spec.size_u_m = spec.size_v_m = side_m;
  spec.nu = spec.nv = n;
  const double c = std::cos(base::kPi / 6.0), s = std::sin(base::kPi / 6.0);
  spec.warp_axis = sim::Vec3(c, s, 0.0);
  spec.weft_axis = sim::Vec3(-s, c, 0.0);
  spec.origin = sim::Vec3(0.0, 0.0, z_m) - 0.5 * side_m * (spec.warp_axis + spec.weft_axis);
  const sim::ClothMesh mesh = sim::make_grid(spec);
  return {mesh.rest_positions, mesh.triangles()};
}

TEST(ShadowArea, LayersAndFoldsCountOnce) {
  const double side = 0.3, cell = 5e-4;
  const Mesh sheet = turned_square(side, 0.2);
  const double bound = shadow_area_error_bound_m2(4.0 * side, cell);
  EXPECT_NEAR(rasterize_shadow(sheet.x, sheet.triangles, cell).area_m2(), side * side, bound);

  // The same sheet twice, 1 cm apart: still one sheet's shadow.
  Mesh two;
  two.x.resize(2 * sheet.x.rows(), 3);
  two.x << sheet.x, sheet.x.rowwise() + Eigen::RowVector3d(0.0, 0.0, 0.01);
  two.triangles = sheet.triangles;
  const sim::Index offset = static_cast<sim::Index>(sheet.x.rows());
  for (const auto& t : sheet.triangles)
    two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  EXPECT_NEAR(rasterize_shadow(two.x, two.triangles, cell).area_m2(), side * side, bound);

  // Folded in half along the line x = 0 (axis-aligned sheet): half the area.
  sim::GridSpec spec;
  spec.size_u_m = spec.size_v_m = side;
  spec.nu = spec.nv = 21;  // a vertex column on x = 0
  spec.origin = sim::Vec3(-0.5 * side, -0.5 * side, 0.2);
  const sim::ClothMesh flat = sim::make_grid(spec);
  sim::Matrix3X folded = flat.rest_positions;
  for (sim::Index v = 0; v < folded.rows(); ++v) {
    if (folded(v, 0) > 0.0) {
      folded(v, 2) += 1e-3 * folded(v, 0);  // lifted slightly, as a real fold would be
      folded(v, 0) = -folded(v, 0);
    }
  }
  EXPECT_NEAR(rasterize_shadow(folded, flat.triangles(), cell).area_m2(), 0.5 * side * side,
              shadow_area_error_bound_m2(3.0 * side, cell));
}

TEST(ShadowArea, EdgeOnTrianglesCastNoShadow) {
  sim::Matrix3X x(3, 3);
  x << 0.0, 0.0, 0.0, 0.1, 0.05, 0.0, 0.0, 0.0, 0.1;  // a vertical triangle
  EXPECT_EQ(rasterize_shadow(x, {{0, 1, 2}}, 1e-4).cell_count(), 0);
}

TEST(ShadowArea, RejectsBadInput) {
  const Mesh disc = fan(sim::Vec2(0.0, 0.0), 16, [](double) { return 0.1; });
  EXPECT_THROW(rasterize_shadow(disc.x, disc.triangles, 0.0), std::invalid_argument);
  EXPECT_THROW(rasterize_shadow(disc.x, disc.triangles, 1e-7), std::invalid_argument);  // too many cells
  EXPECT_THROW(rasterize_shadow(disc.x, {{0, 1, 99}}, 1e-3), std::invalid_argument);
  sim::Matrix3X bad = disc.x;
  bad(3, 1) = std::nan("");
  EXPECT_THROW(rasterize_shadow(bad, disc.triangles, 1e-3), std::invalid_argument);
}

TEST(SpecimenArea, SumsTheKeptQuadsOnly) {
  sim::GridSpec spec;
  spec.size_u_m = 0.4;
  spec.size_v_m = 0.3;
  spec.nu = 9;
  spec.nv = 7;
  EXPECT_NEAR(specimen_rest_area_m2(sim::make_grid(spec)), 0.12, 1e-12);

  spec.size_v_m = 0.4;
  spec.nu = spec.nv = 41;
  spec.shape = sim::SpecimenShape::disc;
  const sim::ClothMesh disc = sim::make_grid(spec);
  const double cell_area = 0.01 * 0.01;
  EXPECT_NEAR(specimen_rest_area_m2(disc), cell_area * static_cast<double>(disc.quads.size()), 1e-12);
  EXPECT_LT(disc.quads.size(), 40u * 40u);
  EXPECT_NEAR(specimen_rest_area_m2(disc), base::kPi * 0.2 * 0.2, 0.02 * base::kPi * 0.2 * 0.2);
}

// A flat specimen keeps its whole area: DC = 1 (Cusick's definition), whatever the support.
TEST(DrapeCoefficient, FlatUnsupportedSpecimenIsOne) {
  const double side = 0.5, cell = 5e-4, support = base::kPi * 0.1 * 0.1;
  const Mesh sheet = turned_square(side, 0.3);
  const double dc =
      drape_coefficient(rasterize_shadow(sheet.x, sheet.triangles, cell).area_m2(), support,
                        side * side);
  EXPECT_NEAR(dc, 1.0, shadow_area_error_bound_m2(4.0 * side, cell) / (side * side - support));

  // A disc specimen: its shadow is exactly its kept cells, the area it is measured against.
  sim::GridSpec spec;
  spec.size_u_m = spec.size_v_m = 0.3;
  spec.nu = spec.nv = 31;
  spec.shape = sim::SpecimenShape::disc;
  spec.origin = sim::Vec3(-0.15, -0.15, 0.2);
  const sim::ClothMesh disc = sim::make_grid(spec);
  const double disc_area = specimen_rest_area_m2(disc);
  const double perimeter = 4.0 * 0.3;  // the staircase outline of the kept cells
  EXPECT_NEAR(drape_coefficient(rasterize_shadow(disc.rest_positions, disc.triangles(), cell).area_m2(),
                                support, disc_area),
              1.0, shadow_area_error_bound_m2(perimeter, cell) / (disc_area - support));
}

// The overhang beyond a square support hangs straight down: the shadow is the support, DC = 0.
TEST(DrapeCoefficient, OverhangHangingStraightDownIsZero) {
  const double side = 0.3, half_support = 0.05, cell = 2.5e-4;
  sim::GridSpec spec;
  spec.size_u_m = spec.size_v_m = side;
  spec.nu = spec.nv = 31;
  spec.origin = sim::Vec3(-0.5 * side, -0.5 * side, 0.1);
  const sim::ClothMesh mesh = sim::make_grid(spec);
  sim::Matrix3X x = mesh.rest_positions;
  for (sim::Index v = 0; v < x.rows(); ++v) {
    const sim::Vec2 p(x(v, 0), x(v, 1));
    const sim::Vec2 clamped = p.cwiseMax(-half_support).cwiseMin(half_support);
    x(v, 0) = clamped.x();
    x(v, 1) = clamped.y();
    x(v, 2) -= (p - clamped).norm();  // the overhang goes down the sides
  }
  const double support = 4.0 * half_support * half_support;
  const double dc = drape_coefficient(rasterize_shadow(x, mesh.triangles(), cell).area_m2(),
                                      support, specimen_rest_area_m2(mesh));
  EXPECT_NEAR(dc, 0.0,
              shadow_area_error_bound_m2(8.0 * half_support, cell) / (side * side - support));
}

TEST(DrapeCoefficient, RejectsASpecimenNoLargerThanItsSupport) {
  EXPECT_THROW(drape_coefficient(0.1, 0.2, 0.2), std::invalid_argument);
  EXPECT_THROW(drape_coefficient(-0.1, 0.1, 0.2), std::invalid_argument);
}

TEST(Support, TheHighestObstacleUnderTheClothCentre) {
  const sim::Vec3 centre(0.01, 0.02, 0.5);
  std::vector<sim::Obstacle> obstacles;
  obstacles.push_back(sim::PlaneObstacle{sim::Vec3(0, 0, 0), sim::Vec3(0, 0, 1)});
  EXPECT_FALSE(find_support(obstacles, centre));  // a plane holds a cloth but is no support

  sim::CylinderObstacle disc{sim::Vec3(0.0, 0.0, 0.2), sim::Vec3(0.0, 0.0, -1.0), 0.1, 0.02};
  obstacles.push_back(disc);
  auto s = find_support(obstacles, centre);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->obstacle, 1u);
  EXPECT_EQ(s->kind, "cylinder");
  EXPECT_NEAR(s->area_m2, base::kPi * 0.01, 1e-15);
  EXPECT_NEAR(s->top_z_m, 0.21, 1e-15);

  sim::BoxObstacle box{sim::Vec3(0.0, 0.0, 0.15), sim::Vec3(0.05, 0.02, 0.15),
                       0.5};  // top at 0.30, turned
  obstacles.push_back(box);
  s = find_support(obstacles, centre);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->kind, "box");
  EXPECT_NEAR(s->area_m2, 4.0 * 0.05 * 0.02, 1e-15);
  // The same box with the centre beyond its narrow side: back to the disc.
  EXPECT_EQ(find_support(obstacles, sim::Vec3(0.0, 0.035, 0.5))->kind, "cylinder");

  obstacles.push_back(sim::SphereObstacle{sim::Vec3(0.0, 0.0, 0.3), 0.05});  // top at 0.35
  s = find_support(obstacles, centre);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->kind, "sphere");
  EXPECT_NEAR(s->area_m2, base::kPi * 0.0025, 1e-15);
  EXPECT_EQ(s->axis_m, sim::Vec2(0.0, 0.0));

  // Nothing is a support for a cloth below it, or beside it; a tilted cylinder never is.
  EXPECT_FALSE(find_support(obstacles, sim::Vec3(0.0, 0.0, 0.1)));
  EXPECT_FALSE(find_support(obstacles, sim::Vec3(0.5, 0.0, 0.5)));
  EXPECT_FALSE(find_support(
      {sim::CylinderObstacle{sim::Vec3(0, 0, 0), sim::Vec3(1, 0, 0), 0.1, 0.02}}, centre));
}

// The rasterized outline of r(θ) = R(1 + a cos k(θ − φ)) has k folds.
TEST(Folds, StarOutlinesGiveTheirNumberOfLobes) {
  const double radius = 0.2, amplitude = 0.1, phase = 0.3;
  const sim::Vec2 centre(0.05, -0.02);
  for (int k = 6; k <= 12; ++k) {
    const Mesh star = fan(centre, 2048, [&](double t) {
      return radius * (1.0 + amplitude * std::cos(k * (t - phase)));
    });
    const double cell = 5e-4;
    const std::vector<double> r = outline_radii(rasterize_shadow(star.x, star.triangles, cell), centre, 360);
    // The outline is within the stated bound of the analytic one in every bin: ρ(1 + √(1 + s²)
    // + s), ρ = h/√2, s ≤ a·k the slope |dr/(r dθ)| (drape_measure.h), with 5 % for curvature.
    const double slope = amplitude * k / (1.0 - amplitude);
    const double tolerance =
        1.05 * cell / std::sqrt(2.0) * (1.0 + std::sqrt(1.0 + slope * slope) + slope);
    for (int b = 0; b < 360; ++b) {
      const double lo = 2.0 * base::kPi * b / 360.0, hi = 2.0 * base::kPi * (b + 1) / 360.0;
      double r_max = 0.0;
      for (int s = 0; s <= 20; ++s) {
        const double t = lo + (hi - lo) * s / 20.0;
        r_max = std::max(r_max, radius * (1.0 + amplitude * std::cos(k * (t - phase))));
      }
      ASSERT_LE(r[b], r_max + 1e-6) << "k " << k << " bin " << b;
      ASSERT_GE(r[b], r_max - tolerance) << "k " << k << " bin " << b;
    }
    FoldCountSettings settings;
    settings.min_prominence_m = 2.0 * cell;
    EXPECT_EQ(count_folds(r, settings), k) << "k = " << k;
  }
}

TEST(Folds, SmallRipplesAndACircleAreNotFolds) {
  std::vector<double> r(360);
  for (int b = 0; b < 360; ++b) {
    const double t = 2.0 * base::kPi * (b + 0.5) / 360.0;
    r[b] = 0.2 * (1.0 + 0.1 * std::cos(8.0 * t) + 0.006 * std::cos(60.0 * t));
  }
  EXPECT_EQ(count_folds(r, {}), 8);

  const double cell = 5e-4;
  const Mesh disc = fan(sim::Vec2(0.0, 0.0), 2048, [](double) { return 0.2; });
  FoldCountSettings settings;
  settings.min_prominence_m = 2.0 * cell;
  EXPECT_EQ(count_folds(outline_radii(rasterize_shadow(disc.x, disc.triangles, cell),
                                      sim::Vec2::Zero(), 360),
                        settings),
            0);
}

TEST(Folds, PeakProminenceOnACircle) {
  EXPECT_EQ(count_peaks({1, 1, 1, 1}, 0.0), 0);
  EXPECT_EQ(count_peaks({0, 1, 1, 1, 0, 0}, 0.5), 1);  // a plateau is one peak
  EXPECT_EQ(count_peaks({3, 0, 0, 0, 0}, 1.0), 1);     // across the wrap-around
  // Peaks 1.0 and 0.55 with a col at 0.5 between them: the lower one stands 0.05 above it.
  const std::vector<double> two{0.0, 1.0, 0.5, 0.55, 0.0};
  EXPECT_EQ(count_peaks(two, 0.04), 2);
  EXPECT_EQ(count_peaks(two, 0.06), 1);
  EXPECT_EQ(circular_moving_average({3, 0, 0}, 3), (std::vector<double>{1, 1, 1}));
  EXPECT_THROW(circular_moving_average({1, 2, 3}, 2), std::invalid_argument);
}

// Where the peaks are: a plateau's middle, a peak across the wrap-around, ascending order.
TEST(Folds, PeakPositions) {
  EXPECT_EQ(find_peaks({0, 1, 1, 1, 0, 0}, 0.5), (std::vector<int>{2}));
  EXPECT_EQ(find_peaks({3, 0, 0, 0, 0}, 1.0), (std::vector<int>{0}));
  EXPECT_EQ(find_peaks({0.0, 1.0, 0.5, 0.55, 0.0}, 0.04), (std::vector<int>{1, 3}));
  // cos 5θ on 360 bins: crests at 0°, 72°, … i.e. bins 0, 72, 144, 216, 288.
  std::vector<double> r(360);
  for (int k = 0; k < 360; ++k) r[static_cast<std::size_t>(k)] = std::cos(5.0 * k * base::kPi / 180.0);
  EXPECT_EQ(fold_crests(r, {}), (std::vector<int>{0, 72, 144, 216, 288}));
}

TEST(SettleTime, ExponentialDecayIsExact) {
  const double v0 = 2.0, tau = 0.4, threshold = settle_speed_threshold_m_s;
  std::vector<double> t, v;
  for (int i = 0; i <= 96; ++i) {  // 4 s at 24 fps
    t.push_back(i / 24.0);
    v.push_back(v0 * std::exp(-t.back() / tau));
  }
  const auto settle = settle_time_s(t, v, threshold);
  ASSERT_TRUE(settle);
  EXPECT_NEAR(*settle, tau * std::log(v0 / threshold), 1e-12);
}

// |v| = v0 e^(−t/τ) |cos ωt| crosses the threshold for the last time before its envelope does,
// and within half a period of it.
TEST(SettleTime, DampedOscillationSettlesWithItsEnvelope) {
  const double v0 = 2.0, tau = 0.4, omega = 2.0 * base::kPi * 1.5, threshold = 0.01;
  std::vector<double> t, v;
  for (int i = 0; i <= 400; ++i) {
    t.push_back(i / 100.0);
    v.push_back(v0 * std::exp(-t.back() / tau) * std::abs(std::cos(omega * t.back())));
  }
  const double envelope = tau * std::log(v0 / threshold);
  const auto settle = settle_time_s(t, v, threshold);
  ASSERT_TRUE(settle);
  EXPECT_LE(*settle, envelope + 0.01);
  EXPECT_GE(*settle, envelope - base::kPi / omega - 0.01);
}

TEST(SettleTime, LateMotionAndBadInput) {
  const std::vector<double> t{0.0, 1.0, 2.0, 3.0};
  EXPECT_EQ(settle_time_s(t, {0.0, 0.0, 0.0, 0.0}, 0.01), 0.0);       // never moved
  EXPECT_FALSE(settle_time_s(t, {1.0, 0.0, 0.0, 0.5}, 0.01));         // moving at the end
  EXPECT_NEAR(*settle_time_s(t, {1.0, 0.0, 0.02, 0.0}, 0.01), 2.5, 1e-12);  // the later crossing
  EXPECT_THROW(settle_time_s(t, {1.0, 0.0}, 0.01), std::invalid_argument);
  EXPECT_THROW(settle_time_s({0.0, 0.0}, {1.0, 0.0}, 0.01), std::invalid_argument);
  EXPECT_THROW(settle_time_s(t, {1.0, 0.0, 0.0, 0.0}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace weft::analysis
