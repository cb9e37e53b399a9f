// Embree ray tracer, checked analytically and against the rasterizer:
// - a single triangle is hit where it projects and missed elsewhere, on its two sides;
// - a Lambertian square under the sun and an open sky shows the analytic value
//       byte/255 = colour × (ambient + intensity · max(0, n·l))^(1/2.2)
//   (reflectance colour^2.2, radiance encoded as L^(1/2.2): render/raytrace/shading.h) within
//   1 % + half a byte's rounding, with ambient occlusion, soft shadows and bounces switched on
//   (nothing blocks the sky or the sun, so none may change it), and ambient alone in a shadow;
// - determinism: two runs, 1, 2 and 3 threads, a kept and a fresh geometry give equal bytes;
// - raster and ray-traced silhouettes of the same mesh and camera agree: IoU >= 0.98 (skipped,
//   with the reason, when no OSMesa context can be created).
// On failure the rendered images are written to <build>/test_output/raytrace/.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "render/primitives.h"
#include "render/raster.h"
#include "render/raytrace/ray_tracer.h"
#include "tests/render/render_test_support.h"

namespace weft::render {
namespace {

using test::Pixel;
using test::project;
using test::rectangle;
using test::same_bytes;
using test::to_rgb8;

// A wavy n×n sheet over [−0.5, 0.5]² around height z_m (folds in both directions).
RenderMesh wavy_sheet(int n, double z_m) {
  return make_grid_mesh(n, n, [z_m](double u, double v) {
    const double x = u - 0.5, y = v - 0.5;
    return Eigen::Vector3d(x, y, z_m + 0.08 * std::sin(9.0 * x) * std::cos(5.0 * y) - 0.3 * x * x);
  });
}

// The shared view from above (render_test_support.h), one sample per pixel, two threads.
RenderSettings view_from_above(int width, int height) {
  RenderSettings s = test::view_from_above(width, height);
  s.raytrace.samples_per_pixel = 1;
  s.raytrace.threads = 2;
  return s;
}

// Each channel of `actual` within 1 % of the analytic display value (0..1) plus half a byte.
::testing::AssertionResult near_analytic(Rgb8 actual, const Eigen::Vector3d& expected) {
  const int got[3] = {actual.r, actual.g, actual.b};
  for (int c = 0; c < 3; ++c) {
    const double want = 255.0 * expected[c];
    if (std::abs(got[c] - want) > 0.01 * want + 0.5) {
      return ::testing::AssertionFailure()
             << "channel " << c << " is " << got[c] << ", analytic " << want << " (colour ("
             << int{actual.r} << ", " << int{actual.g} << ", " << int{actual.b} << "))";
    }
  }
  return ::testing::AssertionSuccess();
}

// colour × (ambient + intensity · max(0, n·l))^(1/2.2), display units 0..1.
Eigen::Vector3d lambert_display(const Eigen::Vector3f& colour, const RenderSettings& s,
                                const Eigen::Vector3d& normal, bool sunlit = true) {
  const double cosine = std::max(0.0, normal.dot(s.light_direction.normalized()));
  const double light = s.ambient + (sunlit ? s.light_intensity * cosine : 0.0);
  return colour.cast<double>() * std::pow(light, 1.0 / 2.2);
}

// Pixels differing from the background.
std::vector<bool> silhouette(const Image& image, Rgb8 background) {
  std::vector<bool> mask;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) mask.push_back(!(image.at(x, y) == background));
  return mask;
}

class RayTrace : public ::testing::Test {
 protected:
  // On failure, every image rendered by the test is written where a person can find it.
  void TearDown() override { m_rendered.save_if_failed(); }

  Image render(const RenderMesh& cloth, const RenderSettings& s, const std::string& name,
               const std::vector<RenderObject>& objects = {}) {
    Image image = m_tracer.render(cloth, s, objects);
    m_rendered.add(name, image);
    return image;
  }

