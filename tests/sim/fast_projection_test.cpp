// Fast projection (Goldenthal et al. 2007) against its one-edge oracle, its invariants and its
// convergence order, and at the extremes the issue lists.
#include "sim/constraints/fast_projection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "base/constants.h"
#include "sim/constraints/inextensibility.h"
#include "sim/constraints/pairwise_projection.h"

namespace weft::sim {
namespace {

ProjectionSettings fast(double tolerance, int max_iterations) {
  ProjectionSettings s;
  s.method = ProjectionMethod::fast_projection;
  s.tolerance = tolerance;
  s.max_iterations = max_iterations;
  return s;
}

// Two vertices, one edge of rest length l stretched to d along a skew direction.
double one_edge_strain_after(int iterations, double d, double l, double inv_ma, double inv_mb) {
  Matrix3X x(2, 3);
  const Eigen::RowVector3d dir = Eigen::RowVector3d(1, 2, -2).normalized();
  x.row(0) << 0.3, -0.1, 0.7;
  x.row(1) = x.row(0) + d * dir;
  Eigen::VectorXd inv_mass(2);
  inv_mass << inv_ma, inv_mb;
  FastProjection p({{0, 1, l}}, inv_mass, fast(0.0, iterations), default_sparse_backend());
  const ProjectionResult r = p.project(x);
  EXPECT_EQ(r.iterations, iterations);
  return (x.row(1) - x.row(0)).norm() / l - 1.0;
}

// One iteration maps the length d to (d² + l²) / (2d), whatever the masses: from 10 % strain
// the strains are 4.545e-3, 1.03e-5, then about 5e-11 (the oracle).
TEST(FastProjection, OneEdgeOracle) {
  const double l = 0.05;
  double d = 1.1 * l;
  std::vector<double> expected;
  for (int k = 0; k < 3; ++k) {
    d = (d * d + l * l) / (2 * d);
    expected.push_back(d / l - 1.0);
  }
  EXPECT_NEAR(expected[0], 4.545e-3, 1e-6);
  EXPECT_NEAR(expected[1], 1.03e-5, 1e-7);
  EXPECT_NEAR(expected[2], 5.2e-11, 1e-11);
  for (auto [ia, ib] : {std::pair{1.0, 1.0}, {3.0, 0.5}, {0.0, 2.0}}) {
    for (int k = 1; k <= 3; ++k) {
      EXPECT_NEAR(one_edge_strain_after(k, 1.1 * l, l, ia, ib), expected[k - 1], 1e-13)
          << "iteration " << k << " inverse masses " << ia << ", " << ib;
    }
  }
}

TEST(FastProjection, ConstraintGradientMatchesFiniteDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    const double l = 0.04, h = 1e-7;
    const Vec3 g = edge_constraint_gradient_b(a, b, l);
    for (int c = 0; c < 3; ++c) {
      Vec3 bp = b, bm = b, ap = a, am = a;
      bp[c] += h;
      bm[c] -= h;
      ap[c] += h;
      am[c] -= h;
      const double fd_b = (edge_constraint(a, bp, l) - edge_constraint(a, bm, l)) / (2 * h);
      const double fd_a = (edge_constraint(ap, b, l) - edge_constraint(am, b, l)) / (2 * h);
      EXPECT_NEAR(g[c], fd_b, 1e-6 * (1 + std::abs(fd_b))) << "trial " << trial;
      EXPECT_NEAR(-g[c], fd_a, 1e-6 * (1 + std::abs(fd_a))) << "trial " << trial;
    }
  }
}

ClothMesh grid(Index n, double size = 1.0) {
  GridSpec spec;
  spec.nu = spec.nv = n;
  spec.size_u_m = spec.size_v_m = size;
  spec.origin = Vec3(0, 0, 1);
  return make_grid(spec);
}

// The rest grid with every vertex jittered by up to `amount` metres in 3-D.
Matrix3X jittered(const ClothMesh& mesh, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  Matrix3X x = mesh.rest_positions;
  for (Index k = 0; k < x.rows(); ++k) x.row(k) += Eigen::RowVector3d(u(rng), u(rng), u(rng));
  return x;
}

Eigen::VectorXd inverse_masses(const ClothMesh& mesh, const std::vector<Index>& pinned) {
  Eigen::VectorXd w = (0.2 * mesh.vertex_area_m2).cwiseInverse();
  for (Index p : pinned) w[p] = 0.0;
  return w;
}

TEST(FastProjection, KeepsTheCentreOfMassWhenNothingIsPinned) {
  const ClothMesh mesh = grid(17);
  const Eigen::VectorXd w = inverse_masses(mesh, {});
  const Eigen::VectorXd m = w.cwiseInverse();
  Matrix3X x = jittered(mesh, 0.01, 1);
  const Eigen::RowVector3d before = m.transpose() * x;
  FastProjection p(make_edge_constraints(mesh, ConstrainedEdges::warp_weft, w), w, fast(1e-8, 30),
                   default_sparse_backend());
  const ProjectionResult r = p.project(x);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.max_strain, 1e-8);
  const Eigen::RowVector3d after = m.transpose() * x;
  EXPECT_LT((after - before).norm() / m.sum(), 1e-13);
}

