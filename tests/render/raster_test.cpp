// OSMesa rasterizer, checked analytically: known quads seen from known cameras, expected colours
// from the shading formula colour × (ambient + intensity × max(0, n·l))^(1/2.2) of a Lambertian
// cloth, and with the cloth's sheen lobe (render/sheen.h) added in linear radiance.
// Every test runs with each GL context (OSMesa and EGL surfaceless, parameter /osmesa and /egl),
// and is skipped (with the reason) when that context cannot be created. On failure the rendered
// images are written to <build>/test_output/render/ for a person to look at.

#include "render/raster.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "render/primitives.h"
#include "render/sheen.h"
#include "tests/render/render_test_support.h"

namespace weft::render {
namespace {

using test::Pixel;
using test::project;
using test::rectangle;
using test::same_bytes;
using test::to_rgb8;

// The view from above (render_test_support.h) of a Lambertian cloth: the tests below check the
// diffuse model; SheenAddsTheKeyLightsCharlieLobe checks the sheen.
RenderSettings view_from_above(int width, int height) {
  RenderSettings s = test::view_from_above(width, height);
  s.cloth_surface.sheen = 0.0;
  return s;
}

constexpr int colour_tolerance = 3;  // 8-bit units, for interpolation and rounding

// The 1 m × 1 m square at z = 0.5 m centred on the z axis.
RenderMesh unit_square() {
  return rectangle(-0.5, 0.5, -0.5, 0.5, 0.5);
}

// The shading formula for a surface of the given colour and facing normal (unit, world).
Rgb8 expected_lit(const Eigen::Vector3f& colour, const RenderSettings& s,
                  const Eigen::Vector3d& normal) {
  const double light =
      s.ambient + s.light_intensity * std::max(0.0, normal.dot(s.light_direction.normalized()));
  return to_rgb8(colour * static_cast<float>(std::pow(light, 1.0 / 2.2)));
}

Rgb8 expected_normal_colour(const Eigen::Vector3d& normal) {
  return to_rgb8((0.5 * normal + Eigen::Vector3d::Constant(0.5)).cast<float>());
}

int max_channel_difference(Rgb8 a, Rgb8 b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

::testing::AssertionResult colour_near(Rgb8 actual, Rgb8 expected, int tolerance) {
  const int d = max_channel_difference(actual, expected);
  if (d <= tolerance) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "colour (" << int{actual.r} << ", " << int{actual.g} << ", " << int{actual.b}
         << ") differs from expected (" << int{expected.r} << ", " << int{expected.g} << ", "
         << int{expected.b} << ") by " << d << " > " << tolerance;
}

::testing::AssertionResult colour_at(const Image& image, Pixel p, Rgb8 expected, int tolerance) {
  if (p.x < 0 || p.y < 0 || p.x >= image.width() || p.y >= image.height()) {
    return ::testing::AssertionFailure() << "pixel (" << p.x << ", " << p.y << ") off-image";
  }
  auto result = colour_near(image.at(p.x, p.y), expected, tolerance);
  if (!result) result << " at pixel (" << p.x << ", " << p.y << ")";
  return result;
}

// The context the test's parameter names, of the given size.
std::unique_ptr<GlContext> make_context(GlBackend backend, int width, int height) {
  return backend == GlBackend::egl ? make_egl_context(width, height)
                                   : make_osmesa_context(width, height);
}

class Raster : public ::testing::TestWithParam<GlBackend> {
 protected:
  void SetUp() override {
    std::unique_ptr<GlContext> context;
    try {
      context = make_context(GetParam(), 64, 64);
    } catch (const std::exception& e) {
      GTEST_SKIP() << "no " << gl_backend_name(GetParam()) << " context: " << e.what();
    }
    // Past this point a failure is a real failure, not a missing back-end.
    m_renderer = std::make_unique<RasterRenderer>(std::move(context));
  }

  // On failure, every image rendered by the test is written where a person can find it.
  void TearDown() override { m_rendered.save_if_failed(); }

  Image render(const RenderMesh& mesh, const RenderSettings& s, const std::string& name) {
    Image image = m_renderer->render(mesh, s);
    m_rendered.add(name, image);
    return image;
  }

  Image render(const RenderMesh& cloth, const RenderSettings& s,
               const std::vector<RenderObject>& objects, const std::string& name) {
    Image image = m_renderer->render(cloth, s, objects);
    m_rendered.add(name, image);
    return image;
  }

  std::unique_ptr<RasterRenderer> m_renderer;
  test::FailureEvidence m_rendered{"render"};
};

TEST_P(Raster, DescriptionNamesTheContext) {
  const char* name = GetParam() == GlBackend::egl ? "EGL" : "OSMesa";
  EXPECT_NE(m_renderer->description().find(name), std::string::npos)
      << m_renderer->description();
}

TEST_P(Raster, FrontFaceIsLitFrontColourOnBackground) {
  const RenderSettings s = view_from_above(160, 120);
  const Image image = render(unit_square(), s, "front");
  ASSERT_EQ(image.width(), 160);
  ASSERT_EQ(image.height(), 120);

  EXPECT_TRUE(colour_at(image, project(s, {0, 0, 0.5}), expected_lit(s.front_color, s, {0, 0, 1}),
                        colour_tolerance));
  const Rgb8 background = to_rgb8(s.background);
  for (Pixel corner : {Pixel{0, 0}, Pixel{159, 0}, Pixel{0, 119}, Pixel{159, 119}}) {
    EXPECT_TRUE(colour_at(image, corner, background, 0));
  }
}

// Light and eye both grazing, from about the same side: the half vector lies near the
// surface, where the Charlie distribution peaks, so the sheen lobe is strong. The pixel at the
// square's centre is (ρ (ambient + I n·l) + (1 + ρ)/2 · sheen · I · sheen_response)^(1/2.2)
// with ρ = colour^2.2, and differs clearly from the Lambertian value.
TEST_P(Raster, SheenAddsTheKeyLightsCharlieLobe) {
  RenderSettings s = test::view_from_above(120, 120);
  s.cloth_surface.sheen = 1.0;
  s.cloth_surface.sheen_roughness = 0.4;
  s.camera.eye = {1.6, 0.0, 1.1};
  s.camera.target = {0.0, 0.0, 0.5};
  s.light_direction = {1.0, 0.4, 0.35};
  const Image image = render(unit_square(), s, "sheen");

  const Eigen::Vector3f n = Eigen::Vector3f::UnitZ();
  const Eigen::Vector3f l = s.light_direction.normalized().cast<float>();
  const Eigen::Vector3f v =
      (s.camera.eye - Eigen::Vector3d(0, 0, 0.5)).normalized().cast<float>();
  const float intensity = static_cast<float>(s.light_intensity);
  const Eigen::Vector3f rho = s.front_color.array().pow(2.2f);
  const Eigen::Vector3f radiance =
      rho * (static_cast<float>(s.ambient) + intensity * n.dot(l)) +
      sheen_tint(rho) * (intensity * sheen_response(n, l, v, 0.4f));
  const Rgb8 want = to_rgb8(radiance.array().pow(1.0f / 2.2f).matrix());
  const Pixel centre = project(s, {0, 0, 0.5});
  EXPECT_TRUE(colour_at(image, centre, want, colour_tolerance));
  EXPECT_GT(max_channel_difference(want, expected_lit(s.front_color, s, {0, 0, 1})), 20)
      << "the sheen should show at this angle";
}

TEST_P(Raster, BackFaceIsTheFrontMaterialByDefault) {
  RenderSettings s = view_from_above(120, 120);
  s.camera.eye = {0, 0, -2};  // below the square: sees its back
  s.light_direction = {0.6, 0.0, -0.8};
  const Image image = render(unit_square(), s, "back_default");
  EXPECT_TRUE(colour_at(image, project(s, {0, 0, 0.5}),
                        expected_lit(s.front_color, s, {0, 0, -1}), colour_tolerance));
}

TEST_P(Raster, BackFaceGetsBackColourAndFlippedNormal) {
  RenderSettings s = view_from_above(120, 120);
  s.back_color = Eigen::Vector3f(0.25f, 0.45f, 0.80f);  // the two-colour view of the sides
  s.camera.eye = {0, 0, -2};  // below the square: sees its back
  // Default light is above: the back face gets ambient only.
  Image image = render(unit_square(), s, "back_ambient");
  const Pixel centre = project(s, {0, 0, 0.5});
  EXPECT_TRUE(
      colour_at(image, centre, expected_lit(*s.back_color, s, {0, 0, -1}), colour_tolerance));
  EXPECT_TRUE(colour_near(expected_lit(*s.back_color, s, {0, 0, -1}),
                          to_rgb8(*s.back_color * std::pow(0.25f, 1.0f / 2.2f)), 1));

  // Light from below: the flipped normal (0, 0, −1) faces it.
  s.light_direction = {0.6, 0.0, -0.8};
  image = render(unit_square(), s, "back_lit");
  EXPECT_TRUE(
      colour_at(image, centre, expected_lit(*s.back_color, s, {0, 0, -1}), colour_tolerance));
}

TEST_P(Raster, NormalsShadingShowsTheFacingNormal) {
  RenderSettings s = view_from_above(100, 100);
  s.shading = Shading::normals;
  Image image = render(unit_square(), s, "normals_front");
  const Pixel centre = project(s, {0, 0, 0.5});
  EXPECT_TRUE(colour_at(image, centre, expected_normal_colour({0, 0, 1}), 1));

  s.camera.eye = {0, 0, -2};
  image = render(unit_square(), s, "normals_back");
  EXPECT_TRUE(colour_at(image, project(s, {0, 0, 0.5}), expected_normal_colour({0, 0, -1}), 1));
}

TEST_P(Raster, ImageHasTheRequestedSizeAcrossResizes) {
  RenderSettings s = view_from_above(64, 48);
  const Image first = render(unit_square(), s, "64x48");
  EXPECT_EQ(first.width(), 64);
  EXPECT_EQ(first.height(), 48);

  s.width = 101;  // odd: rows are not 4-byte aligned
  s.height = 31;
  const Image wide = render(unit_square(), s, "101x31");
  EXPECT_EQ(wide.width(), 101);
  EXPECT_EQ(wide.height(), 31);

  s.width = 64;
  s.height = 48;
  s.msaa_samples = 0;
  EXPECT_EQ(render(unit_square(), s, "64x48_no_msaa").width(), 64);
  s.msaa_samples = 4;
  EXPECT_TRUE(same_bytes(render(unit_square(), s, "64x48_again"), first));
}

TEST_P(Raster, RowsRunTopToBottomAndColumnsLeftToRight) {
  // A rectangle in the +x, +y quadrant must appear in the image's top-right quarter only.
  const RenderSettings s = view_from_above(120, 90);
  const Image image = render(rectangle(0.15, 0.65, 0.15, 0.65, 0.5), s, "top_right");
  const Rgb8 background = to_rgb8(s.background);
  int cloth_top_right = 0, cloth_elsewhere = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (image.at(x, y) == background) continue;
      (x >= image.width() / 2 && y < image.height() / 2 ? cloth_top_right : cloth_elsewhere)++;
    }
  }
  EXPECT_GT(cloth_top_right, 100);
  EXPECT_EQ(cloth_elsewhere, 0);
  EXPECT_TRUE(colour_at(image, project(s, {0.4, 0.4, 0.5}),
                        expected_lit(s.front_color, s, {0, 0, 1}), colour_tolerance));
}

TEST_P(Raster, MultisamplingBlendsEdgesAndIsDeterministic) {
  // A slanted triangle: its edges cross pixels at every fraction.
  RenderMesh triangle;
  triangle.positions = {{-0.6f, -0.5f, 0.5f}, {0.6f, -0.3f, 0.5f}, {0.1f, 0.6f, 0.5f}};
  triangle.triangles = {{0, 1, 2}};
  compute_vertex_normals(triangle);
  RenderSettings s = view_from_above(128, 128);
  const Rgb8 background = to_rgb8(s.background);
  const Rgb8 cloth = expected_lit(s.front_color, s, {0, 0, 1});

  const auto count_blended = [&](const Image& image) {
    int blended = 0;
    for (int y = 0; y < image.height(); ++y) {
      for (int x = 0; x < image.width(); ++x) {
        const Rgb8 c = image.at(x, y);
        if (!(c == background) && max_channel_difference(c, cloth) > colour_tolerance) ++blended;
      }
    }
    return blended;
  };

  s.msaa_samples = 4;
  const Image msaa = render(triangle, s, "msaa4");
  EXPECT_GT(count_blended(msaa), 50) << "edge pixels should mix cloth and background";
  EXPECT_TRUE(same_bytes(render(triangle, s, "msaa4_again"), msaa));

  s.msaa_samples = 1;
  EXPECT_EQ(count_blended(render(triangle, s, "msaa1")), 0)
      << "without multisampling every pixel is cloth or background";
}

TEST_P(Raster, FreshRendererGivesTheSameBytes) {
  RenderSettings s = view_from_above(96, 80);
  s.ground = true;
  s.camera.eye = {1.5, -2.0, 1.5};
  const Image first = render(unit_square(), s, "first");
  RasterRenderer other(make_context(GetParam(), 16, 16));
  EXPECT_TRUE(same_bytes(other.render(unit_square(), s), first));
}

TEST_P(Raster, MissingNormalsAreComputed) {
  const RenderSettings s = view_from_above(80, 60);
  RenderMesh without = unit_square();
  without.normals.clear();
  EXPECT_TRUE(same_bytes(render(without, s, "computed"), render(unit_square(), s, "given")));
}

TEST_P(Raster, GroundIsLitAndShadowedByTheCloth) {
  RenderSettings s;  // default oblique camera, ground on at z = 0
  s.width = 200;
  s.height = 150;
  s.cloth_surface.sheen = 0.0;    // a Lambertian cloth
  s.light_direction = {0, 0, 1};  // straight down: the shadow is the square's footprint
  const Image image = render(unit_square(), s, "ground");

  // Points in the middle of 10 cm grid cells, away from the grid lines, and not hidden by the
  // square from the camera.
  const Pixel in_shadow = project(s, {0.25, 0.25, 0.0});
  const Pixel in_light = project(s, {0.75, -0.65, 0.0});
  const Rgb8 shadowed = expected_lit(s.ground_color, s, Eigen::Vector3d::Zero());  // ambient only
  EXPECT_TRUE(colour_at(image, in_shadow, shadowed, colour_tolerance));
  EXPECT_TRUE(
      colour_at(image, in_light, expected_lit(s.ground_color, s, {0, 0, 1}), colour_tolerance));
  // The cloth itself, seen from above at an angle, is its lit front colour.
  EXPECT_TRUE(colour_at(image, project(s, {0.2, -0.3, 0.5}),
                        expected_lit(s.front_color, s, {0, 0, 1}), colour_tolerance));
}

TEST_P(Raster, EmptyMeshDrawsOnlyTheBackground) {
  RenderSettings s = view_from_above(40, 30);
  const Image image = render(RenderMesh{}, s, "empty");
  const Rgb8 background = to_rgb8(s.background);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) ASSERT_EQ(image.at(x, y), background);
  }
}

