#pragma once
// What `weft fit` reports for a drape_photos target (app/fit/drape_photos_target.h): the fitted
// drape, settled again at the fitted values, against every image — those fitted to and those
// held out of the fit ("check_images": its prediction on images not used) — and the pictures:
//   drape_photos.png     the fitted drape's top view and each image's overlay, labelled with
//                        DC, nodes and outline distance
//   outline_spectra.png  the outline amplitudes aₖ of the fitted drape and of every image, and
//                        the objective's three parts per evaluation

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/fit/fit_optimizer.h"

namespace weft::app {

// The top view of a drape as a silhouette of size_px × size_px pixels at mm_per_px, the point
// axis_m of the horizontal plane at the image's centre: the vertical projection of the mesh's
// triangles at positions x (analysis::rasterize_shadow, a pixel set when its centre is inside),
// turned counter-clockwise by rotation_rad about axis_m, then mirrored (y → −y) if asked. White
// cloth on black when written as a PNG, as `weft measure --photo` reads a silhouette.
render::Mask drape_top_view(const sim::ClothMesh& mesh, const sim::Matrix3X& x, const sim::Vec2& axis_m,
                            double mm_per_px, int size_px, double rotation_rad = 0.0,
                            bool mirrored = false);

// The fitted drape against one image.
struct DrapePhotoComparison {
  std::string key;                // "target.drape_photos.check_images[0]"
  std::filesystem::path file;
  bool held_out = false;          // from check_images
  double image_drape_coefficient = 0.0;
  int image_nodes = 0;
  double outline_mm = 0.0;        // outline_spectrum.h's D between the fitted drape and the image
};

struct FittedDrapeCheck {
  analysis::DrapeShape fitted;    // the drape at the fitted values
  bool settled = false;
  render::Mask top_view;          // drape_top_view at the first image's scale
  double top_view_mm_per_px = 0.0;
  std::vector<DrapePhotoComparison> images;  // the fitted images, then the held-out ones
};

// Settles the scene at `values` (settle_to_rest, as every evaluation) and compares its drape
// with every image of the drape_photos target of problem.spec().
FittedDrapeCheck check_fitted_drape(FitProblem& problem, const std::vector<double>& values);

nlohmann::ordered_json fitted_drape_json(const FittedDrapeCheck& check);

// Writes drape_photos.png and outline_spectra.png into `dir` and returns the report's section.
std::string write_drape_photo_outputs(const std::filesystem::path& dir, const FitSpec& spec,
                                      const FitResult& result, const FittedDrapeCheck& check);

// "held out c.png: DC 0.512 (fitted 0.498), 8 nodes (fitted 8), outline distance 1.3 mm".
std::string describe_comparison(const DrapePhotoComparison& c, const analysis::DrapeShape& fitted);

}  // namespace weft::app
