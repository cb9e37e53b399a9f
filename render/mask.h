#pragma once
// A binary image: the cloth's silhouette in a photo or a render (render/photo_compare/), or the
// cloth mask a renderer draws from its own geometry (render/renderer.h).

#include <cstdint>
#include <vector>

namespace weft::render {

// width × height, row-major, top row first, 1 = cloth (or covered), 0 = background.
struct Mask {
  int width = 0, height = 0;
  std::vector<std::uint8_t> in;

  Mask() = default;
  Mask(int w, int h) : width(w), height(h), in(static_cast<std::size_t>(w) * h, 0) {}
  bool at(int x, int y) const { return in[static_cast<std::size_t>(y) * width + x] != 0; }
  // false outside the image
  bool at_or_out(int x, int y) const {
    return x >= 0 && y >= 0 && x < width && y < height && at(x, y);
  }
  void set(int x, int y, bool v) { in[static_cast<std::size_t>(y) * width + x] = v ? 1 : 0; }
  // How many of the image's outermost pixels (each counted once) are set: > 0 when the
  // silhouette touches the image border.
  long border_pixels() const {
    if (width <= 0 || height <= 0) return 0;
    long n = 0;
    for (int x = 0; x < width; ++x) n += at(x, 0) + (height > 1 ? at(x, height - 1) : 0);
    for (int y = 1; y + 1 < height; ++y) n += at(0, y) + (width > 1 ? at(width - 1, y) : 0);
    return n;
  }
};

}  // namespace weft::render
