// Canvas: which pixels lines, rectangles, circles and text set, clipping, and the text's
// metrics. Expected pixel sets come from the geometry (a line between pixel centres, a disc's
// area), not from earlier output.

#include "render/canvas.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "base/constants.h"

namespace weft::render {
namespace {

const Rgb8 kWhite{255, 255, 255};
const Rgb8 kInk{10, 20, 200};

using Pixel = std::pair<int, int>;  // (x, y)

std::set<Pixel> inked(const Canvas& canvas, Rgb8 ink = kInk) {
  std::set<Pixel> pixels;
  for (int y = 0; y < canvas.height(); ++y) {
    for (int x = 0; x < canvas.width(); ++x) {
      if (canvas.image().at(x, y) == ink) pixels.insert({x, y});
    }
  }
  return pixels;
}

struct Box {
  int x_min = std::numeric_limits<int>::max(), y_min = std::numeric_limits<int>::max();
  int x_max = std::numeric_limits<int>::min(), y_max = std::numeric_limits<int>::min();
};

Box bounds(const std::set<Pixel>& pixels) {
  Box box;
  for (const auto& [x, y] : pixels) {
    box.x_min = std::min(box.x_min, x);
    box.y_min = std::min(box.y_min, y);
    box.x_max = std::max(box.x_max, x);
    box.y_max = std::max(box.y_max, y);
  }
  return box;
}

TEST(Canvas, StartsAsBackground) {
  Canvas canvas(7, 5, kWhite);
  EXPECT_EQ(canvas.width(), 7);
  EXPECT_EQ(canvas.height(), 5);
  EXPECT_EQ(inked(canvas, kWhite).size(), 35u);
}

TEST(Canvas, HorizontalLineCoversBothEndPixelsAndNothingElse) {
  Canvas canvas(12, 8, kWhite);
  canvas.line(2, 3, 7, 3, kInk);
  std::set<Pixel> expected;
  for (int x = 2; x <= 7; ++x) expected.insert({x, 3});
  EXPECT_EQ(inked(canvas), expected);
}

TEST(Canvas, DiagonalLineIsThePixelDiagonal) {
  Canvas canvas(8, 8, kWhite);
  canvas.line(5, 5, 1, 1, kInk);  // drawn backwards on purpose
  std::set<Pixel> expected;
  for (int i = 1; i <= 5; ++i) expected.insert({i, i});
  EXPECT_EQ(inked(canvas), expected);
}

TEST(Canvas, SteepLineHasOnePixelPerRowWithinHalfAPixelOfTheLine) {
  Canvas canvas(10, 20, kWhite);
  const double x0 = 1, y0 = 2, x1 = 4, y1 = 17;
  canvas.line(x0, y0, x1, y1, kInk);
  const std::set<Pixel> pixels = inked(canvas);
  EXPECT_EQ(pixels.size(), static_cast<std::size_t>(y1 - y0 + 1));
  for (const auto& [x, y] : pixels) {
    const double x_on_line = x0 + (x1 - x0) * (y - y0) / (y1 - y0);
    EXPECT_LE(std::abs(x - x_on_line), 0.5) << "pixel (" << x << ", " << y << ")";
  }
}

TEST(Canvas, ThickLineIsThatManyPixelsWide) {
  Canvas canvas(20, 20, kWhite);
  canvas.line(3, 10, 15, 10, kInk, 3);
  const Box box = bounds(inked(canvas));
  EXPECT_EQ(box.y_max - box.y_min + 1, 3);
  EXPECT_EQ(box.x_min, 2);
  EXPECT_EQ(box.x_max, 16);
  EXPECT_EQ(inked(canvas).size(), 3u * 15u);
}

TEST(Canvas, LinesAreClippedToTheCanvas) {
  Canvas canvas(10, 10, kWhite);
  canvas.line(-100, 5, 100, 5, kInk);
  std::set<Pixel> expected;
  for (int x = 0; x < 10; ++x) expected.insert({x, 5});
  EXPECT_EQ(inked(canvas), expected);

  // Entirely outside: nothing drawn. Huge or non-finite coordinates: no hang, nothing wrong.
  Canvas outside(10, 10, kWhite);
  outside.line(-5, -5, 20, -3, kInk);
  outside.line(1e12, 1e12, 2e12, -1e12, kInk);
  outside.line(std::nan(""), 0, 5, 5, kInk);
  outside.line(0, 0, std::numeric_limits<double>::infinity(), 5, kInk);
  EXPECT_TRUE(inked(outside).empty());

  // A line from far away that crosses the canvas keeps its in-canvas part.
  Canvas crossing(10, 10, kWhite);
  crossing.line(-1e9, -1e9, 1e9, 1e9, kInk);
  std::set<Pixel> diagonal;
  for (int i = 0; i < 10; ++i) diagonal.insert({i, i});
  EXPECT_EQ(inked(crossing), diagonal);
}

TEST(Canvas, FillRectIsHalfOpenAndClipped) {
  Canvas canvas(10, 10, kWhite);
  canvas.fill_rect(-5, -5, 3, 2, kInk);
  std::set<Pixel> expected;
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) expected.insert({x, y});
  }
  EXPECT_EQ(inked(canvas), expected);
  Canvas empty(10, 10, kWhite);
  empty.fill_rect(5, 5, 5, 9, kInk);  // zero width
  empty.fill_rect(20, 20, 30, 30, kInk);
  EXPECT_TRUE(inked(empty).empty());
}