TEST_P(Raster, GroundWithoutClothIsLit) {
  // No cloth, so no shadow pass: the ground alone, seen from straight above (10 cm grid lines
  // are too dense at this size and fade out; the points are away from the 1 m lines).
  RenderSettings s = view_from_above(40, 30);
  s.ground = true;
  const Image image = render(RenderMesh{}, s, "ground_only");
  EXPECT_TRUE(colour_at(image, project(s, {0.45, 0.45, 0.0}),
                        expected_lit(s.ground_color, s, {0, 0, 1}), colour_tolerance));
  // Light from below the ground: ambient only, and no shadow pass either.
  s.light_direction = {0.0, 0.3, -1.0};
  const Image from_below = render(unit_square(), s, "light_below");
  EXPECT_TRUE(colour_at(from_below, project(s, {0.75, 0.65, 0.0}),
                        expected_lit(s.ground_color, s, Eigen::Vector3d::Zero()),
                        colour_tolerance));
}

TEST_P(Raster, BadInputThrows) {
  RenderSettings s = view_from_above(32, 32);
  s.width = 0;
  EXPECT_THROW(m_renderer->render(unit_square(), s), std::invalid_argument);

  s = view_from_above(32, 32);
  RenderMesh bad_index = unit_square();
  bad_index.triangles.push_back({0, 1, 9});
  EXPECT_THROW(m_renderer->render(bad_index, s), std::invalid_argument);

  RenderMesh not_finite = unit_square();
  not_finite.positions[2].x() = std::nanf("");
  EXPECT_THROW(m_renderer->render(not_finite, s), std::invalid_argument);

  // Still usable afterwards.
  EXPECT_EQ(m_renderer->render(unit_square(), s).width(), 32);
}

