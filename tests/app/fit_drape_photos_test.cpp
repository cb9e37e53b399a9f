// weft fit's drape_photos target, quick and in process: the outline distance of
// app/fit/outline_spectrum.h is 0 for a turned or mirrored outline and grows as the analytic
// formula says with a real difference; fit files with drape photos read their images as
// `weft measure --photo` does, average DC and nodes (a real number), and name the key of every
// mistake; the objective's parts follow the documented formula; a measured "folds" target may
// be a mean such as 7.5. The fit itself, on simulated silhouettes: fit_cusick_photos_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "app/fit/fit_spec.h"
#include "app/fit/outline_spectrum.h"
#include "base/constants.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;
using base::kPi;

const std::string kCusick = std::string(WEFT_SOURCE_DIR) + "/assets/scenes/cusick_drape.json";
constexpr double kMmPerPx = 0.5;
constexpr int kBins = 360;

// r(θ) in drape_measure's bins: bin j at θ = 2π(j + ½)/N.
std::vector<double> sampled(const std::function<double(double)>& r) {
  std::vector<double> v;
  for (int j = 0; j < kBins; ++j) v.push_back(r(2.0 * kPi * (j + 0.5) / kBins));
  return v;
}

// A 600 × 600 px silhouette at 0.5 mm per pixel, centred, of outline r_mm(θ) (θ counter-clockwise
// on the picture from +x).
render::Mask silhouette_of_outline(const std::function<double(double)>& r_mm) {
  render::Mask m(600, 600);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x)
      m.set(x, y, kMmPerPx * std::hypot(x - 299.5, 299.5 - y) < r_mm(std::atan2(299.5 - y, x - 299.5)));
  return m;
}

// The amplitudes of a silhouette as the drape_photos target measures an image.
std::vector<double> measured_amplitudes(const std::function<double(double)>& r_mm) {
  DrapePhotoSetup setup;
  setup.mm_per_px = kMmPerPx;
  setup.disc_mm = 180.0;
  setup.specimen_mm = 300.0;
  const DrapePhotoMeasurement m = measure_drape_silhouette(silhouette_of_outline(r_mm), setup, "drawn");
  return outline_amplitudes(m.shape.radii_m, default_outline_harmonics);
}

// A chiral outline: 8 nodes, a 3-lobed and a 14-lobed term with their own phases, and a cos θ
// term (an off-centre specimen) that the distance leaves out.
double chiral(double t) {
  return 125.0 + 12.0 * std::cos(8.0 * t + 0.3) + 4.0 * std::cos(3.0 * t + 1.0) +
         3.0 * std::cos(14.0 * t + 2.0) + 5.0 * std::cos(t);
}

TEST(OutlineSpectrum, ZeroForATurnedOrMirroredCopy) {
  const std::vector<double> r = sampled(chiral);
  std::vector<double> turned(kBins), mirrored(kBins);
  for (int j = 0; j < kBins; ++j) {
    turned[j] = r[(j + 37) % kBins];
    mirrored[j] = r[kBins - 1 - j];  // θ → −θ
  }
  const std::vector<double> a = outline_amplitudes(r, 30);
  EXPECT_NEAR(outline_spectrum_distance(a, outline_amplitudes(turned, 30)), 0.0, 1e-9);
  EXPECT_NEAR(outline_spectrum_distance(a, outline_amplitudes(mirrored, 30)), 0.0, 1e-9);
  // Only the cos θ term differs: no distance.
  const std::vector<double> shifted = sampled([](double t) { return chiral(t) + 3.0 * std::cos(t + 1.0); });
  EXPECT_NEAR(outline_spectrum_distance(a, outline_amplitudes(shifted, 30)), 0.0, 1e-9);
  EXPECT_NEAR(a[0], 125.0, 1e-9);
  EXPECT_NEAR(a[8], 12.0, 1e-9);
  EXPECT_NEAR(a[14], 3.0, 1e-9);
}

