// Spherical-harmonic projection of an environment map and the irradiance it gives
// (environment.h; Ramamoorthi & Hanrahan 2001, "An Efficient Representation for Irradiance
// Environment Maps"). Each basis function is a product f(θ) g(φ) of sines and cosines, so its
// integral over a texel (dω = sin θ dθ dφ) has a closed form: the projection of the piecewise-
// constant map is exact, not a sum at texel centres.

#include <array>
#include <cmath>
#include <vector>

#include "base/constants.h"
#include "render/environment.h"

namespace weft::render {

namespace {

using base::kPi;
// Normalisation constants of the real basis (environment.h's order).
const double c0 = 0.5 / std::sqrt(kPi);             // 0.282095
const double c1 = std::sqrt(3.0 / (4.0 * kPi));     // 0.488603
const double c2 = std::sqrt(15.0 / (4.0 * kPi));    // 1.092548
const double c3 = std::sqrt(5.0 / (16.0 * kPi));    // 0.315392
const double c4 = std::sqrt(15.0 / (16.0 * kPi));   // 0.546274

// ∫ f(θ) sin θ dθ over [a, b] for f = 1, cos, cos², sin, cos·sin, sin².
struct ThetaIntegrals {
  double one, z, zz, s, zs, ss;
};
ThetaIntegrals theta_integrals(double a, double b) {
  const auto diff = [&](auto f) { return f(b) - f(a); };
  return {diff([](double t) { return -std::cos(t); }),
          diff([](double t) { return 0.5 * std::sin(t) * std::sin(t); }),
          diff([](double t) { return -std::pow(std::cos(t), 3) / 3.0; }),
          diff([](double t) { return 0.5 * t - 0.25 * std::sin(2.0 * t); }),
          diff([](double t) { return std::pow(std::sin(t), 3) / 3.0; }),
          diff([](double t) { return -std::cos(t) + std::pow(std::cos(t), 3) / 3.0; })};
}

// ∫ g(φ) dφ over [a, b] for g = 1, cos φ, sin φ, cos 2φ, sin 2φ.
struct PhiIntegrals {
  double one, c1, s1, c2, s2;
};
PhiIntegrals phi_integrals(double a, double b) {
  return {b - a, std::sin(b) - std::sin(a), std::cos(a) - std::cos(b),
          0.5 * (std::sin(2.0 * b) - std::sin(2.0 * a)),
          0.5 * (std::cos(2.0 * a) - std::cos(2.0 * b))};
}

// ∫ Y_k dω over one texel, k in environment.h's order.
std::array<double, 9> texel_integrals(const ThetaIntegrals& t, const PhiIntegrals& p) {
  return {c0 * t.one * p.one,          c1 * t.s * p.s1,          c1 * t.z * p.one,
          c1 * t.s * p.c1,             0.5 * c2 * t.ss * p.s2,   c2 * t.zs * p.s1,
          c3 * (3.0 * t.zz - t.one) * p.one, c2 * t.zs * p.c1, c4 * t.ss * p.c2};
}

}  // namespace

ShBasis sh_basis(const Eigen::Vector3f& d) {
  const double x = d.x(), y = d.y(), z = d.z();
  const std::array<double, 9> b = {c0,         c1 * y,     c1 * z,
                                   c1 * x,     c2 * x * y, c2 * y * z,
                                   c3 * (3.0 * z * z - 1.0), c2 * x * z, c4 * (x * x - y * y)};
  ShBasis out;
  for (int k = 0; k < 9; ++k) out[k] = static_cast<float>(b[k]);
  return out;
}

ShCoefficients project_sh(const Environment& environment) {
  const EnvironmentMap& map = *environment.map;
  const int w = map.width(), h = map.height();
  const double rotation = base::deg_to_rad(environment.rotation_deg);
  // Column x spans map azimuths π (1 − 2(x+1)/W) … π (1 − 2x/W); the world's are turned by α.
  std::vector<PhiIntegrals> columns(static_cast<std::size_t>(w));
  for (int x = 0; x < w; ++x) {
    columns[x] = phi_integrals(kPi * (1.0 - 2.0 * (x + 1) / w) + rotation,
                               kPi * (1.0 - 2.0 * x / w) + rotation);
  }
  std::array<Eigen::Vector3d, 9> sum;
  sum.fill(Eigen::Vector3d::Zero());
  for (int y = 0; y < h; ++y) {
    const ThetaIntegrals row = theta_integrals(kPi * y / h, kPi * (y + 1) / h);
    for (int x = 0; x < w; ++x) {
      const std::array<double, 9> integral = texel_integrals(row, columns[x]);
      const Eigen::Vector3d radiance = map.texel(x, y).cast<double>();
      for (int k = 0; k < 9; ++k) sum[k] += integral[k] * radiance;
    }
  }
  ShCoefficients out;
  for (int k = 0; k < 9; ++k) out[k] = (environment.intensity * sum[k]).cast<float>();
  return out;
}

ShCoefficients sh_reflected_radiance(const ShCoefficients& radiance) {
  // Â_l / π: 1, 2/3, 1/4 for bands 0, 1, 2.
  constexpr float band[9] = {1.0f,        2.0f / 3.0f, 2.0f / 3.0f, 2.0f / 3.0f, 0.25f,
                             0.25f,       0.25f,       0.25f,       0.25f};
  ShCoefficients out;
  for (int k = 0; k < 9; ++k) out[k] = band[k] * radiance[k];
  return out;
}

ShCoefficients sh_reflected_polynomial(const ShCoefficients& radiance) {
  const double constant[9] = {c0, c1, c1, c1, c2, c2, c3, c2, c4};
  ShCoefficients out = sh_reflected_radiance(radiance);
  for (int k = 0; k < 9; ++k) out[k] *= static_cast<float>(constant[k]);
  return out;
}

Eigen::Vector3f sh_polynomial_value(const ShCoefficients& p, const Eigen::Vector3f& n) {
  const float x = n.x(), y = n.y(), z = n.z();
  return p[0] + p[1] * y + p[2] * z + p[3] * x + p[4] * (x * y) + p[5] * (y * z) +
         p[6] * (3.0f * z * z - 1.0f) + p[7] * (x * z) + p[8] * (x * x - y * y);
}

Eigen::Vector3f sh_irradiance(const ShCoefficients& radiance, const Eigen::Vector3f& n) {
  const ShCoefficients reflected = sh_reflected_radiance(radiance);
  const ShBasis y = sh_basis(n);
  Eigen::Vector3f e = Eigen::Vector3f::Zero();
  for (int k = 0; k < 9; ++k) e += y[k] * reflected[k];
  return base::kPiF * e;
}

}  // namespace weft::render