// Extra opaque objects (obstacles): a sphere seen from straight above, lit from straight above
// so that the shading near its top hardly depends on the tessellation.
RenderSettings sphere_view(int width, int height) {
  RenderSettings s = view_from_above(width, height);
  s.light_direction = {0, 0, 1};
  return s;
}

RenderObject sphere_object(const Eigen::Vector3d& centre, double radius,
                           const Eigen::Vector3f& colour) {
  return {make_sphere_mesh(centre, radius), colour};
}

TEST_P(Raster, SphereObjectIsLitInItsOwnColour) {
  const RenderSettings s = sphere_view(160, 120);
  const Eigen::Vector3f colour(0.3f, 0.7f, 0.4f);
  const Eigen::Vector3d centre(0, 0, 0.5);
  const double radius = 0.3;
  const Image image = render(RenderMesh{}, s, {sphere_object(centre, radius, colour)}, "sphere");

  EXPECT_TRUE(
      colour_at(image, project(s, centre), expected_lit(colour, s, {0, 0, 1}), colour_tolerance));
  // Half-way out along +x the surface normal is (0.5, 0, √0.75): darker, as the formula says.
  const Eigen::Vector3d normal(0.5, 0.0, std::sqrt(0.75));
  EXPECT_TRUE(colour_at(image, project(s, centre + radius * normal),
                        expected_lit(colour, s, normal), colour_tolerance));
  const Rgb8 background = to_rgb8(s.background);
  for (Pixel corner : {Pixel{0, 0}, Pixel{159, 0}, Pixel{0, 119}, Pixel{159, 119}}) {
    EXPECT_TRUE(colour_at(image, corner, background, 0));
  }
}