TEST(FastProjection, PinnedVerticesNeverMove) {
  const ClothMesh mesh = grid(9);
  const std::vector<Index> pinned{0, 8, 40, 72, 80};
  const Eigen::VectorXd w = inverse_masses(mesh, pinned);
  Matrix3X x = jittered(mesh, 0.02, 2);
  const Matrix3X x0 = x;
  FastProjection p(make_edge_constraints(mesh, ConstrainedEdges::warp_weft, w), w, fast(1e-6, 30),
                   default_sparse_backend());
  (void)p.project(x);
  for (Index v : pinned) EXPECT_EQ(Vec3(x.row(v)), Vec3(x0.row(v)));
}

// Holding more vertices by set_inverse_masses (as the impact zones do) projects as a projector
// made with those masses: held vertices never move, the others meet the tolerance (edges
// between two held vertices, rigid together here, are left out), and a vertex held at
// construction cannot be freed.
TEST(FastProjection, VerticesHeldLaterStayPutAndTheRestConverges) {
  const ClothMesh mesh = grid(9);
  const Eigen::VectorXd w = inverse_masses(mesh, {0});
  Eigen::VectorXd held = w;
  const std::vector<Index> block{30, 31, 39, 40};  // one cell, held where it lies at rest
  for (Index v : block) held[v] = 0.0;
  Matrix3X x = jittered(mesh, 0.02, 4);
  for (Index v : block) x.row(v) = mesh.rest_positions.row(v);
  const Matrix3X x0 = x;
  FastProjection later(make_edge_constraints(mesh, ConstrainedEdges::warp_weft, w), w,
                       fast(1e-8, 30), default_sparse_backend());
  later.set_inverse_masses(held, /*fresh=*/true);
  Matrix3X x_later = x;
  const ProjectionResult r = later.project(x_later);
  EXPECT_TRUE(r.converged);
  for (Index v : block) EXPECT_EQ(Vec3(x_later.row(v)), Vec3(x0.row(v)));
  EXPECT_LE(max_edge_strain(later.constraints(), x_later), 1e-8);
  FastProjection made(make_edge_constraints(mesh, ConstrainedEdges::warp_weft, held), held,
                      fast(1e-8, 30), default_sparse_backend());
  Matrix3X x_made = x;
  EXPECT_TRUE(made.project(x_made).converged);
  EXPECT_LT((x_made - x_later).cwiseAbs().maxCoeff(), 1e-6);
  Eigen::VectorXd freed = w;
  freed[0] = 1.0;
  EXPECT_THROW(later.set_inverse_masses(freed, true), std::invalid_argument);
}

