// Drape from a top-view photo (app/run/drape_photo.h): silhouettes drawn from a
// known polar outline r(θ) = R + a cos(nθ + φ) (+ other terms), whose area ½∫r²dθ and hence DC
// are exact and whose node count is n, measured through the same ruler as a simulation. With
// ragged edges, speckle, a shifted disc, uneven nodes, and a noisy grey "photo" segmented by
// render/photo_compare; bad setups give errors naming the cause.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

#include "app/run/drape_photo.h"
#include "app/scene/scene.h"
#include "base/constants.h"
#include "render/photo_compare/photo_compare.h"

namespace {

using weft::app::DrapePhotoSetup;
using weft::app::measure_drape_silhouette;
using weft::base::kPi;
using weft::render::Mask;
using weft::sim::Vec2;

// Cusick: a Ø180 mm disc under a Ø300 mm specimen, photographed at 0.5 mm per pixel.
constexpr double kDiscMm = 180.0, kSpecimenMm = 300.0, kMmPerPx = 0.5;

DrapePhotoSetup cusick_setup() {
  DrapePhotoSetup s;
  s.mm_per_px = kMmPerPx;
  s.disc_mm = kDiscMm;
  s.specimen_mm = kSpecimenMm;
  return s;
}

// A width × height silhouette: pixel (x, y) is cloth when its distance from `centre` is below
// radius_px(θ) + jitter(x, y), θ counter-clockwise on the picture (y up) from +x.
Mask draw(int width, int height, const Vec2& centre, const std::function<double(double)>& radius_px,
          const std::function<double(int, int)>& jitter = {}) {
  Mask m(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double dx = x - centre.x(), dy = centre.y() - y;
      const double r = radius_px(std::atan2(dy, dx)) + (jitter ? jitter(x, y) : 0.0);
      m.set(x, y, std::hypot(dx, dy) < r);
    }
  return m;
}

// DC of r(θ) = R + a cos(nθ) (mm): area π(R² + a²/2).
double exact_dc(double r_mm, double a_mm) {
  const double area = kPi * (r_mm * r_mm + 0.5 * a_mm * a_mm);
  const double disc = kPi * 0.25 * kDiscMm * kDiscMm, specimen = kPi * 0.25 * kSpecimenMm * kSpecimenMm;
  return (area - disc) / (specimen - disc);
}

// The raster's bound on the DC error (drape_measure.h's shadow_area_error_bound_m2) for an
// outline of length about 2π(R + a)·√(1 + (na/R)²) ≥ the true length's mean-slope estimate.
double dc_tolerance(double r_mm, double a_mm, int n) {
  const double perimeter_m = 2e-3 * kPi * (r_mm + a_mm) * std::sqrt(1.0 + std::pow(n * a_mm / r_mm, 2));
  const double bound = weft::analysis::shadow_area_error_bound_m2(perimeter_m, 1e-3 * kMmPerPx);
  return bound / (kPi * 0.25e-6 * (kSpecimenMm * kSpecimenMm - kDiscMm * kDiscMm));
}

TEST(DrapePhoto, CleanOutlinesGiveTheirDcAndNodeCount) {
  for (int n : {4, 6, 8, 11}) {
    const double r_mm = 120.0, a_mm = 14.0;
    const Mask m = draw(600, 600, {300.0, 300.0}, [&](double t) {
      return (r_mm + a_mm * std::cos(n * t + 0.3)) / kMmPerPx;
    });
    const auto res = measure_drape_silhouette(m, cusick_setup(), "synthetic");
    EXPECT_EQ(res.shape.folds, n);
    EXPECT_NEAR(res.shape.drape_coefficient, exact_dc(r_mm, a_mm), dc_tolerance(r_mm, a_mm, n))
        << "n = " << n;
    // A centred drape without a cos θ term: the centroid is the centre.
    EXPECT_NEAR(res.center_px.x(), 300.0, 0.25);
    EXPECT_NEAR(res.center_px.y(), 300.0, 0.25);
  }
}

// The pixel raster is what limits DC: the measured error is far inside the stated worst-case
// bound (the in and out pixels along the outline largely cancel).
TEST(DrapePhoto, DcErrorIsInsideTheRasterBound) {
  const double r_mm = 110.0, a_mm = 10.0;
  const Mask m = draw(520, 520, {260.0, 260.0}, [&](double t) { return (r_mm + a_mm * std::cos(9 * t)) / kMmPerPx; });
  const auto res = measure_drape_silhouette(m, cusick_setup(), "synthetic");
  const double err = std::abs(res.shape.drape_coefficient - exact_dc(r_mm, a_mm));
  EXPECT_LT(err, 0.1 * dc_tolerance(r_mm, a_mm, 9))
      << "error " << err << ", bound " << dc_tolerance(r_mm, a_mm, 9);
  std::printf("DC %.5f, exact %.5f, error %.2g (bound %.2g)\n", res.shape.drape_coefficient,
              exact_dc(r_mm, a_mm), err, dc_tolerance(r_mm, a_mm, 9));
}

// Off the image centre by (37.3, −21.6) px, with a ragged ±3 px edge (uniform per pixel) and
// 1 % of the pixels flipped (specks outside, pinholes inside): same nodes, DC within 0.01.
TEST(DrapePhoto, NoiseAndAnOffCentreDiscKeepTheNodeCount) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> ragged(-3.0, 3.0), coin(0.0, 1.0);
  for (int n : {5, 7, 9}) {
    const double r_mm = 125.0, a_mm = 12.0;
    const Vec2 centre(337.3, 278.4);
    Mask m = draw(640, 600, centre, [&](double t) { return (r_mm + a_mm * std::cos(n * t + 1.0)) / kMmPerPx; },
                  [&](int, int) { return ragged(rng); });
    for (auto& v : m.in)
      if (coin(rng) < 0.01) v = !v;
    const auto res = measure_drape_silhouette(m, cusick_setup(), "synthetic");
    EXPECT_EQ(res.shape.folds, n);
    EXPECT_NEAR(res.shape.drape_coefficient, exact_dc(r_mm, a_mm), 0.01) << "n = " << n;
    std::printf("n = %d: DC %.4f (exact %.4f), centre (%.2f, %.2f) px\n", n,
                res.shape.drape_coefficient, exact_dc(r_mm, a_mm), res.center_px.x(), res.center_px.y());
    EXPECT_NEAR(res.center_px.x(), centre.x(), 1.0);
    EXPECT_NEAR(res.center_px.y(), centre.y(), 1.0);
  }
}

