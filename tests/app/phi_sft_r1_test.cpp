// φ-SfT R1 frame 0 (tests/data/photos/phi_sft_R1, SOURCE.md): real data checked before it is
// relied on — the camera's (row, column) order, by projecting the depth camera's point cloud
// onto the cloth mask — and the two-corner hang of assets/scenes/phi_sft_R1_hang.json held
// against it: its corners where the data puts them, and its 3D Chamfer distance to the point
// cloud (docs/photos.md, "φ-SfT R1").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "app/fit/chamfer_3d.h"
#include "app/run/frame_mesh.h"
#include "app/io/mesh_file.h"
#include "app/run/renderer_choice.h"
#include "app/io/npy_file.h"
#include "app/scene/scene.h"
#include "render/image.h"
#include "render/photo_compare/metrics.h"
#include "render/photo_compare/silhouette.h"

namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(WEFT_SOURCE_DIR) / "tests" / "data" / "photos" / "phi_sft_R1";

// R1_scene.json's pairs: focal_lengths (944.575, 971.522), optical_centers (554.778, 962.134)
// px for 1920×1080; the small copies are 4× smaller.
constexpr double kFirstF = 944.575, kSecondF = 971.522, kFirstC = 554.778, kSecondC = 962.134;
constexpr double kScale = 0.25;

// The share of the points that land on a cloth pixel of the mask when x = fx X/Z + cx,
// y = fy Y/Z + cy (full-size pixels, centre of pixel (0, 0) at (0, 0)), scaled to the mask.
double share_inside(const weft::render::Mask& mask, const Eigen::MatrixX3d& points, double fx,
                    double fy, double cx, double cy) {
  long inside = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double X = points(i, 0), Y = points(i, 1), Z = points(i, 2);
    const double x = kScale * (fx * X / Z + cx + 0.5) - 0.5, y = kScale * (fy * Y / Z + cy + 0.5) - 0.5;
    inside += mask.at_or_out(static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y)));
  }
  return static_cast<double>(inside) / static_cast<double>(points.rows());
}

// Read as (row, column) — fx = 971.522, cx = 962.134 along the columns — the cloud lands on
// the cloth (the script on the full cloud: 99.6 % inside, coverage IoU 0.923); read as (x, y)
// it misses it (0.1 %).
TEST(PhiSftR1, CameraPairsAreRowColumn) {
  const auto points = weft::app::read_npy_points(kData / "point_cloud_000.npy");
  const weft::render::Mask mask =
      weft::render::mask_from_image(weft::render::read_image(kData / "mask_000.png"));
  ASSERT_EQ(mask.width, 480);
  ASSERT_EQ(mask.height, 270);
  ASSERT_GT(points.rows(), 4000);
  const Eigen::MatrixX3d p = points;
  const double row_column = share_inside(mask, p, kSecondF, kFirstF, kSecondC, kFirstC);
  const double x_y = share_inside(mask, p, kFirstF, kSecondF, kFirstC, kSecondC);
  std::printf("points on the cloth: (row, column) %.2f %%, (x, y) %.2f %%\n", 100 * row_column,
              100 * x_y);
  EXPECT_GT(row_column, 0.98);
  EXPECT_LT(x_y, 0.02);
}

// The dataset's frame-0 template (0_R1_quad.obj, 32 × 32 vertices) is the camera's frame turned
// half a turn about z: with x and y negated it lies on the point cloud, 6.2 mm away in the
// symmetric 3D Chamfer distance (measured; the floor a 32 × 32 vertex set can reach here, its
// vertices 17.7 mm apart), its held corners (vertices 0 and 992) where the scene pins the hang.
TEST(PhiSftR1, TemplateLiesOnThePointCloudWithXAndYNegated) {
  const weft::app::TriangleMesh obj = weft::app::load_triangle_mesh(kData / "0_R1_quad.obj");
  ASSERT_EQ(obj.vertices.rows(), 1024);
  weft::app::Points turned(obj.vertices.rows(), 3), as_read(obj.vertices.rows(), 3);
  for (Eigen::Index i = 0; i < obj.vertices.rows(); ++i) {
    as_read.row(i) = obj.vertices.row(i);
    turned.row(i) << -obj.vertices(i, 0), -obj.vertices(i, 1), obj.vertices(i, 2);
  }
  const auto cloud = weft::app::read_npy_points(kData / "point_cloud_000.npy");
  const double turned_mm = 1e3 * weft::app::chamfer_3d(turned, cloud).symmetric_m;
  const double as_read_mm = 1e3 * weft::app::chamfer_3d(as_read, cloud).symmetric_m;
  std::printf("template vs cloud: x, y negated %.2f mm, as read %.1f mm\n", turned_mm, as_read_mm);
  EXPECT_LT(turned_mm, 7.0);
  EXPECT_GT(as_read_mm, 100.0);
}

// The frame-0 template's held corners, vertices 0 and 992 of 0_R1_quad.obj with x and y negated
// (the OBJ's axes are the camera's turned half a turn about z), m.
const Eigen::Vector3d kCorner0(-0.713166, -0.153658, 1.274754);
const Eigen::Vector3d kCorner992(-0.139769, -0.155677, 1.221038);

