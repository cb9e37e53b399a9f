#pragma once
// Drape from a top-view photo: `weft measure --photo` reads a photo or a
// silhouette of a Cusick drape seen from above and measures its drape coefficient and folds with
// the same code that measures a simulated drape (analysis/measure/drape_measure.h's
// measure_shadow): the silhouette's pixels become the shadow's cells, one ruler for both.
// docs/measure.md ("A drape photographed from above") states the rules.
//
// Image coordinates: pixel (x, y)'s centre at (x, y), (0, 0) the top-left pixel, y down (as
// render/photo_compare). The shadow is the image seen from above with y flipped to point up, so
// θ runs counter-clockwise on the picture from its +x (rightwards) direction.

#include <filesystem>
#include <optional>
#include <string>

#include "analysis/measure/drape_measure.h"
#include "render/image.h"
#include "render/photo_compare/silhouette.h"

namespace weft::app {

// What is known about the photographed drape. Exactly one of mm_per_px and disc_px sets the
// scale (disc_px: the support disc's diameter measured in the image, so mm per px = disc_mm /
// disc_px).
struct DrapePhotoSetup {
  std::optional<double> mm_per_px;
  std::optional<double> disc_px;
  double disc_mm = 0.0;      // the support disc's diameter (Cusick: 180 mm)
  double specimen_mm = 0.0;  // the flat circular specimen's diameter (Cusick: 240, 300 or 360 mm)
  // The disc's centre in the image, px; none: the silhouette's centroid, which is the centre of
  // any outline r(θ) = R + Σ a_k cos(kθ + φ_k) without a k = 1 term (a shifted drape).
  std::optional<sim::Vec2> center_px;
};

// The scale in mm per pixel. Throws InputError naming `source` and the option when the setup is
// not usable: neither or both of mm_per_px and disc_px, a value not finite and > 0, or a
// specimen no larger than the disc.
double drape_photo_mm_per_px(const DrapePhotoSetup& setup, const std::string& source);

// The mask as a shadow of square cells cell_m wide: pixel (x, y) is cell (x, height − 1 − y),
// cell (0, 0)'s corner at the origin.
analysis::ShadowMask shadow_from_mask(const render::Mask& mask, double cell_m);
// Pixel coordinates → the shadow's plane, m.
sim::Vec2 shadow_point_m(const render::Mask& mask, double cell_m, const sim::Vec2& pixel);

struct DrapePhotoMeasurement {
  render::Mask silhouette;  // the largest component of the given one, holes filled
  double mm_per_px = 0.0;
  sim::Vec2 center_px{0.0, 0.0};
  bool center_given = false;
  double disc_radius_px = 0.0, specimen_radius_px = 0.0;
  double support_m2 = 0.0, specimen_m2 = 0.0;
  analysis::DrapeShape shape;  // cell_m = the pixel's side
};

// Measures a silhouette (1 = cloth). Throws InputError naming `source` for a bad setup
// (drape_photo_mm_per_px), an empty silhouette, one touching the image border (the drape is cut
// off, its area unknown), a centre outside the silhouette, or a shadow smaller than the disc or
// more than 2 % larger than the flat specimen (a wrong scale or diameter).
DrapePhotoMeasurement measure_drape_silhouette(const render::Mask& silhouette,
                                               const DrapePhotoSetup& setup,
                                               const std::string& source,
                                               const analysis::DrapeMeasureSettings& settings = {});

// The photo with the silhouette's outline (magenta), the disc and the flat specimen (cyan,
// dashed grey), the centre, and each fold crest marked at its smoothed radius (orange dots).
render::Image drape_photo_overlay(const render::Image& photo, const DrapePhotoMeasurement& m,
                                  const analysis::FoldCountSettings& folds);

// A drape photo and how errors name its files: `weft measure --photo` calls them "--photo" and
// "--mask-photo", a fit file by its keys.
struct DrapePhotoFiles {
  std::filesystem::path photo;                // photo or silhouette (PNG/JPG)
  std::optional<std::filesystem::path> mask;  // white = cloth
  std::string photo_name = "--photo", mask_name = "--mask-photo";
};

struct DrapePhotoReading {
  render::Image photo;
  bool from_mask_image = false;  // the silhouette is the mask's, not the photo's segmentation
  DrapePhotoMeasurement measurement;
};

// Reads a photo (and its mask, if any), takes its silhouette (render/photo_compare's
// silhouette_of: the mask, else the segmentation) and measures it (measure_drape_silhouette):
// what `weft measure --photo` and weft fit's drape_photos target both do. Throws InputError for a
// missing or unreadable file (naming it by photo_name or mask_name), or as
// measure_drape_silhouette (naming the mask if given, else the photo).
DrapePhotoReading read_drape_photo(const DrapePhotoFiles& files, const DrapePhotoSetup& setup,
                                   const analysis::DrapeMeasureSettings& settings = {});

struct MeasurePhotoOptions {
  std::filesystem::path photo;                    // photo or silhouette (PNG/JPG)
  std::optional<std::filesystem::path> mask;      // --mask-photo: white = cloth
  DrapePhotoSetup setup;
  std::optional<std::filesystem::path> out;       // default out/<photo stem>
  std::string command_line;
};

// `weft measure --photo`: prints the table, writes outline.csv, overlay.png and measure.txt.
int run_measure_photo(const MeasurePhotoOptions& options);

}  // namespace weft::app
