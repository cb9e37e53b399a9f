// TrueType text through stb_truetype (see font.h). stb's implementation is compiled into
// Debian's libstb; only its declarations are included here, as in image.cpp.

#include "render/font.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include <stb_truetype.h>

namespace weft::render {

namespace {

constexpr char32_t kReplacement = 0xFFFD;
const char* const kDebianFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// The length of the UTF-8 sequence a lead byte starts (0: not a lead byte) and its payload bits.
int sequence_length(unsigned char lead, char32_t& bits) {
  if (lead < 0x80) { bits = lead; return 1; }
  if ((lead & 0xE0) == 0xC0) { bits = lead & 0x1Fu; return 2; }
  if ((lead & 0xF0) == 0xE0) { bits = lead & 0x0Fu; return 3; }
  if ((lead & 0xF8) == 0xF0) { bits = lead & 0x07u; return 4; }
  return 0;
}

}  // namespace

std::u32string decode_utf8(const std::string& utf8) {
  std::u32string out;
  for (std::size_t i = 0; i < utf8.size();) {
    char32_t cp = 0;
    const int n = sequence_length(static_cast<unsigned char>(utf8[i]), cp);
    bool ok = n > 0 && i + n <= utf8.size();
    for (int k = 1; ok && k < n; ++k) {
      const auto c = static_cast<unsigned char>(utf8[i + k]);
      ok = (c & 0xC0) == 0x80;
      cp = (cp << 6) | (c & 0x3Fu);
    }
    out.push_back(ok ? cp : kReplacement);
    i += ok ? static_cast<std::size_t>(n) : 1;
  }
  return out;
}

std::filesystem::path chart_font_path() {
  const char* env = std::getenv("WEFT_FONT");
  const std::filesystem::path path = env && *env ? env : kDebianFont;
  if (!std::filesystem::is_regular_file(path)) {
    throw std::runtime_error(
        "the chart font " + path.string() + " does not exist: install Debian's fonts-dejavu-core "
        "(apt-get install fonts-dejavu-core, or scripts/setup), or set WEFT_FONT to a .ttf file");
  }
  return path;
}

struct Font::Impl {
  std::vector<unsigned char> data;
  stbtt_fontinfo info{};
  int ascent = 0, descent = 0, line_gap = 0;  // font units; descent < 0
  double scale(double size_px) const {
    return static_cast<double>(stbtt_ScaleForPixelHeight(&info, static_cast<float>(size_px)));
  }
};

Font::Font(const std::filesystem::path& ttf) : m_impl(std::make_unique<Impl>()) {
  std::ifstream in(ttf, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the font " + ttf.string());
  m_impl->data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  const int offset = stbtt_GetFontOffsetForIndex(m_impl->data.data(), 0);
  if (m_impl->data.size() < 12 || offset < 0 ||
      !stbtt_InitFont(&m_impl->info, m_impl->data.data(), offset)) {
    throw std::runtime_error("not a TrueType font: " + ttf.string());
  }
  stbtt_GetFontVMetrics(&m_impl->info, &m_impl->ascent, &m_impl->descent, &m_impl->line_gap);
}

Font::~Font() = default;

const Font& Font::chart_font() {
  static const Font font(chart_font_path());
  return font;
}

double Font::ascent(double size_px) const { return m_impl->ascent * m_impl->scale(size_px); }

double Font::descent(double size_px) const { return -m_impl->descent * m_impl->scale(size_px); }

bool Font::has_glyph(char32_t code_point) const {
  return stbtt_FindGlyphIndex(&m_impl->info, static_cast<int>(code_point)) != 0;
}

double Font::width(const std::string& utf8, double size_px) const {
  const std::u32string text = decode_utf8(utf8);
  const double scale = m_impl->scale(size_px);
  double pen = 0.0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    int advance = 0, bearing = 0;
    stbtt_GetCodepointHMetrics(&m_impl->info, static_cast<int>(text[i]), &advance, &bearing);
    pen += advance * scale;
    if (i + 1 < text.size())
      pen += scale * stbtt_GetCodepointKernAdvance(&m_impl->info, static_cast<int>(text[i]),
                                                   static_cast<int>(text[i + 1]));
  }
  return pen;
}

TextBitmap Font::rasterize(const std::string& utf8, double size_px, double x_offset) const {
  const std::u32string text = decode_utf8(utf8);
  const double scale = m_impl->scale(size_px);
  const auto fscale = static_cast<float>(scale);
  TextBitmap bitmap;
  bitmap.origin_x = 1;
  bitmap.baseline = static_cast<int>(std::ceil(ascent(size_px))) + 1;
  bitmap.width = static_cast<int>(std::ceil(width(utf8, size_px) + x_offset)) + 3;
  bitmap.height = bitmap.baseline + static_cast<int>(std::ceil(descent(size_px))) + 2;
  bitmap.coverage.assign(static_cast<std::size_t>(bitmap.width) * bitmap.height, 0);
  double pen = bitmap.origin_x + x_offset;
  std::vector<unsigned char> glyph;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const int cp = static_cast<int>(text[i]);
    const float shift = static_cast<float>(pen - std::floor(pen));
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    stbtt_GetCodepointBitmapBoxSubpixel(&m_impl->info, cp, fscale, fscale, shift, 0.0f, &x0, &y0,
                                        &x1, &y1);
    const int gw = x1 - x0, gh = y1 - y0;
    if (gw > 0 && gh > 0) {
      glyph.assign(static_cast<std::size_t>(gw) * gh, 0);
      stbtt_MakeCodepointBitmapSubpixel(&m_impl->info, glyph.data(), gw, gh, gw, fscale, fscale,
                                        shift, 0.0f, cp);
      const int left = static_cast<int>(std::floor(pen)) + x0, top = bitmap.baseline + y0;
      for (int y = 0; y < gh; ++y)
        for (int x = 0; x < gw; ++x) {
          const int bx = left + x, by = top + y;
          if (bx < 0 || by < 0 || bx >= bitmap.width || by >= bitmap.height) continue;
          std::uint8_t& c = bitmap.coverage[static_cast<std::size_t>(by) * bitmap.width + bx];
          c = static_cast<std::uint8_t>(std::min(255, c + glyph[static_cast<std::size_t>(y) * gw + x]));
        }
    }
    int advance = 0, bearing = 0;
    stbtt_GetCodepointHMetrics(&m_impl->info, cp, &advance, &bearing);
    pen += advance * scale;
    if (i + 1 < text.size())
      pen += scale * stbtt_GetCodepointKernAdvance(&m_impl->info, cp, static_cast<int>(text[i + 1]));
  }
  return bitmap;
}

}  // namespace weft::render
