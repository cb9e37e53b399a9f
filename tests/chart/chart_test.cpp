// chart/: axis ticks, the palette, the font's µ ² σ, and the PNG and SVG of one figure agreeing
// on where the ticks are.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "chart/chart.h"
#include "chart/draw_list.h"
#include "render/font.h"

namespace weft::chart {
namespace {

TEST(LinearTicks, StepsOfOneTwoOrFiveTimesAPowerOfTenInsideTheRange) {
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
           {0.0, 1.0}, {-3.2, 7.9}, {1e-6, 4.4e-5}, {100.0, 100.5}, {-2e4, -1e3}}) {
    const std::vector<double> t = linear_ticks(lo, hi);
    ASSERT_GE(t.size(), 2u) << lo << " " << hi;
    const double step = t[1] - t[0];
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 ||
                std::abs(mantissa - 5) < 1e-6) << step;
    EXPECT_GE(t.front(), lo - 1e-9 * step);
    EXPECT_LE(t.back(), hi + 1e-9 * step);
    EXPECT_LT(t.front() - lo, step);  // no tick missing at either end
    EXPECT_LT(hi - t.back(), step);
    EXPECT_LE(t.size(), 11u);
  }
}

TEST(LogTicks, LabelsAndDecades) {
  EXPECT_EQ(log_tick_label(1.0), "1");
  EXPECT_EQ(log_tick_label(0.01), "0.01");
  EXPECT_EQ(log_tick_label(200.0), "200");
  EXPECT_EQ(log_tick_label(1e-5), "1e-5");
  EXPECT_EQ(log_tick_label(2e-4), "2e-4");
  EXPECT_EQ(log_tick_label(5e4), "5e4");
  const Axis axis{"h", Scale::log, 2e-5, 3e-2};  // > 2.6 decades: decades labelled only
  int labelled = 0;
  for (const Tick& t : automatic_ticks(axis)) {
    EXPECT_GE(t.value, axis.lo * (1 - 1e-9));
    EXPECT_LE(t.value, axis.hi * (1 + 1e-9));
    if (!t.label.empty()) {
      ++labelled;
      EXPECT_TRUE(t.major) << t.label;
    }
  }
  EXPECT_EQ(labelled, 3);  // 1e-4, 0.001, 0.01
  EXPECT_DOUBLE_EQ(axis.fraction(axis.lo), 0.0);
  EXPECT_DOUBLE_EQ(axis.fraction(axis.hi), 1.0);
  EXPECT_DOUBLE_EQ(axis.fraction(0.0), 0.0);  // ≤ 0 on a log axis: its low end
}

// The documented colours (palette.h): Okabe & Ito's eight, viridis' stops.
TEST(Palette, EntriesAreTheDocumentedOnes) {
  const std::vector<std::string> okabe_ito{"#000000", "#e69f00", "#56b4e9", "#009e73",
                                           "#f0e442", "#0072b2", "#d55e00", "#cc79a7"};
  ASSERT_EQ(okabe_ito::all.size(), okabe_ito.size());
  for (std::size_t k = 0; k < okabe_ito.size(); ++k) EXPECT_EQ(hex(okabe_ito::all[k]), okabe_ito[k]);
  EXPECT_EQ(hex(viridis(0.0)), "#440154");
  EXPECT_EQ(hex(viridis(0.25)), "#3b528b");
  EXPECT_EQ(hex(viridis(0.5)), "#21918c");
  EXPECT_EQ(hex(viridis(0.75)), "#5ec962");
  EXPECT_EQ(hex(viridis(1.0)), "#fde725");
  EXPECT_EQ(hex(viridis(7.0)), "#fde725");  // clamped
  EXPECT_EQ(hex(series_colour(0)), "#d55e00");
  EXPECT_EQ(hex(series_colour(6)), hex(series_colour(0)));
  // Luminance rises along viridis: it reads in grey.
  double previous = -1.0;
  for (int k = 0; k <= 20; ++k) {
    const Rgb8 c = viridis(k / 20.0);
    const double y = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    EXPECT_GT(y, previous - 1.0) << k;
    previous = y;
  }
}

// µ, ², σ have their own glyphs in the chart font (not the missing-glyph box) and ink pixels.
TEST(Font, MicroSquaredSigmaRenderNonEmptyGlyphs) {
  const render::Font& font = render::Font::chart_font();
  const render::TextBitmap box = font.rasterize("\xEF\xBF\xBF", 14.0);  // U+FFFF: no glyph
  for (const char* s : {"µ", "²", "σ"}) {
    EXPECT_TRUE(font.has_glyph(render::decode_utf8(s).at(0))) << s;
    const render::TextBitmap b = font.rasterize(s, 14.0);
    int inked = 0;
    for (const std::uint8_t c : b.coverage) inked += c > 0;
    EXPECT_GT(inked, 3) << s;
    EXPECT_NE(b.coverage, box.coverage) << s;
    EXPECT_GT(font.width(s, 14.0), 2.0) << s;
  }
  EXPECT_EQ(render::decode_utf8("aµ²σ"), (std::u32string{U'a', 0xB5, 0xB2, 0x3C3}));
  EXPECT_EQ(render::decode_utf8("\xC2"), std::u32string{0xFFFD});
}