// Where no shape meets the tolerance the iterations crawl: a sheet whose two side columns are
// held 3 % farther apart than its width, jittered. With stall_fraction the projection stops
// when a shortened step leaves Σ C² above that fraction of its value before, unconverged, at
// a strain near the one a hundred iterations reach; on a reachable shape it changes no bit.
TEST(FastProjection, StopsWhereItStallsAndNowhereElse) {
  const ClothMesh mesh = grid(9);
  std::vector<Index> sides;
  for (Index j = 0; j < 9; ++j) sides.insert(sides.end(), {mesh.index(0, j), mesh.index(8, j)});
  const Eigen::VectorXd w = inverse_masses(mesh, sides);
  Matrix3X x = jittered(mesh, 0.01, 6);
  for (Index j = 0; j < 9; ++j) x(mesh.index(8, j), 0) += 0.03;  // 3 % of the 1 m width
  ProjectionSettings crawl = fast(1e-3, 100), stall = crawl;
  stall.stall_fraction = 0.9;
  Matrix3X x_crawl = x, x_stall = x;
  const auto constraints = make_edge_constraints(mesh, ConstrainedEdges::warp_weft, w);
  const ProjectionResult a = FastProjection(constraints, w, crawl, default_sparse_backend()).project(x_crawl);
  const ProjectionResult b = FastProjection(constraints, w, stall, default_sparse_backend()).project(x_stall);
  EXPECT_FALSE(a.converged);
  EXPECT_FALSE(b.converged);
  EXPECT_LT(b.iterations, a.iterations / 4);
  EXPECT_LT(b.max_strain, 1.2 * a.max_strain);
  std::cout << "held apart: " << a.iterations << " iterations to strain " << a.max_strain
            << " without, " << b.iterations << " to " << b.max_strain << " with stall_fraction\n";
  const Eigen::VectorXd one_pin = inverse_masses(mesh, {0});
  const auto free_constraints = make_edge_constraints(mesh, ConstrainedEdges::warp_weft, one_pin);
  Matrix3X y_crawl = jittered(mesh, 0.05, 7), y_stall = y_crawl;
  EXPECT_TRUE(FastProjection(free_constraints, one_pin, crawl, default_sparse_backend()).project(y_crawl).converged);
  EXPECT_TRUE(FastProjection(free_constraints, one_pin, stall, default_sparse_backend()).project(y_stall).converged);
  EXPECT_EQ(y_crawl, y_stall);
}

// Near the solution each iteration at least squares the strain (Newton's quadratic order).
// One pin: two pins at exactly their rest distance make the edge chain between them a taut
// string whose only solution is straight, a singular root where Newton is linear (tested with
// the two-corner hang in simulator_test.cpp).
// Also with the factorization reused as a preconditioner (reuse_iterations > 0): an inexact
// Newton method whose forcing term is proportional to the strain keeps the order.
class FastProjectionReuse : public testing::TestWithParam<int> {};

TEST_P(FastProjectionReuse, ConvergesQuadratically) {
  const ClothMesh mesh = grid(21);
  const Eigen::VectorXd w = inverse_masses(mesh, {mesh.index(0, 20)});
  const auto constraints = make_edge_constraints(mesh, ConstrainedEdges::warp_weft, w);
  const Matrix3X start = jittered(mesh, 0.004, 5);
  std::vector<double> strains;
  for (int k = 0; k <= 5; ++k) {
    Matrix3X x = start;
    ProjectionSettings settings = fast(0.0, k);
    settings.reuse_iterations = GetParam();
    FastProjection p(constraints, w, settings, default_sparse_backend());
    const ProjectionResult r = p.project(x);
    if (GetParam() > 0 && k >= 3) {
      EXPECT_LT(r.factorizations, k) << "iteration " << k;
    }
    strains.push_back(r.max_strain);
  }
  ASSERT_GT(strains[0], 1e-2);
  // Quadratic: s_{k+1} ≤ c s_k² with a bounded c (the one-edge oracle has c = 1/2; the sheet's
  // coupled edges give c ≈ 10–21 here; a linear rate would send c to infinity), and the observed order ln(s_{k+1}/s_k) / ln(s_k/s_{k−1})
  // approaching 2 once in the quadratic regime.
  for (int k = 2; k <= 4; ++k) {
    if (strains[k] > 1e-2 || strains[k + 1] < 1e-13) continue;
    EXPECT_LE(strains[k + 1], 30.0 * strains[k] * strains[k]) << "iteration " << k + 1;
    const double order = std::log(strains[k + 1] / strains[k]) / std::log(strains[k] / strains[k - 1]);
    EXPECT_GT(order, 1.6) << "iteration " << k + 1 << ": strains " << strains[k - 1] << ", "
                          << strains[k] << ", " << strains[k + 1];
  }
  EXPECT_LT(strains[5], 1e-11);
}

