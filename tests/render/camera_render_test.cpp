// Calibrated cameras and cloth masks through both renderers (render/renderer.h):
// - markers (small white spheres on black) at known 3D points appear where OpenCV's projection
//   puts them — the coverage-weighted centroid of each marker within 0.5 px — in the raster
//   and the ray-traced image, with fx ≠ fy, an off-centre principal point and an image half
//   the calibrated size;
// - the cloth mask (Renderer::render_mask) of a flat rectangle seen square-on has the area
//   fx fy A / Z² within the perimeter's pixels, and both renderers' masks of a wavy cloth behind
//   a sphere agree (IoU ≥ 0.99) and leave out what the sphere hides;
// - the look-at path is unchanged (the golden images check that bit for bit).
// The rasterizer's half is skipped, with the reason, when no GL context can be created.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "render/primitives.h"
#include "render/renderer.h"
#include "tests/render/render_test_support.h"

namespace weft::render {
namespace {

// Intrinsics for 640×480 (fx ≠ fy, principal point off the centre); the tests render 320×240.
PinholeIntrinsics calibration() {
  PinholeIntrinsics k;
  k.fx_px = 520.0;
  k.fy_px = 585.0;
  k.cx_px = 351.3;
  k.cy_px = 221.7;
  k.width_px = 640;
  k.height_px = 480;
  return k;
}

// OpenCV's pixel of p in an image scaled by s from the calibrated size (edges kept).
Eigen::Vector2d opencv_pixel(const PinholeIntrinsics& k, const Eigen::Matrix3d& r,
                             const Eigen::Vector3d& t, const Eigen::Vector3d& p, double s) {
  const Eigen::Vector3d c = r.transpose() * (p - t);
  const Eigen::Vector2d full(k.fx_px * c.x() / c.z() + k.cx_px, k.fy_px * c.y() / c.z() + k.cy_px);
  return s * (full + Eigen::Vector2d::Constant(0.5)) - Eigen::Vector2d::Constant(0.5);
}

// Unlit, flat: surfaces white, background black, no ground.
RenderSettings flat_settings(RendererKind kind, const Camera& camera) {
  RenderSettings s;
  s.width = 320;
  s.height = 240;
  s.camera = camera;
  s.ground = false;
  s.light_intensity = 0.0;
  s.ambient = 1.0;
  s.front_color = Eigen::Vector3f::Ones();
  s.background = Eigen::Vector3f::Zero();
  s.msaa_samples = 8;
  s.renderer = kind;
  s.raytrace.samples_per_pixel = 64;
  s.raytrace.bounces = 0;
  s.raytrace.ao_samples = 0;
  s.raytrace.threads = 2;
  return s;
}


// Coverage-weighted centroid of the pixels within `radius` px of `around`: the raster's bytes
// are linear in coverage (flat white, multisample resolve), the ray tracer's are encoded as
// coverage^(1/2.2) (raytrace/shading.h) and decoded here.
Eigen::Vector2d marker_centroid(const Image& image, const Eigen::Vector2d& around, int radius,
                                bool encoded) {
  double sum = 0.0;
  Eigen::Vector2d weighted = Eigen::Vector2d::Zero();
  const int x0 = static_cast<int>(std::lround(around.x())), y0 = static_cast<int>(std::lround(around.y()));
  for (int y = y0 - radius; y <= y0 + radius; ++y) {
    for (int x = x0 - radius; x <= x0 + radius; ++x) {
      if (x < 0 || y < 0 || x >= image.width() || y >= image.height()) continue;
      const double byte = image.at(x, y).g / 255.0;
      const double w = encoded ? std::pow(byte, 2.2) : byte;
      sum += w;
      weighted += w * Eigen::Vector2d(x, y);
    }
  }
  return sum > 0.0 ? Eigen::Vector2d(weighted / sum) : Eigen::Vector2d::Constant(-1e9);
}

class CameraRender : public ::testing::Test {
 protected:
  void TearDown() override { m_evidence.save_if_failed(); }
  test::FailureEvidence m_evidence{"camera_render"};
};

TEST_F(CameraRender, MarkersLandWhereOpenCVProjectsThem) {
  const PinholeIntrinsics k = calibration();
  const Eigen::Vector3d eye(0.45, -1.6, 0.95);
  const Eigen::Matrix3d r = test::opencv_look_at(eye, {0.0, 0.0, 0.3}, 0.15);
  const Camera camera = Camera::calibrated(k, r, eye);
  std::vector<Eigen::Vector3d> points;
  for (int i = -2; i <= 2; ++i)
    for (int j = -1; j <= 1; ++j) points.emplace_back(0.18 * i, 0.1 * j, 0.3 + 0.17 * j + 0.02 * i);
  // Each marker about 2.5 px in radius in the 320×240 image.
  std::vector<RenderObject> markers;
  for (const Eigen::Vector3d& p : points) {
    const double depth = (r.transpose() * (p - eye)).z();
    markers.push_back({make_sphere_mesh(p, 2.5 * depth / (0.5 * k.fy_px), 24, 12),
                       Eigen::Vector3f::Ones()});
  }
  const RenderMesh cloth = markers.front().mesh;  // the first marker stands in for the cloth
  markers.erase(markers.begin());
  for (const RendererKind kind : {RendererKind::raster, RendererKind::raytrace}) {
    const RenderSettings s = flat_settings(kind, camera);
    std::string why;
    const std::unique_ptr<Renderer> renderer = test::try_renderer(s, why);
    if (!renderer) {
      std::cout << "skipped " << renderer_name(kind) << ": " << why << "\n";
      continue;
    }
    const Image image = renderer->render(cloth, s, markers);
    m_evidence.add(renderer_name(kind), image);
    double worst = 0.0;
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector2d want = opencv_pixel(k, r, eye, p, 0.5);
      ASSERT_TRUE(want.x() > 6 && want.y() > 6 && want.x() < 313 && want.y() < 233) << want;
      const Eigen::Vector2d got =
          marker_centroid(image, want, 6, kind == RendererKind::raytrace);
      EXPECT_LT((got - want).norm(), 0.5)
          << renderer_name(kind) << ": marker at " << p.transpose() << " expected at ("
          << want.transpose() << "), centroid (" << got.transpose() << ")";
      worst = std::max(worst, (got - want).norm());
    }
    std::cout << renderer_name(kind) << ": worst marker centroid error " << worst << " px over "
              << points.size() << " markers\n";
  }
}

// A camera straight above (0, 0, 0), 1.5 m up, image x along world +x, image y along world −y.
Camera camera_above() {
  Eigen::Matrix3d r;
  r << Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitZ();
  return Camera::calibrated(calibration(), r, {0.0, 0.0, 1.5});
}

double iou(const Mask& a, const Mask& b) {
  long both = 0, either = 0;
  for (std::size_t i = 0; i < a.in.size(); ++i) {
    both += a.in[i] && b.in[i];
    either += a.in[i] || b.in[i];
  }
  return either > 0 ? static_cast<double>(both) / static_cast<double>(either) : 0.0;
}

// A flat 0.4 m × 0.3 m cloth seen square-on: its mask is exactly the pixels whose centres lie
// inside its projection, u in (u0, u1) and v in (v0, v1) from OpenCV's formula; a sphere
// above it hides part of it from the cloth mask but not from the surfaces mask.
TEST_F(CameraRender, MaskOfAFlatClothIsItsProjectedRectangle) {
  const Camera camera = camera_above();
  const RenderMesh cloth = test::rectangle(-0.23, 0.17, -0.11, 0.19, 0.0);
  const Eigen::Matrix3d r = camera.rotation;
  const Eigen::Vector2d lo = opencv_pixel(calibration(), r, camera.eye, {-0.23, 0.19, 0.0}, 0.5);
  const Eigen::Vector2d hi = opencv_pixel(calibration(), r, camera.eye, {0.17, -0.11, 0.0}, 0.5);
  for (const double edge : {lo.x(), lo.y(), hi.x(), hi.y()})
    ASSERT_GT(std::abs(edge - std::round(edge)), 0.01) << "an edge too near a pixel centre";
  const RenderObject sphere{make_sphere_mesh({0.05, 0.02, 0.2}, 0.04, 32, 16),
                            Eigen::Vector3f::Ones()};
  const Eigen::Vector2d hidden = opencv_pixel(calibration(), r, camera.eye, {0.05, 0.02, 0.2}, 0.5);
  for (const RendererKind kind : {RendererKind::raster, RendererKind::raytrace}) {
    RenderSettings s = flat_settings(kind, camera);
    s.ground = true;  // under the cloth: neither in the cloth mask nor hiding it
    s.ground_z_m = -0.01;
    std::string why;
    const std::unique_ptr<Renderer> renderer = test::try_renderer(s, why);
    if (!renderer) {
      std::cout << "skipped " << renderer_name(kind) << ": " << why << "\n";
      continue;
    }
    const Mask plain = renderer->render_mask(cloth, s, {}, Renderer::MaskOf::cloth);
    long wrong = 0, area = 0;
    for (int y = 0; y < plain.height; ++y) {
      for (int x = 0; x < plain.width; ++x) {
        const bool inside = x > lo.x() && x < hi.x() && y > lo.y() && y < hi.y();
        wrong += plain.at(x, y) != inside;
        area += inside;
      }
    }
    EXPECT_EQ(wrong, 0) << renderer_name(kind) << ": pixels off the projected rectangle (area "
                        << area << " px)";
    const Mask hidden_mask = renderer->render_mask(cloth, s, {sphere}, Renderer::MaskOf::cloth);
    const Mask surfaces = renderer->render_mask(cloth, s, {sphere}, Renderer::MaskOf::surfaces);
    const int hx = static_cast<int>(std::lround(hidden.x())), hy = static_cast<int>(std::lround(hidden.y()));
    EXPECT_FALSE(hidden_mask.at(hx, hy)) << renderer_name(kind) << ": the sphere hides the cloth";
    EXPECT_TRUE(plain.at(hx, hy));
    EXPECT_TRUE(surfaces.at(hx, hy)) << renderer_name(kind) << ": the sphere is a surface";
    EXPECT_TRUE(surfaces.at(2, 2)) << renderer_name(kind) << ": the ground is a surface";
    EXPECT_FALSE(hidden_mask.at(2, 2)) << renderer_name(kind) << ": the ground is not cloth";
  }
}

TEST_F(CameraRender, RasterAndRayTracedClothMasksAgree) {
  const PinholeIntrinsics k = calibration();
  const Eigen::Vector3d eye(0.75, -1.05, 1.0);
  const Camera camera = Camera::calibrated(k, test::opencv_look_at(eye, {0.0, 0.0, 0.35}, 0.05), eye);
  const RenderMesh cloth = make_grid_mesh(32, 32, [](double u, double v) {
    const double x = u - 0.5, y = v - 0.5;
    return Eigen::Vector3d(x, y, 0.6 + 0.08 * std::sin(9.0 * x) * std::cos(5.0 * y) - 0.3 * x * x);
  });
  const std::vector<RenderObject> sphere{{make_sphere_mesh({0.1, -0.2, 0.75}, 0.15, 32, 16)}};
  std::vector<Mask> masks;
  for (const RendererKind kind : {RendererKind::raster, RendererKind::raytrace}) {
    RenderSettings s = flat_settings(kind, camera);
    s.ground = true;
    std::string why;
    const std::unique_ptr<Renderer> renderer = test::try_renderer(s, why);
    if (!renderer) GTEST_SKIP() << renderer_name(kind) << ": " << why;
    masks.push_back(renderer->render_mask(cloth, s, sphere, Renderer::MaskOf::cloth));
  }
  long area = 0;
  for (const std::uint8_t in : masks[0].in) area += in;
  ASSERT_GT(area, 320 * 240 / 10) << "the cloth should fill a good part of the image";
  const double agreement = iou(masks[0], masks[1]);
  EXPECT_GE(agreement, 0.99);
  std::cout << "cloth mask IoU raster vs ray traced: " << agreement << " (" << area
            << " px in the raster mask)\n";
}

// A mask is geometry only: a bright environment map shown as the background, lighting both
// renderers, leaves the cloth mask as it is without one.
TEST_F(CameraRender, MaskIsTheSameUnderABrightEnvironmentMap) {
  const Camera camera = camera_above();
  const RenderMesh cloth = test::rectangle(-0.23, 0.17, -0.11, 0.19, 0.0);
  auto bright = std::make_shared<const EnvironmentMap>(
      8, 4, std::vector<Eigen::Vector3f>(32, Eigen::Vector3f::Constant(2.0f)));
  for (const RendererKind kind : {RendererKind::raster, RendererKind::raytrace}) {
    RenderSettings s = flat_settings(kind, camera);
    std::string why;
    const std::unique_ptr<Renderer> renderer = test::try_renderer(s, why);
    if (!renderer) {
      std::cout << "skipped " << renderer_name(kind) << ": " << why << "\n";
      continue;
    }
    const Mask plain = renderer->render_mask(cloth, s, {}, Renderer::MaskOf::cloth);
    s.environment.map = bright;
    s.environment.background = true;
    const Mask lit = renderer->render_mask(cloth, s, {}, Renderer::MaskOf::cloth);
    long cloth_px = 0, differ = 0;
    for (std::size_t i = 0; i < plain.in.size(); ++i) {
      cloth_px += plain.in[i];
      differ += plain.in[i] != lit.in[i];
    }
    EXPECT_GT(cloth_px, 1000) << renderer_name(kind);
    EXPECT_EQ(differ, 0) << renderer_name(kind) << ": the environment leaked into the mask";
  }
}

}  // namespace
}  // namespace weft::render
