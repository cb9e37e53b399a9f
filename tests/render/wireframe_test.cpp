// The wireframe overlay (render/wireframe_overlay.h) through both renderers:
// - pixels on a projected mesh line take the line's colour, and pixels away from every line
//   (cell centres, which lie on the cells' undrawn diagonals) keep the bytes of the frame
//   drawn without the overlay;
// - a line behind an object is hidden; the lines stay on a subdivided, thickened cloth;
// - lines are as wide on screen as asked;
// - a bad width or colour is an error naming the setting.
// A renderer that cannot start here is skipped with the reason.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/primitives.h"
#include "render/renderer.h"
#include "tests/render/render_test_support.h"

namespace weft::render {
namespace {

using test::FailureEvidence;

constexpr int cells = 4;             // per side
constexpr double half_side_m = 0.8;  // the cloth spans [−0.8, 0.8]² at z = 0.5
const Eigen::Vector3f line_colour(0.1f, 0.9f, 0.2f);

double grid_coordinate(int i) {
  return -half_side_m + 2.0 * half_side_m * i / cells;
}

// A flat cells×cells grid facing the camera, with its warp and weft lines as edges (not the
// diagonals).
RenderMesh grid_cloth() {
  RenderMesh mesh = make_grid_mesh(cells + 1, cells + 1, [](double u, double v) {
    return Eigen::Vector3d(-half_side_m + 2 * half_side_m * u, -half_side_m + 2 * half_side_m * v,
                           0.5);
  });
  const auto index = [](int i, int j) { return static_cast<std::uint32_t>(j * (cells + 1) + i); };
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      if (i < cells) mesh.edges.push_back({index(i, j), index(i + 1, j)});
      if (j < cells) mesh.edges.push_back({index(i, j), index(i, j + 1)});
    }
  return mesh;
}

// The pixel whose centre is nearest to where world point p projects.
test::Pixel pixel_at(const RenderSettings& s, const Eigen::Vector3d& p) {
  const Eigen::Vector3d uv = s.camera.project(p, s.width, s.height);
  return {static_cast<int>(std::lround(uv.x())), static_cast<int>(std::lround(uv.y()))};
}

int difference(Rgb8 a, Rgb8 b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

class WireframeOverlay : public ::testing::TestWithParam<RendererKind> {
 protected:
  void SetUp() override {
    m_settings = test::view_from_above(160, 120);
    m_settings.renderer = GetParam();
    m_settings.raytrace.samples_per_pixel = 4;
    std::string why;
    m_renderer = test::try_renderer(m_settings, why);
    if (!m_renderer) GTEST_SKIP() << renderer_name(GetParam()) << ": " << why;
  }
  void TearDown() override { m_rendered.save_if_failed(); }

  Image render(const RenderMesh& cloth, const RenderSettings& s,
               const std::vector<RenderObject>& objects, const std::string& name) {
    Image image = m_renderer->render(cloth, s, objects);
    m_rendered.add(name, image);
    return image;
  }
  RenderSettings with_wireframe(double width_px) const {
    RenderSettings s = m_settings;
    s.cloth_surface.wireframe = {true, width_px, line_colour};
    return s;
  }

  RenderSettings m_settings;
  std::unique_ptr<Renderer> m_renderer;
  FailureEvidence m_rendered{"wireframe"};
};

// Midpoints of the grid's lines, and the centres of its cells.
std::vector<Eigen::Vector3d> line_midpoints() {
  std::vector<Eigen::Vector3d> points;
  for (int a = 0; a <= cells; ++a)
    for (int b = 0; b < cells; ++b) {
      const double along = 0.5 * (grid_coordinate(b) + grid_coordinate(b + 1));
      points.emplace_back(grid_coordinate(a), along, 0.5);
      points.emplace_back(along, grid_coordinate(a), 0.5);
    }
  return points;
}

std::vector<Eigen::Vector3d> cell_centres() {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      points.emplace_back(0.5 * (grid_coordinate(i) + grid_coordinate(i + 1)),
                          0.5 * (grid_coordinate(j) + grid_coordinate(j + 1)), 0.5);
  return points;
}

TEST_P(WireframeOverlay, LinesTakeTheirColourAndFacesKeepTheirBytes) {
  const RenderMesh cloth = grid_cloth();
  const Image plain = render(cloth, m_settings, {}, "plain");
  const Image wired = render(cloth, with_wireframe(3.0), {}, "wired");
  const Rgb8 line = test::to_rgb8(line_colour);
  for (const Eigen::Vector3d& p : line_midpoints()) {
    const test::Pixel px = pixel_at(m_settings, p);
    EXPECT_LE(difference(wired.at(px.x, px.y), line), 1) << "line at " << p.transpose();
    EXPECT_GT(difference(plain.at(px.x, px.y), line), 60) << "the cloth is not line-coloured";
  }
  for (const Eigen::Vector3d& p : cell_centres()) {
    const test::Pixel px = pixel_at(m_settings, p);
    EXPECT_EQ(wired.at(px.x, px.y), plain.at(px.x, px.y)) << "cell centre " << p.transpose();
  }
  // Without edges, every triangle side is drawn: the cells' diagonals through their centres.
  RenderMesh no_edges = cloth;
  no_edges.edges.clear();
  const Image all_sides = render(no_edges, with_wireframe(3.0), {}, "all_sides");
  for (const Eigen::Vector3d& p : cell_centres()) {
    const test::Pixel px = pixel_at(m_settings, p);
    EXPECT_LE(difference(all_sides.at(px.x, px.y), line), 1) << "diagonal at " << p.transpose();
  }
}

TEST_P(WireframeOverlay, LinesBehindAnObjectAreHidden) {
  // An opaque sheet 0.5 m above the cloth's left half (x < 0).
  RenderObject cover;
  cover.mesh = test::rectangle(-1.2, 0.0, -1.2, 1.2, 1.0);
  const RenderMesh cloth = grid_cloth();
  const Image plain = render(cloth, m_settings, {cover}, "plain");
  const Image wired = render(cloth, with_wireframe(3.0), {cover}, "wired");
  const Rgb8 line = test::to_rgb8(line_colour);
  int hidden = 0, shown = 0;
  for (const Eigen::Vector3d& p : line_midpoints()) {
    const test::Pixel px = pixel_at(m_settings, p);
    if (p.x() < -0.1) {
      EXPECT_EQ(wired.at(px.x, px.y), plain.at(px.x, px.y)) << "hidden line at " << p.transpose();
      ++hidden;
    } else if (p.x() > 0.1) {
      EXPECT_LE(difference(wired.at(px.x, px.y), line), 1) << "line at " << p.transpose();
      ++shown;
    }
  }
  EXPECT_GT(hidden, 4);
  EXPECT_GT(shown, 4);
}

TEST_P(WireframeOverlay, LinesStayOnASubdividedThickenedCloth) {
  RenderSettings plain_settings = m_settings;
  plain_settings.cloth_surface.subdivision_levels = 2;
  plain_settings.cloth_surface.thickness_m = 0.002;
  RenderSettings wired_settings = with_wireframe(3.0);
  wired_settings.cloth_surface.subdivision_levels = 2;
  wired_settings.cloth_surface.thickness_m = 0.002;
  const RenderMesh cloth = grid_cloth();
  const Image plain = render(cloth, plain_settings, {}, "plain");
  const Image wired = render(cloth, wired_settings, {}, "wired");
  const Rgb8 line = test::to_rgb8(line_colour);
  for (const Eigen::Vector3d& p : line_midpoints()) {
    const test::Pixel px = pixel_at(m_settings, p);
    EXPECT_LE(difference(wired.at(px.x, px.y), line), 1) << "line at " << p.transpose();
  }
  for (const Eigen::Vector3d& p : cell_centres()) {
    const test::Pixel px = pixel_at(m_settings, p);
    EXPECT_EQ(wired.at(px.x, px.y), plain.at(px.x, px.y)) << "cell centre " << p.transpose();
  }
}

// Across a vertical line in the middle of a cell row, the pixels that changed number about the
// width asked for (an antialiased line touches at most one more pixel on each side).
TEST_P(WireframeOverlay, LinesAreAsWideOnScreenAsAsked) {
  const RenderMesh cloth = grid_cloth();
  const Image plain = render(cloth, m_settings, {}, "plain");
  const double y_m = 0.5 * (grid_coordinate(1) + grid_coordinate(2));
  const test::Pixel centre = pixel_at(m_settings, {grid_coordinate(2), y_m, 0.5});
  for (const double width : {1.0, 3.0, 6.0}) {
    const Image wired = render(cloth, with_wireframe(width), {}, "wired");
    int changed = 0, strong = 0;
    for (int x = centre.x - 10; x <= centre.x + 10; ++x) {
      const int d = difference(wired.at(x, centre.y), plain.at(x, centre.y));
      changed += d > 0;
      strong += d > difference(test::to_rgb8(line_colour), plain.at(x, centre.y)) / 2;
    }
    EXPECT_GE(changed, static_cast<int>(width)) << "width " << width;
    EXPECT_LE(changed, static_cast<int>(width) + 2) << "width " << width;
    EXPECT_NEAR(strong, width, 1.0) << "width " << width;
  }
}

TEST_P(WireframeOverlay, BadWidthOrColourNamesTheSetting) {
  const RenderMesh cloth = grid_cloth();
  const auto error_of = [&](const RenderSettings& s) -> std::string {
    try {
      m_renderer->render(cloth, s, {});
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(error_of(with_wireframe(-1.0)).find("wireframe.width_px"), std::string::npos);
  EXPECT_NE(error_of(with_wireframe(std::nan(""))).find("wireframe.width_px"), std::string::npos);
  RenderSettings s = with_wireframe(2.0);
  s.cloth_surface.wireframe.color = {0.5f, 1.5f, 0.0f};
  EXPECT_NE(error_of(s).find("wireframe.color"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Renderers, WireframeOverlay,
                         ::testing::Values(RendererKind::raster, RendererKind::raytrace),
                         [](const auto& kind) { return std::string(renderer_name(kind.param)); });

}  // namespace
}  // namespace weft::render
