// A texture projected from a photo onto a cloth grid; see photo_texture.h.

#include "render/photo_compare/photo_texture.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>

namespace weft::render {
namespace {

// The nearest depth of the cloth's triangles at every photo pixel centre (+∞ where none).
std::vector<double> cloth_depth_buffer(const std::vector<Eigen::Vector3d>& projected,
                                       const ClothGridShape& c, int w, int h) {
  std::vector<double> depth(static_cast<std::size_t>(w) * h,
                            std::numeric_limits<double>::infinity());
  const auto triangle = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& d) {
    if (a.z() <= 0 || b.z() <= 0 || d.z() <= 0) return;
    const double area = (b.x() - a.x()) * (d.y() - a.y()) - (b.y() - a.y()) * (d.x() - a.x());
    if (std::abs(area) < 1e-12) return;
    const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x(), b.x(), d.x()}))));
    const int x1 = std::min(w - 1, static_cast<int>(std::floor(std::max({a.x(), b.x(), d.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y(), b.y(), d.y()}))));
    const int y1 = std::min(h - 1, static_cast<int>(std::floor(std::max({a.y(), b.y(), d.y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double wb = ((x - a.x()) * (d.y() - a.y()) - (y - a.y()) * (d.x() - a.x())) / area;
        const double wd = ((b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x())) / area;
        const double wa = 1.0 - wb - wd;
        if (wa < -1e-9 || wb < -1e-9 || wd < -1e-9) continue;
        // Perspective-correct depth: 1/Z is linear on the screen.
        const double z = 1.0 / (wa / a.z() + wb / b.z() + wd / d.z());
        double& slot = depth[static_cast<std::size_t>(y) * w + x];
        slot = std::min(slot, z);
      }
  };
  for (int j = 0; j + 1 < c.nv; ++j)
    for (int i = 0; i + 1 < c.nu; ++i) {
      const auto& p00 = projected[static_cast<std::size_t>(j) * c.nu + i];
      const auto& p10 = projected[static_cast<std::size_t>(j) * c.nu + i + 1];
      const auto& p01 = projected[static_cast<std::size_t>(j + 1) * c.nu + i];
      const auto& p11 = projected[static_cast<std::size_t>(j + 1) * c.nu + i + 1];
      triangle(p00, p10, p11);
      triangle(p00, p11, p01);
    }
  return depth;
}

Rgb8 photo_bilinear(const Image& img, double u, double v) {
  const int x0 = static_cast<int>(std::floor(u)), y0 = static_cast<int>(std::floor(v));
  const double fx = u - x0, fy = v - y0;
  double rgb[3] = {0, 0, 0};
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const double weight = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
      const Rgb8 p =
          img.at(std::clamp(x0 + dx, 0, img.width() - 1), std::clamp(y0 + dy, 0, img.height() - 1));
      rgb[0] += weight * p.r, rgb[1] += weight * p.g, rgb[2] += weight * p.b;
    }
  const auto byte = [](double v_) {
    return static_cast<std::uint8_t>(std::clamp(std::lround(v_), 0L, 255L));
  };
  return {byte(rgb[0]), byte(rgb[1]), byte(rgb[2])};
}

// Unseen texels take the colour of the nearest seen one (breadth-first over 4-neighbours).
void fill_unseen(Image& texture, const Mask& seen) {
  const int w = texture.width(), h = texture.height();
  std::vector<std::uint8_t> done(seen.in);
  std::deque<std::pair<int, int>> queue;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (seen.at(x, y)) queue.emplace_back(x, y);
  while (!queue.empty()) {
    const auto [x, y] = queue.front();
    queue.pop_front();
    const int nx[4] = {x + 1, x - 1, x, x}, ny[4] = {y, y, y + 1, y - 1};
    for (int k = 0; k < 4; ++k) {
      if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h) continue;
      std::uint8_t& d = done[static_cast<std::size_t>(ny[k]) * w + nx[k]];
      if (d) continue;
      d = 1;
      texture.set(nx[k], ny[k], texture.at(x, y));
      queue.emplace_back(nx[k], ny[k]);
    }
  }
}

}  // namespace

