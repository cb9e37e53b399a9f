// Figure → DrawList: where the title, the plots' frames, ticks, labels, cells, series and the
// legend go (see chart.h and draw_list.h).

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "chart/draw_list.h"
#include "render/font.h"

namespace weft::chart {

namespace {

constexpr double kMargin = 10.0;       // around the figure
constexpr double kTickMajor = 6.0, kTickMinor = 3.0;
constexpr double kGap = 4.0;           // between a tick and its label
constexpr double kLineStep = 17.0;     // one line of body text
constexpr double kSwatch = 16.0;       // a legend swatch's width

double ascent(double size_px) { return render::Font::chart_font().ascent(size_px); }

// The pixel centre nearest to v: where a crisp one-pixel line goes.
double centre(double v) { return std::floor(v) + 0.5; }

// Space around one plot's frame, pixels.
struct Margins {
  double left = 0, right = 14, top = 10, bottom = 0;
};

Margins margins_of(const Figure& figure) {
  Margins m;
  double widest = 0.0;
  bool titled = false;
  for (const Plot& plot : figure.plots) {
    for (const Tick& t : plot.y.drawn_ticks()) widest = std::max(widest, text_width(t.label));
    titled = titled || !plot.title.empty() || !plot.note.empty();
  }
  const double label_h = kBodyPx + 4.0;
  m.left = kMargin + label_h + 6.0 + widest + kGap + kTickMajor + 1.0;
  m.top = titled ? kPlotTitlePx + 14.0 : 10.0;
  m.bottom = 1.0 + kTickMajor + kGap + label_h + 4.0 + label_h + 4.0;
  return m;
}

struct Frame {  // a plot's data area, pixel edges
  double x0, y0, x1, y1;
};

struct Mapping {
  const Plot& plot;
  Frame f;
  double x(double v) const { return f.x0 + plot.x.fraction(v) * (f.x1 - f.x0); }
  double y(double v) const { return f.y1 - plot.y.fraction(v) * (f.y1 - f.y0); }
};

LineItem crisp(Point a, Point b, Rgb8 colour, std::string role) {
  LineItem line{{a, b}, colour, 1.0, false, true, "", std::move(role)};
  return line;
}

void add_cells(DrawList& out, const Mapping& m) {
  for (const Cell& c : m.plot.cells) {
    const double xa = std::round(m.x(c.x0)), xb = std::round(m.x(c.x1));
    const double ya = std::round(m.y(c.y1)), yb = std::round(m.y(c.y0));
    out.items.push_back(RectItem{std::min(xa, xb), std::min(ya, yb), std::max(xa, xb),
                                 std::max(ya, yb), true, c.fill, "cell"});
  }
}

void add_axes(DrawList& out, const Mapping& m) {
  const Frame& f = m.f;
  for (const Tick& t : m.plot.x.drawn_ticks()) {
    const double x = centre(m.x(t.value));
    if (m.plot.x.grid && t.major) out.items.push_back(crisp({x, f.y0}, {x, f.y1}, kGrid, "grid"));
    out.items.push_back(crisp({x, f.y1 + 1}, {x, f.y1 + 1 + (t.major ? kTickMajor : kTickMinor)},
                              t.major ? kInk : kLightGrey, "x-tick"));
    if (!t.label.empty())
      out.items.push_back(TextItem{x, f.y1 + 1 + kTickMajor + kGap + ascent(kBodyPx), t.label,
                                   kInk, kBodyPx, Anchor::middle, false, "x-tick-label"});
  }
  for (const Tick& t : m.plot.y.drawn_ticks()) {
    const double y = centre(m.y(t.value));
    if (m.plot.y.grid && t.major) out.items.push_back(crisp({f.x0, y}, {f.x1, y}, kGrid, "grid"));
    out.items.push_back(crisp({f.x0 - 1 - (t.major ? kTickMajor : kTickMinor), y}, {f.x0 - 1, y},
                              t.major ? kInk : kLightGrey, "y-tick"));
    if (!t.label.empty())
      out.items.push_back(TextItem{f.x0 - 1 - kTickMajor - kGap, y + 0.36 * kBodyPx, t.label, kInk,
                                   kBodyPx, Anchor::end, false, "y-tick-label"});
  }
  out.items.push_back(RectItem{f.x0 - 1, f.y0 - 1, f.x1 + 1, f.y1 + 1, false, kInk, "frame"});
  const double label_base = f.y1 + 1 + kTickMajor + kGap + 2 * (kBodyPx + 4.0) - 2.0;
  out.items.push_back(TextItem{0.5 * (f.x0 + f.x1), label_base, m.plot.x.label, kInk, kBodyPx,
                               Anchor::middle, false, "x-label"});
}

void add_series(DrawList& out, const Mapping& m, const Series& s) {
  std::vector<Point> points;
  std::vector<std::size_t> index;
  for (std::size_t k = 0; k < s.x.size(); ++k) {
    if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
    points.push_back({m.x(s.x[k]), m.y(s.y[k])});
    index.push_back(k);
  }
  if (s.line_width > 0.0 && !points.empty())
    out.items.push_back(LineItem{points, s.colour, s.line_width, s.dashed, false, s.name, "series"});
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Point q = points[p];
    const double r = s.marker_radius;
    if (s.marker == Marker::disc) out.items.push_back(CircleItem{q.x, q.y, r, true, s.colour});
    if (s.marker == Marker::ring) {
      out.items.push_back(CircleItem{q.x, q.y, r, true, s.marker_fill});
      out.items.push_back(CircleItem{q.x, q.y, r, false, s.colour});
    }
    if (s.marker == Marker::square)
      out.items.push_back(RectItem{std::round(q.x - r), std::round(q.y - r), std::round(q.x + r),
                                   std::round(q.y + r), true, s.colour, "marker"});
    if (!s.point_labels.empty())
      out.items.push_back(TextItem{q.x + r + 3, q.y - 4, s.point_labels[index[p]], s.label_colour,
                                   kBodyPx, Anchor::start, false, "point-label"});
  }
}

void add_plot(DrawList& out, const Plot& plot, double left, double top, const Figure& figure,
              const Margins& mg) {
  const Frame f{left + mg.left, top + mg.top, left + mg.left + figure.plot_width,
                top + mg.top + figure.plot_height};
  const Mapping m{plot, f};
  if (!plot.title.empty() || !plot.note.empty()) {
    const double base = f.y0 - 10.0;
    out.items.push_back(TextItem{f.x0 - 1, base, plot.title, kInk, kPlotTitlePx, Anchor::start,
                                 false, "plot-title"});
    const double after = plot.title.empty() ? 0.0 : text_width(plot.title, kPlotTitlePx) + 8.0;
    out.items.push_back(TextItem{f.x0 - 1 + after, base, plot.note, kInk, kBodyPx, Anchor::start,
                                 false, "plot-note"});
  }
  add_cells(out, m);
  add_axes(out, m);
  out.items.push_back(TextItem{left + kMargin + ascent(kBodyPx), 0.5 * (f.y0 + f.y1), plot.y.label,
                               kInk, kBodyPx, Anchor::middle, true, "y-label"});
  for (const Series& s : plot.series) add_series(out, m, s);
}

// The swatch of a legend entry with its left edge at x, centred on the text line at baseline y.
void add_swatch(DrawList& out, const LegendEntry& e, double x, double baseline) {
  const double yc = baseline - 0.36 * kBodyPx;
  switch (e.swatch) {
    case Swatch::none: return;
    case Swatch::line:
    case Swatch::dashed_line:
      out.items.push_back(LineItem{{{x, yc}, {x + kSwatch, yc}}, e.colour, 2.0,
                                   e.swatch == Swatch::dashed_line, false, "", "legend"});
      return;
    case Swatch::disc: out.items.push_back(CircleItem{x + 8, yc, 4.5, true, e.colour}); return;
    case Swatch::ring:
      out.items.push_back(CircleItem{x + 8, yc, 4.5, true, kWhite});
      out.items.push_back(CircleItem{x + 8, yc, 4.5, false, e.colour});
      return;
    case Swatch::square:
      out.items.push_back(RectItem{x + 4, std::round(yc - 4), x + 12, std::round(yc + 4), true,
                                   e.colour, "legend"});
      return;
    case Swatch::box:
      out.items.push_back(RectItem{x + 2, std::round(yc - 6), x + 14, std::round(yc + 6), true,
                                   e.colour, "legend"});
      return;
  }
}

double entry_width(const LegendEntry& e) {
  return (e.swatch == Swatch::none ? 0.0 : kSwatch + 5.0) + text_width(e.text);
}

// Entries side by side from x on baseline y; returns the x after the last.
double add_legend_row(DrawList& out, const std::vector<LegendEntry>& entries, double x, double y) {
  for (const LegendEntry& e : entries) {
    add_swatch(out, e, x, y);
    const double tx = x + (e.swatch == Swatch::none ? 0.0 : kSwatch + 5.0);
    out.items.push_back(TextItem{tx, y, e.text, e.text_colour, kBodyPx, Anchor::start, false, "legend"});
    x += entry_width(e) + 18.0;
  }
  return x;
}

void add_legend_column(DrawList& out, const Figure& figure, double x, double y) {
  for (const LegendEntry& e : figure.legend) {
    add_swatch(out, e, x, y);
    const double tx = x + (e.swatch == Swatch::none ? 0.0 : kSwatch + 5.0);
    out.items.push_back(TextItem{tx, y, fit_text(e.text, figure.legend_width - (tx - x)),
                                 e.text_colour, kBodyPx, Anchor::start, false, "legend"});
    y += kLineStep;
  }
}

double row_width(const std::vector<LegendEntry>& entries) {
  double w = 0.0;
  for (const LegendEntry& e : entries) w += entry_width(e) + 18.0;
  return entries.empty() ? 0.0 : w - 18.0;
}

}  // namespace

