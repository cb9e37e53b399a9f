#pragma once
// A contact sheet: small copies of a sequence's images in a grid, each labelled (weft
// turntable's contact_sheet.png).

#include <string>
#include <vector>

#include "render/image.h"

namespace weft::app {

// `image` shrunk to `width` pixels wide (height in proportion, at least 1), each pixel the
// mean of the source pixels its area covers (a box filter: no aliasing of fine folds), or a
// copy when it is no wider than `width`. Throws std::invalid_argument for width < 1 or an
// empty image.
render::Image thumbnail(const render::Image& image, int width);

// The thumbnails in rows of `columns` (left to right, top to bottom), each above its label
// (UTF-8, in render/canvas.h's text), with a margin of `gap` pixels around and between
// them, on a white background. Thumbnails of different sizes get cells of the largest size.
// Throws std::invalid_argument when there are no thumbnails, the label count differs, or
// columns < 1.
render::Image contact_sheet(const std::vector<render::Image>& thumbnails,
                            const std::vector<std::string>& labels, int columns, int gap = 8);

// Columns for n tiles of tile_width × tile_height pixels that make the sheet about square:
// ceil(sqrt(n · tile_height / tile_width)), within 1..n (e.g. 12 tiles of 4:3 → 3 columns).
int contact_sheet_columns(int n, int tile_width, int tile_height);

}  // namespace weft::app
