// The two GL contexts of the rasterizer (gl_context.h): choosing one by name (WEFT_GL is read by
// app/, tests/app/gl_scene_test.cpp), and OSMesa and EGL surfaceless drawing the same scene (ground, shadow, obstacle, 4× MSAA) into
// images within a tight tolerance: both run Mesa's llvmpipe with the same shaders, so they may
// differ only where the two drivers round or rasterise differently. Tests that need a context
// are skipped (with the reason) when it cannot be created. On failure the rendered images are
// written to <build>/test_output/gl_context/.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/constants.h"
#include "render/gl_context.h"
#include "render/image_diff.h"
#include "render/primitives.h"
#include "render/raster.h"
#include "tests/render/render_test_support.h"

namespace weft::render {
namespace {

TEST(GlBackend, NamesRoundTripAndUnknownNamesListTheChoices) {
  for (GlBackend b : {GlBackend::automatic, GlBackend::osmesa, GlBackend::egl})
    EXPECT_EQ(gl_backend_from_name(gl_backend_name(b), "test"), b);
  try {
    gl_backend_from_name("vulkan", "render.gl");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("render.gl"), std::string::npos) << message;
    EXPECT_NE(message.find("'osmesa'"), std::string::npos) << message;
    EXPECT_NE(message.find("'egl'"), std::string::npos) << message;
    EXPECT_NE(message.find("vulkan"), std::string::npos) << message;
  }
}

TEST(GlBackend, EglDescriptionSaysSurfaceless) {
  std::unique_ptr<GlContext> context;
  try {
    context = make_egl_context(8, 8);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "no EGL context: " << e.what();
  }
  EXPECT_NE(context->description().find("surfaceless"), std::string::npos)
      << context->description();
  EXPECT_NE(context->description().find("Core Profile"), std::string::npos) << context->description();
}

// A sheet draped over a sphere (folds below the equator), the sphere as an obstacle, lit with a
// ground shadow, seen obliquely.
struct Scene {
  RenderMesh cloth;
  std::vector<RenderObject> objects;
  RenderSettings settings;
};

Scene draped_sphere() {
  const Eigen::Vector3d centre(0.0, 0.0, 0.25);
  const double r = 0.052;
  Scene scene;
  scene.cloth = make_grid_mesh(48, 48, [&](double u, double v) {
    const double x = 0.3 * (u - 0.5), y = 0.3 * (v - 0.5);
    const double s = std::hypot(x, y), phi = std::atan2(y, x);
    if (s <= 0.5 * base::kPi * r) {
      const double theta = s / r;
      return Eigen::Vector3d(centre + r * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                          std::sin(theta) * std::sin(phi),
                                                          std::cos(theta)));
    }
    const double d = s - 0.5 * base::kPi * r;
    const double rho = r + 0.35 * d * (1.0 + 0.5 * std::sin(8.0 * phi));
    return Eigen::Vector3d(centre + Eigen::Vector3d(rho * std::cos(phi), rho * std::sin(phi), -d));
  });
  scene.objects.push_back({make_sphere_mesh(centre, 0.05), {0.70f, 0.74f, 0.80f}});
  RenderSettings& s = scene.settings;
  s.width = 200;
  s.height = 150;
  s.camera.eye = {0.45, -0.55, 0.55};
  s.camera.target = {0, 0, 0.2};
  s.camera.fov_y_deg = 35;
  s.light_direction = {1.0, -0.5, 0.8};
  s.ground_half_size_m = 1.0;
  return scene;
}

TEST(GlContexts, OsmesaAndEglDrawTheSameImage) {
  const Scene scene = draped_sphere();
  std::vector<Image> images;
  for (GlBackend backend : {GlBackend::osmesa, GlBackend::egl}) {
    std::unique_ptr<GlContext> context;
    try {
      context = backend == GlBackend::egl ? make_egl_context(8, 8) : make_osmesa_context(8, 8);
    } catch (const std::runtime_error& e) {
      GTEST_SKIP() << "no " << gl_backend_name(backend) << " context: " << e.what();
    }
    RasterRenderer renderer(std::move(context));  // destroyed before the next one is made
    images.push_back(renderer.render(scene.cloth, scene.settings, scene.objects));
  }
  test::FailureEvidence evidence("gl_context");
  evidence.add("osmesa", images[0]);
  evidence.add("egl", images[1]);
  const ImageDifference d = compare_images(images[0], images[1], 2);
  std::cout << "OSMesa vs EGL: PSNR " << d.psnr_db << " dB, max difference " << d.max_abs
            << ", pixels over 2: " << d.fraction_over << "\n";
  // The same driver and shaders: at most a rounding step anywhere, and not a visible picture.
  EXPECT_LE(d.max_abs, 2);
  EXPECT_GE(d.psnr_db, 50.0);
  evidence.save_if_failed();
}

}  // namespace
}  // namespace weft::render
