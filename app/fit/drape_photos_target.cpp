// weft fit's drape_photos target (see drape_photos_target.h).

#include "app/fit/drape_photos_target.h"

#include <cmath>

#include "app/fit/fit_spec.h"
#include "app/fit/outline_spectrum.h"
#include "app/run/measure.h"
#include "base/constants.h"
#include "base/format.h"

namespace weft::app {
namespace {

// How far the scene's support disc and specimen may differ in area from the target's.
constexpr double kSceneAreaTolerance = 0.05;

// The scale given in `r` ("mm_per_px" or "disc_px", at most one), if any.
void read_drape_scale(ObjectReader& r, DrapePhotoSetup& setup) {
  std::optional<double> mm_per_px, disc_px;
  if (r.has("mm_per_px")) mm_per_px = r.number("mm_per_px", required, Range::gt(0.0));
  if (r.has("disc_px")) disc_px = r.number("disc_px", required, Range::gt(0.0));
  if (mm_per_px && disc_px)
    r.fail("disc_px", "give the scale by one of 'mm_per_px' and 'disc_px', not both");
  if (mm_per_px || disc_px) {
    setup.mm_per_px = mm_per_px;
    setup.disc_px = disc_px;
  }
}

// One entry of "images" or "check_images": a file name, or an object with its own mask, scale
// and centre. `defaults` holds the diameters and the target's scale.
DrapePhotoImage read_drape_image(const Json& entry, const std::string& file, const std::string& key,
                                 const DrapePhotoSetup& defaults, int harmonics) {
  DrapePhotoImage image;
  image.key = key;
  image.setup = defaults;
  image.files.photo_name = "image";
  image.files.mask_name = "mask";
  if (entry.is_string()) {
    image.files.photo = fit_file_path(file, entry.get<std::string>());
  } else if (entry.is_object()) {
    ObjectReader r(entry, file, key);
    image.files.photo = fit_file_path(file, r.string("image", required));
    if (r.has("mask")) image.files.mask = fit_file_path(file, r.string("mask", required));
    read_drape_scale(r, image.setup);
    if (r.has("center_px")) {
      const std::vector<double> c = r.numbers("center_px", 2, required);
      image.setup.center_px = sim::Vec2(c[0], c[1]);
    }
    r.finish();
  } else {
    throw_scene_error(file, key, "expected an image file name or an object {\"image\": …}, got " +
                                     std::string(entry.type_name()));
  }
  if (!image.setup.mm_per_px && !image.setup.disc_px)
    throw_scene_error(file, key, "no scale: give 'mm_per_px' or 'disc_px' here or beside 'images'");
  try {
    DrapePhotoReading reading = read_drape_photo(image.files, image.setup);
    image.photo = std::move(reading.photo);
    image.measurement = std::move(reading.measurement);
  } catch (const InputError& e) {
    throw_scene_error(file, key, e.what());
  }
  image.amplitudes_m = outline_amplitudes(image.measurement.shape.radii_m, harmonics);
  return image;
}

std::vector<DrapePhotoImage> read_drape_images(const Json& object, const std::string& name,
                                               const std::string& file, const std::string& path,
                                               const DrapePhotoSetup& defaults, int harmonics) {
  const std::string key = path + "." + name;
  const Json& list = object.at(name);
  if (!list.is_array())
    throw_scene_error(file, key, "expected an array of images, got " + std::string(list.type_name()));
  std::vector<DrapePhotoImage> images;
  for (std::size_t i = 0; i < list.size(); ++i)
    images.push_back(read_drape_image(list[i], file, key + "[" + std::to_string(i) + "]", defaults,
                                      harmonics));
  return images;
}

double disc_area_m2(double diameter_m) { return base::kPi * 0.25 * diameter_m * diameter_m; }

}  // namespace

DrapePhotosTarget read_drape_photos(const Json& object, const std::string& file,
                                    const std::string& path) {
  // "images" and "check_images" hold strings or objects, which ObjectReader has no accessor
  // for: they are read below, the other keys through the reader.
  Json rest = object;
  rest.erase("images");
  rest.erase("check_images");
  ObjectReader r(rest, file, path);
  r.has("images");
  r.has("check_images");
  DrapePhotosTarget t;
  t.specimen_m = r.quantity("specimen", Quantity::length, required, Range::gt(0.0));
  t.support_m = r.quantity("support", Quantity::length, required, Range::gt(0.0));
  if (!(t.specimen_m > t.support_m))
    r.fail("specimen", base::format("%g mm", 1e3 * t.specimen_m) + " must be larger than the support's " +
                           base::format("%g mm", 1e3 * t.support_m) + ": no overhang to measure");
  DrapePhotoSetup defaults;
  defaults.specimen_mm = 1e3 * t.specimen_m;
  defaults.disc_mm = 1e3 * t.support_m;
  read_drape_scale(r, defaults);
  ObjectReader w = r.object("weights");
  t.weights.outline = w.number("outline", t.weights.outline, Range::ge(0.0));
  t.weights.drape_coefficient = w.number("drape_coefficient", t.weights.drape_coefficient, Range::ge(0.0));
  t.weights.nodes = w.number("nodes", t.weights.nodes, Range::ge(0.0));
  w.finish();
  if (!(t.weights.outline + t.weights.drape_coefficient + t.weights.nodes > 0.0))
    r.fail("weights", "expected at least one weight > 0");
  t.harmonics = static_cast<int>(r.integer("harmonics", default_outline_harmonics, Range::closed(2, 179)));
  r.finish();
  if (!object.contains("images"))
    r.fail("images", "required key is missing (expected an array of images: file names or "
                     "objects {\"image\": …})");
  t.images = read_drape_images(object, "images", file, path, defaults, t.harmonics);
  if (t.images.empty()) r.fail("images", "expected at least one image to fit");
  if (object.contains("check_images"))
    t.check_images = read_drape_images(object, "check_images", file, path, defaults, t.harmonics);
  for (const DrapePhotoImage& image : t.images) {
    t.mean_drape_coefficient += image.measurement.shape.drape_coefficient / double(t.images.size());
    t.mean_nodes += image.measurement.shape.folds / double(t.images.size());
  }
  return t;
}

void check_drape_photos_scene(const DrapePhotosTarget& target, const Scene& scene,
                              const std::string& file) {
  const std::string key = "target.drape_photos";
  const sim::ClothMesh mesh = cloth_mesh(scene);
  std::optional<analysis::DrapeSupport> support;
  try {
    support = scene_support(scene, mesh, true);
  } catch (const InputError& e) {
    throw_scene_error(file, key, e.what());
  }
  const auto check = [&](const char* name, double target_m, double scene_m2, const std::string& what) {
    const double target_m2 = disc_area_m2(target_m);
    if (std::abs(scene_m2 / target_m2 - 1.0) > kSceneAreaTolerance)
      throw_scene_error(file, key + "." + name,
                        base::format("%g mm", 1e3 * target_m) + " (" +
                            base::format("%.1f cm^2", 1e4 * target_m2) + ") but the scene's " + what +
                            " has " + base::format("%.1f cm^2", 1e4 * scene_m2) +
                            " (more than 5 % apart): the images and the scene are not the same test");
  };
  check("support", target.support_m, support->area_m2, support_name(*support));
  check("specimen", target.specimen_m, analysis::specimen_rest_area_m2(mesh), "cloth");
}

double drape_outline_distance_mm(const DrapePhotosTarget& target,
                                 const analysis::DrapeShape& simulated, const DrapePhotoImage& image) {
  return 1e3 * outline_spectrum_distance(outline_amplitudes(simulated.radii_m, target.harmonics),
                                         image.amplitudes_m);
}

DrapePhotoMisfit drape_photo_misfit(const DrapePhotosTarget& target,
                                    const analysis::DrapeShape& simulated) {
  DrapePhotoMisfit m;
  const std::vector<double> a = outline_amplitudes(simulated.radii_m, target.harmonics);
  double sum_squares = 0.0;
  for (const DrapePhotoImage& image : target.images) {
    const double d_m = outline_spectrum_distance(a, image.amplitudes_m);
    m.outline_mm.push_back(1e3 * d_m);
    sum_squares += std::pow(d_m / drape_outline_unit_m, 2);
  }
  const double count = static_cast<double>(target.images.size());
  m.outline_rms_mm = 1e3 * drape_outline_unit_m * std::sqrt(sum_squares / count);
  m.outline_part = target.weights.outline * sum_squares / count;
  m.drape_coefficient_part =
      target.weights.drape_coefficient *
      std::pow((simulated.drape_coefficient - target.mean_drape_coefficient) / drape_coefficient_unit, 2);
  m.nodes_part = target.weights.nodes * std::pow(simulated.folds - target.mean_nodes, 2);
  m.objective = m.outline_part + m.drape_coefficient_part + m.nodes_part;
  return m;
}

}  // namespace weft::app
