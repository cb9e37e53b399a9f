// The geometry of a scene from a photo (render/photo_compare/held_corners.h, photo_texture.h):
// held corners found in masks of known quadrilaterals with noise, specks and fibres; a texture
// projected from a synthetic photo of a known pattern on a known surface, through a pinhole.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/photo_compare/held_corners.h"
#include "render/photo_compare/photo_texture.h"
#include "render/photo_compare/silhouette.h"

namespace {

using namespace weft::render;

// Pixels whose centres lie inside the convex quadrilateral a b c d (clockwise on screen).
Mask quad_mask(int w, int h, const std::array<Eigen::Vector2d, 4>& q) {
  Mask m(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool inside = true;
      for (int k = 0; k < 4; ++k) {
        const Eigen::Vector2d e =
            q[static_cast<std::size_t>((k + 1) % 4)] - q[static_cast<std::size_t>(k)];
        const Eigen::Vector2d p = Eigen::Vector2d(x, y) - q[static_cast<std::size_t>(k)];
        if (e.x() * p.y() - e.y() * p.x() < 0) inside = false;
      }
      m.set(x, y, inside);
    }
  return m;
}

TEST(HeldCorners, TopCornersOfAHangingQuadrilateral) {
  // Top corners at (40.2, 30.6) and (150.7, 34.1), the sides widening a little downwards.
  const std::array<Eigen::Vector2d, 4> q = {
      Eigen::Vector2d(40.2, 30.6), Eigen::Vector2d(150.7, 34.1), Eigen::Vector2d(153.0, 140.0),
      Eigen::Vector2d(37.0, 138.0)};
  const HeldCorners c = find_held_corners(quad_mask(200, 160, q));
  EXPECT_LT((c.px[0] - q[0]).norm(), 1.5) << c.px[0].transpose();
  EXPECT_LT((c.px[1] - q[1]).norm(), 1.5) << c.px[1].transpose();
}

TEST(HeldCorners, IgnoresSpecksFibresAndHoles) {
  const std::array<Eigen::Vector2d, 4> q = {Eigen::Vector2d(60, 40), Eigen::Vector2d(260, 40),
                                            Eigen::Vector2d(262, 230), Eigen::Vector2d(58, 232)};
  Mask m = quad_mask(320, 260, q);
  std::mt19937 random(7);
  std::uniform_int_distribution<int> px(0, 319), py(0, 259);
  for (int k = 0; k < 300; ++k) m.set(px(random), py(random), true);       // specks around
  for (int k = 0; k < 200; ++k) m.set(100 + k % 20, 100 + k / 20, false);  // a hole inside
  for (int k = 1; k <= 12; ++k) m.set(60 - k, 40 - k, true);               // a fibre off the corner
  for (int y = 5; y < 9; ++y)                                              // a blob above
    for (int x = 150; x < 154; ++x) m.set(x, y, true);
  const HeldCorners c = find_held_corners(m);
  EXPECT_LT((c.px[0] - q[0]).norm(), 2.5) << c.px[0].transpose();
  EXPECT_LT((c.px[1] - q[1]).norm(), 2.5) << c.px[1].transpose();
  EXPECT_GE(c.opening_radius_px, 1);
}

TEST(HeldCorners, EmptyMaskIsAnError) {
  EXPECT_THROW(find_held_corners(Mask(20, 20)), std::invalid_argument);
}

// A pinhole at the origin looking along +z (fx = fy = 400, centre (160, 120), 320 × 240).
Eigen::Vector3d pinhole(const Eigen::Vector3d& p) {
  return {400.0 * p.x() / p.z() + 160.0, 400.0 * p.y() / p.z() + 120.0, p.z()};
}

// The pattern on the cloth, a function of the material point (u, v) in metres.
Rgb8 pattern(double u, double v) {
  return {static_cast<std::uint8_t>(40 + 400 * u), static_cast<std::uint8_t>(40 + 400 * v),
          static_cast<std::uint8_t>(120 + 80 * std::sin(40 * u) * std::cos(30 * v))};
}

// A 0.4 × 0.3 m cloth whose front faces the camera (warp right = +x, weft up = −y), 1 m away,
// bent back in z by `bulge` along u; the photo painted by ray casting the exact surface.
struct SyntheticPhoto {
  ClothGridShape cloth;
  Image photo{320, 240, {0, 0, 0}};
  Mask mask{320, 240};
};

SyntheticPhoto synthetic_photo(double bulge) {
  SyntheticPhoto s;
  ClothGridShape& c = s.cloth;
  c.nu = 41;
  c.nv = 31;
  c.width_m = 0.4;
  c.height_m = 0.3;
  const auto surface = [&](double u, double v) {
    return Eigen::Vector3d(u - 0.2, 0.15 - v, 1.0 + bulge * std::sin(3.14159265 * u / 0.4));
  };
  for (int j = 0; j < c.nv; ++j)
    for (int i = 0; i < c.nu; ++i) c.positions.push_back(surface(0.01 * i, 0.01 * j));
  // Paint: sample the material densely, splat to the nearest pixel (front to back irrelevant:
  // the surface is a height field seen from the front).
  for (int j = 0; j <= 1200; ++j)
    for (int i = 0; i <= 1600; ++i) {
      const double u = 0.4 * i / 1600.0, v = 0.3 * j / 1200.0;
      const Eigen::Vector3d q = pinhole(surface(u, v));
      const int x = static_cast<int>(std::lround(q.x())), y = static_cast<int>(std::lround(q.y()));
      if (x < 0 || y < 0 || x >= 320 || y >= 240) continue;
      s.photo.set(x, y, pattern(u, v));
      s.mask.set(x, y, true);
    }
  return s;
}

TEST(PhotoTexture, RecoversThePatternOfAFlatAndABentCloth) {
  for (const double bulge : {0.0, 0.08}) {
    const SyntheticPhoto s = synthetic_photo(bulge);
    const PhotoTexture t =
        project_photo_texture(s.photo, s.mask, s.cloth, pinhole, Eigen::Vector3d::Zero(), 80, 60);
    EXPECT_GT(t.seen_fraction, 0.85) << "bulge " << bulge;
    double sum = 0.0;
    long n = 0;
    for (int y = 0; y < 60; ++y)
      for (int x = 0; x < 80; ++x) {
        if (!t.seen.at(x, y)) continue;
        // Texel (x, y): material ((x + ½) W / 80, (60 − y − ½) H / 60).
        const Rgb8 want = pattern((x + 0.5) * 0.4 / 80, (59.5 - y) * 0.3 / 60);
        const Rgb8 got = t.texture.at(x, y);
        sum += std::abs(got.r - want.r) + std::abs(got.g - want.g) + std::abs(got.b - want.b);
        n += 3;
      }
    // A photo pixel is about 2.5 mm of cloth, a texel 5 mm: the pattern changes by about
    // 1 level per mm in r and g.
    EXPECT_LT(sum / static_cast<double>(n), 4.0) << "bulge " << bulge;
    // Unseen texels are filled: no black (background) texel is left.
    for (int y = 0; y < 60; ++y)
      for (int x = 0; x < 80; ++x) EXPECT_GT(t.texture.at(x, y).r, 30);
  }
}

TEST(PhotoTexture, BackFacingAndHiddenTexelsAreNotSeen) {
  SyntheticPhoto s = synthetic_photo(0.0);
  // Turned around (warp to the left): the camera sees its back; nothing is seen.
  ClothGridShape back = s.cloth;
  for (auto& p : back.positions) p.x() = -p.x();
  EXPECT_THROW(
      project_photo_texture(s.photo, s.mask, back, pinhole, Eigen::Vector3d::Zero(), 80, 60),
      std::invalid_argument);
  // The left half of the mask removed: only the right half is seen.
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 160; ++x) s.mask.set(x, y, false);
  const PhotoTexture t =
      project_photo_texture(s.photo, s.mask, s.cloth, pinhole, Eigen::Vector3d::Zero(), 80, 60);
  EXPECT_FALSE(t.seen.at(10, 30));
  EXPECT_TRUE(t.seen.at(70, 30));
  EXPECT_NEAR(t.seen_fraction, 0.5, 0.05);
}

}  // namespace