double text_width(const std::string& text, double size_px) {
  return render::Font::chart_font().width(text, size_px);
}

std::string fit_text(const std::string& text, double max_width, double size_px) {
  if (text_width(text, size_px) <= max_width) return text;
  // Cut whole UTF-8 sequences from the end until the rest and "…" fit.
  std::string cut = text;
  while (!cut.empty() && text_width(cut + "…", size_px) > max_width) {
    std::size_t n = cut.size() - 1;
    while (n > 0 && (static_cast<unsigned char>(cut[n]) & 0xC0) == 0x80) --n;
    cut.resize(n);
  }
  return cut + "…";
}

void check(const Figure& figure) {
  const auto check_axis = [](const Axis& a) {
    if (!(a.hi > a.lo)) throw std::invalid_argument("chart: axis '" + a.label + "' is empty");
    if (a.scale == Scale::log && !(a.lo > 0.0))
      throw std::invalid_argument("chart: log axis '" + a.label + "' starts at or below 0");
  };
  for (const Plot& plot : figure.plots) {
    check_axis(plot.x);
    check_axis(plot.y);
    for (const Series& s : plot.series) {
      if (s.y.size() != s.x.size() || (!s.point_labels.empty() && s.point_labels.size() != s.x.size()))
        throw std::invalid_argument("chart: series '" + s.name + "' has " +
                                    std::to_string(s.y.size()) + " values for " +
                                    std::to_string(s.x.size()) + " x values");
    }
  }
}

