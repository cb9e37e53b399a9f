#pragma once
// Cloth textures, mapped by material coordinates (RenderMesh::uvs, metres along warp and weft)
// in one of two ways:
// - repeat: (s, t) = (warp, weft) / repeat_m, the image repeated in both directions (a weave,
//   a print that repeats);
// - piece: the image stretched once over the whole piece, (s, t) = (uv − lo) / (hi − lo) for
//   the bounding box [lo, hi] of the cloth's material coordinates, clamped at its edges (a
//   printed scarf, a scan or a photo of the whole cloth).
// An image lies on the material as it looks in a viewer with warp to the right and weft up:
// column x at s = (x + 0.5) / width, and row y (0 the top row) at t = 1 − (y + 0.5) / height, so
// the image's bottom-left corner sits at material (0, 0) (repeat) or at lo (piece).
// Both renderers sample it bilinearly: the ray tracer with sample_texture(), the rasterizer
// through a GL texture (mipmapped for distant cloth).
// A texel is a colour as displayed (0..1), which replaces RenderSettings::front_color; it
// covers the back side too unless the scene gives the back its own colour
// (render_settings.h: texture_on_back). Colour management: a texel c is the reflectance
// c^2.2 and shading is linear (raytrace/shading.h, the rasterizer's c · light^(1/2.2)).
// Images are read with read_image (render/image.h: PNG/JPG through stb).

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "base/enum_names.h"
#include "render/image.h"

namespace weft::render {

enum class TextureMapping { repeat, piece };
inline constexpr base::EnumNames<TextureMapping, 2> texture_mapping_names{
    {{TextureMapping::repeat, "repeat"}, {TextureMapping::piece, "piece"}}};

struct ClothTexture {
  std::shared_ptr<const Image> image;  // null: no texture (the plain front colour)
  Eigen::Vector2d repeat_m{0.1, 0.1};  // repeat: metres of material per repeat along warp, weft
  TextureMapping mapping = TextureMapping::repeat;
};

// Where a texture lies on one mesh's material coordinates: (s, t) = (uv − origin) / size,
// repeated or clamped to the image's edge.
struct TexturePlacement {
  Eigen::Vector2f origin{0.0f, 0.0f};
  Eigen::Vector2f size{0.1f, 0.1f};  // > 0
  bool repeat = true;
};

// The placement of `texture` on a mesh with material coordinates `uvs`: (0, repeat_m, repeat)
// for TextureMapping::repeat; the bounding box of uvs, clamped, for piece (a side of zero
// extent, as a single line of vertices, counts as 1 m).
TexturePlacement texture_placement(const ClothTexture& texture,
                                   const std::vector<Eigen::Vector2f>& uvs);

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

// Bilinear sample at texture coordinates (s, t) (see above), repeating or clamped to the edge
// texels: a colour as displayed, 0..1 per channel. The image must not be empty.
Eigen::Vector3f sample_texture(const Image& image, float s, float t, bool repeat = true);

// The texture's colour at material coordinates uv (metres), placed by `placement`.
inline Eigen::Vector3f sample_placed_texture(const Image& image, const TexturePlacement& placement,
                                             const Eigen::Vector2f& uv) {
  const Eigen::Vector2f st = (uv - placement.origin).cwiseQuotient(placement.size);
  return sample_texture(image, st.x(), st.y(), placement.repeat);
}

}  // namespace weft::render