// A real drape's nodes differ in depth, and a specimen laid off-centre on the disc hangs
// lower on one side (a cos θ term), which moves the centroid off the disc's axis. Uneven nodes
// (depth ×0.5…×1.5), a cos θ and a cos 2θ term, measured about the centroid and about the
// given centre: the node count holds; with the disc's true centre given it is the one used.
TEST(DrapePhoto, UnevenNodesAndAnOffCentreSpecimen) {
  const int n = 7;
  const Vec2 disc(300.0, 300.0);
  const Mask m = draw(600, 600, disc, [&](double t) {
    const double depth = 1.0 + 0.5 * std::sin(3.0 * t);
    return (120.0 + 13.0 * depth * std::cos(n * t) + 6.0 * std::cos(t - 0.4) + 4.0 * std::cos(2.0 * t)) /
           kMmPerPx;
  });
  const auto by_centroid = measure_drape_silhouette(m, cusick_setup(), "synthetic");
  EXPECT_EQ(by_centroid.shape.folds, n);
  EXPECT_FALSE(by_centroid.center_given);
  DrapePhotoSetup given = cusick_setup();
  given.center_px = disc;
  const auto by_disc = measure_drape_silhouette(m, given, "synthetic");
  EXPECT_EQ(by_disc.shape.folds, n);
  EXPECT_TRUE(by_disc.center_given);
  EXPECT_DOUBLE_EQ(by_disc.center_px.x(), disc.x());
  // DC does not depend on the centre.
  EXPECT_DOUBLE_EQ(by_disc.shape.drape_coefficient, by_centroid.shape.drape_coefficient);
}

