// The wireframe overlay (wireframe_overlay.h): a depth buffer of the surfaces, then the mesh's
// lines as antialiased coverage, blended once.

#include "render/wireframe_overlay.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/check.h"
#include "base/constants.h"
#include "render/render_settings.h"

namespace weft::render {

namespace {

constexpr float no_surface = std::numeric_limits<float>::infinity();

// View depth (metres along the view axis) of the nearest surface at each pixel centre, rows
// top first; no_surface where none.
class DepthBuffer {
 public:
  explicit DepthBuffer(const RenderSettings& s)
      : m_s(s), m_depth(std::size_t(s.width) * s.height, no_surface) {}

  void add(const RenderMesh& mesh) {
    std::vector<Eigen::Vector3d> p(mesh.positions.size());
    for (std::size_t v = 0; v < p.size(); ++v) p[v] = project(mesh.positions[v]);
    for (const auto& t : mesh.triangles) add_triangle(p[t[0]], p[t[1]], p[t[2]]);
  }

  Eigen::Vector3d project(const Eigen::Vector3f& world_m) const {
    return m_s.camera.project(world_m.cast<double>(), m_s.width, m_s.height);
  }

  // The farthest surface in the 3×3 pixels about (x, y); no_surface when any has none.
  float farthest_about(int x, int y) const {
    float z = 0.0f;
    for (int j = y - 1; j <= y + 1; ++j)
      for (int i = x - 1; i <= x + 1; ++i)
        z = std::max(z, (i < 0 || j < 0 || i >= m_s.width || j >= m_s.height)
                            ? no_surface
                            : m_depth[std::size_t(j) * m_s.width + i]);
    return z;
  }

 private:
  // Pixel centres inside the projected triangle (edges included) take the perspective-correct
  // depth: 1/z is linear on screen.
  void add_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const double near = m_s.camera.near_m;
    if (a.z() <= near || b.z() <= near || c.z() <= near) return;
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (!(std::abs(area) > 1e-12)) return;
    const int x0 = std::max(0, int(std::ceil(std::min({a.x(), b.x(), c.x()}))));
    const int x1 = std::min(m_s.width - 1, int(std::floor(std::max({a.x(), b.x(), c.x()}))));
    const int y0 = std::max(0, int(std::ceil(std::min({a.y(), b.y(), c.y()}))));
    const int y1 = std::min(m_s.height - 1, int(std::floor(std::max({a.y(), b.y(), c.y()}))));
    const auto edge = [](const Eigen::Vector3d& p, const Eigen::Vector3d& q, double x, double y) {
      return (q.x() - p.x()) * (y - p.y()) - (x - p.x()) * (q.y() - p.y());
    };
    constexpr double inside = -1e-9;
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const double wa = edge(b, c, x, y) / area, wb = edge(c, a, x, y) / area,
                     wc = edge(a, b, x, y) / area;
        if (wa < inside || wb < inside || wc < inside) continue;
        const double z = 1.0 / (wa / a.z() + wb / b.z() + wc / c.z());
        float& d = m_depth[std::size_t(y) * m_s.width + x];
        d = std::min(d, float(z));
      }
    }
  }

  const RenderSettings& m_s;
  std::vector<float> m_depth;
};

}  // namespace

void draw_wireframe(Image& image, const RenderMesh& cloth, const RenderSettings& s,
                    const std::vector<RenderObject>& objects) {
  const Wireframe& w = s.cloth_surface.wireframe;
  if (!w.enabled) return;
  WEFT_CHECK(image.width() == s.width && image.height() == s.height,
             "draw_wireframe: the image is not the settings' size");
  DepthBuffer depth(s);
  depth.add(cloth);
  for (const RenderObject& object : objects) depth.add(object.mesh);

  // Metres per pixel at unit depth, for the tolerance.
  const double footprint = 2.0 * std::tan(0.5 * s.camera.fov_y_deg * base::kPi / 180.0) / s.height;
  const double half = 0.5 * std::max(w.width_px, 1.0), thin = std::min(w.width_px, 1.0);
  std::vector<float> coverage(std::size_t(s.width) * s.height, 0.0f);
  const std::vector<std::array<std::uint32_t, 2>> own =
      cloth.edges.empty() ? triangle_edges(cloth) : std::vector<std::array<std::uint32_t, 2>>{};
  for (const auto& [ia, ib] : cloth.edges.empty() ? own : cloth.edges) {
    const Eigen::Vector3d a = depth.project(cloth.positions[ia]);
    const Eigen::Vector3d b = depth.project(cloth.positions[ib]);
    if (a.z() <= s.camera.near_m || b.z() <= s.camera.near_m) continue;
    const Eigen::Vector2d a2 = a.head<2>(), ab = b.head<2>() - a2;
    const double length2 = ab.squaredNorm();
    const double reach = half + 0.5;
    const int x0 = std::max(0, int(std::floor(std::min(a.x(), b.x()) - reach)));
    const int x1 = std::min(s.width - 1, int(std::ceil(std::max(a.x(), b.x()) + reach)));
    const int y0 = std::max(0, int(std::floor(std::min(a.y(), b.y()) - reach)));
    const int y1 = std::min(s.height - 1, int(std::ceil(std::max(a.y(), b.y()) + reach)));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d p(x, y);
        const double t = length2 > 0.0 ? std::clamp((p - a2).dot(ab) / length2, 0.0, 1.0) : 0.0;
        const Eigen::Vector2d nearest = a2 + t * ab;
        const double c = thin * std::clamp(reach - (p - nearest).norm(), 0.0, 1.0);
        float& cell = coverage[std::size_t(y) * s.width + x];
        if (!(c > cell)) continue;
        const double z = 1.0 / ((1.0 - t) / a.z() + t / b.z());  // 1/z is linear on screen
        const double tolerance = 0.002 * z + 2.0 * footprint * z;
        if (z > depth.farthest_about(int(std::lround(nearest.x())), int(std::lround(nearest.y()))) +
                    tolerance)
          continue;
        cell = float(c);
      }
    }
  }

  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      const float c = coverage[std::size_t(y) * s.width + x];
      if (c <= 0.0f) continue;
      const Rgb8 old = image.at(x, y);
      const auto mix = [c](std::uint8_t from, float to) {
        return std::uint8_t(std::lround((1.0f - c) * from + c * 255.0f * to));
      };
      image.set(x, y, {mix(old.r, w.color.x()), mix(old.g, w.color.y()), mix(old.b, w.color.z())});
    }
  }
}

}  // namespace weft::render