// D² = (Δa₀)² + ½ Σ (Δaₖ)²: deeper nodes by δ give δ/√2, a larger mean radius by δ gives δ, and
// a node more (8 → 9 of the same depth) gives the rms of both waves, a/√2·√2 = a.
TEST(OutlineSpectrum, GrowsWithARealDifferenceAsTheFormulaSays) {
  const auto wave = [](double mean, double depth, int nodes) {
    return outline_amplitudes(sampled([=](double t) { return mean + depth * std::cos(nodes * t); }), 30);
  };
  const std::vector<double> a = wave(125.0, 12.0, 8);
  for (double delta : {0.5, 1.0, 2.0, 4.0}) {
    EXPECT_NEAR(outline_spectrum_distance(a, wave(125.0, 12.0 + delta, 8)), delta / std::sqrt(2.0), 1e-9);
    EXPECT_NEAR(outline_spectrum_distance(a, wave(125.0 + delta, 12.0, 8)), delta, 1e-9);
  }
  EXPECT_NEAR(outline_spectrum_distance(a, wave(125.0, 12.0, 9)), 12.0, 1e-9);
  EXPECT_THROW(outline_amplitudes(std::vector<double>(40, 1.0), 30), std::invalid_argument);
}

// Drawn as silhouettes and measured as photos, turned by an angle that is no whole number of
// bins and mirrored: within the raster's noise of each other (0.1 mm here), while nodes 1 mm
// deeper are 0.71 mm away.
TEST(OutlineSpectrum, MeasuredSilhouettesTurnedByAnyAngleAndMirroredStayClose) {
  const std::vector<double> a = measured_amplitudes(chiral);
  const double turned = 1e3 * outline_spectrum_distance(a, measured_amplitudes([](double t) { return chiral(t + 0.2345); }));
  const double mirrored = 1e3 * outline_spectrum_distance(a, measured_amplitudes([](double t) { return chiral(-t); }));
  const double deeper = 1e3 * outline_spectrum_distance(
                                  a, measured_amplitudes([](double t) { return chiral(t) + std::cos(8.0 * t + 0.3); }));
  std::printf("D: turned 0.2345 rad %.3f mm, mirrored %.3f mm, nodes 1 mm deeper %.3f mm\n", turned,
              mirrored, deeper);
  EXPECT_LT(turned, 0.1);
  EXPECT_LT(mirrored, 0.1);
  EXPECT_NEAR(deeper, 1.0 / std::sqrt(2.0), 0.1);
}

