// φ-SfT R1 frame 0 (tests/data/photos/phi_sft_R1, SOURCE.md): real data checked before it is
// relied on — the camera's (row, column) order, by projecting the depth camera's point cloud
// onto the cloth mask.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/npy_file.h"
#include "render/image.h"
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

}  // namespace