TEST(Canvas, RectIsTheOutlineOfFillRect) {
  Canvas canvas(20, 20, kWhite);
  const int x0 = 2, y0 = 3, x1 = 12, y1 = 9;  // 10 × 6 pixels
  canvas.rect(x0, y0, x1, y1, kInk);
  const std::set<Pixel> pixels = inked(canvas);
  EXPECT_EQ(pixels.size(), static_cast<std::size_t>(2 * 10 + 2 * 6 - 4));
  for (const auto& [x, y] : pixels) {
    EXPECT_TRUE(x == x0 || x == x1 - 1 || y == y0 || y == y1 - 1) << x << ", " << y;
  }
  const Box box = bounds(pixels);
  EXPECT_EQ(box.x_min, x0);
  EXPECT_EQ(box.x_max, x1 - 1);
  EXPECT_EQ(box.y_min, y0);
  EXPECT_EQ(box.y_max, y1 - 1);
}

TEST(Canvas, FilledCircleHasTheDiscsAreaAndSymmetry) {
  Canvas canvas(41, 41, kWhite);
  const double r = 12.0;
  canvas.circle(20, 20, r, kInk, true);
  const std::set<Pixel> pixels = inked(canvas);
  const double area = base::kPi * r * r;  // pixel count of a disc ≈ its area, error O(r)
  EXPECT_NEAR(static_cast<double>(pixels.size()), area, 0.03 * area);
  for (const auto& [x, y] : pixels) {
    EXPECT_TRUE(pixels.count({40 - x, y}) && pixels.count({x, 40 - y}) && pixels.count({y, x}))
        << "asymmetric at " << x << ", " << y;
  }
  EXPECT_TRUE(pixels.count({20, 20}));
  EXPECT_TRUE(pixels.count({32, 20}));
  EXPECT_FALSE(pixels.count({33, 20}));
}

TEST(Canvas, CircleOutlineIsARingAroundTheRadius) {
  Canvas canvas(41, 41, kWhite);
  const double r = 10.0;
  canvas.circle(20, 20, r, kInk, false);
  const std::set<Pixel> pixels = inked(canvas);
  ASSERT_FALSE(pixels.empty());
  for (const auto& [x, y] : pixels) EXPECT_LE(std::abs(std::hypot(x - 20, y - 20) - r), 0.5);
  EXPECT_FALSE(pixels.count({20, 20}));
  // A ring one pixel wide: about its circumference in pixels (within 10 %).
  EXPECT_NEAR(static_cast<double>(pixels.size()), 2 * base::kPi * r, 0.3 * 2 * base::kPi * r);
}

