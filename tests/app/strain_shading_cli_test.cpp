// `weft run --shading strain`: the per-vertex strain weft draws
// (app/run/frame_mesh.h vertex_strains) on known deformations, and the frames the real command
// writes: the cloth in the map's colours (render/strain_colour.h) and the legend in the corner.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "app/run/frame_mesh.h"
#include "render/image.h"
#include "sim/grid.h"
#include "tests/app/cli_test_support.h"

namespace weft::app {
namespace {

sim::ClothMesh grid_5x4() {
  sim::GridSpec spec;
  spec.size_u_m = 0.20;
  spec.size_v_m = 0.15;
  spec.nu = 5;
  spec.nv = 4;
  return sim::make_grid(spec);
}

TEST(VertexStrains, UniformStretchAndRigidMotion) {
  const sim::ClothMesh mesh = grid_5x4();
  // Scaled by 1.03 about a point and rotated: every edge 3 % longer.
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  sim::Matrix3X x = mesh.rest_positions;
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    x.row(v) = (1.03 * rotation * x.row(v).transpose() + Eigen::Vector3d(0.1, -2, 5)).transpose();
  for (const double s : vertex_strains(mesh, x)) EXPECT_NEAR(s, 0.03, 1e-12);
  // Rigid motion alone: no strain.
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    x.row(v) = (rotation * mesh.rest_positions.row(v).transpose()).transpose();
  for (const double s : vertex_strains(mesh, x)) EXPECT_NEAR(s, 0.0, 1e-12);
}

TEST(VertexStrains, WarpStretchIsAveragedWithTheWeftEdges) {
  const sim::ClothMesh mesh = grid_5x4();
  sim::Matrix3X x = mesh.rest_positions;
  x.col(0) *= 1.10;  // warp edges 10 % longer, weft edges unchanged
  const std::vector<double> s = vertex_strains(mesh, x);
  // A corner has one warp and one weft edge, an inner vertex two of each: 5 % both; a vertex
  // on a warp side (j = 0) has two warp edges and one weft edge: 6.67 %.
  EXPECT_NEAR(s[static_cast<std::size_t>(mesh.index(0, 0))], 0.05, 1e-12);
  EXPECT_NEAR(s[static_cast<std::size_t>(mesh.index(2, 1))], 0.05, 1e-12);
  EXPECT_NEAR(s[static_cast<std::size_t>(mesh.index(2, 0))], 0.2 / 3.0, 1e-12);
  const render::RenderMesh drawn = to_render_mesh(mesh, x);
  ASSERT_EQ(drawn.strain.size(), drawn.positions.size());
  EXPECT_NEAR(drawn.strain[static_cast<std::size_t>(mesh.index(2, 1))], 0.05, 1e-7);
}

class StrainShadingCli : public test::CliDirectoryTest {
 protected:
  StrainShadingCli() : CliDirectoryTest("strain_shading_cli") {}
};

// Pixels outside the legend's corner (x < width − 100 or y > 140) whose red exceeds their blue
// by more than 60 (stretched), and the reverse (compressed).
struct Hues {
  int red = 0, blue = 0;
};
Hues strong_hues(const render::Image& image) {
  Hues h;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (x >= image.width() - 100 && y < 140) continue;
      const render::Rgb8 c = image.at(x, y);
      h.red += c.r > c.b + 60;
      h.blue += c.b > c.r + 60;
    }
  }
  return h;
}

// The tiny two-corner hang, frame 2 of 240 × 180: on a scale of ±50 % its strain (a few tenths
// of a per cent) is grey — no strongly coloured pixel anywhere but the legend, where lit shading
// has the red cloth; on a scale of ±0.001 % every strained vertex takes an end colour.
TEST_F(StrainShadingCli, ColoursFollowTheScaleAndTheLegendIsDrawn) {
  const auto scene = write_scene("tiny.json", test::tiny_scene());
  const std::string common = "run " + scene.string() + " --frames 2 --size 240x180 ";
  const auto lit = test::run_weft(common + "--out " + (m_dir / "lit").string());
  ASSERT_EQ(lit.exit_code, 0) << lit.output;
  const auto wide = test::run_weft(common + "--shading strain --set render.strain_scale=0.5 --out " +
                                   (m_dir / "wide").string());
  ASSERT_EQ(wide.exit_code, 0) << wide.output;
  const auto narrow = test::run_weft(common + "--shading strain --set render.strain_scale=1e-5 "
                                     "--out " + (m_dir / "narrow").string());
  ASSERT_EQ(narrow.exit_code, 0) << narrow.output;

  const render::Image lit_frame = render::read_image(m_dir / "lit" / "frame_0002.png");
  const render::Image wide_frame = render::read_image(m_dir / "wide" / "frame_0002.png");
  const render::Image narrow_frame = render::read_image(m_dir / "narrow" / "frame_0002.png");
  const Hues lit_hues = strong_hues(lit_frame), wide_hues = strong_hues(wide_frame);
  const Hues narrow_hues = strong_hues(narrow_frame);
  EXPECT_GT(lit_hues.red, 200) << "the lit cloth is red";
  EXPECT_EQ(wide_hues.red + wide_hues.blue, 0) << "±50 %: the cloth is grey";
  EXPECT_GT(narrow_hues.red + narrow_hues.blue, lit_hues.red / 2) << "±0.001 %: saturated";
  EXPECT_GT(narrow_hues.red, 0);
  // The legend: a white panel in the top-right corner holding the bar, red at the top (its
  // upper rows), blue at the bottom; none in the lit frame.
  struct Legend {
    int white = 0, red_above = 0, blue_below = 0;
  };
  const auto legend = [](const render::Image& image) {
    Legend l;
    for (int y = 0; y < 140; ++y)
      for (int x = image.width() - 100; x < image.width(); ++x) {
        const render::Rgb8 c = image.at(x, y);
        l.white += c.r == 255 && c.g == 255 && c.b == 255;
        l.red_above += y < 70 && c.r > c.b + 100;
        l.blue_below += y >= 70 && c.b > c.r + 100;
      }
    return l;
  };
  for (const render::Image* frame : {&wide_frame, &narrow_frame}) {
    const Legend l = legend(*frame);
    EXPECT_GT(l.white, 1500);
    EXPECT_GT(l.red_above, 50);
    EXPECT_GT(l.blue_below, 50);
  }
  EXPECT_EQ(legend(lit_frame).white, 0);
}

TEST_F(StrainShadingCli, BadScaleNamesTheKey) {
  const auto scene = write_scene("tiny.json", test::tiny_scene());
  const auto r = test::run_weft("run " + scene.string() + " --frames 1 --shading strain --set "
                                "render.strain_scale=0 --out " + (m_dir / "bad").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("render.strain_scale"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace weft::app