// A circle (no nodes) with a ragged edge has none; the smoothing and the prominence floor keep
// raster and edge noise from counting as folds.
TEST(DrapePhoto, ARaggedCircleHasNoNodes) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ragged(-2.0, 2.0);
  const Mask m = draw(600, 600, {300.0, 300.0}, [](double) { return 130.0 / kMmPerPx; },
                      [&](int, int) { return ragged(rng); });
  EXPECT_EQ(measure_drape_silhouette(m, cusick_setup(), "synthetic").shape.folds, 0);
}

// The scale from the disc's diameter in pixels gives the same DC as the same scale in mm/px.
TEST(DrapePhoto, ScaleFromTheDiscDiameterInPixels) {
  const Mask m = draw(600, 600, {300.0, 300.0}, [](double t) { return (120.0 + 12.0 * std::cos(6 * t)) / kMmPerPx; });
  DrapePhotoSetup by_disc = cusick_setup();
  by_disc.mm_per_px.reset();
  by_disc.disc_px = kDiscMm / kMmPerPx;
  EXPECT_DOUBLE_EQ(measure_drape_silhouette(m, by_disc, "synthetic").shape.drape_coefficient,
                   measure_drape_silhouette(m, cusick_setup(), "synthetic").shape.drape_coefficient);
}

// A grey photo of a dark drape on a light ground with ±40 grey levels of noise, segmented by
// render/photo_compare (weft measure --photo without a mask): the same nodes and DC as drawn.
TEST(DrapePhoto, SegmentedNoisyPhoto) {
  const double r_mm = 118.0, a_mm = 15.0;
  const int n = 8;
  const Mask drawn = draw(600, 560, {290.0, 270.0}, [&](double t) { return (r_mm + a_mm * std::cos(n * t)) / kMmPerPx; });
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> noise(-40, 40);
  weft::render::Image photo(drawn.width, drawn.height);
  for (int y = 0; y < drawn.height; ++y)
    for (int x = 0; x < drawn.width; ++x) {
      const int v = std::clamp((drawn.at(x, y) ? 70 : 200) + noise(rng), 0, 255);
      photo.set(x, y, {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v)});
    }
  const auto s = weft::render::silhouette_of(photo, std::nullopt);
  const auto res = measure_drape_silhouette(s.mask, cusick_setup(), "photo.png");
  EXPECT_EQ(res.shape.folds, n);
  EXPECT_NEAR(res.shape.drape_coefficient, exact_dc(r_mm, a_mm), 0.01);
  std::printf("segmented: DC %.4f (exact %.4f)\n", res.shape.drape_coefficient, exact_dc(r_mm, a_mm));
}

// Bad input: an error naming the cause.
void expect_error(const Mask& m, const DrapePhotoSetup& s, const std::string& words) {
  try {
    measure_drape_silhouette(m, s, "drape.png");
    ADD_FAILURE() << "no error; expected one mentioning '" << words << "'";
  } catch (const weft::app::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("drape.png"), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

TEST(DrapePhoto, BadInputIsAClearError) {
  const Mask drape = draw(600, 600, {300.0, 300.0}, [](double t) { return (120.0 + 12.0 * std::cos(6 * t)) / kMmPerPx; });
  DrapePhotoSetup s = cusick_setup();
  expect_error(Mask(600, 600), s, "empty");
  expect_error(draw(300, 300, {150.0, 150.0}, [](double) { return 200.0; }), s, "touches the image border");
  s.mm_per_px = 0.2;  // the silhouette then is 2.5× too small: smaller than the disc
  expect_error(drape, s, "smaller than the support disc");
  s.mm_per_px = 1.5;
  expect_error(drape, s, "larger than the flat specimen");
  s.disc_px = 360.0;
  expect_error(drape, s, "exactly one of --mm-per-px and --disc-px");
  s.mm_per_px.reset();
  s.disc_px = -1.0;
  expect_error(drape, s, "--disc-px");
  s = cusick_setup();
  s.specimen_mm = 150.0;
  expect_error(drape, s, "must be larger than --disc-mm");
  s = cusick_setup();
  s.center_px = Vec2(5.0, 5.0);
  expect_error(drape, s, "outside the silhouette");
}

}  // namespace
