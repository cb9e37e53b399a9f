// Appearance inside the cloth mask (render/photo_compare/appearance.h): masked SSIM against
// analytic values and the mask restriction; CIEDE2000 against the 34 pairs of Sharma, Wu &
// Dalal (2005), Table 1; sRGB → CIELAB at known colours; ΔE2000 mean and 95th percentile.
#include "render/photo_compare/appearance.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "render/image_diff.h"

namespace {

using namespace weft::render;

// {L1, a1, b1, L2, a2, b2, ΔE00}: Sharma, Wu & Dalal, Color Res. Appl. 30(1), 2005, Table 1.
constexpr std::array<std::array<double, 7>, 34> kSharmaPairs = {{
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
}};

Mask rectangle(int w, int h, int x0, int y0, int x1, int y1) {  // [x0, x1) × [y0, y1)
  Mask m(w, h);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) m.set(x, y, true);
  return m;
}

std::vector<double> constant_inside(const Mask& m, double inside, double outside_seed) {
  std::vector<double> v(m.in.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = m.in[i] ? inside : std::fmod(outside_seed * static_cast<double>(i * 7919 % 257), 255.0);
  return v;
}

TEST(Appearance, Ciede2000MatchesSharmasTable) {
  for (std::size_t k = 0; k < kSharmaPairs.size(); ++k) {
    const auto& r = kSharmaPairs[k];
    const Lab p{r[0], r[1], r[2]}, q{r[3], r[4], r[5]};
    EXPECT_NEAR(ciede2000(p, q), r[6], 1e-4) << "pair " << k + 1;
    EXPECT_NEAR(ciede2000(q, p), ciede2000(p, q), 1e-12) << "pair " << k + 1 << " is symmetric";
  }
  const Lab grey{50, 0, 0};
  EXPECT_EQ(ciede2000(grey, grey), 0.0);
}

TEST(Appearance, SrgbToLabAtKnownColours) {
  const Lab white = srgb_to_lab({255, 255, 255}), black = srgb_to_lab({0, 0, 0});
  EXPECT_NEAR(white[0], 100.0, 1e-9);
  EXPECT_NEAR(white[1], 0.0, 1e-9);
  EXPECT_NEAR(white[2], 0.0, 1e-9);
  EXPECT_NEAR(black[0], 0.0, 1e-12);
  // sRGB red is linear (1, 0, 0): XYZ the matrix's first column (0.4124, 0.2126, 0.0193), all
  // three above the Lab curve's knee, so L* = 116 ∛Y − 16, a* = 500 (∛(X/Xn) − ∛Y),
  // b* = 200 (∛Y − ∛(Z/Zn)) — about the published (53.24, 80.09, 67.20), which use another
  // rounding of the white point.
  const Lab red = srgb_to_lab({255, 0, 0});
  EXPECT_NEAR(red[0], 116.0 * std::cbrt(0.2126) - 16.0, 1e-9);
  EXPECT_NEAR(red[1], 500.0 * (std::cbrt(0.4124 / 0.9505) - std::cbrt(0.2126)), 1e-9);
  EXPECT_NEAR(red[2], 200.0 * (std::cbrt(0.2126) - std::cbrt(0.0193 / 1.0890)), 1e-9);
  EXPECT_NEAR(red[0], 53.24, 0.05);
  EXPECT_NEAR(red[1], 80.09, 0.05);
  EXPECT_NEAR(red[2], 67.20, 0.05);
  // Mid grey 128: Y = ((128/255 + 0.055)/1.055)^2.4 = 0.21586, L* = 116 Y^(1/3) − 16.
  const double y = std::pow((128.0 / 255.0 + 0.055) / 1.055, 2.4);
  EXPECT_NEAR(srgb_to_lab({128, 128, 128})[0], 116.0 * std::cbrt(y) - 16.0, 1e-9);
}

TEST(Appearance, ErodedMaskKeepsTheCentresOfWindowsInside) {
  const Mask m = rectangle(60, 40, 10, 5, 40, 30);  // 30 × 25
  const Mask e = eroded_mask(m, 5);
  EXPECT_EQ(moments(e).area_px, 20.0 * 15.0);
  EXPECT_TRUE(e.at(15, 10));
  EXPECT_FALSE(e.at(14, 10));
  EXPECT_TRUE(e.at(34, 24));
  EXPECT_FALSE(e.at(35, 24));
  // A rectangle touching the image edge: centres stay 5 px from the edge.
  EXPECT_EQ(moments(eroded_mask(rectangle(30, 30, 0, 0, 30, 30), 5)).area_px, 20.0 * 20.0);
}

TEST(Appearance, MaskedSsimOfIdenticalImagesIsOne) {
  const int w = 64, h = 48;
  const Mask m = rectangle(w, h, 8, 6, 50, 40);
  std::vector<double> a(static_cast<std::size_t>(w) * h);
  for (std::size_t i = 0; i < a.size(); ++i)
    a[i] = 128 + 100 * std::sin(0.37 * static_cast<double>(i));
  const auto s = masked_ssim(a, a, w, h, m);
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->mean, 1.0, 1e-12);
  EXPECT_EQ(s->windows, 32L * 24L);
}

