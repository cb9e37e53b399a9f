// Environment maps (render/environment.h), checked against integrals computed here by fine
// midpoint quadrature:
// - the spherical-harmonic projection of a constant map is exact (1e-5: float sums), that of a
//   128×64 map holding the texel means of a band-≤2 function exact up to the map's
//   discretisation (1e-3), and rotating the map by 90° turns the function as the direction
//   mapping says;
// - sample() and pdf() agree, and the pdf integrates to 1 over the sphere;
// - on a real map (tests/data/hdri/studio_128x64.hdr, CC0), irradiance estimated by importance
//   sampling and by uniform sampling agree within 4 combined standard errors, both agree with
//   the quadrature, and importance sampling has the smaller standard error;
// - the 9-coefficient irradiance of that map is within 8 % of its largest irradiance (over the
//   test normals) of the quadrature: the band-limiting error of a map lit by two compact
//   softboxes (measured 6.5 %: 0.79 against 0.65 facing up, largest 2.06 facing −y).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "base/constants.h"
#include "render/environment.h"
#include "render/raytrace/sampling.h"

namespace weft::render {
namespace {

constexpr double pi = base::kPi;

// Direction of map point (u, v) (environment.h's mapping).
Eigen::Vector3d map_direction(double u, double v) {
  const double theta = pi * v, phi = pi * (1.0 - 2.0 * u);
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// ∫ f dω over texel (x, y) of a w×h map, by n×n midpoints, divided by the texel's solid angle
// when `mean`.
double texel_integral(int x, int y, int w, int h, const std::function<double(Eigen::Vector3d)>& f,
                      int n = 16, bool mean = false) {
  double sum = 0.0, area = 0.0;
  for (int j = 0; j < n; ++j) {
    const double v = (y + (j + 0.5) / n) / h;
    const double d_omega = (2.0 * pi / (w * n)) * (pi / (h * n)) * std::sin(pi * v);
    for (int i = 0; i < n; ++i) {
      sum += f(map_direction((x + (i + 0.5) / n) / w, v)) * d_omega;
      area += d_omega;
    }
  }
  return mean ? sum / area : sum;
}

// A w×h map whose texels hold the texel means of f (grey).
std::shared_ptr<const EnvironmentMap> map_of(int w, int h,
                                             const std::function<double(Eigen::Vector3d)>& f) {
  std::vector<Eigen::Vector3f> texels;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x)
      texels.push_back(
          Eigen::Vector3f::Constant(static_cast<float>(texel_integral(x, y, w, h, f, 4, true))));
  }
  return std::make_shared<const EnvironmentMap>(w, h, std::move(texels));
}

TEST(EnvironmentSh, ConstantMapProjectsExactly) {
  const Eigen::Vector3f radiance(0.7f, 1.3f, 2.0f);
  Environment e;
  e.map = std::make_shared<const EnvironmentMap>(
      24, 12, std::vector<Eigen::Vector3f>(24 * 12, radiance));
  e.intensity = 1.5;
  e.rotation_deg = 33.0;
  const ShCoefficients c = project_sh(e);
  // L_00 = L · Y_00 · 4π = L · 2√π; the other bands integrate to zero over the sphere.
  const Eigen::Vector3f l00 = 1.5f * radiance * static_cast<float>(2.0 * std::sqrt(pi));
  EXPECT_LT((c[0] - l00).norm(), 1e-5f * l00.norm());
  for (int k = 1; k < 9; ++k) EXPECT_LT(c[k].norm(), 1e-5f * l00.norm()) << "coefficient " << k;
  // Irradiance of a uniform radiance L is π L for every normal.
  for (const Eigen::Vector3f& n : {Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(0, 0, -1),
                                  Eigen::Vector3f(0.6f, -0.8f, 0.0f)}) {
    const Eigen::Vector3f expected = base::kPiF * 1.5f * radiance;
    EXPECT_LT((sh_irradiance(c, n) - expected).norm(), 1e-5f * expected.norm());
  }
}

// L(d) = a + b z + e x y, a function of bands 0, 1 and 2, held by a 128×64 map of its texel
// means: the projection is exact up to the map's own discretisation (the function varies
// within a texel; the error is second order in the texel size, under 1e-3 here).
TEST(EnvironmentSh, LowOrderFunctionProjectsExactlyAndTurnsWithTheMap) {
  const double a = 1.0, b = 0.6, e = 0.8;
  Environment env;
  env.map = map_of(128, 64, [&](Eigen::Vector3d d) { return a + b * d.z() + e * d.x() * d.y(); });
  const double c1 = std::sqrt(3.0 / (4.0 * pi)), c2 = std::sqrt(15.0 / (4.0 * pi));
  // ∫ Y_00 L = a 2√π; ∫ c1 z · b z = b c1 4π/3; ∫ c2 x y · e x y = e c2 4π/15.
  for (const double rotation : {0.0, 90.0}) {
    env.rotation_deg = rotation;
    const ShCoefficients c = project_sh(env);
    // Turned 90° counter-clockwise, the world sees the map's (x, y) at (−y, x): e x y → −e x y.
    const double sign = rotation == 0.0 ? 1.0 : -1.0;
    const double expected[9] = {a * 2.0 * std::sqrt(pi), 0, b * c1 * 4.0 * pi / 3.0, 0,
                                sign * e * c2 * 4.0 * pi / 15.0, 0, 0, 0, 0};
    for (int k = 0; k < 9; ++k)
      EXPECT_NEAR(c[k].x(), expected[k], 1e-3) << "coefficient " << k << ", rotation " << rotation;
    // E(n) = π a + (2π/3) b n_z + (π/4) e n_x n_y, exactly, for this band-limited radiance.
    const Eigen::Vector3f n = Eigen::Vector3f(0.5f, 0.7f, -0.3f).normalized();
    const double want = pi * a + 2.0 * pi / 3.0 * b * n.z() + sign * pi / 4.0 * e * n.x() * n.y();
    EXPECT_NEAR(sh_irradiance(c, n).x(), want, 1e-3 * want) << "rotation " << rotation;
  }
}

std::shared_ptr<const EnvironmentMap> studio() {
  return std::make_shared<const EnvironmentMap>(read_environment_map(
      std::filesystem::path(WEFT_SOURCE_DIR) / "tests/data/hdri/studio_128x64.hdr"));
}

double luminance(const Eigen::Vector3f& c) {
  return 0.2126 * c.x() + 0.7152 * c.y() + 0.0722 * c.z();
}

TEST(EnvironmentSampling, SampleAndPdfAgreeAndThePdfIntegratesToOne) {
  const auto map = studio();
  ASSERT_EQ(map->width(), 128);
  ASSERT_EQ(map->height(), 64);
  rt::Pcg32 rng(7);
  for (int k = 0; k < 2000; ++k) {
    const EnvironmentMap::Sample s = map->sample(rng.next_float(), rng.next_float());
    ASSERT_NEAR(s.direction.norm(), 1.0f, 1e-5f);
    ASSERT_NEAR(map->pdf(s.direction), s.pdf, 2e-3f * s.pdf) << "sample " << k;
  }
  double integral = 0.0;
  const int w = 1024, h = 512;
  for (int y = 0; y < h; ++y) {
    const double d_omega = (2.0 * pi / w) * (pi / h) * std::sin(pi * (y + 0.5) / h);
    for (int x = 0; x < w; ++x)
      integral += map->pdf(map_direction((x + 0.5) / w, (y + 0.5) / h).cast<float>()) * d_omega;
  }
  EXPECT_NEAR(integral, 1.0, 2e-3);
}

struct Estimate {
  double mean = 0.0, standard_error = 0.0;
};

// Luminance of the irradiance E(n) = ∫ L max(0, n·d) dω from n samples of `draw`, which returns
// a direction and its pdf.
Estimate irradiance_estimate(const EnvironmentMap& map, const Eigen::Vector3f& normal, int n,
                             const std::function<EnvironmentMap::Sample(rt::Pcg32&)>& draw) {
  rt::Pcg32 rng(12345);
  double sum = 0.0, sum2 = 0.0;
  for (int k = 0; k < n; ++k) {
    const EnvironmentMap::Sample s = draw(rng);
    const double value = s.pdf > 0.0f ? luminance(map.radiance(s.direction)) *
                                            std::max(0.0f, normal.dot(s.direction)) / s.pdf
                                      : 0.0;
    sum += value;
    sum2 += value * value;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

// The same by quadrature: 8×8 midpoints per texel, each texel's own radiance.
double irradiance_quadrature(const EnvironmentMap& map, const Eigen::Vector3f& normal) {
  double e = 0.0;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      e += luminance(map.texel(x, y)) *
           texel_integral(x, y, map.width(), map.height(),
                          [&](Eigen::Vector3d d) { return std::max(0.0, normal.cast<double>().dot(d)); },
                          8);
    }
  }
  return e;
}

const std::vector<Eigen::Vector3f>& test_normals() {
  static const std::vector<Eigen::Vector3f> normals = {
      Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(0, -1, 0),
      Eigen::Vector3f(-0.5f, 0.5f, 0.7f).normalized(), Eigen::Vector3f(0.3f, 0.2f, -0.9f).normalized()};
  return normals;
}

TEST(EnvironmentSampling, ImportanceAndUniformSamplingAgreeOnARealMap) {
  const auto map = studio();
  for (const Eigen::Vector3f& n : test_normals()) {
    const Estimate importance = irradiance_estimate(*map, n, 20000, [&](rt::Pcg32& rng) {
      return map->sample(rng.next_float(), rng.next_float());
    });
    const Estimate uniform = irradiance_estimate(*map, n, 200000, [](rt::Pcg32& rng) {
      const float z = 1.0f - 2.0f * rng.next_float(), phi = 2.0f * base::kPiF * rng.next_float();
      const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
      return EnvironmentMap::Sample{{r * std::cos(phi), r * std::sin(phi), z},
                                    1.0f / (4.0f * base::kPiF)};
    });
    const double reference = irradiance_quadrature(*map, n);
    const double combined = std::hypot(importance.standard_error, uniform.standard_error);
    SCOPED_TRACE("normal " + std::to_string(n.x()) + " " + std::to_string(n.y()) + " " +
                 std::to_string(n.z()) + ": quadrature " + std::to_string(reference) +
                 ", importance " + std::to_string(importance.mean) + " ± " +
                 std::to_string(importance.standard_error) + ", uniform " +
                 std::to_string(uniform.mean) + " ± " + std::to_string(uniform.standard_error));
    EXPECT_LT(std::abs(importance.mean - uniform.mean), 4.0 * combined);
    EXPECT_LT(std::abs(importance.mean - reference), 4.0 * importance.standard_error + 1e-3 * reference);
    EXPECT_LT(std::abs(uniform.mean - reference), 4.0 * uniform.standard_error + 1e-3 * reference);
    // Per sample, importance sampling's spread is smaller for surfaces that face the lights
    // (the map's pdf ignores the cosine, so a surface facing down gets few useful samples).
    if (n.z() >= 0.0f) {
      EXPECT_LT(importance.standard_error * std::sqrt(20000.0),
                uniform.standard_error * std::sqrt(200000.0));
    }
  }
}

TEST(EnvironmentSh, IrradianceOfARealMapIsWithinTheBandLimitError) {
  Environment env;
  env.map = studio();
  const ShCoefficients c = project_sh(env);
  double worst = 0.0, largest = 0.0;
  for (const Eigen::Vector3f& n : test_normals()) {
    const double reference = irradiance_quadrature(*env.map, n);
    const double sh = luminance(sh_irradiance(c, n));
    std::cout << "normal " << n.transpose() << ": quadrature " << reference << ", SH " << sh
              << "\n";
    worst = std::max(worst, std::abs(sh - reference));
    largest = std::max(largest, reference);
  }
  std::cout << "studio_128x64: largest SH irradiance error " << worst / largest
            << " of the largest irradiance\n";
  EXPECT_LT(worst, 0.08 * largest);
}

TEST(EnvironmentMapFile, WritesAndReadsRadianceFiles) {
  const std::filesystem::path path =
      std::filesystem::path(WEFT_BINARY_DIR) / "test_output" / "environment" / "gradient.hdr";
  std::filesystem::create_directories(path.parent_path());
  const auto map = map_of(16, 8, [](Eigen::Vector3d d) { return 2.0 + d.z(); });
  write_environment_map(path, *map);
  const EnvironmentMap back = read_environment_map(path);
  ASSERT_EQ(back.width(), 16);
  ASSERT_EQ(back.height(), 8);
  // RGBE keeps 8 bits of mantissa: within 1 %.
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 16; ++x)
      EXPECT_NEAR(back.texel(x, y).x(), map->texel(x, y).x(), 0.01 * map->texel(x, y).x());
  }
  try {
    read_environment_map(path.parent_path() / "missing.hdr");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.hdr"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace weft::render
