#pragma once
// Anti-aliased text from a TrueType font (stb_truetype, Debian's libstb-dev): the one font of
// weft's charts and image labels, DejaVu Sans from Debian's fonts-dejavu-core, which covers
// Latin, Greek (σ, ω) and the signs charts need (µ, ², ×, −, ≤).
//
// Sizes are pixel heights: a font of size s spans s pixels from its highest ascender to its
// lowest descender. Text is laid out on one line, advancing by the glyphs' widths with kerning;
// a character the font lacks draws as the font's missing-glyph box.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace weft::render {

// Coverage of a line of text, 0 (none) … 255 (full), `width` × `height` pixels, rows from the
// top. The pen starts at pixel column `origin_x` on row `baseline` (the baseline's row).
struct TextBitmap {
  int width = 0, height = 0;
  int origin_x = 0, baseline = 0;
  std::vector<std::uint8_t> coverage;
  std::uint8_t at(int x, int y) const { return coverage[static_cast<std::size_t>(y) * width + x]; }
};

class Font {
 public:
  // Reads a .ttf file; throws std::runtime_error naming the path when it cannot be read or is
  // not a TrueType font.
  explicit Font(const std::filesystem::path& ttf);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  // The font of weft's charts, read once: chart_font_path().
  static const Font& chart_font();

  // Advance width of the text, pixels, at `size_px`.
  double width(const std::string& utf8, double size_px) const;
  // Ascender height above the baseline and descender depth below it, pixels (both ≥ 0; their
  // sum is size_px).
  double ascent(double size_px) const;
  double descent(double size_px) const;
  // Whether the font has a glyph for the code point (U+FFFD and such fall back to the box).
  bool has_glyph(char32_t code_point) const;
  // The text's coverage, anti-aliased, with the pen starting at a sub-pixel offset `x_offset`
  // (0 ≤ x_offset < 1) from origin_x.
  TextBitmap rasterize(const std::string& utf8, double size_px, double x_offset = 0.0) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

// The chart font's file: $WEFT_FONT when set, else DejaVu Sans where fonts-dejavu-core puts it
// (/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf). Throws std::runtime_error, saying which
// package to install, when the file does not exist.
std::filesystem::path chart_font_path();

// UTF-8 to code points; a malformed sequence becomes U+FFFD.
std::u32string decode_utf8(const std::string& utf8);

}  // namespace weft::render
