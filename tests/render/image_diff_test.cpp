// Image comparison (render/image_diff.h): identical images give PSNR = ∞ and SSIM = 1; a
// constant offset gives its analytic mean, RMS and PSNR; two constant images their analytic
// SSIM; and each perturbation — shift, blur, noise, brightness, a changed region — moves every
// metric the same way as it grows.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "render/image_diff.h"

namespace weft::render {
namespace {

std::uint8_t clamp8(double v) { return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L)); }

// A smooth test picture with structure at several scales (no flat regions).
Image picture(int w = 96, int h = 80) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double v = 128 + 60 * std::sin(0.21 * x) * std::cos(0.17 * y) + 30 * std::sin(0.05 * (x + 2 * y));
      img.set(x, y, {clamp8(v), clamp8(255 - v), clamp8(0.5 * v + 40)});
    }
  return img;
}

Image mapped(const Image& src, const std::function<Rgb8(int, int)>& f) {
  Image out(src.width(), src.height());
  for (int y = 0; y < src.height(); ++y)
    for (int x = 0; x < src.width(); ++x) out.set(x, y, f(x, y));
  return out;
}

Image shifted(const Image& a, int k) {
  return mapped(a, [&](int x, int y) { return a.at(std::min(a.width() - 1, x + k), y); });
}

Image blurred(const Image& a, int r) {  // box blur of radius r
  return mapped(a, [&](int x, int y) {
    double s[3] = {0, 0, 0};
    int n = 0;
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        const Rgb8 p = a.at(std::clamp(x + dx, 0, a.width() - 1), std::clamp(y + dy, 0, a.height() - 1));
        s[0] += p.r, s[1] += p.g, s[2] += p.b, ++n;
      }
    return Rgb8{clamp8(s[0] / n), clamp8(s[1] / n), clamp8(s[2] / n)};
  });
}

Image noisy(const Image& a, double amplitude) {  // the same noise field, scaled
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> field(3 * static_cast<std::size_t>(a.width() * a.height()));
  for (double& v : field) v = u(rng);
  return mapped(a, [&](int x, int y) {
    const std::size_t i = 3 * static_cast<std::size_t>(y * a.width() + x);
    const Rgb8 p = a.at(x, y);
    return Rgb8{clamp8(p.r + amplitude * field[i]), clamp8(p.g + amplitude * field[i + 1]),
                clamp8(p.b + amplitude * field[i + 2])};
  });
}

Image brighter(const Image& a, int by) {
  return mapped(a, [&](int x, int y) {
    const Rgb8 p = a.at(x, y);
    return Rgb8{clamp8(p.r + by), clamp8(p.g + by), clamp8(p.b + by)};
  });
}

Image with_square(const Image& a, int side) {
  return mapped(a, [&](int x, int y) {
    return x >= 20 && x < 20 + side && y >= 10 && y < 10 + side ? Rgb8{250, 250, 20} : a.at(x, y);
  });
}

TEST(ImageDiff, IdenticalImages) {
  const Image a = picture();
  const ImageDifference d = compare_images(a, a);
  EXPECT_EQ(d.max_abs, 0);
  EXPECT_EQ(d.mean_abs, 0.0);
  EXPECT_TRUE(std::isinf(d.psnr_db) && d.psnr_db > 0);
  EXPECT_DOUBLE_EQ(d.ssim, 1.0);
  EXPECT_EQ(d.fraction_over, 0.0);
}

TEST(ImageDiff, ConstantOffsetHasItsAnalyticErrors) {
  const Image a(40, 30, {100, 100, 100}), b(40, 30, {110, 110, 110});
  const ImageDifference d = compare_images(a, b, 9);
  EXPECT_DOUBLE_EQ(d.mean_abs, 10.0);
  EXPECT_DOUBLE_EQ(d.rms, 10.0);
  EXPECT_EQ(d.max_abs, 10);
  EXPECT_NEAR(d.psnr_db, 10.0 * std::log10(255.0 * 255.0 / 100.0), 1e-12);
  EXPECT_DOUBLE_EQ(d.fraction_over, 1.0);
  // Constant images: no variance, so SSIM is the luminance term (2 μa μb + C1)/(μa² + μb² + C1).
  const double c1 = std::pow(0.01 * 255, 2);
  EXPECT_NEAR(d.ssim, (2 * 100.0 * 110.0 + c1) / (100.0 * 100.0 + 110.0 * 110.0 + c1), 1e-12);
}

TEST(ImageDiff, SsimIsSymmetricAndBounded) {
  const Image a = picture(), b = noisy(picture(), 40);
  const double ab = compare_images(a, b).ssim, ba = compare_images(b, a).ssim;
  EXPECT_NEAR(ab, ba, 1e-12);
  EXPECT_LT(ab, 1.0);
  EXPECT_GT(ab, -1.0);
  // Smaller than the window: one window of equal weights, still 1 for identical images.
  const Image small = picture(8, 6);
  EXPECT_DOUBLE_EQ(compare_images(small, small).ssim, 1.0);
}

struct Perturbation {
  const char* name;
  std::function<Image(const Image&, int)> apply;  // strength k = 1, 2, 3, 4
};

TEST(ImageDiff, EveryMetricMovesMonotonicallyWithThePerturbation) {
  const Image a = picture();
  const std::vector<Perturbation> perturbations = {
      {"shift", [](const Image& i, int k) { return shifted(i, k); }},
      {"blur", [](const Image& i, int k) { return blurred(i, k); }},
      {"noise", [](const Image& i, int k) { return noisy(i, 6.0 * k); }},
      {"brightness", [](const Image& i, int k) { return brighter(i, 6 * k); }},
      {"region", [](const Image& i, int k) { return with_square(i, 8 * k); }},
  };
  for (const Perturbation& p : perturbations) {
    ImageDifference before = compare_images(a, a);
    for (int k = 1; k <= 4; ++k) {
      const ImageDifference d = compare_images(a, p.apply(a, k));
      SCOPED_TRACE(std::string(p.name) + " strength " + std::to_string(k));
      EXPECT_GT(d.mean_abs, before.mean_abs);
      EXPECT_GT(d.rms, before.rms);
      EXPECT_GE(d.max_abs, before.max_abs);
      EXPECT_LT(d.psnr_db, before.psnr_db);
      EXPECT_LT(d.ssim, before.ssim);
      EXPECT_GE(d.fraction_over, before.fraction_over);
      before = d;
    }
  }
}

TEST(ImageDiff, HeatmapMarksWhereTheyDiffer) {
  const Image a = picture(), b = with_square(a, 16);
  const Image h = difference_heatmap(a, b);
  const Rgb8 inside = h.at(25, 15), outside = h.at(70, 60);
  EXPECT_GT(inside.r + inside.g + inside.b, 255);  // a bright ramp colour
  EXPECT_EQ(outside.r, outside.g);                  // a dim grey
  EXPECT_LT(outside.r, 70);
}

TEST(ImageDiff, SizesMustMatch) {
  EXPECT_THROW(compare_images(Image(4, 4), Image(4, 5)), std::invalid_argument);
  EXPECT_THROW(difference_heatmap(Image(4, 4), Image(5, 4)), std::invalid_argument);
}

}  // namespace
}  // namespace weft::render
