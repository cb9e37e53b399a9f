#pragma once
// The relief of a plain weave, as a normal map in material coordinates, the same in both
// renderers: warp threads (running along the warp) and weft threads pass over and under each
// other, one repeat holding two threads each way. It tilts the cloth's shading normal (not its
// geometry), so that light grazing the cloth picks out the threads; seen from afar it averages
// out (the rasterizer's mipmaps, the ray tracer's samples per pixel).
//
// The map is an Image whose texel (r, g, b) encodes the tangent-space normal
// m = 2 (r, g, b)/255 − 1 with x along the warp, y along the weft and z out of the cloth,
// placed on the material like a repeating texture (render/texture.h) of `repeat_m`. The normal
// used is normalize(T m.x d + B m.y d + n m.z) for the tangents T = ∂p/∂warp, B = ∂p/∂weft
// made orthonormal to the shading normal n, and d = depth.

#include <Eigen/Core>
#include <memory>

#include "render/image.h"

namespace weft::render {

struct Weave {
  std::shared_ptr<const Image> normal_map;  // null: no relief (make_weave_normal_map)
  Eigen::Vector2d repeat_m{0.002, 0.002};   // material per repeat (two threads) along warp, weft
  double depth = 0.5;                       // 0 (flat) .. 1: scales the map's tilt
};

// One repeat of a plain weave's normal map, size×size texels (size 8..1024): each thread a
// rounded ridge across its width, rising and falling along its length over and under the
// threads it crosses. Its mean normal is (0, 0, 1) up to byte rounding.
Image make_weave_normal_map(int size = 64);

// The normal map's tangent-space normal at texture coordinates (s, t), bilinear and repeating;
// x, y scaled by depth, normalised.
Eigen::Vector3f weave_normal(const Image& map, float s, float t, float depth);

// n tilted by the tangent-space normal m: T and B (any lengths; the directions of increasing
// warp and weft) are made orthonormal to n (unit). Returns n when the tangents are degenerate.
Eigen::Vector3f tilt_normal(const Eigen::Vector3f& n, const Eigen::Vector3f& t_warp,
                            const Eigen::Vector3f& t_weft, const Eigen::Vector3f& m);

}  // namespace weft::render