// Text is anti-aliased DejaVu Sans (render/font.h): the pixels it touches, not one ink.
std::set<Pixel> touched(const Canvas& canvas, Rgb8 background = kWhite) {
  std::set<Pixel> pixels;
  for (int y = 0; y < canvas.height(); ++y)
    for (int x = 0; x < canvas.width(); ++x)
      if (!(canvas.image().at(x, y) == background)) pixels.insert({x, y});
  return pixels;
}

TEST(Canvas, TextMetricsGrowWithLengthAndSize) {
  EXPECT_EQ(Canvas::text_width(""), 0);
  EXPECT_GT(Canvas::text_width("A"), 4);
  EXPECT_GT(Canvas::text_width("abc"), Canvas::text_width("ab"));
  EXPECT_NEAR(Canvas::text_width("abcdef", 24.0), 2 * Canvas::text_width("abcdef", 12.0), 2);
  EXPECT_EQ(Canvas::text_height(), 12);
  EXPECT_EQ(Canvas::text_height(30.0), 30);
}

TEST(Canvas, TextStaysInsideItsMeasuredBox) {
  for (double size : {12.0, 24.0}) {
    Canvas canvas(420, 60, kWhite);
    const std::string s = "Wall time [s] 1e-3 |gjpqy_ µ² σ";
    canvas.text(4, 6, s, kInk, size);
    const Box box = bounds(touched(canvas));
    EXPECT_GE(box.x_min, 4);
    EXPECT_GE(box.y_min, 6);
    EXPECT_LE(box.x_max, 4 + Canvas::text_width(s, size));
    EXPECT_LE(box.y_max, 6 + Canvas::text_height(size));
    // The box is used: from near its top to near its bottom.
    EXPECT_LE(box.y_min, 6 + 0.25 * size);
    EXPECT_GE(box.y_max, 6 + 0.75 * size);
  }
}

// Capitals, digits and lower case without descenders stand on the baseline, above the box's
// bottom by the font's descent; a 'p' goes below it.
TEST(Canvas, OnlyDescendersGoBelowTheBaseline) {
  Canvas canvas(200, 20, kWhite);
  canvas.text(0, 0, "AZ09 ackx", kInk);
  Canvas descender(20, 20, kWhite);
  descender.text(0, 0, "p", kInk);
  EXPECT_GE(bounds(touched(descender)).y_max, bounds(touched(canvas)).y_max + 2);
}

// Every printable ASCII character and µ, ², σ, ω have a glyph, and no two look the same.
TEST(Canvas, EveryPrintableGlyphIsDistinctAndNonEmpty) {
  std::vector<std::string> characters;
  for (char c = '!'; c <= '~'; ++c) characters.push_back(std::string(1, c));
  for (const char* c : {"µ", "²", "σ", "ω", "×", "−"}) characters.push_back(c);
  std::set<std::vector<std::uint8_t>> seen;
  for (const std::string& c : characters) {
    Canvas canvas(16, 16, kWhite);
    canvas.text(1, 1, c, kInk);
    EXPECT_FALSE(touched(canvas).empty()) << "glyph '" << c << "' is blank";
    const std::vector<std::uint8_t> bytes(canvas.image().data(), canvas.image().data() + 16 * 16 * 3);
    EXPECT_TRUE(seen.insert(bytes).second) << "glyph '" << c << "' repeats an earlier one";
  }
  Canvas space(16, 16, kWhite);
  space.text(1, 1, " ", kInk);
  EXPECT_TRUE(touched(space).empty());
}

// Malformed UTF-8 draws as the replacement character, not as nothing.
TEST(Canvas, MalformedTextStillDrawsSomething) {
  Canvas high(16, 16, kWhite);
  high.text(1, 1, "\xC2", kInk);
  EXPECT_FALSE(touched(high).empty());
}