PhotoTexture project_photo_texture(const Image& photo, const Mask& mask, const ClothGridShape& c,
                                   const PhotoProjection& project, const Eigen::Vector3d& eye,
                                   int tw, int th) {
  const int w = photo.width(), h = photo.height();
  if (c.nu < 2 || c.nv < 2 || c.positions.size() != static_cast<std::size_t>(c.nu) * c.nv ||
      !(c.width_m > 0) || !(c.height_m > 0))
    throw std::invalid_argument(
        "photo texture: expected a grid of at least 2 x 2 vertices with a "
        "positive size, got " +
        std::to_string(c.nu) + " x " + std::to_string(c.nv) + " and " +
        std::to_string(c.positions.size()) + " positions");
  if (mask.width != w || mask.height != h)
    throw std::invalid_argument("photo texture: the mask's size differs from the photo's");
  if (tw < 1 || th < 1)
    throw std::invalid_argument("photo texture: the texture size must be positive");
  std::vector<Eigen::Vector3d> projected;
  projected.reserve(c.positions.size());
  for (const auto& p : c.positions) projected.push_back(project(p));
  const std::vector<double> depth = cloth_depth_buffer(projected, c, w, h);
  const auto inside_mask = [&](double u, double v) {
    const int x0 = static_cast<int>(std::floor(u)), y0 = static_cast<int>(std::floor(v));
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx)
        if (!mask.at_or_out(x0 + dx, y0 + dy)) return false;
    return true;
  };
  PhotoTexture out{Image(tw, th, {0, 0, 0}), Mask(tw, th), 0.0};
  long seen = 0;
  for (int y = 0; y < th; ++y)
    for (int x = 0; x < tw; ++x) {
      // Grid coordinates of the texel's material point.
      const double gu = (x + 0.5) / tw * (c.nu - 1), gv = (th - y - 0.5) / th * (c.nv - 1);
      const int i = std::min(static_cast<int>(gu), c.nu - 2),
                j = std::min(static_cast<int>(gv), c.nv - 2);
      const double s = gu - i, t = gv - j;
      const auto& p00 = c.positions[static_cast<std::size_t>(j) * c.nu + i];
      const auto& p10 = c.positions[static_cast<std::size_t>(j) * c.nu + i + 1];
      const auto& p01 = c.positions[static_cast<std::size_t>(j + 1) * c.nu + i];
      const auto& p11 = c.positions[static_cast<std::size_t>(j + 1) * c.nu + i + 1];
      const Eigen::Vector3d p =
          (1 - s) * (1 - t) * p00 + s * (1 - t) * p10 + (1 - s) * t * p01 + s * t * p11;
      const Eigen::Vector3d n = (p11 - p00).cross(p01 - p10);  // warp × weft
      if (n.dot(eye - p) <= 0) continue;
      const Eigen::Vector3d q = project(p);
      if (q.z() <= 0 || q.x() < 0 || q.y() < 0 || q.x() > w - 1 || q.y() > h - 1) continue;
      const double nearest =
          depth[static_cast<std::size_t>(std::lround(q.y())) * w + std::lround(q.x())];
      if (q.z() > nearest * 1.005 + 0.002) continue;
      if (!inside_mask(q.x(), q.y())) continue;
      out.texture.set(x, y, photo_bilinear(photo, q.x(), q.y()));
      out.seen.set(x, y, true);
      ++seen;
    }
  if (seen == 0)
    throw std::invalid_argument(
        "photo texture: no texel of the cloth is seen in the photo (is the "
        "cloth in front of the camera, its front facing it?)");
  out.seen_fraction = static_cast<double>(seen) / (static_cast<double>(tw) * th);
  fill_unseen(out.texture, out.seen);
  return out;
}

}  // namespace weft::render
