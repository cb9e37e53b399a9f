#pragma once
// Shared by the renderer tests (raster_test.cpp, raytrace_test.cpp): simple meshes, where a
// world point lands in the image, byte comparisons, and the images a failed test leaves behind
// in <build>/test_output/<folder>/ for a person to look at.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "render/camera.h"
#include "render/gl_context.h"
#include "render/image.h"
#include "render/raster.h"
#include "render/render_mesh.h"
#include "render/renderer.h"

namespace weft::render::test {

// Axis-aligned rectangle in the plane z = z_m, counter-clockwise seen from +z (front = +z).
inline RenderMesh rectangle(double x0, double x1, double y0, double y1, double z_m) {
  RenderMesh mesh;
  mesh.positions = {
      Eigen::Vector3d(x0, y0, z_m).cast<float>(), Eigen::Vector3d(x1, y0, z_m).cast<float>(),
      Eigen::Vector3d(x1, y1, z_m).cast<float>(), Eigen::Vector3d(x0, y1, z_m).cast<float>()};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  compute_vertex_normals(mesh);
  return mesh;
}

// Camera on the +z axis looking straight down at z = 0.5 m, +y up on screen, +x right; no
// ground.
inline RenderSettings view_from_above(int width, int height) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.ground = false;
  s.camera.eye = {0, 0, 3};
  s.camera.target = {0, 0, 0.5};
  s.camera.up = {0, 1, 0};
  s.camera.fov_y_deg = 40;
  return s;
}

struct Pixel {
  int x = 0, y = 0;  // image coordinates, (0, 0) top-left
};

// Pixel containing the projection of a world point.
inline Pixel project(const RenderSettings& s, const Eigen::Vector3d& world) {
  const double aspect = static_cast<double>(s.width) / s.height;
  const Eigen::Vector4f clip = s.camera.projection_matrix(aspect) * s.camera.view_matrix() *
                               Eigen::Vector4f(world.cast<float>().homogeneous());
  const double x_ndc = clip.x() / clip.w(), y_ndc = clip.y() / clip.w();
  return {static_cast<int>(std::floor((0.5 * x_ndc + 0.5) * s.width)),
          static_cast<int>(std::floor((0.5 - 0.5 * y_ndc) * s.height))};
}

inline std::uint8_t to_byte(double c) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0));
}

inline Rgb8 to_rgb8(const Eigen::Vector3f& c) {
  return {to_byte(c.x()), to_byte(c.y()), to_byte(c.z())};
}

inline bool same_bytes(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::equal(a.data(), a.data() + 3 * a.width() * a.height(), b.data());
}

// Images rendered by the current test, written to <build>/test_output/<folder>/ when it fails.
class FailureEvidence {
 public:
  explicit FailureEvidence(std::string folder) : m_folder(std::move(folder)) {}
  void add(const std::string& name, const Image& image) { m_images.emplace_back(name, image); }
  // Call from TearDown().
  void save_if_failed() const {
    if (!::testing::Test::HasFailure() || m_images.empty()) return;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::filesystem::path dir =
        std::filesystem::path(WEFT_BINARY_DIR) / "test_output" / m_folder;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    for (std::size_t i = 0; i < m_images.size(); ++i) {
      const std::filesystem::path path =
          dir /
          (std::string(info->name()) + "_" + std::to_string(i) + "_" + m_images[i].first + ".png");
      try {
        write_png(m_images[i].second, path);
        std::cerr << "  rendered image: " << path.string() << "\n";
      } catch (const std::exception& e) {
        std::cerr << "  could not save evidence: " << e.what() << "\n";
      }
    }
  }

 private:
  std::string m_folder;
  std::vector<std::pair<std::string, Image>> m_images;
};

// A camera-to-world rotation in OpenCV's axes (columns x right, y down, z forward) looking from
// `eye` at `target` with world z up on screen, then rolled by `roll_rad` about the view axis.
inline Eigen::Matrix3d opencv_look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                                      double roll_rad) {
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d r;
  r << x, y, z;
  return r * Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// A rasterizer on an OSMesa context, or null (with the reason in `why`) where this machine
// cannot make one: the caller skips.
inline std::unique_ptr<RasterRenderer> osmesa_raster_or_null(std::string& why) {
  try {
    return std::make_unique<RasterRenderer>(make_osmesa_context(64, 64));
  } catch (const std::exception& e) {
    why = e.what();
    return nullptr;
  }
}

// The renderer the settings name (render/renderer.h), or null (with the reason in `why`) when
// it cannot start here: the caller skips.
inline std::unique_ptr<Renderer> try_renderer(const RenderSettings& s, std::string& why) {
  try {
    return make_renderer(s);
  } catch (const std::exception& e) {
    why = e.what();
    return nullptr;
  }
}

}  // namespace weft::render::test