class FitDrapePhotos : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test: ctest runs this fixture's tests in parallel, and each writes its images.
    m_dir = fs::path(WEFT_BINARY_DIR) / "test_output" / "fit_drape_photos" /
            ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(m_dir);
    // 8 and 7 nodes: a mean of 7.5.
    render::write_png(silhouette_of_outline([](double t) { return 125.0 + 12.0 * std::cos(8.0 * t); }),
                      m_dir / "eight.png");
    render::write_png(silhouette_of_outline([](double t) { return 122.0 + 14.0 * std::cos(7.0 * t + 1.0); }),
                      m_dir / "seven.png");
  }
  FitSpec parse(const std::string& target) const {
    return parse_fit_spec(R"({"scene": ")" + kCusick +
                              R"(", "parameters": [{"name": "bend", "start": "1e-5 N*m"}], "target": )" +
                              target + "}",
                          (m_dir / "fit.json").string());
  }
  std::string error_of(const std::string& target) const {
    try {
      parse(target);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
  fs::path m_dir;
};

const std::string kGood =
    R"("images": ["eight.png", "seven.png"], "mm_per_px": 0.5, "specimen": "30 cm", "support": "18 cm")";

TEST_F(FitDrapePhotos, ReadsTheImagesAsMeasurePhotoDoesAndAveragesThem) {
  const FitSpec spec = parse(R"({"drape_photos": {)" + kGood +
                             R"(, "check_images": [{"image": "eight.png", "disc_px": 360, "center_px": [299.5, 299.5]}]}})");
  const auto& t = std::get<DrapePhotosTarget>(spec.target);
  ASSERT_EQ(t.images.size(), 2u);
  ASSERT_EQ(t.check_images.size(), 1u);
  EXPECT_EQ(t.images[0].measurement.shape.folds, 8);
  EXPECT_EQ(t.images[1].measurement.shape.folds, 7);
  EXPECT_DOUBLE_EQ(t.mean_nodes, 7.5);
  EXPECT_DOUBLE_EQ(t.mean_drape_coefficient, 0.5 * (t.images[0].measurement.shape.drape_coefficient +
                                                    t.images[1].measurement.shape.drape_coefficient));
  EXPECT_EQ(t.images[1].key, "target.drape_photos.images[1]");
  // disc_px 360 for a Ø180 mm disc: 0.5 mm per pixel, the same image measured the same.
  EXPECT_DOUBLE_EQ(t.check_images[0].measurement.mm_per_px, 0.5);
  EXPECT_TRUE(t.check_images[0].measurement.center_given);
  EXPECT_NEAR(t.check_images[0].measurement.shape.drape_coefficient,
              t.images[0].measurement.shape.drape_coefficient, 1e-3);
  EXPECT_EQ(t.harmonics, default_outline_harmonics);
  EXPECT_DOUBLE_EQ(default_band(spec.target), 1.0);
}

TEST_F(FitDrapePhotos, ParseErrorsNameTheKey) {
  const auto with = [](const std::string& fields) { return R"({"drape_photos": {)" + fields + "}}"; };
  const std::string sizes = R"("specimen": "30 cm", "support": "18 cm")";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {with(R"("images": ["eight.png"], "mm_per_px": 0.5, "support": "18 cm")"),
       "fit.json: target.drape_photos.specimen: required key is missing"},
      {with(R"("mm_per_px": 0.5, )" + sizes), "target.drape_photos.images: required key is missing"},
      {with(R"("images": "eight.png", "mm_per_px": 0.5, )" + sizes), "target.drape_photos.images: expected an array"},
      {with(R"("images": [], "mm_per_px": 0.5, )" + sizes), "target.drape_photos.images: expected at least one image"},
      {with(R"("images": [3], "mm_per_px": 0.5, )" + sizes), "target.drape_photos.images[0]: expected an image file name"},
      {with(R"("images": ["eight.png", "missing.png"], "mm_per_px": 0.5, )" + sizes),
       "target.drape_photos.images[1]: image " + (m_dir / "missing.png").string() + ": no such file"},
      {with(R"("images": ["eight.png"], )" + sizes), "target.drape_photos.images[0]: no scale"},
      {with(R"("images": ["eight.png"], "mm_per_px": 0.5, "disc_px": 360, )" + sizes),
       "target.drape_photos.disc_px: give the scale by one of"},
      {with(R"("images": [{"image": "eight.png", "mm_per_px": -1}], )" + sizes),
       "target.drape_photos.images[0].mm_per_px: expected a number > 0"},
      {with(R"("images": [{"image": "eight.png", "scale": 1}], "mm_per_px": 0.5, )" + sizes),
       "target.drape_photos.images[0].scale: unknown key"},
      {with(R"("imagse": ["eight.png"], "mm_per_px": 0.5, )" + sizes), "did you mean 'images'?"},
      {with(kGood + R"(, "weights": {"node": 1})"), "target.drape_photos.weights.node: unknown key; did you mean 'nodes'?"},
      {with(kGood + R"(, "weights": {"outline": 0, "drape_coefficient": 0, "nodes": 0})"),
       "target.drape_photos.weights: expected at least one weight > 0"},
      {with(kGood + R"(, "harmonics": 1)"), "target.drape_photos.harmonics"},
      {with(R"("images": ["eight.png"], "mm_per_px": 0.5, "specimen": "18 cm", "support": "18 cm")"),
       "target.drape_photos.specimen: 180 mm must be larger than the support's 180 mm"},
      // At 0.7 mm per pixel the silhouette is larger than the flat specimen: a wrong scale.
      {with(R"("images": ["eight.png"], "mm_per_px": 0.7, )" + sizes),
       "target.drape_photos.images[0]: " + (m_dir / "eight.png").string() + ": the silhouette is larger than the flat specimen"},
      // The scene's Ø18 cm disc is not the images' Ø20 cm one.
      {with(R"("images": ["eight.png"], "mm_per_px": 0.5, "specimen": "30 cm", "support": "20 cm")"),
       "target.drape_photos.support: 200 mm (314.2 cm^2) but the scene's the cylinder obstacles[0] has 254.5 cm^2"},
      {with(kGood + R"(, "check_images": ["missing.png"])"), "target.drape_photos.check_images[0]: image"},
      {R"({"drape_photos": {)" + kGood + R"(}, "measured": {"folds": 8}})", "target: expected exactly one of"},
  };
  for (const auto& [target, message] : cases) {
    const std::string error = error_of(target);
    EXPECT_NE(error.find(message), std::string::npos) << "target " << target << "\nerror: " << error;
  }
}

