#pragma once
// A small 2-D drawing surface for charts (weft sweep's error-vs-time plot, weft stability's
// heatmap): filled rectangles, lines, markers and text in a built-in bitmap font, on an Image
// that write_png() saves. No anti-aliasing: the same calls give the same bits.

#include <string>

#include "render/image.h"

namespace weft::render {

class Canvas {
 public:
  Canvas(int width, int height, Rgb8 background);
  // Draws over an existing image (e.g. a photo).
  explicit Canvas(Image image);

  int width() const { return m_image.width(); }
  int height() const { return m_image.height(); }
  const Image& image() const { return m_image; }

  // Pixels x0 ≤ x < x1, y0 ≤ y < y1 ((0, 0) is the top left), clipped to the canvas.
  void fill_rect(int x0, int y0, int x1, int y1, Rgb8 colour);
  // Outline of the same rectangle, 1 pixel wide.
  void rect(int x0, int y0, int x1, int y1, Rgb8 colour);
  // A straight line between pixel centres, `thickness` pixels wide, clipped.
  void line(double x0, double y0, double x1, double y1, Rgb8 colour, int thickness = 1);
  // The same line dashed: `dash` pixels drawn, `gap` pixels skipped, measured along the line
  // from `phase` pixels into the dash–gap period. Returns the phase at (x1, y1), so that the
  // segments of a polyline continue one pattern.
  double dashed_line(double x0, double y0, double x1, double y1, Rgb8 colour, int thickness,
                     double dash, double gap, double phase = 0.0);
  // A circle of radius r pixels centred at (cx, cy), filled or as an outline.
  void circle(double cx, double cy, double r, Rgb8 colour, bool filled = true);
  // Printable ASCII (other characters draw as '?') in the built-in font, each glyph
  // glyph_width × glyph_height pixels times `scale`; (x, y) is the top left of the first glyph.
  void text(int x, int y, const std::string& s, Rgb8 colour, int scale = 1);
  // The same, rotated 90° counter-clockwise (for a y-axis label), reading bottom to top from
  // (x, y), the bottom-left corner of the first glyph.
  void text_vertical(int x, int y, const std::string& s, Rgb8 colour, int scale = 1);

  static int text_width(const std::string& s, int scale = 1);
  static int text_height(int scale = 1);

 private:
  Image m_image;
};

}  // namespace weft::render
