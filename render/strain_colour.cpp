// Strain false colour and its legend (see strain_colour.h).

#include "render/strain_colour.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "render/canvas.h"

namespace weft::render {

namespace {

// Colours at −1, −0.5, 0, +0.5 and +1 full scale (display values, after Moreland 2009).
constexpr std::array<std::array<float, 3>, 5> ramp{{{0.230f, 0.299f, 0.754f},
                                                    {0.552f, 0.690f, 0.996f},
                                                    {0.865f, 0.865f, 0.865f},
                                                    {0.958f, 0.604f, 0.482f},
                                                    {0.706f, 0.016f, 0.150f}}};

Rgb8 to_rgb8(const Eigen::Vector3f& c) {
  const auto byte = [](float v) {
    return static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(v, 0.0f, 1.0f)));
  };
  return {byte(c.x()), byte(c.y()), byte(c.z())};
}

// "+5 %", "0", "−0.5 %": a percentage with up to two significant decimals.
std::string percent_label(double fraction) {
  if (fraction == 0.0) return "0";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g %%", 100.0 * std::abs(fraction));
  return (fraction > 0.0 ? "+" : "\u2212") + std::string(text);
}

}  // namespace

Eigen::Vector3f strain_colour(float strain, float full_scale) {
  if (!(strain == strain)) strain = 0.0f;  // NaN: the middle colour
  const float t = std::clamp(strain / full_scale, -1.0f, 1.0f);  // −1 .. 1
  const float position = 2.0f * (t + 1.0f);                      // 0 .. 4 along the ramp
  const int k = std::min(static_cast<int>(position), 3);
  const float f = position - static_cast<float>(k);
  const Eigen::Vector3f a(ramp[k][0], ramp[k][1], ramp[k][2]);
  const Eigen::Vector3f b(ramp[k + 1][0], ramp[k + 1][1], ramp[k + 1][2]);
  return (1.0f - f) * a + f * b;
}

std::vector<Eigen::Vector3f> strain_colours(const RenderMesh& mesh, float full_scale) {
  const bool has_strain = mesh.strain.size() == mesh.positions.size();
  std::vector<Eigen::Vector3f> colours(mesh.positions.size());
  for (std::size_t k = 0; k < colours.size(); ++k)
    colours[k] = strain_colour(has_strain ? mesh.strain[k] : 0.0f, full_scale);
  return colours;
}

void draw_strain_legend(Image& image, double full_scale) {
  const double size = Canvas::kTextPx;
  const int text_h = Canvas::text_height(size);
  const std::string top = percent_label(full_scale), bottom = percent_label(-full_scale);
  const int label_w = std::max({Canvas::text_width(top, size), Canvas::text_width(bottom, size),
                                Canvas::text_width("strain", size) - 18});
  const int bar_w = 14, bar_h = std::clamp(image.height() / 3, 3 * text_h, 160);
  const int pad = 6, panel_w = pad + bar_w + 4 + label_w + pad;
  const int panel_h = pad + text_h + 4 + bar_h + text_h / 2 + pad;
  if (image.width() < panel_w + 2 * pad || image.height() < panel_h + 2 * pad) return;
  Canvas canvas(std::move(image));
  const int x0 = canvas.width() - pad - panel_w, y0 = pad;
  const Rgb8 ink{30, 30, 30};
  canvas.fill_rect(x0, y0, x0 + panel_w, y0 + panel_h, Rgb8{255, 255, 255});
  canvas.rect(x0, y0, x0 + panel_w, y0 + panel_h, Rgb8{160, 160, 160});
  canvas.text(x0 + pad, y0 + pad, "strain", ink, size);
  const int bar_x = x0 + pad, bar_y = y0 + pad + text_h + 4 + text_h / 4;
  for (int row = 0; row < bar_h; ++row) {
    const float t = 1.0f - 2.0f * (static_cast<float>(row) + 0.5f) / static_cast<float>(bar_h);
    canvas.fill_rect(bar_x, bar_y + row, bar_x + bar_w, bar_y + row + 1,
                     to_rgb8(strain_colour(t, 1.0f)));
  }
  canvas.rect(bar_x, bar_y, bar_x + bar_w, bar_y + bar_h, ink);
  const int label_x = bar_x + bar_w + 4;
  canvas.text(label_x, bar_y - text_h / 2, top, ink, size);
  canvas.text(label_x, bar_y + bar_h / 2 - text_h / 2, "0", ink, size);
  canvas.text(label_x, bar_y + bar_h - text_h / 2, bottom, ink, size);
  image = canvas.image();
}

}  // namespace weft::render