// The objective of the simulated drape equal to the "eight" image: its own outline distance 0,
// the other's D; nodes 8 against the mean 7.5; DC against the mean; each part weighted.
TEST_F(FitDrapePhotos, MisfitPartsFollowTheFormula) {
  const FitSpec spec = parse(R"({"drape_photos": {)" + kGood +
                             R"(, "weights": {"outline": 2, "drape_coefficient": 0.5, "nodes": 4}}})");
  const auto& t = std::get<DrapePhotosTarget>(spec.target);
  const analysis::DrapeShape& eight = t.images[0].measurement.shape;
  const DrapePhotoMisfit m = drape_photo_misfit(t, eight);
  const double d = 1e3 * outline_spectrum_distance(t.images[0].amplitudes_m, t.images[1].amplitudes_m);
  ASSERT_EQ(m.outline_mm.size(), 2u);
  EXPECT_NEAR(m.outline_mm[0], 0.0, 1e-12);
  EXPECT_NEAR(m.outline_mm[1], d, 1e-12);
  EXPECT_GT(d, 5.0);  // 7 against 8 nodes of 12–14 mm
  EXPECT_NEAR(m.outline_rms_mm, d / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(m.outline_part, 2.0 * 0.5 * d * d, 1e-9);
  EXPECT_NEAR(m.drape_coefficient_part,
              0.5 * std::pow((eight.drape_coefficient - t.mean_drape_coefficient) / 0.01, 2), 1e-9);
  EXPECT_NEAR(m.nodes_part, 4.0 * 0.25, 1e-12);
  EXPECT_NEAR(m.objective, m.outline_part + m.drape_coefficient_part + m.nodes_part, 1e-12);
  EXPECT_NEAR(drape_outline_distance_mm(t, eight, t.images[1]), d, 1e-12);
}

// Several specimens give a mean node count such as 7.5: a measured "folds" target is a real
// number ≥ 1.
TEST_F(FitDrapePhotos, MeasuredFoldsTargetMayBeAMeanOfSpecimens) {
  const FitSpec spec = parse(R"({"measured": {"drape_coefficient": 0.45, "folds": 7.5}})");
  EXPECT_DOUBLE_EQ(*std::get<MeasuredTarget>(spec.target).folds, 7.5);
  EXPECT_NE(error_of(R"({"measured": {"folds": 0.5}})").find("target.measured.folds: expected a number ≥ 1"),
            std::string::npos)
      << error_of(R"({"measured": {"folds": 0.5}})");
}

}  // namespace
}  // namespace weft::app
