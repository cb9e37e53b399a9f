// The spring Hessian against finite differences of the spring gradient, its eigenvalues against
// their closed form, and the projected Hessian's positive semi-definiteness.
#include "sim/energies/spring_hessian.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>
#include <sstream>
#include <string>

#include "sim/energies/spring.h"

namespace weft::sim {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;

// Central differences of spring_gradient_b with respect to xb (which = 1) or xa (which = 0):
// column c is (g(x + ε e_c) − g(x − ε e_c)) / 2ε, N/m.
Mat3 fd_jacobian_of_gradient(Vec3 xa, Vec3 xb, double rest, double k, int which, double eps) {
  Mat3 J;
  Vec3& x = which == 0 ? xa : xb;
  for (int c = 0; c < 3; ++c) {
    const double saved = x[c];
    x[c] = saved + eps;
    const Vec3 plus = spring_gradient_b(xa, xb, rest, k);
    x[c] = saved - eps;
    const Vec3 minus = spring_gradient_b(xa, xb, rest, k);
    x[c] = saved;
    J.col(c) = (plus - minus) / (2 * eps);
  }
  return J;
}

std::string show(const Mat3& analytic, const Mat3& fd) {
  std::ostringstream out;
  out << "\n analytic\n" << analytic << "\n fd\n" << fd;
  return out.str();
}

Mat6 full_hessian(const Mat3& H) {
  Mat6 F;
  F << H, -H, -H, H;
  return F;
}

// Random spring lengths from 0.3 l (strongly compressed) to 2 l (stretched), random directions.
struct Generated {
  Vec3 xa, xb;
};
Generated generate(std::mt19937& rng, double rest) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), length(0.3 * rest, 2.0 * rest);
  const Vec3 xa(u(rng), u(rng), u(rng));
  Vec3 dir(u(rng), u(rng), u(rng));
  while (dir.norm() < 1e-3) dir = Vec3(u(rng), u(rng), u(rng));
  return {xa, xa + length(rng) * dir.normalized()};
}

TEST(SpringHessian, MatchesFiniteDifferencesOfTheGradientForStretchedAndCompressedSprings) {
  std::mt19937 rng(2024);
  const double rest = 0.04, k = 830.0;
  for (int trial = 0; trial < 300; ++trial) {
    const auto [xa, xb] = generate(rng, rest);
    const Mat3 H = spring_hessian_b(xa, xb, rest, k);
    const Mat3 fd_b = fd_jacobian_of_gradient(xa, xb, rest, k, 1, 1e-7);
    const Mat3 fd_a = fd_jacobian_of_gradient(xa, xb, rest, k, 0, 1e-7);
    const double tol = 1e-6 * std::max(k, fd_b.norm());
    const std::string what =
        "trial " + std::to_string(trial) + ", |d|/l = " + std::to_string((xb - xa).norm() / rest);
    EXPECT_LE((H - fd_b).norm(), tol) << what << " (∂/∂xb)" << show(H, fd_b);
    // The off-diagonal block of the 6×6 Hessian: ∂(∂E/∂xb)/∂xa = −H.
    EXPECT_LE((-H - fd_a).norm(), tol) << what << " (∂/∂xa)" << show(-H, fd_a);
    EXPECT_LE((H - H.transpose()).norm(), 1e-12 * k) << what;
  }
}

TEST(SpringHessian, EigenvaluesAreKAlongTheSpringAndKTimesOneMinusRestOverLengthAcross) {
  const double rest = 0.5, k = 40.0;
  const Vec3 xa(0.3, -0.2, 1.0), dir = Vec3(2, -1, 0.5).normalized();
  for (double ratio : {0.4, 0.9, 1.0, 1.3, 3.0}) {
    const Vec3 xb = xa + ratio * rest * dir;
    const Mat3 H = spring_hessian_b(xa, xb, rest, k);
    EXPECT_NEAR(dir.dot(H * dir), k, 1e-12 * k) << "ratio " << ratio;
    EXPECT_LT((H * dir - k * dir).norm(), 1e-12 * k) << "ratio " << ratio;  // d̂ is an eigenvector
    const Vec3 across = dir.unitOrthogonal();
    EXPECT_LT((H * across - k * (1.0 - 1.0 / ratio) * across).norm(), 1e-12 * k)
        << "ratio " << ratio;
  }
}

TEST(SpringHessian, ProjectedIsPositiveSemiDefiniteForCompressedAndStretchedSprings) {
  std::mt19937 rng(99);
  const double rest = 0.02, k = 1e5;
  int compressed = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const auto [xa, xb] = generate(rng, rest);
    const bool is_compressed = (xb - xa).norm() < rest;
    compressed += is_compressed;
    const Mat3 P = spring_hessian_b_projected(xa, xb, rest, k);
    const Mat3 H = spring_hessian_b(xa, xb, rest, k);
    const Eigen::Vector3d eig3 = Eigen::SelfAdjointEigenSolver<Mat3>(P).eigenvalues();
    const Eigen::Matrix<double, 6, 1> eig6 =
        Eigen::SelfAdjointEigenSolver<Mat6>(full_hessian(P)).eigenvalues();
    EXPECT_GE(eig3.minCoeff(), -1e-12 * k)
        << "trial " << trial << " eigenvalues " << eig3.transpose();
    EXPECT_GE(eig6.minCoeff(), -1e-12 * k)
        << "trial " << trial << " eigenvalues " << eig6.transpose();
    EXPECT_LE(eig3.maxCoeff(), k * (1 + 1e-12)) << "trial " << trial;
    if (is_compressed) {
      // The unprojected Hessian buckles (negative transverse eigenvalues); the projection keeps
      // only the stiffness along the spring: k d̂d̂ᵀ.
      EXPECT_LT(Eigen::SelfAdjointEigenSolver<Mat3>(H).eigenvalues().minCoeff(), 0.0);
      const Vec3 u = (xb - xa).normalized();
      EXPECT_LT((P - k * u * u.transpose()).norm(), 1e-12 * k) << "trial " << trial;
    } else {
      EXPECT_LT((P - H).norm(), 1e-12 * k) << "trial " << trial;  // nothing to project
    }
  }
  EXPECT_GT(compressed, 50);  // the generator covers both cases
  EXPECT_LT(compressed, 250);
}

TEST(SpringHessian, ZeroLengthSpringHasZeroHessianLikeItsZeroGradient) {
  const Vec3 x(0.1, 0.2, 0.3);
  EXPECT_EQ(spring_hessian_b(x, x, 0.5, 10.0), Mat3::Zero());
  EXPECT_EQ(spring_hessian_b_projected(x, x, 0.5, 10.0), Mat3::Zero());
}

}  // namespace
}  // namespace weft::sim
