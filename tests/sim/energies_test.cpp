// Finite-difference checks of every energy kernel's gradient over generated inputs.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "sim/energies/bend_angle.h"
#include "sim/energies/spring.h"

namespace weft::sim {
namespace {

using Energy = std::function<double(const std::vector<Vec3>&)>;

// Central differences of `energy` with respect to each coordinate of each point.
std::vector<Vec3> fd_gradient(const Energy& energy, std::vector<Vec3> x, double h) {
  std::vector<Vec3> g(x.size(), Vec3::Zero());
  for (std::size_t p = 0; p < x.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      const double saved = x[p][c];
      x[p][c] = saved + h;
      const double plus = energy(x);
      x[p][c] = saved - h;
      const double minus = energy(x);
      x[p][c] = saved;
      g[p][c] = (plus - minus) / (2 * h);
    }
  }
  return g;
}

void expect_gradients_agree(const std::vector<Vec3>& analytic, const std::vector<Vec3>& fd,
                            double rel_tol, const std::string& what) {
  double scale = 1e-12;
  for (const auto& g : fd) scale = std::max(scale, g.norm());
  for (std::size_t p = 0; p < fd.size(); ++p)
    EXPECT_LE((analytic[p] - fd[p]).norm(), rel_tol * scale)
        << what << " point " << p << "\n analytic " << analytic[p].transpose() << "\n fd       "
        << fd[p].transpose();
}

std::vector<Vec3> random_points(std::mt19937& rng, int count, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  std::vector<Vec3> x(count);
  for (auto& p : x) p = Vec3(u(rng), u(rng), u(rng));
  return x;
}

TEST(SpringEnergy, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const auto x = random_points(rng, 2, 0.05);
    const double rest = 0.03, k = 250.0;
    const Energy e = [&](const std::vector<Vec3>& p) { return spring_energy(p[0], p[1], rest, k); };
    const Vec3 gb = spring_gradient_b(x[0], x[1], rest, k);
    expect_gradients_agree({-gb, gb}, fd_gradient(e, x, 1e-7), 1e-6, "trial " + std::to_string(trial));
  }
}

TEST(SpringEnergy, ZeroAtRestLengthWhateverTheDirection) {
  const Vec3 a(0.1, 0.2, 0.3), d = Vec3(1, -2, 0.5).normalized();
  EXPECT_NEAR(spring_energy(a, a + 0.7 * d, 0.7, 1e3), 0.0, 1e-25);
  EXPECT_LT(spring_gradient_b(a, a + 0.7 * d, 0.7, 1e3).norm(), 1e-10);
  EXPECT_EQ(spring_gradient_b(a, a, 0.7, 1e3), Vec3::Zero());
}

TEST(BendAngleEnergy, GradientMatchesFiniteDifferencesForBentStraightAndFoldedLines) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    auto x = random_points(rng, 3, 0.02);
    if (trial % 3 == 1) x[2] = x[1] + 0.8 * (x[1] - x[0]) + Vec3(1e-4, -2e-4, 3e-4);  // nearly straight
    const double rest = (trial % 2 == 0) ? 0.0 : 0.4;
    const double k = 3e-4;
    const Energy e = [&](const std::vector<Vec3>& p) {
      return bend_angle_energy(p[0], p[1], p[2], rest, k);
    };
    const auto g = bend_angle_gradient(x[0], x[1], x[2], rest, k);
    expect_gradients_agree({g[0], g[1], g[2]}, fd_gradient(e, x, 1e-8), 2e-5,
                           "trial " + std::to_string(trial));
  }
}

TEST(BendAngleEnergy, ExactlyStraightLineHasNoForceAndTheGradientSumsToZero) {
  const Vec3 x0(0, 0, 0), x1(0.1, 0, 0), x2(0.2, 0, 0);
  for (const auto& g : bend_angle_gradient(x0, x1, x2, 0.0, 1.0)) EXPECT_EQ(g, Vec3::Zero());
  const auto g = bend_angle_gradient(x0, x1, Vec3(0.25, 0.07, -0.02), 0.0, 1.0);
  EXPECT_LT((g[0] + g[1] + g[2]).norm(), 1e-12);
}

TEST(BendAngleEnergy, SmallAngleEnergyIsHalfKThetaSquared) {
  const double theta = 1e-3;
  const Vec3 x2(1.0 + std::cos(theta), std::sin(theta), 0.0);
  EXPECT_NEAR(bend_angle_energy(Vec3::Zero(), Vec3(1, 0, 0), x2, 0.0, 2.0), theta * theta, 1e-15);
}

}  // namespace
}  // namespace weft::sim
