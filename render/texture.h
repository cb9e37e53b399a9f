#pragma once
// Cloth textures, mapped by material coordinates: texture coordinates
//     (s, t) = (warp, weft) / repeat_m   (RenderMesh::uvs, metres, over metres per repeat),
// repeated in both directions. An image lies on the material as it looks in a viewer with warp
// to the right and weft up: column x at s = (x + 0.5) / width, and row y (0 the top row) at
// t = 1 − (y + 0.5) / height, so the image's bottom-left corner sits at material (0, 0).
// Both renderers sample it bilinearly with repeat: the ray tracer with sample_texture(), the
// rasterizer through a GL texture (mipmapped for distant cloth).
// A texel is a colour as displayed (0..1), which replaces RenderSettings::front_color on the
// front side of the cloth; the back side keeps back_color.
// Images are read with read_image (render/image.h: PNG/JPG through stb).

#include <Eigen/Core>
#include <memory>

#include "render/image.h"

namespace weft::render {

struct ClothTexture {
  std::shared_ptr<const Image> image;  // null: no texture (the plain front colour)
  Eigen::Vector2d repeat_m{0.1, 0.1};  // metres of material per repeat along warp and weft
};

// A woven check (gingham): bands of warp threads (running along the warp, so stacked along
// the weft) in warp_color and bands of weft threads (running along the weft) in weft_color,
// `stripes` of each per repeat, each half a period wide; where they cross the two colours mix
// half and half, elsewhere the ground colour. Fine thread lines (8 per band) darken the bands
// a little, across the warp bands along the weft and vice versa, so the thread direction shows.
struct WovenCheck {
  Eigen::Vector3f warp_color{0.75f, 0.12f, 0.10f};  // as displayed, 0..1
  Eigen::Vector3f weft_color{0.15f, 0.25f, 0.65f};
  Eigen::Vector3f ground_color{0.93f, 0.90f, 0.82f};
  int stripes = 4;  // per repeat, 1..64
};

// The woven check drawn into a size×size image (one repeat). Throws std::invalid_argument for
// stripes outside 1..64, size outside 16..4096 or a colour outside [0, 1].
Image make_woven_check(const WovenCheck& check, int size = 512);

// Bilinear, repeating sample at texture coordinates (s, t) (see above): a colour as displayed,
// 0..1 per channel. The image must not be empty.
Eigen::Vector3f sample_texture(const Image& image, float s, float t);

// The texture's colour at material coordinates uv (metres).
inline Eigen::Vector3f sample_cloth_texture(const ClothTexture& texture,
                                            const Eigen::Vector2f& uv) {
  return sample_texture(*texture.image, uv.x() / static_cast<float>(texture.repeat_m.x()),
                        uv.y() / static_cast<float>(texture.repeat_m.y()));
}

}  // namespace weft::render