TEST(Font, AMissingFontFileSaysWhichPackageToInstall) {
  ::setenv("WEFT_FONT", "/nonexistent/font.ttf", 1);
  try {
    (void)render::chart_font_path();
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("fonts-dejavu-core"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/nonexistent/font.ttf"), std::string::npos) << e.what();
  }
  ::unsetenv("WEFT_FONT");
  EXPECT_NO_THROW((void)render::chart_font_path());
}

Figure two_axis_figure() {
  Plot plot;
  plot.x = Axis::linear_fit("time [s]", {0.0, 3.7});
  plot.y = Axis::log_fit("error [µm²]", {2e-3, 0.4});
  plot.series.push_back({"line", series_colour(0), {0.0, 1.0, 2.0, 3.0}, {0.01, 0.03, 0.1, 0.3}});
  Figure figure;
  figure.title = "σ against time";
  figure.plots = {plot};
  figure.legend = {{"line", Swatch::line, series_colour(0)}};
  return figure;
}

// The x1 attributes (x-tick) or y1 attributes (y-tick) of the SVG's tick lines.
std::vector<double> svg_ticks(const std::string& svg, const std::string& role) {
  const std::regex pattern("<polyline class=\"" + role + "\"[^>]*points=\"([-0-9.]+),([-0-9.]+) ");
  std::vector<double> out;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), pattern); it != std::sregex_iterator(); ++it)
    out.push_back(std::stod((*it)[role == "x-tick" ? 1 : 2].str()));
  return out;
}

bool dark(const render::Image& image, int x, int y) {
  const Rgb8 c = image.at(x, y);
  return c.r < 200 && c.g < 200 && c.b < 200;
}

TEST(Chart, SvgAndPngAgreeOnTickPositions) {
  const Figure figure = two_axis_figure();
  const std::string svg = draw_svg(figure);
  const render::Image png = draw_png(figure);
  const DrawList list = lay_out(figure);
  EXPECT_NE(svg.find("width=\"" + std::to_string(png.width()) + "\""), std::string::npos);
  EXPECT_NE(svg.find("height=\"" + std::to_string(png.height()) + "\""), std::string::npos);
  const RectItem* frame = nullptr;
  for (const Item& item : list.items)
    if (const auto* r = std::get_if<RectItem>(&item); r && r->role == "frame") frame = r;
  ASSERT_NE(frame, nullptr);
  const int below = static_cast<int>(frame->y1) + 1, left = static_cast<int>(frame->x0) - 2;

  const std::vector<double> xs = svg_ticks(svg, "x-tick"), ys = svg_ticks(svg, "y-tick");
  ASSERT_GE(xs.size(), 3u);
  ASSERT_GE(ys.size(), 3u);
  for (const double x : xs) {  // a tick at SVG x covers PNG column ⌊x⌋, and not its neighbours
    const int column = static_cast<int>(std::floor(x));
    EXPECT_TRUE(dark(png, column, below)) << x;
    EXPECT_FALSE(dark(png, column - 2, below)) << x;
    EXPECT_FALSE(dark(png, column + 2, below)) << x;
  }
  int major = 0;
  for (const double y : ys) {  // minor ticks are light grey: check the row is not white
    const int row = static_cast<int>(std::floor(y));
    EXPECT_FALSE(png.at(left, row) == kWhite) << y;
    EXPECT_TRUE(png.at(left, row + 3) == kWhite || png.at(left, row - 3) == kWhite) << y;
    major += dark(png, left, row);
  }
  EXPECT_GE(major, 2);
}

// The series' polyline has one point per value, straight data stay straight, and mismatched
// lengths are refused.
TEST(Chart, StraightDataGiveAStraightPolylineAndLengthsMustMatch) {
  Figure figure;
  Plot plot;
  plot.x = Axis::linear_fit("x", {0.0, 3.0});
  plot.y = Axis::linear_fit("y", {1.0, 7.0});
  plot.series.push_back({"line", okabe_ito::black, {0.0, 1.0, 2.0, 3.0}, {1.0, 3.0, 5.0, 7.0}});
  figure.plots = {plot};
  const std::string svg = draw_svg(figure);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, std::regex("<polyline data-series=\"line\"[^>]*points=\"([^\"]*)\"")));
  std::vector<double> xs, ys;
  std::stringstream s(m[1].str());
  for (std::string p; s >> p;) {
    xs.push_back(std::stod(p.substr(0, p.find(','))));
    ys.push_back(std::stod(p.substr(p.find(',') + 1)));
  }
  ASSERT_EQ(xs.size(), 4u);
  for (std::size_t k = 2; k < xs.size(); ++k) {
    EXPECT_NEAR(xs[k] - xs[k - 1], xs[1] - xs[0], 0.11);
    EXPECT_NEAR(ys[k] - ys[k - 1], ys[1] - ys[0], 0.11);
  }
  EXPECT_LT(ys[3], ys[0]);  // larger values higher up
  figure.plots[0].series[0].y.pop_back();
  EXPECT_THROW((void)draw_svg(figure), std::invalid_argument);
  EXPECT_THROW((void)draw_png(figure), std::invalid_argument);
}

TEST(Chart, SameFigureGivesTheSameBitsAndText) {
  const Figure figure = two_axis_figure();
  EXPECT_EQ(draw_svg(figure), draw_svg(figure));
  const render::Image a = draw_png(figure), b = draw_png(figure);
  ASSERT_EQ(a.width(), b.width());
  const std::size_t bytes = static_cast<std::size_t>(a.width()) * a.height() * 3;
  EXPECT_TRUE(std::equal(a.data(), a.data() + bytes, b.data()));
  // Text is escaped, and the font is named.
  Figure quoted = figure;
  quoted.title = "a < b & \"c\"";
  const std::string svg = draw_svg(quoted);
  EXPECT_NE(svg.find("a &lt; b &amp; &quot;c&quot;"), std::string::npos);
  EXPECT_NE(svg.find("DejaVu Sans"), std::string::npos);
}

}  // namespace
}  // namespace weft::chart
