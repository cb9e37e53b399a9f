#pragma once
// weft fit's drape_photos target (docs/photos.md, "Fitting a material"): top-view photos or
// silhouettes of Cusick drapes of one fabric, read exactly as `weft measure --photo` reads them
// (app/run/drape_photo.h), against the simulated drape over the scene's support:
//
//   "target": {"drape_photos": {
//      "images": ["a.png", {"image": "b.png", "mask": "b_mask.png", "mm_per_px": 0.45,
//                           "center_px": [310, 298]}],      (a string or an object each)
//      "check_images": ["c.png"],   (optional: held out of the fit, compared after it)
//      "mm_per_px": 0.5 | "disc_px": 360,   (the scale of every image without its own)
//      "specimen": "30 cm", "support": "18 cm",   (the flat specimen's and the disc's diameters)
//      "weights": {"outline": 1, "drape_coefficient": 1, "nodes": 1},   (optional)
//      "harmonics": 30}}            (optional: the outline's highest harmonic, outline_spectrum.h)
//
// Objective, with the simulated drape's outline amplitudes a, drape coefficient DC and node
// count n (analysis/measure/drape_measure.h, the rules `weft measure` applies), over the m
// images i (outline_spectrum.h's D):
//
//   J = w_outline · (1/m) Σᵢ (D(a, aᵢ) / 1 mm)²  +  w_dc · ((DC − mean DCᵢ) / 0.01)²
//       + w_nodes · (n − mean nᵢ)²
//
// Each part is in units of what a top view resolves: 1 mm of outline (two pixels at 0.5 mm per
// px), 0.01 of DC, 1 node; so the default sensitivity band is 1. The node count of a simulation
// is a whole number, so its part is a step function of the parameters; the outline and DC parts
// carry the smooth change.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/run/drape_photo.h"
#include "app/scene/json_reader.h"
#include "app/scene/scene.h"

namespace weft::app {

// What one unit of each part of the objective is.
inline constexpr double drape_outline_unit_m = 1e-3;
inline constexpr double drape_coefficient_unit = 0.01;

struct DrapePhotoWeights {
  double outline = 1.0, drape_coefficient = 1.0, nodes = 1.0;
};

// One image of the target, measured.
struct DrapePhotoImage {
  std::string key;                 // its key path in the fit file, "target.drape_photos.images[0]"
  DrapePhotoFiles files;
  DrapePhotoSetup setup;
  render::Image photo;
  DrapePhotoMeasurement measurement;
  std::vector<double> amplitudes_m;  // outline_amplitudes of measurement.shape.radii_m
};

struct DrapePhotosTarget {
  std::vector<DrapePhotoImage> images;        // fitted to, at least one
  std::vector<DrapePhotoImage> check_images;  // held out, compared after the fit
  double specimen_m = 0.0, support_m = 0.0;   // diameters
  DrapePhotoWeights weights;
  int harmonics = 0;
  double mean_drape_coefficient = 0.0;        // over `images`
  double mean_nodes = 0.0;                    // over `images`: a real number, e.g. 7.5
};

// Reads the target's object (`object` at key path `path` of fit file `file`) and measures every
// image. Throws InputError naming the file and key path: a bad or unknown key, no images, a
// missing or unreadable image, no scale, a specimen no larger than its support, or an image
// measure_drape_silhouette rejects.
DrapePhotosTarget read_drape_photos(const Json& object, const std::string& file,
                                    const std::string& path);

// Throws InputError naming `file` and target.drape_photos.support/specimen when the scene has no
// drape support, or its support disc or flat specimen differs in area from the target's by more
// than 5 % (a coarse grid's staircase disc is a few % off).
void check_drape_photos_scene(const DrapePhotosTarget& target, const Scene& scene,
                              const std::string& file);

// The simulated drape against one image: its outline distance D, mm.
double drape_outline_distance_mm(const DrapePhotosTarget& target,
                                 const analysis::DrapeShape& simulated, const DrapePhotoImage& image);

// The objective J above and its parts.
struct DrapePhotoMisfit {
  std::vector<double> outline_mm;  // D to each image
  double outline_rms_mm = 0.0;     // √((1/m) Σ D²)
  double outline_part = 0.0, drape_coefficient_part = 0.0, nodes_part = 0.0;
  double objective = 0.0;          // the sum of the parts
};
DrapePhotoMisfit drape_photo_misfit(const DrapePhotosTarget& target,
                                    const analysis::DrapeShape& simulated);

}  // namespace weft::app