// Vertical text is horizontal text rotated 90° counter-clockwise: horizontal pixel (c, r)
// (column c of the string from its left, row r from its top) lands at (x + r, y − c).
TEST(Canvas, VerticalTextIsHorizontalTextRotatedCounterClockwise) {
  const std::string s = "Ab1% µ²";
  const int w = Canvas::text_width(s), h = Canvas::text_height();
  Canvas flat(w + 4, h + 4, kWhite), upright(h + 14, w + 14, kWhite);
  flat.text(0, 0, s, kInk);
  const int x = 3, y = w + 8;  // bottom-left corner of the text's box
  upright.text_vertical(x, y, s, kInk);
  std::set<Pixel> expected;
  for (const auto& [c, r] : touched(flat)) expected.insert({x + r, y - c});
  EXPECT_EQ(touched(upright), expected);
  for (const auto& [c, r] : touched(flat))
    ASSERT_EQ(flat.image().at(c, r), upright.image().at(x + r, y - c));
}

// A smooth line covers the pixels within half its width of the segment fully, and blends the
// ones at its edge.
TEST(Canvas, SmoothLineIsFullOnItsAxisAndBlendedAtItsEdge) {
  Canvas canvas(20, 10, kWhite);
  canvas.smooth_line(2, 4.5, 17, 4.5, kInk, 2.0);
  EXPECT_EQ(canvas.image().at(10, 4), kInk);
  EXPECT_EQ(canvas.image().at(10, 5), kInk);
  EXPECT_EQ(canvas.image().at(10, 1), kWhite);
  Canvas thin(20, 10, kWhite);
  thin.smooth_line(2, 4.25, 17, 4.25, kInk, 1.0);
  const Rgb8 edge = thin.image().at(10, 5);
  EXPECT_FALSE(edge == kInk);
  EXPECT_FALSE(edge == kWhite);
}

TEST(Canvas, SameCallsGiveTheSameBits) {
  auto draw = [] {
    Canvas canvas(64, 48, kWhite);
    canvas.line(0.3, 47.7, 63.2, 0.4, kInk, 2);
    canvas.circle(30.25, 20.75, 7.5, Rgb8{200, 0, 0}, false);
    canvas.text_vertical(2, 40, "error", kInk);
    canvas.text(10.3, 30, "1e-2 µm²", kInk);
    canvas.smooth_circle(40.2, 10.7, 5.0, kInk, false, 1.5);
    return canvas;
  };
  const Canvas a = draw(), b = draw();
  const std::size_t bytes = 64u * 48u * 3u;
  EXPECT_TRUE(std::equal(a.image().data(), a.image().data() + bytes, b.image().data()));
}

// A dashed horizontal line: dashes of 4 pixels every 7 (4 on, 3 off) from x = 0, and the
// pattern carried over to a second segment by the returned phase.
TEST(Canvas, DashedLineAlternatesDashesAndGaps) {
  Canvas canvas(40, 5, kWhite);
  const double phase = canvas.dashed_line(0, 2, 20, 2, kInk, 1, 4.0, 3.0);
  canvas.dashed_line(20, 2, 39, 2, kInk, 1, 4.0, 3.0, phase);
  for (int x = 0; x < 40; ++x)
    EXPECT_EQ(canvas.image().at(x, 2) == kInk, x % 7 < 4) << "x = " << x;
  EXPECT_EQ(bounds(inked(canvas)).y_min, 2);
  EXPECT_EQ(bounds(inked(canvas)).y_max, 2);
}

// Drawing over an existing image keeps its pixels where nothing is drawn.
TEST(Canvas, DrawsOverAnExistingImage) {
  Image photo(8, 8, Rgb8{50, 60, 70});
  Canvas canvas(photo);
  canvas.line(0, 0, 7, 0, kInk);
  EXPECT_EQ(canvas.image().at(3, 0), kInk);
  EXPECT_EQ(canvas.image().at(3, 5), (Rgb8{50, 60, 70}));
}

}  // namespace
}  // namespace weft::render
