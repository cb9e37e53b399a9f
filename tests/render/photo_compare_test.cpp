// Photo comparison (render/photo_compare): segmentation, alignment and metrics on synthetic
// "photos" — a procedural curtain with known perturbations (shift, scale, blur, noise, colour
// cast, background change, a different number of folds) — and on discs with analytic answers.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "render/image_diff.h"
#include "render/photo_compare/photo_compare.h"
#include "tests/render/photo_compare_support.h"

namespace {

using namespace weft::render;
using weft::render::test::CurtainSpec;
using weft::render::test::draw_curtain;

PhotoComparison compare(const Image& photo, const Image& render,
                        const std::optional<Similarity>& t = std::nullopt) {
  return compare_with_photo(photo, silhouette_of(photo, std::nullopt), render,
                            silhouette_of(render, std::nullopt), t);
}

Image disc(int w, int h, double cx, double cy, double r) {
  Image img(w, h, {20, 30, 40});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (std::hypot(x - cx, y - cy) <= r) img.set(x, y, {230, 200, 40});
  return img;
}

TEST(PhotoCompare, SegmentationFindsTheDrawnCloth) {
  CurtainSpec spec;
  const Image photo = draw_curtain(spec);
  const Silhouette s = silhouette_of(photo, std::nullopt);
  EXPECT_EQ(s.background, spec.background) << "the border median is the background";
  Mask truth(spec.width, spec.height);
  for (int y = 0; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x) truth.set(x, y, test::curtain_inside(x - spec.cx, y - spec.cy));
  EXPECT_GT(silhouette_iou(s.mask, truth), 0.97);
}

TEST(PhotoCompare, IdenticalImagesAgreeExactly) {
  const Image render = draw_curtain({});
  const PhotoComparison c = compare(render, render);
  EXPECT_NEAR(c.transform.scale, 1.0, 1e-12);
  EXPECT_NEAR(c.transform.tx_px, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(c.iou, 1.0);
  EXPECT_DOUBLE_EQ(c.chamfer.symmetric_px, 0.0);
  EXPECT_DOUBLE_EQ(c.folds.f_score, 1.0);
  EXPECT_GT(c.folds.compared_px, 1000);
  EXPECT_DOUBLE_EQ(c.ssim, 1.0);
}

TEST(PhotoCompare, AlignmentRecoversShiftAndScale) {
  const CurtainSpec base;
  const Image render = draw_curtain(base);
  CurtainSpec shifted = base;
  shifted.cx += 13.5;
  shifted.cy -= 6.25;
  const PhotoComparison s = compare(draw_curtain(shifted), render);
  EXPECT_NEAR(s.transform.tx_px, 13.5, 1.0);
  EXPECT_NEAR(s.transform.ty_px, -6.25, 1.0);
  EXPECT_NEAR(s.transform.scale, 1.0, 0.02);
  EXPECT_GT(s.iou, 0.97);

  CurtainSpec larger = base;
  larger.scale = 1.3;  // about the centre (100, 75): t = c − 1.3 c
  const PhotoComparison l = compare(draw_curtain(larger), render);
  EXPECT_NEAR(l.transform.scale, 1.3, 0.02 * 1.3);
  EXPECT_NEAR(l.transform.tx_px, base.cx - 1.3 * base.cx, 1.0);
  EXPECT_NEAR(l.transform.ty_px, base.cy - 1.3 * base.cy, 1.0);
  EXPECT_GT(l.iou, 0.95);
  EXPECT_GT(l.folds.f_score, 0.7) << "the same folds, magnified";
}

TEST(PhotoCompare, RenderOfAnotherSizeIsResampledOntoThePhoto) {
  CurtainSpec big;
  big.width = 400;
  big.height = 300;
  big.cx = 180;
  big.cy = 160;
  big.scale = 2.0;
  const PhotoComparison c = compare(draw_curtain({}), draw_curtain(big));
  EXPECT_EQ(c.render_aligned.width(), 200);
  EXPECT_NEAR(c.transform.scale, 0.5, 0.01);
  EXPECT_NEAR(c.transform.tx_px, 100 - 0.5 * 180, 1.0);
  EXPECT_GT(c.iou, 0.96);
  EXPECT_GT(c.ssim, 0.8);
}

TEST(PhotoCompare, MetricsRankThePerturbations) {
  const CurtainSpec base;
  const Image render = draw_curtain(base);
  const PhotoComparison same = compare(render, render);
  const PhotoComparison blur = compare(test::blurred(render, 2), render);
  const PhotoComparison noise = compare(test::noisy(render, 12), render);
  const PhotoComparison cast = compare(test::colour_cast(render, 1.1, 1.0, 0.8), render);
  CurtainSpec other_bg = base;
  other_bg.background = {180, 185, 170};
  const PhotoComparison background = compare(draw_curtain(other_bg), render);
  CurtainSpec eight = base;
  eight.folds = 8;
  const PhotoComparison folds8 = compare(draw_curtain(eight), render);

  // The silhouette does not care about shading, colour or background: every photo aligns.
  for (const PhotoComparison* c : {&blur, &noise, &cast, &background, &folds8}) {
    EXPECT_GT(c->iou, 0.96);
    EXPECT_LT(c->chamfer.symmetric_px, 1.0);
  }
  // A different fold count is a different cloth: worse fold agreement and SSIM than any
  // imaging perturbation of the same cloth.
  for (const PhotoComparison* c : {&blur, &noise, &cast, &background}) {
    EXPECT_LT(folds8.folds.f_score, c->folds.f_score);
    EXPECT_LT(folds8.ssim, c->ssim);
    EXPECT_LE(c->ssim, same.ssim);
  }
  EXPECT_LT(folds8.folds.f_score, 0.6);
  // Fold labels depend on the sign and relative size of the curvature: a colour cast that scales
  // the cloth's luminance leaves them (nearly) unchanged, unlike its SSIM.
  EXPECT_GT(cast.folds.f_score, 0.95);
  EXPECT_GT(blur.folds.f_score, 0.9);
  EXPECT_LT(cast.ssim, 1.0);
}

TEST(PhotoCompare, MisalignmentWorsensMonotonically) {
  const Image render = draw_curtain({});
  const Similarity identity;
  double last_iou = 1.0 + 1e-12, last_chamfer = -1.0;
  for (double shift : {0.0, 2.0, 5.0, 10.0}) {
    CurtainSpec spec;
    spec.cx += shift;
    const PhotoComparison c = compare(draw_curtain(spec), render, identity);
    EXPECT_LT(c.iou, last_iou) << shift;
    EXPECT_GT(c.chamfer.symmetric_px, last_chamfer) << shift;
    last_iou = c.iou;
    last_chamfer = c.chamfer.symmetric_px;
  }
}

TEST(PhotoCompare, ConcentricDiscsHaveAnalyticIouAndChamfer) {
  const double r1 = 30, r2 = 40;
  const Image a = disc(160, 120, 80, 60, r1), b = disc(160, 120, 80, 60, r2);
  const PhotoComparison c = compare(a, b, Similarity{});
  EXPECT_NEAR(c.iou, (r1 * r1) / (r2 * r2), 0.02);
  // Every point of one circle is |r2 − r1| from the other; outline pixels sit inside the disc.
  EXPECT_NEAR(c.chamfer.symmetric_px, r2 - r1, 0.7);
  EXPECT_NEAR(c.chamfer.percent_of_diagonal, 100 * (r2 - r1) / 200.0, 0.4);
  // Aligned by area, the discs coincide.
  EXPECT_NEAR(compare(a, b).transform.scale, r1 / r2, 0.01);
}

TEST(PhotoCompare, DistanceTransformIsEuclidean) {
  Mask m(9, 7);
  m.set(2, 3, true);
  const std::vector<double> d = distance_transform(m);
  EXPECT_DOUBLE_EQ(d[3 * 9 + 2], 0.0);
  EXPECT_DOUBLE_EQ(d[6 * 9 + 6], 5.0);  // (4, 3)
  EXPECT_DOUBLE_EQ(d[0], std::hypot(2, 3));
}

TEST(PhotoCompare, MaskOverridesSegmentation) {
  CurtainSpec spec;
  spec.cx = 60;
  Image photo = draw_curtain(spec);
  // A bigger, brighter object beside the cloth: segmentation keeps it, not the cloth.
  for (int y = 20; y < 140; ++y)
    for (int x = 120; x < 195; ++x) photo.set(x, y, {250, 240, 30});
  const Silhouette found = silhouette_of(photo, std::nullopt);
  EXPECT_GT(moments(found.mask).cx, 120.0);
  Image mask_image(spec.width, spec.height);
  for (int y = 0; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x)
      if (test::curtain_inside(x - spec.cx, y - spec.cy)) mask_image.set(x, y, {255, 255, 255});
  const Silhouette given = silhouette_of(photo, mask_image);
  EXPECT_TRUE(given.from_mask_image);
  EXPECT_EQ(given.mask.in, mask_from_image(mask_image).in);
  const Image render = draw_curtain({});
  const PhotoComparison c =
      compare_with_photo(photo, given, render, silhouette_of(render, std::nullopt));
  EXPECT_NEAR(c.transform.tx_px, 60 - 100, 1.0);
  EXPECT_GT(c.iou, 0.96);
}

TEST(PhotoCompare, EmptySilhouetteIsAnError) {
  const Image flat(64, 48, {90, 90, 90});
  try {
    (void)silhouette_of(flat, std::nullopt);
    FAIL() << "a uniform image has no silhouette";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("empty silhouette"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)silhouette_of(draw_curtain({}), Image(200, 150)), std::invalid_argument);
  EXPECT_THROW((void)silhouette_of(draw_curtain({}), Image(20, 15, {255, 255, 255})),
               std::invalid_argument);
}

}  // namespace
