// weft measure --photo: a Cusick drape photographed from above, measured by the simulation's
// ruler (app/run/drape_photo.h, docs/measure.md).

#include "app/run/drape_photo.h"

#include <cmath>
#include <cstdio>

#include "app/run/measure.h"
#include "app/io/exit_code.h"
#include "app/io/input_error.h"
#include "app/io/output_files.h"
#include "base/format.h"
#include "base/constants.h"
#include "render/canvas.h"
#include "render/photo_compare/photo_compare.h"

namespace weft::app {

namespace {

namespace fs = std::filesystem;

using base::format;

void require_positive(double v, const std::string& source, const char* option) {
  if (!(std::isfinite(v) && v > 0.0))
    throw InputError(source + ": " + option + " must be a finite number > 0, got " +
                     format("%g", v));
}

// The areas must allow a drape coefficient in [0, 1], give or take the 2 % a pixel outline and
// a slightly stretched specimen account for.
void check_areas(const DrapePhotoMeasurement& m, const std::string& source) {
  const double shadow_cm2 = 1e4 * m.shape.shadow_m2;
  const std::string areas = " (silhouette " + format("%.1f cm^2", shadow_cm2) + ", disc " +
                            format("%.1f cm^2", 1e4 * m.support_m2) + ", specimen " +
                            format("%.1f cm^2", 1e4 * m.specimen_m2) + " at " +
                            format("%.4g mm per pixel)", m.mm_per_px);
  if (m.shape.shadow_m2 < m.support_m2)
    throw InputError(source + ": the silhouette is smaller than the support disc" + areas +
                     "; check the scale (--mm-per-px or --disc-px) and --disc-mm");
  if (m.shape.shadow_m2 > 1.02 * m.specimen_m2)
    throw InputError(source + ": the silhouette is larger than the flat specimen" + areas +
                     "; check the scale (--mm-per-px or --disc-px) and --specimen-mm");
}

render::Image read_input(const fs::path& path, const std::string& name) {
  if (!fs::exists(path)) throw InputError(name + " " + path.string() + ": no such file");
  try {
    return render::read_image(path);
  } catch (const std::exception& e) {
    throw InputError(name + ": " + e.what());
  }
}

void print_table(const MeasurePhotoOptions& o, bool from_mask_image, const DrapePhotoMeasurement& m) {
  const analysis::DrapeShape& d = m.shape;
  std::string crests;
  for (int k : d.crests)
    crests += (crests.empty() ? " at " : ", ") +
              format("%.0f", std::fmod(std::round(360.0 * (k + 0.5) / static_cast<double>(
                                                      d.radii_m.size())), 360.0));
  std::printf("weft: %s (%dx%d px, silhouette from %s)\n", o.photo.c_str(), m.silhouette.width,
              m.silhouette.height, from_mask_image ? o.mask->c_str() : "segmentation");
  std::printf("  drape coefficient  %.3f\n", d.drape_coefficient);
  std::printf("  folds              %d%s\n", d.folds,
              (crests.empty() ? "" : crests + " deg (counter-clockwise from +x, y up)").c_str());
  std::printf("  shadow area        %.1f cm^2 (%.0f px at %.4g mm per pixel)\n", 1e4 * d.shadow_m2,
              d.shadow_m2 / (d.cell_m * d.cell_m), m.mm_per_px);
  std::printf("  support            disc %.4g cm^2, centre (%.1f, %.1f) px (%s)\n",
              1e4 * m.support_m2, m.center_px.x(), m.center_px.y(),
              m.center_given ? "given" : "the silhouette's centroid");
  std::printf("  specimen area      %.1f cm^2\n", 1e4 * m.specimen_m2);
}

}  // namespace

double drape_photo_mm_per_px(const DrapePhotoSetup& setup, const std::string& source) {
  require_positive(setup.disc_mm, source, "--disc-mm (the support disc's diameter, mm)");
  require_positive(setup.specimen_mm, source, "--specimen-mm (the flat specimen's diameter, mm)");
  if (!(setup.specimen_mm > setup.disc_mm))
    throw InputError(source + ": --specimen-mm " + format("%g", setup.specimen_mm) +
                     " must be larger than --disc-mm " + format("%g", setup.disc_mm) +
                     ": no overhang to measure");
  if (setup.mm_per_px.has_value() == setup.disc_px.has_value())
    throw InputError(source + ": give the scale by exactly one of --mm-per-px and --disc-px "
                              "(the disc's diameter in the image, px)");
  if (setup.mm_per_px) {
    require_positive(*setup.mm_per_px, source, "--mm-per-px");
    return *setup.mm_per_px;
  }
  require_positive(*setup.disc_px, source, "--disc-px");
  return setup.disc_mm / *setup.disc_px;
}

analysis::ShadowMask shadow_from_mask(const render::Mask& mask, double cell_m) {
  analysis::ShadowMask s;
  s.cell_m = cell_m;
  s.nx = mask.width;
  s.ny = mask.height;
  s.inside.resize(mask.in.size());
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      s.inside[static_cast<std::size_t>(mask.height - 1 - y) * mask.width + x] = mask.at(x, y);
  return s;
}

sim::Vec2 shadow_point_m(const render::Mask& mask, double cell_m, const sim::Vec2& pixel) {
  return {(pixel.x() + 0.5) * cell_m, (mask.height - 0.5 - pixel.y()) * cell_m};
}

DrapePhotoMeasurement measure_drape_silhouette(const render::Mask& silhouette,
                                               const DrapePhotoSetup& setup,
                                               const std::string& source,
                                               const analysis::DrapeMeasureSettings& settings) {
  DrapePhotoMeasurement m;
  m.mm_per_px = drape_photo_mm_per_px(setup, source);
  m.silhouette = render::fill_holes(render::largest_component(silhouette));
  const render::SilhouetteMoments mo = render::moments(m.silhouette);
  if (mo.area_px == 0.0) throw InputError(source + ": the silhouette is empty: no cloth found");
  if (m.silhouette.border_pixels() > 0)
    throw InputError(source + ": the silhouette touches the image border: the drape is cut off "
                              "and its area unknown; photograph or crop it with a margin");
  m.center_given = setup.center_px.has_value();
  m.center_px = setup.center_px.value_or(sim::Vec2(mo.cx, mo.cy));
  const int cx = static_cast<int>(std::lround(m.center_px.x()));
  const int cy = static_cast<int>(std::lround(m.center_px.y()));
  if (!m.silhouette.at_or_out(cx, cy))
    throw InputError(source + ": the disc centre (" + format("%.1f", m.center_px.x()) + ", " +
                     format("%.1f", m.center_px.y()) +
                     ") px is outside the silhouette; give --center-px X,Y");
  const double cell_m = 1e-3 * m.mm_per_px;
  m.disc_radius_px = 0.5 * setup.disc_mm / m.mm_per_px;
  m.specimen_radius_px = 0.5 * setup.specimen_mm / m.mm_per_px;
  m.support_m2 = base::kPi * std::pow(0.5e-3 * setup.disc_mm, 2);
  m.specimen_m2 = base::kPi * std::pow(0.5e-3 * setup.specimen_mm, 2);
  m.shape = analysis::measure_shadow(shadow_from_mask(m.silhouette, cell_m),
                                shadow_point_m(m.silhouette, cell_m, m.center_px), m.support_m2,
                                m.specimen_m2, settings);
  check_areas(m, source);
  return m;
}

render::Image drape_photo_overlay(const render::Image& photo, const DrapePhotoMeasurement& m,
                                  const analysis::FoldCountSettings& folds) {
  const int w = photo.width(), h = photo.height();
  const int thick = std::max(1, static_cast<int>(std::lround(std::hypot(w, h) / 400.0)));
  render::Canvas canvas(photo);
  const render::Mask edge = render::outline(m.silhouette);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (edge.at(x, y)) canvas.fill_rect(x, y, x + thick, y + thick, {255, 0, 200});
  const double cx = m.center_px.x(), cy = m.center_px.y();
  canvas.smooth_circle(cx, cy, m.disc_radius_px, {0, 220, 255}, false, thick);
  const int steps = 180;
  for (int k = 0; k < steps; k += 2) {  // the flat specimen, dashed
    const double a0 = 2.0 * base::kPi * k / steps, a1 = 2.0 * base::kPi * (k + 1) / steps;
    canvas.line(cx + m.specimen_radius_px * std::cos(a0), cy - m.specimen_radius_px * std::sin(a0),
                cx + m.specimen_radius_px * std::cos(a1), cy - m.specimen_radius_px * std::sin(a1),
                {150, 150, 150}, thick);
  }
  canvas.line(cx - 3 * thick, cy, cx + 3 * thick, cy, {0, 220, 255}, thick);
  canvas.line(cx, cy - 3 * thick, cx, cy + 3 * thick, {0, 220, 255}, thick);
  const std::vector<double> smooth =
      analysis::circular_moving_average(m.shape.radii_m, folds.smoothing_bins);
  const int bins = static_cast<int>(smooth.size());
  for (int k : m.shape.crests) {
    const double theta = 2.0 * base::kPi * (k + 0.5) / bins;
    const double r_px = smooth[static_cast<std::size_t>(k)] / m.shape.cell_m;
    canvas.smooth_circle(cx + r_px * std::cos(theta), cy - r_px * std::sin(theta), 2.5 * thick,
                         {255, 150, 30}, true);
  }
  return canvas.image();
}

DrapePhotoReading read_drape_photo(const DrapePhotoFiles& files, const DrapePhotoSetup& setup,
                                   const analysis::DrapeMeasureSettings& settings) {
  DrapePhotoReading r;
  r.photo = read_input(files.photo, files.photo_name);
  std::optional<render::Image> mask;
  if (files.mask) mask = read_input(*files.mask, files.mask_name);
  const std::string source = (files.mask ? *files.mask : files.photo).string();
  render::Silhouette s;
  try {
    s = render::silhouette_of(r.photo, mask);
  } catch (const std::invalid_argument& e) {
    throw InputError(source + ": " + e.what());
  }
  r.from_mask_image = s.from_mask_image;
  r.measurement = measure_drape_silhouette(s.mask, setup, source, settings);
  return r;
}

int run_measure_photo(const MeasurePhotoOptions& o) {
  const analysis::DrapeMeasureSettings settings;
  const DrapePhotoReading r = read_drape_photo({o.photo, o.mask}, o.setup, settings);
  const DrapePhotoMeasurement& m = r.measurement;
  const fs::path dir = o.out.value_or(fs::path("out") / o.photo.stem());
  std::optional<OutputFolderLock> lock;
  start_output(lock, dir, {}, {{"measure.txt", run_record(o.command_line, {{"photo", o.photo.string()}})}});
  write_outline(dir / "outline.csv", m.shape, settings.folds);
  render::write_png(drape_photo_overlay(r.photo, m, settings.folds), dir / "overlay.png");
  print_table(o, r.from_mask_image, m);
  std::printf("weft: wrote outline.csv and overlay.png to %s\n", dir.c_str());
  return exit_ok;
}

}  // namespace weft::app