TEST_P(Raster, ClothAndObjectsOccludeEachOtherByDepth) {
  const RenderSettings s = sphere_view(160, 120);
  const Eigen::Vector3f sphere_colour(0.3f, 0.7f, 0.4f);
  const RenderObject sphere = sphere_object({0, 0, 0.5}, 0.3, sphere_colour);
  const Rgb8 cloth_lit = expected_lit(s.front_color, s, {0, 0, 1});
  const Rgb8 sphere_top = expected_lit(sphere_colour, s, {0, 0, 1});

  // The cloth above the sphere's left half (z = 1 > 0.8, the sphere's top) hides that half.
  Image image = render(rectangle(-0.6, 0.0, -0.6, 0.6, 1.0), s, {sphere}, "cloth_in_front");
  EXPECT_TRUE(colour_at(image, project(s, {-0.05, 0.0, 1.0}), cloth_lit, colour_tolerance));
  EXPECT_TRUE(colour_at(image, project(s, {0.05, 0.0, 0.8}), sphere_top, colour_tolerance));

  // A cloth cutting through the sphere's lower part (z = 0.3; the sphere spans 0.2 … 0.8) is
  // hidden by it in the middle and seen around it.
  image = render(rectangle(-1.0, 1.0, -1.0, 1.0, 0.3), s, {sphere}, "cloth_behind");
  EXPECT_TRUE(colour_at(image, project(s, {0, 0, 0.8}), sphere_top, colour_tolerance));
  EXPECT_TRUE(colour_at(image, project(s, {0.6, 0.4, 0.3}), cloth_lit, colour_tolerance));

  // Objects against each other: a small red sphere in front of the big one, listed first.
  const Eigen::Vector3f red(0.9f, 0.1f, 0.1f);
  image = render(RenderMesh{}, s, {sphere_object({0, 0, 0.95}, 0.1, red), sphere}, "two_spheres");
  EXPECT_TRUE(colour_at(image, project(s, {0, 0, 1.05}), expected_lit(red, s, {0, 0, 1}),
                        colour_tolerance));
  image = render(RenderMesh{}, s, {sphere, sphere_object({0, 0, 0.95}, 0.1, red)},
                 "two_spheres_reversed");
  EXPECT_TRUE(colour_at(image, project(s, {0, 0, 1.05}), expected_lit(red, s, {0, 0, 1}),
                        colour_tolerance));
}