INSTANTIATE_TEST_SUITE_P(ReuseIterations, FastProjectionReuse, testing::Values(0, 8),
                         [](const testing::TestParamInfo<int>& reuse) {
                           return "reuse" + std::to_string(reuse.param);
                         });

// Redundant constraints: a pinned top row (edges between pinned vertices dropped) plus a
// closed loop of pins around the centre. No NaN; converges.
TEST(FastProjection, RedundantPinsAndClosedPinLoops) {
  const ClothMesh mesh = grid(13);
  std::vector<Index> pinned;
  for (Index i = 0; i < 13; ++i) pinned.push_back(mesh.index(i, 12));
  for (Index i = 4; i <= 8; ++i)
    for (Index j = 4; j <= 8; ++j)
      if (i == 4 || i == 8 || j == 4 || j == 8) pinned.push_back(mesh.index(i, j));
  const Eigen::VectorXd w = inverse_masses(mesh, pinned);
  Matrix3X x = mesh.rest_positions;
  for (Index k = 0; k < x.rows(); ++k)
    if (w[k] > 0) x(k, 2) -= 0.01;  // every free vertex dropped by 1 cm
  FastProjection p(make_edge_constraints(mesh, ConstrainedEdges::warp_weft, w), w, fast(1e-6, 50),
                   default_sparse_backend());
  const ProjectionResult r = p.project(x);
  EXPECT_TRUE(x.allFinite());
  EXPECT_TRUE(r.converged) << "max strain " << r.max_strain << " after " << r.iterations;
}

// A taut string: a straight line pinned at both ends at exactly its rest length, its middle
// pulled down. The only solution is the straight line, where the Jacobian loses rank: the
// iteration may not reach the tolerance but must stay finite, never increase the strain, and
// say whether it converged.
TEST(FastProjection, NearlyCollinearEdgesStayFiniteAndHonest) {
  const int n = 11;
  Matrix3X x(n, 3);
  std::vector<EdgeConstraint> constraints;
  Eigen::VectorXd w = Eigen::VectorXd::Ones(n);
  w[0] = w[n - 1] = 0.0;
  for (int i = 0; i < n; ++i) x.row(i) << 0.1 * i, 0.0, -0.002 * std::sin(base::kPi * i / (n - 1));
  for (int i = 0; i + 1 < n; ++i) constraints.push_back({i, i + 1, 0.1});
  const double before = max_edge_strain(constraints, x);
  FastProjection p(constraints, w, fast(1e-6, 30), default_sparse_backend());
  const ProjectionResult r = p.project(x);
  EXPECT_TRUE(x.allFinite());
  EXPECT_LE(r.max_strain, before);
  EXPECT_EQ(r.converged, r.max_strain <= 1e-6);
  EXPECT_NEAR(r.max_strain, max_edge_strain(constraints, x), 1e-15);
}

TEST(PairwiseProjection, ProvotLimitIsMetExactlyForOneEdgeAndApproachedOnAGrid) {
  Matrix3X x(2, 3);
  x << 0, 0, 0, 0.15, 0, 0;
  Eigen::VectorXd w(2);
  w << 1.0, 1.0;
  ProjectionSettings s;
  s.method = ProjectionMethod::pairwise;
  s.max_iterations = 1;
  s.max_stretch = 0.1;
  PairwiseProjection one({{0, 1, 0.1}}, w, s);
  EXPECT_NEAR(one.project(x).max_strain, 0.1, 1e-12);
  EXPECT_NEAR(x(0, 0) + x(1, 0), 0.15, 1e-15);  // equal masses: the midpoint stays

  const ClothMesh mesh = grid(17);
  const Eigen::VectorXd wg = inverse_masses(mesh, {});
  s.max_stretch = 0.0;
  double previous = 1e9;
  for (int sweeps : {1, 4, 16, 64}) {
    Matrix3X xg = jittered(mesh, 0.01, 9);
    s.max_iterations = sweeps;
    PairwiseProjection p(make_edge_constraints(mesh, ConstrainedEdges::warp_weft, wg), wg, s);
    const double strain = p.project(xg).max_strain;
    EXPECT_LT(strain, previous) << sweeps << " sweeps";
    previous = strain;
  }
}

}  // namespace
}  // namespace weft::sim