  RayTracer m_tracer;
  test::FailureEvidence m_rendered{"raytrace"};
};

TEST_F(RayTrace, SingleTriangleIsHitWhereItProjectsAndMissedElsewhere) {
  RenderSettings s = view_from_above(96, 96);
  s.cloth_surface.sheen = 0.0;  // Lambertian only
  RenderMesh triangle;
  triangle.positions = {{-0.4f, -0.3f, 0.5f}, {0.4f, -0.3f, 0.5f}, {0.0f, 0.5f, 0.5f}};
  triangle.triangles = {{0, 1, 2}};  // counter-clockwise from above: front faces the camera
  const Image image = render(triangle, s, "triangle");
  const Rgb8 background = to_rgb8(s.background);
  const Pixel centroid = project(s, {0.0, -1.0 / 30.0, 0.5});
  EXPECT_TRUE(near_analytic(image.at(centroid.x, centroid.y),
                            lambert_display(s.front_color, s, {0, 0, 1})));
  // Outside the triangle, beside its slanted edges and below its base: the background.
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(-0.35, 0.4, 0.5), Eigen::Vector3d(0.35, 0.4, 0.5),
        Eigen::Vector3d(0.0, -0.45, 0.5), Eigen::Vector3d(0.7, 0.0, 0.5)}) {
    const Pixel q = project(s, p);
    EXPECT_EQ(image.at(q.x, q.y), background) << "at (" << p.transpose() << ")";
  }
  EXPECT_EQ(m_tracer.last_ray_counts().camera, 96u * 96u);

  // Seen from below: the front's colour by default, or the back colour when one is given,
  // lit by the sky alone (the sun is above).
  s.camera.eye = {0, 0, -2};
  const Pixel under = project(s, {0.0, -1.0 / 30.0, 0.5});
  const Image below = render(triangle, s, "triangle_below");
  EXPECT_TRUE(
      near_analytic(below.at(under.x, under.y), lambert_display(s.front_color, s, {0, 0, -1})));
  s.back_color = Eigen::Vector3f(0.25f, 0.45f, 0.80f);
  const Image below_coloured = render(triangle, s, "triangle_below_back_color");
  EXPECT_TRUE(near_analytic(below_coloured.at(under.x, under.y),
                            lambert_display(*s.back_color, s, {0, 0, -1})));
}

TEST_F(RayTrace, LambertianSquareMatchesTheAnalyticValue) {
  RenderSettings s = view_from_above(64, 64);
  s.front_color = {0.9f, 0.6f, 0.3f};
  s.ambient = 0.2;
  s.light_intensity = 0.6;
  s.cloth_surface.sheen = 0.0;  // Lambertian only
  s.raytrace.ao_samples = 4;
  s.raytrace.samples_per_pixel = 4;
  const Pixel centre = project(s, {0.1, -0.1, 0.5});
  for (const Eigen::Vector3d& light :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.3, -0.2, 1), Eigen::Vector3d(1, 0.5, 0.4)}) {
    for (int bounces : {0, 3}) {
      s.light_direction = light;
      s.raytrace.bounces = bounces;
      const Image image = render(rectangle(-0.5, 0.5, -0.5, 0.5, 0.5), s, "lambert");
      EXPECT_TRUE(
          near_analytic(image.at(centre.x, centre.y), lambert_display(s.front_color, s, {0, 0, 1})))
          << "light (" << light.transpose() << "), " << bounces << " bounces";
    }
  }
}

TEST_F(RayTrace, ShadowedPointGetsTheSkyAlone) {
  RenderSettings s = view_from_above(96, 96);
  s.light_direction = {0, 0, 1};
  s.cloth_surface.sheen = 0.0;
  s.raytrace.ao_samples = 0;  // the blocker must not darken the sky term
  s.raytrace.sun_angular_radius_deg = 1.0;
  // A 0.3 m square 0.2 m above the floor's centre: its umbra on the floor is 0.3 − 2·0.2·tan 1°
  // = 0.293 m wide. Seen from above it hides its own shadow, so the camera looks from the side,
  // low enough to see under it.
  RenderObject blocker{rectangle(-0.15, 0.15, -0.15, 0.15, 0.7), {0.2f, 0.8f, 0.2f}};
  s.camera.eye = {2.5, 0, 1.0};
  s.camera.up = {0, 0, 1};
  const RenderMesh floor = rectangle(-1, 1, -1, 1, 0.5);
  const Image image = render(floor, s, "shadow", {blocker});
  const Pixel in_umbra = project(s, {-0.1, 0.0, 0.5});
  const Pixel lit = project(s, {-0.6, 0.0, 0.5});
  EXPECT_TRUE(near_analytic(image.at(in_umbra.x, in_umbra.y),
                            lambert_display(s.front_color, s, {0, 0, 1}, false)));
  EXPECT_TRUE(near_analytic(image.at(lit.x, lit.y), lambert_display(s.front_color, s, {0, 0, 1})));
}