// The hang as `weft run` settles it (48 frames of dynamic relaxation, 2 s of pseudo-time, frame
// by frame as weft run advances; about 7 s here). Its corners are the template's; it hangs its 0.55 m and a little (the top edge is
// drawn from 0.55 to 0.576 m, the sides stretch under the weight); and its 3D Chamfer distance
// to the depth camera's cloud is 10.9 mm (measured: cloth → cloud 9.7, cloud → cloth 12.0).
// The bound of 12 mm: the dataset's own frame-0 template, a 32 × 32 vertex set fitted to this
// frame, scores 6.2 mm on the same cloud (its vertices 17.7 mm apart set that floor); the rest
// of the misfit is the real scarf's twist out of the corners' vertical plane (up to 38 mm at
// the lower right, docs/photos.md) that a static hang in still air does not make.
class PhiSftR1Hang : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    s_scene = new weft::app::Scene(weft::app::load_scene(
        fs::path(WEFT_SOURCE_DIR) / "assets" / "scenes" / "phi_sft_R1_hang.json"));
    s_simulator = weft::app::make_simulator(*s_scene).release();
    for (int frame = 0; frame < s_scene->frames; ++frame) s_simulator->advance(1.0 / s_scene->fps);
  }
  static void TearDownTestSuite() {
    delete s_simulator;
    delete s_scene;
  }
  static weft::app::Scene* s_scene;
  static weft::sim::Simulator* s_simulator;
};
weft::app::Scene* PhiSftR1Hang::s_scene = nullptr;
weft::sim::Simulator* PhiSftR1Hang::s_simulator = nullptr;

TEST_F(PhiSftR1Hang, MatchesThePointCloud) {
  const weft::sim::ClothMesh& mesh = s_simulator->mesh();
  const weft::sim::Matrix3X& x = s_simulator->state().x;
  EXPECT_LT((x.row(mesh.index(0, 0)).transpose() - kCorner0).norm(), 1e-5);
  EXPECT_LT((x.row(mesh.index(mesh.nu - 1, 0)).transpose() - kCorner992).norm(), 1e-5);
  // The bottom edge's drop below the corners (y is down).
  double bottom_y = 0.0;
  for (weft::sim::Index i = 0; i < mesh.nu; ++i) bottom_y += x(mesh.index(i, mesh.nv - 1), 1) / mesh.nu;
  EXPECT_GT(bottom_y - kCorner0.y(), 0.54);
  EXPECT_LT(bottom_y - kCorner0.y(), 0.57);
  const auto cloud = weft::app::read_npy_points(kData / "point_cloud_000.npy");
  const weft::app::Chamfer3d c = weft::app::chamfer_3d(weft::app::cloth_points(mesh, x), cloud);
  std::printf("3D Chamfer: cloth -> cloud %.2f mm, cloud -> cloth %.2f mm, symmetric %.2f mm\n",
              1e3 * c.a_to_b_m, 1e3 * c.b_to_a_m, 1e3 * c.symmetric_m);
  EXPECT_LT(c.symmetric_m, 0.012);
}

// Through the dataset's camera (render.camera: the calibrated pinhole, scaled to 480 × 270), the
// hang's cloth mask (the renderer's geometry) against mask_000.png's cloth — its largest
// component: the dataset's mask also holds two small blobs below the scarf, not cloth.
// Measured: IoU 0.960, outline Chamfer 1.03 px (a pixel here is about 5 mm on the cloth, 1.25 m
// from a lens of 243 px focal length). Bounds: IoU > 0.9 and Chamfer < 2 px, about twice the
// measured misfit.
TEST_F(PhiSftR1Hang, MatchesTheMaskThroughTheDatasetsCamera) {
  std::unique_ptr<weft::render::Renderer> renderer;
  try {
    renderer = weft::app::make_chosen_renderer(s_scene->render);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "no renderer: " << e.what();
  }
  const weft::render::Mask sim = renderer->render_mask(
      weft::app::to_render_mesh(s_simulator->mesh(), s_simulator->state().x), s_scene->render, {},
      weft::render::Renderer::MaskOf::cloth);
  const weft::render::Mask photo = weft::render::largest_component(
      weft::render::mask_from_image(weft::render::read_image(kData / "mask_000.png")));
  ASSERT_EQ(sim.width, photo.width);
  ASSERT_EQ(sim.height, photo.height);
  const double iou = weft::render::silhouette_iou(photo, sim);
  const auto chamfer = weft::render::chamfer_distance(photo, sim);
  std::printf("IoU %.4f, outline Chamfer %.3f px (photo -> sim %.3f, sim -> photo %.3f)\n", iou,
              chamfer.symmetric_px, chamfer.a_to_b_px, chamfer.b_to_a_px);
  EXPECT_GT(iou, 0.9);
  EXPECT_LT(chamfer.symmetric_px, 2.0);
}

}  // namespace
