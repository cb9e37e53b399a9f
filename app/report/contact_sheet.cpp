// Contact sheets (see contact_sheet.h).

#include "app/report/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/canvas.h"

namespace weft::app {

render::Image thumbnail(const render::Image& image, int width) {
  if (width < 1) throw std::invalid_argument("thumbnail: width must be >= 1");
  if (image.width() < 1 || image.height() < 1)
    throw std::invalid_argument("thumbnail: empty image");
  if (image.width() <= width) return image;
  const double scale = static_cast<double>(image.width()) / width;  // source pixels per pixel
  const int height = std::max(1, static_cast<int>(std::lround(image.height() / scale)));
  const double scale_y = static_cast<double>(image.height()) / height;
  render::Image out(width, height);
  // Each output pixel averages the source area [x0, x1) × [y0, y1), partial pixels weighted
  // by the fraction covered.
  for (int y = 0; y < height; ++y) {
    const double y0 = y * scale_y, y1 = (y + 1) * scale_y;
    for (int x = 0; x < width; ++x) {
      const double x0 = x * scale, x1 = (x + 1) * scale;
      double sum[3] = {0.0, 0.0, 0.0}, weight = 0.0;
      for (int sy = static_cast<int>(y0); sy < std::min(image.height(), static_cast<int>(std::ceil(y1))); ++sy) {
        const double wy = std::min<double>(sy + 1, y1) - std::max<double>(sy, y0);
        for (int sx = static_cast<int>(x0); sx < std::min(image.width(), static_cast<int>(std::ceil(x1))); ++sx) {
          const double w = wy * (std::min<double>(sx + 1, x1) - std::max<double>(sx, x0));
          const render::Rgb8 p = image.at(sx, sy);
          sum[0] += w * p.r;
          sum[1] += w * p.g;
          sum[2] += w * p.b;
          weight += w;
        }
      }
      const auto channel = [&](int c) {
        return static_cast<std::uint8_t>(std::clamp(std::lround(sum[c] / weight), 0L, 255L));
      };
      out.set(x, y, {channel(0), channel(1), channel(2)});
    }
  }
  return out;
}

int contact_sheet_columns(int n, int tile_width, int tile_height) {
  if (n < 1) return 1;
  const double aspect = static_cast<double>(tile_height) / std::max(tile_width, 1);
  const int columns = static_cast<int>(std::ceil(std::sqrt(n * aspect)));
  return std::clamp(columns, 1, n);
}

render::Image contact_sheet(const std::vector<render::Image>& thumbnails,
                            const std::vector<std::string>& labels, int columns, int gap) {
  if (thumbnails.empty()) throw std::invalid_argument("contact_sheet: no images");
  if (labels.size() != thumbnails.size())
    throw std::invalid_argument("contact_sheet: one label per image expected");
  if (columns < 1) throw std::invalid_argument("contact_sheet: columns must be >= 1");
  gap = std::max(gap, 0);
  int cell_w = 0, cell_h = 0;
  for (const render::Image& t : thumbnails) {
    cell_w = std::max(cell_w, t.width());
    cell_h = std::max(cell_h, t.height());
  }
  const int label_h = render::Canvas::text_height() + 4;
  const int n = static_cast<int>(thumbnails.size());
  columns = std::min(columns, n);
  const int rows = (n + columns - 1) / columns;
  const int width = gap + columns * (cell_w + gap);
  const int height = gap + rows * (cell_h + label_h + gap);
  const render::Rgb8 white{255, 255, 255}, ink{40, 40, 40}, frame{200, 200, 200};
  render::Image sheet(width, height, white);
  for (int k = 0; k < n; ++k) {
    const render::Image& t = thumbnails[static_cast<std::size_t>(k)];
    const int x0 = gap + (k % columns) * (cell_w + gap);
    const int y0 = gap + (k / columns) * (cell_h + label_h + gap);
    for (int y = 0; y < t.height(); ++y)
      for (int x = 0; x < t.width(); ++x) sheet.set(x0 + x, y0 + y, t.at(x, y));
  }
  render::Canvas labelled(std::move(sheet));
  for (int k = 0; k < n; ++k) {
    const render::Image& t = thumbnails[static_cast<std::size_t>(k)];
    const int x0 = gap + (k % columns) * (cell_w + gap);
    const int y0 = gap + (k / columns) * (cell_h + label_h + gap);
    labelled.rect(x0 - 1, y0 - 1, x0 + t.width() + 1, y0 + t.height() + 1, frame);
    const std::string& label = labels[static_cast<std::size_t>(k)];
    const int text_x = x0 + (t.width() - render::Canvas::text_width(label)) / 2;
    labelled.text(std::max(x0, text_x), y0 + cell_h + 3, label, ink);
  }
  return labelled.image();
}

}  // namespace weft::app
