// DrawList → SVG text. Numbers are printed with one decimal, so the same figure gives the same
// text; text names the chart font first, so a viewer with DejaVu Sans shows what the PNG shows.

#include <cstdio>
#include <sstream>

#include "base/html_escape.h"
#include "chart/draw_list.h"

namespace weft::chart {

namespace {

std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", v);
  return text;
}

std::string role(const std::string& r) { return r.empty() ? "" : " class=\"" + r + "\""; }

void write(std::ostream& svg, const LineItem& l) {
  if (!l.series.empty()) {
    svg << "<polyline data-series=\"" << base::html_escape(l.series) << "\"" << role(l.role);
  } else {
    svg << "<polyline" << role(l.role);
  }
  svg << " fill=\"none\" stroke=\"" << hex(l.colour) << "\" stroke-width=\"" << num(l.width) << "\"";
  if (l.dashed) svg << " stroke-dasharray=\"" << num(6 * l.width) << ' ' << num(4 * l.width) << "\"";
  if (!l.crisp) svg << " stroke-linecap=\"round\" stroke-linejoin=\"round\"";
  svg << " points=\"";
  for (std::size_t k = 0; k < l.points.size(); ++k)
    svg << (k ? " " : "") << num(l.points[k].x) << ',' << num(l.points[k].y);
  svg << "\"/>\n";
}

void write(std::ostream& svg, const RectItem& r) {
  if (r.filled) {
    svg << "<rect" << role(r.role) << " x=\"" << num(r.x0) << "\" y=\"" << num(r.y0) << "\" width=\""
        << num(r.x1 - r.x0) << "\" height=\"" << num(r.y1 - r.y0) << "\" fill=\"" << hex(r.colour)
        << "\"/>\n";
  } else {  // the 1-pixel outline inside the edges, as the PNG draws it
    svg << "<rect" << role(r.role) << " x=\"" << num(r.x0 + 0.5) << "\" y=\"" << num(r.y0 + 0.5)
        << "\" width=\"" << num(r.x1 - r.x0 - 1) << "\" height=\"" << num(r.y1 - r.y0 - 1)
        << "\" fill=\"none\" stroke=\"" << hex(r.colour) << "\"/>\n";
  }
}

void write(std::ostream& svg, const CircleItem& c) {
  svg << "<circle cx=\"" << num(c.cx) << "\" cy=\"" << num(c.cy) << "\" r=\"" << num(c.r) << "\"";
  if (c.filled) svg << " fill=\"" << hex(c.colour) << "\"/>\n";
  else svg << " fill=\"none\" stroke=\"" << hex(c.colour) << "\" stroke-width=\"1.5\"/>\n";
}

void write(std::ostream& svg, const TextItem& t) {
  if (t.text.empty()) return;
  const char* anchor = t.anchor == Anchor::start ? "start" : t.anchor == Anchor::middle ? "middle" : "end";
  svg << "<text" << role(t.role);
  if (t.vertical) {
    svg << " transform=\"translate(" << num(t.x) << ' ' << num(t.y) << ") rotate(-90)\"";
  } else {
    svg << " x=\"" << num(t.x) << "\" y=\"" << num(t.y) << "\"";
  }
  if (t.anchor != Anchor::start) svg << " text-anchor=\"" << anchor << "\"";
  if (t.size_px != kBodyPx) svg << " font-size=\"" << num(t.size_px) << "\"";
  if (!(t.colour == kInk)) svg << " fill=\"" << hex(t.colour) << "\"";
  svg << '>' << base::html_escape(t.text) << "</text>\n";
}

}  // namespace

std::string to_svg(const DrawList& list) {
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << list.width << "\" height=\""
      << list.height << "\" viewBox=\"0 0 " << list.width << ' ' << list.height
      << "\" font-family=\"DejaVu Sans, Verdana, sans-serif\" font-size=\"" << num(kBodyPx)
      << "px\" fill=\"" << hex(kInk) << "\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  for (const Item& item : list.items) std::visit([&](const auto& i) { write(svg, i); }, item);
  svg << "</svg>";
  return svg.str();
}

std::string draw_svg(const Figure& figure) { return to_svg(lay_out(figure)); }

}  // namespace weft::chart