TEST_P(Raster, ObjectsCastShadowsOnTheGround) {
  RenderSettings s;  // default oblique camera, ground on at z = 0
  s.width = 200;
  s.height = 150;
  s.light_direction = {0, 0, 1};  // straight down: the shadow is the sphere's disc
  const Image image =
      render(RenderMesh{}, s, {sphere_object({0, 0, 0.5}, 0.2, s.obstacle_color)}, "shadow");
  // Middles of 10 cm grid cells: under the sphere (seen in front of it) and far from it.
  const Rgb8 shadowed = expected_lit(s.ground_color, s, Eigen::Vector3d::Zero());
  EXPECT_TRUE(colour_at(image, project(s, {0.05, -0.05, 0.0}), shadowed, colour_tolerance));
  EXPECT_TRUE(colour_at(image, project(s, {0.75, -0.65, 0.0}),
                        expected_lit(s.ground_color, s, {0, 0, 1}), colour_tolerance));
}

TEST_P(Raster, NoObjectsIsTheClothAlone) {
  RenderSettings s = view_from_above(96, 80);
  s.ground = true;
  s.camera.eye = {1.5, -2.0, 1.5};
  EXPECT_TRUE(same_bytes(render(unit_square(), s, {}, "no_objects"),
                         render(unit_square(), s, "cloth_only")));
}