TEST(Appearance, MaskedSsimOfConstantPatchesIsTheLuminanceTermAndIgnoresTheOutside) {
  // Both images constant inside the mask (variances 0): every window inside has
  // SSIM = (2 μa μb + C1) / (μa² + μb² + C1), whatever lies outside the mask.
  const int w = 50, h = 40;
  const Mask m = rectangle(w, h, 5, 5, 45, 35);
  const double ma = 90.0, mb = 160.0, c1 = (0.01 * 255) * (0.01 * 255);
  const double expected = (2 * ma * mb + c1) / (ma * ma + mb * mb + c1);
  const auto s1 = masked_ssim(constant_inside(m, ma, 1.0), constant_inside(m, mb, 3.0), w, h, m);
  const auto s2 = masked_ssim(constant_inside(m, ma, 5.0), constant_inside(m, mb, 0.5), w, h, m);
  ASSERT_TRUE(s1 && s2);
  EXPECT_NEAR(s1->mean, expected, 1e-9);
  EXPECT_EQ(s1->mean, s2->mean) << "pixels outside the mask never enter";
  // The plain SSIM over the whole image sees the outside and differs.
  EXPECT_GT(
      std::abs(ssim(constant_inside(m, ma, 1.0), constant_inside(m, mb, 3.0), w, h) - expected),
      0.01);
  // No window fits in a 10 px wide mask: no value.
  EXPECT_FALSE(masked_ssim(constant_inside(m, ma, 1.0), constant_inside(m, ma, 1.0), w, h,
                           rectangle(w, h, 5, 5, 15, 35)));
}

TEST(Appearance, ColourDifferenceMeanAndPercentileOverTheMask) {
  const int w = 40, h = 20;
  const Mask m = rectangle(w, h, 0, 0, 20, 20);  // left half: 400 px
  const Rgb8 a{200, 120, 40}, b{60, 140, 210};
  Image photo(w, h, a), render(w, h, a);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (x >= 20) photo.set(x, y, {0, 0, 0});    // outside the mask: ignored
      if (x >= 10 || y < 2) render.set(x, y, b);  // inside: 200 + 20 px differ
    }
  const double de = ciede2000(srgb_to_lab(a), srgb_to_lab(b));
  const ColourDifference d = mask_colour_difference(photo, render, m);
  EXPECT_EQ(d.pixels, 400);
  EXPECT_NEAR(d.mean, de * 220.0 / 400.0, 1e-9);
  EXPECT_NEAR(d.p95, de, 1e-12);
  EXPECT_THROW(mask_colour_difference(photo, render, Mask(w, h)), std::invalid_argument);
  EXPECT_THROW(mask_colour_difference(photo, Image(10, 10), m), std::invalid_argument);
}

}  // namespace