TEST_F(RayTrace, ImagesAreTheSameBytesAcrossRunsAndThreadCounts) {
  RenderSettings s = view_from_above(80, 60);
  s.camera.eye = {1.2, -1.6, 1.6};
  s.camera.up = {0, 0, 1};
  s.ground = true;
  s.raytrace.samples_per_pixel = 4;
  s.raytrace.bounces = 1;
  const RenderMesh cloth = wavy_sheet(24, 0.6);
  const std::vector<RenderObject> sphere{{make_sphere_mesh({0, 0, 0.25}, 0.25, 24, 12)}};
  s.raytrace.threads = 1;
  const Image one = render(cloth, s, "threads1", sphere);
  const Image again = render(cloth, s, "threads1_again", sphere);
  s.raytrace.threads = 2;
  const Image two = render(cloth, s, "threads2", sphere);
  s.raytrace.threads = 3;
  const Image three = render(cloth, s, "threads3", sphere);
  EXPECT_TRUE(same_bytes(one, again));
  EXPECT_TRUE(same_bytes(one, two));
  EXPECT_TRUE(same_bytes(one, three));
  RayTracer fresh;
  EXPECT_TRUE(same_bytes(one, fresh.render(cloth, s, sphere)));
  // Not vacuous: another seed draws other samples.
  s.raytrace.seed = 7;
  EXPECT_FALSE(same_bytes(one, render(cloth, s, "seed7", sphere)));
}

TEST_F(RayTrace, MovedClothUpdatesItsVertexBufferAndMatchesAFreshScene) {
  RenderSettings s = view_from_above(64, 48);
  s.raytrace.samples_per_pixel = 2;
  const Image first = render(wavy_sheet(16, 0.5), s, "first");
  const RenderMesh moved = wavy_sheet(16, 0.8);  // same triangles, other positions
  const Image second = render(moved, s, "moved");
  EXPECT_EQ(m_tracer.cloth_geometry_creations(), 1);
  EXPECT_FALSE(same_bytes(first, second));
  RayTracer fresh;
  EXPECT_TRUE(same_bytes(second, fresh.render(moved, s, {})));
  // Other triangles: a new geometry.
  render(wavy_sheet(12, 0.5), s, "other_topology");
  EXPECT_EQ(m_tracer.cloth_geometry_creations(), 2);
}

TEST_F(RayTrace, BadInputThrowsNamingTheSettingOrObject) {
  RenderSettings s = view_from_above(32, 32);
  s.raytrace.samples_per_pixel = 0;
  try {
    m_tracer.render(wavy_sheet(4, 0.5), s, {});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("raytrace.samples_per_pixel"), std::string::npos)
        << e.what();
  }
  s.raytrace.samples_per_pixel = 1;
  RenderObject bad{wavy_sheet(4, 0.5)};
  bad.mesh.triangles.push_back({0, 1, 99});
  try {
    m_tracer.render(wavy_sheet(4, 0.5), s, {bad});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("object 0: triangle"), std::string::npos) << e.what();
  }
}

TEST_F(RayTrace, SilhouetteMatchesTheRasterizer) {
  std::string why;
  const std::unique_ptr<RasterRenderer> raster = test::osmesa_raster_or_null(why);
  if (!raster) GTEST_SKIP() << "no OSMesa context: " << why;
  RenderSettings s = view_from_above(160, 120);
  s.camera.eye = {1.3, -1.7, 1.4};
  s.camera.target = {0, 0, 0.35};
  s.camera.up = {0, 0, 1};
  s.msaa_samples = 1;  // one sample at each pixel centre, as the ray tracer's single sample
  const RenderMesh cloth = wavy_sheet(32, 0.6);
  const std::vector<RenderObject> sphere{{make_sphere_mesh({0, 0, 0.25}, 0.25, 32, 16)}};
  const Image rasterized = raster->render(cloth, s, sphere);
  m_rendered.add("raster", rasterized);
  const Image traced = render(cloth, s, "traced", sphere);

  const Rgb8 background = to_rgb8(s.background);
  const std::vector<bool> a = silhouette(rasterized, background);
  const std::vector<bool> b = silhouette(traced, background);
  std::size_t intersection = 0, union_count = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    intersection += a[i] && b[i];
    union_count += a[i] || b[i];
  }
  ASSERT_GT(union_count, a.size() / 10) << "the objects should fill a good part of the image";
  const double iou = static_cast<double>(intersection) / static_cast<double>(union_count);
  EXPECT_GE(iou, 0.98) << intersection << " of " << union_count << " pixels agree";
  std::cout << "silhouette IoU raster vs ray traced: " << iou << " (" << union_count
            << " pixels)\n";
}

}  // namespace
}  // namespace weft::render
