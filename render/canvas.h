#pragma once
// A small 2-D drawing surface: the raster back-end of chart/ (weft sweep's, stability's and
// report's charts) and the labels of contact sheets and overlays. Hard-edged rectangles, lines
// and circles; anti-aliased lines, circles and text (render/font.h, DejaVu Sans) blended by
// coverage. Deterministic: the same calls give the same bits.

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
  // Anti-aliased: a line `width` pixels wide with round ends, and a circle (filled, or its
  // outline `width` pixels wide), blended over what is there by each pixel's coverage.
  void smooth_line(double x0, double y0, double x1, double y1, Rgb8 colour, double width);
  void smooth_circle(double cx, double cy, double r, Rgb8 colour, bool filled, double width = 1.0);
  // Blends `colour` over pixel (x, y) with opacity alpha ∈ [0, 1]; ignored outside the canvas.
  void blend(int x, int y, Rgb8 colour, double alpha);

  // Body text size, pixels: the font's height from ascender to descender (render/font.h).
  static constexpr double kTextPx = 12.0;
  // UTF-8 text, anti-aliased, in the chart font at `size_px`; (x, y) is the top-left corner of
  // its box, text_width × text_height pixels (descenders included).
  void text(double x, double y, const std::string& s, Rgb8 colour, double size_px = kTextPx);
  // The same, rotated 90° counter-clockwise (for a y-axis label), reading bottom to top from
  // (x, y), the bottom-left corner of its box.
  void text_vertical(double x, double y, const std::string& s, Rgb8 colour,
                     double size_px = kTextPx);

  static int text_width(const std::string& s, double size_px = kTextPx);
  static int text_height(double size_px = kTextPx);

 private:
  Image m_image;
};

}  // namespace weft::render
