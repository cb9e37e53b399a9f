#pragma once
// The cloth's rendering aids in a scene's `render` block (render/cloth_surface.h):
//   "subdivision": 0..3      Loop subdivision levels (default 0)
//   "thickness": length      a closed shell this thick (default 0: a single sheet)
//   "texture": {"file": "cloth.png" | "woven_check": {...}, "scale": [warp, weft]}
//   "wireframe": true | false | {"width": pixels, "color": [r, g, b]}   the simulation mesh's
//                            lines over the frame (render/wireframe_overlay.h; default off)
// The texture file's path is relative to the scene file; it is read here, so a missing or
// unreadable image is a scene error naming render.texture.file and the file.

#include "app/scene/json_reader.h"
#include "render/cloth_surface.h"

namespace weft::app {

inline constexpr double max_wireframe_width_px = 64.0;

// Reads the keys above from the `render` object into `surface`. Throws InputError.
void read_cloth_surface(ObjectReader& render, render::ClothSurface& surface);

}  // namespace weft::app