DrawList lay_out(const Figure& figure) {
  check(figure);
  DrawList out;
  const Margins mg = margins_of(figure);
  const int columns = std::max(1, std::min<int>(figure.columns, static_cast<int>(figure.plots.size())));
  const int rows = (static_cast<int>(figure.plots.size()) + columns - 1) / columns;
  const double panel_w = mg.left + figure.plot_width + mg.right;
  const double panel_h = mg.top + figure.plot_height + mg.bottom;
  double header = kMargin;
  if (!figure.title.empty() || figure.legend_place == LegendPlace::top_right) header += kTitlePx + 4;
  if (!figure.subtitle.empty()) header += kLineStep;
  const double grid_w = columns * panel_w, grid_h = rows * panel_h;
  double width = grid_w + kMargin, height = header + grid_h;
  if (figure.legend_place == LegendPlace::right) width += figure.legend_width + kMargin;
  if (figure.legend_place == LegendPlace::below && !figure.legend.empty()) height += kLineStep + 8;
  if (figure.legend_place == LegendPlace::right)
    height = std::max(height, header + mg.top + kLineStep * static_cast<double>(figure.legend.size()) + kMargin);
  width = std::max({width, text_width(figure.title, kTitlePx) + 2 * kMargin,
                    text_width(figure.subtitle) + 2 * kMargin});
  out.width = static_cast<int>(std::ceil(width));
  out.height = static_cast<int>(std::ceil(height));

  const double title_base = kMargin + ascent(kTitlePx);
  out.items.push_back(TextItem{kMargin, title_base, figure.title, kInk, kTitlePx, Anchor::start, false, "title"});
  if (!figure.subtitle.empty())
    out.items.push_back(TextItem{kMargin, title_base + kLineStep, figure.subtitle, kGrey, kBodyPx,
                                 Anchor::start, false, "subtitle"});
  for (std::size_t p = 0; p < figure.plots.size(); ++p) {
    const int col = static_cast<int>(p) % columns, row = static_cast<int>(p) / columns;
    add_plot(out, figure.plots[p], col * panel_w, header + row * panel_h, figure, mg);
  }
  if (figure.legend_place == LegendPlace::top_right)
    add_legend_row(out, figure.legend, width - kMargin - row_width(figure.legend), title_base);
  if (figure.legend_place == LegendPlace::below)
    add_legend_row(out, figure.legend, mg.left, header + grid_h + ascent(kBodyPx));
  if (figure.legend_place == LegendPlace::right)
    add_legend_column(out, figure, grid_w + kMargin, header + mg.top + ascent(kBodyPx));
  return out;
}

}  // namespace weft::chart