TEST_P(Raster, BadObjectThrowsNamingIt) {
  const RenderSettings s = sphere_view(32, 32);
  RenderObject bad = sphere_object({0, 0, 0.5}, 0.2, {0.5f, 0.5f, 0.5f});
  bad.mesh.triangles.push_back({0, 1, 100000});
  try {
    m_renderer->render(unit_square(), s, {sphere_object({0, 0, 0}, 0.1, {1, 1, 1}), bad});
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("object 1: triangle", 0), 0u) << e.what();
  }
  // Normals are computed when missing: the same image as with the analytic ones.
  RenderObject without = sphere_object({0, 0, 0.5}, 0.2, {0.5f, 0.5f, 0.5f});
  without.mesh.normals.clear();
  const Image computed = render(RenderMesh{}, s, {without}, "computed_normals");
  EXPECT_TRUE(colour_at(computed, project(s, {0, 0, 0.7}),
                        expected_lit({0.5f, 0.5f, 0.5f}, s, {0, 0, 1}), colour_tolerance));
}

INSTANTIATE_TEST_SUITE_P(Contexts, Raster, ::testing::Values(GlBackend::osmesa, GlBackend::egl),
                         [](const ::testing::TestParamInfo<GlBackend>& param) {
                           return std::string(gl_backend_name(param.param));
                         });

}  // namespace
}  // namespace weft::render
