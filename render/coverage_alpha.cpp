// Coverage alpha and background unblending (see coverage_alpha.h).

#include "render/coverage_alpha.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace weft::render {

int coverage_factor(int width, int height) {
  constexpr int max_side = 8192;
  const int side = std::max(width, height);
  for (int factor : {4, 2})
    if (side * factor <= max_side) return factor;
  return 1;
}

std::vector<std::uint8_t> surface_coverage(Renderer& renderer, const RenderMesh& cloth,
                                           const RenderSettings& settings,
                                           const std::vector<RenderObject>& objects) {
  const int k = coverage_factor(settings.width, settings.height);
  RenderSettings fine = settings;
  fine.width = k * settings.width;
  fine.height = k * settings.height;
  const Mask mask = renderer.render_mask(cloth, fine, objects, Renderer::MaskOf::surfaces);
  std::vector<std::uint8_t> alpha(static_cast<std::size_t>(settings.width) * settings.height);
  const int samples = k * k;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      int covered = 0;
      for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) covered += mask.at(k * x + i, k * y + j);
      alpha[static_cast<std::size_t>(y) * settings.width + x] =
          static_cast<std::uint8_t>((255 * covered + samples / 2) / samples);
    }
  return alpha;
}

void unblend_background(Image& image, const std::vector<std::uint8_t>& alpha,
                        const Eigen::Vector3f& background) {
  const std::size_t n = static_cast<std::size_t>(image.width()) * image.height();
  if (alpha.size() != n)
    throw std::invalid_argument("unblend_background: " + std::to_string(alpha.size()) +
                                " alpha values for " + std::to_string(n) + " pixels");
  std::uint8_t* rgb = image.data();
  for (std::size_t p = 0; p < n; ++p) {
    if (alpha[p] == 0 || alpha[p] == 255) continue;
    const float a = alpha[p] / 255.0f;
    for (int c = 0; c < 3; ++c) {
      const float b = 255.0f * std::clamp(background[c], 0.0f, 1.0f);
      const float value = (static_cast<float>(rgb[3 * p + c]) - (1.0f - a) * b) / a;
      rgb[3 * p + c] = static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0f, 255.0f)));
    }
  }
}

}  // namespace weft::render
