// What `weft fit` reports for a drape_photos target (see drape_photos_report.h).

#include "app/fit/drape_photos_report.h"

#include <cmath>
#include <limits>

#include "app/fit/outline_spectrum.h"
#include "app/report/contact_sheet.h"
#include "app/run/measure.h"
#include "app/scene/units.h"
#include "base/check.h"
#include "base/format.h"
#include "base/html_escape.h"
#include "chart/chart.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;
using base::format;

// The value of measure `name` of an evaluation, NaN when it has none (a diverged one).
double measure_of(const Evaluation& e, const std::string& name) {
  for (const auto& [n, v] : e.measures)
    if (n == name) return v;
  return std::numeric_limits<double>::quiet_NaN();
}

render::Image mask_picture(const render::Mask& mask) {
  render::Image image(mask.width, mask.height);
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (mask.at(x, y)) image.set(x, y, {255, 255, 255});
  return image;
}

// The fitted drape's top view with the disc, the flat specimen and its nodes drawn as on a
// photo's overlay; the bare silhouette if the photo ruler rejects it (e.g. smaller than the disc).
render::Image fitted_picture(const DrapePhotosTarget& target, const FittedDrapeCheck& check) {
  const render::Image picture = mask_picture(check.top_view);
  DrapePhotoSetup setup;
  setup.mm_per_px = check.top_view_mm_per_px;
  setup.disc_mm = 1e3 * target.support_m;
  setup.specimen_mm = 1e3 * target.specimen_m;
  const double centre = 0.5 * check.top_view.width - 0.5;
  setup.center_px = sim::Vec2(centre, centre);
  const analysis::DrapeMeasureSettings settings;
  try {
    return drape_photo_overlay(picture, measure_drape_silhouette(check.top_view, setup, "fitted", settings),
                               settings.folds);
  } catch (const InputError&) {
    return picture;
  }
}

// The fitted drape and every image, each with its numbers.
render::Image drape_photos_sheet(const DrapePhotosTarget& target, const FittedDrapeCheck& check) {
  constexpr int width = 360;  // room for the label
  std::vector<render::Image> tiles = {thumbnail(fitted_picture(target, check), width)};
  std::vector<std::string> labels = {format("fitted: DC %.3f, ", check.fitted.drape_coefficient) +
                                     std::to_string(check.fitted.folds) + " nodes"};
  const analysis::FoldCountSettings folds = analysis::DrapeMeasureSettings{}.folds;
  std::size_t k = 0;
  for (const auto* list : {&target.images, &target.check_images})
    for (const DrapePhotoImage& image : *list) {
      const DrapePhotoComparison& c = check.images[k++];
      tiles.push_back(thumbnail(drape_photo_overlay(image.photo, image.measurement, folds), width));
      labels.push_back(c.file.filename().string() + (c.held_out ? " (held out)" : "") +
                       format(": DC %.3f, ", c.image_drape_coefficient) +
                       std::to_string(c.image_nodes) + format(" nodes, D %.2f mm", c.outline_mm));
    }
  return contact_sheet(tiles, labels, contact_sheet_columns(static_cast<int>(tiles.size()), 4, 4));
}

// Adds a series to the plot and its values to `all`, the values its y axis must hold.
void add_series(chart::Plot& plot, std::vector<double>& all, const chart::Series& s) {
  all.insert(all.end(), s.y.begin(), s.y.end());
  plot.series.push_back(s);
}

chart::Plot spectra_plot(const DrapePhotosTarget& target, const FittedDrapeCheck& check) {
  std::vector<double> k;
  for (int h = 2; h <= target.harmonics; ++h) k.push_back(h);
  const auto amplitudes_mm = [&](const std::vector<double>& a_m) {
    std::vector<double> y;
    for (std::size_t h = 2; h < a_m.size(); ++h) y.push_back(1e3 * a_m[h]);
    return y;
  };
  chart::Plot plot;
  plot.title = "outline amplitudes";
  plot.note = "k = 2 … " + std::to_string(target.harmonics);
  std::vector<double> all;
  add_series(plot, all, chart::Series("fitted", chart::series_colour(0), k,
                                      amplitudes_mm(outline_amplitudes(check.fitted.radii_m, target.harmonics)), 2.5));
  for (const auto* list : {&target.images, &target.check_images})
    for (const DrapePhotoImage& image : *list) {
      chart::Series s(image.key, chart::series_colour(list == &target.images ? 1 : 2), k,
                      amplitudes_mm(image.amplitudes_m), 1.0);
      s.dashed = list != &target.images;
      add_series(plot, all, s);
    }
  plot.x = chart::Axis::linear_fit("harmonic k", k);
  plot.y = chart::Axis::linear_fit("amplitude a_k [mm]", all);
  plot.y.grid = true;
  return plot;
}

chart::Plot parts_plot(const FitResult& r) {
  chart::Plot plot;
  plot.title = "objective parts per evaluation";
  std::vector<double> n, all;
  for (std::size_t k = 0; k < r.evaluations.size(); ++k) n.push_back(static_cast<double>(k + 1));
  const char* names[] = {"outline_part", "dc_part", "nodes_part"};
  for (std::size_t p = 0; p < 3; ++p) {
    std::vector<double> y;
    for (const Evaluation& e : r.evaluations) {
      const double v = measure_of(e, names[p]);
      y.push_back(v > 0.0 ? v : std::numeric_limits<double>::quiet_NaN());  // 0: off the log axis
    }
    chart::Series s(names[p], chart::series_colour(p + 3), n, y, 0.0);  // no line across a 0
    s.marker = chart::Marker::disc;
    s.marker_radius = 2.5;
    add_series(plot, all, s);
  }
  plot.x = chart::Axis::linear_fit("evaluation", n);
  plot.y = chart::Axis::log_fit("part of the objective", all);
  plot.y.grid = true;
  return plot;
}

std::string comparison_rows(const FittedDrapeCheck& c) {
  std::string rows;
  for (const DrapePhotoComparison& i : c.images)
    rows += "<tr><td>" + base::html_escape(i.key) + "</td><td>" + base::html_escape(i.file.string()) +
            "</td><td>" + (i.held_out ? "held out" : "fitted") + "</td><td>" +
            format("%.3f", i.image_drape_coefficient) + "</td><td>" + std::to_string(i.image_nodes) +
            "</td><td>" + format("%.2f", i.outline_mm) + "</td></tr>\n";
  return rows;
}

}  // namespace

render::Mask drape_top_view(const sim::ClothMesh& mesh, const sim::Matrix3X& x, const sim::Vec2& axis_m,
                            double mm_per_px, int size_px, double rotation_rad, bool mirrored) {
  WEFT_CHECK(mm_per_px > 0.0 && size_px > 0, "drape_top_view needs a scale > 0 and a size > 0");
  const double cell_m = 1e-3 * mm_per_px, side_m = size_px * cell_m;
  const double c = std::cos(rotation_rad), s = std::sin(rotation_rad);
  const sim::Index n = static_cast<sim::Index>(x.rows());
  sim::Matrix3X p(n, 3);
  for (sim::Index v = 0; v < n; ++v) {
    const double dx = x(v, 0) - axis_m.x(), dy = x(v, 1) - axis_m.y();
    const double qy = s * dx + c * dy;
    p.row(v) << c * dx - s * dy + 0.5 * side_m, (mirrored ? -qy : qy) + 0.5 * side_m, x(v, 2);
  }
  // Two triangles of a thousandth of a cell at the image's corners stretch the raster over it
  // exactly: its cell (ix, iy) centre is then at ((ix − ½) h, (iy − ½) h), pixel (ix − 1,
  // size − iy). They hold no cell centre. (One triangle of no area across the image would hold
  // the centres on its edge.)
  const double tiny = 1e-3 * cell_m;
  p.conservativeResize(n + 6, 3);
  p.row(n) << 0.0, 0.0, 0.0;
  p.row(n + 1) << tiny, 0.0, 0.0;
  p.row(n + 2) << 0.0, tiny, 0.0;
  p.row(n + 3) << side_m, side_m, 0.0;
  p.row(n + 4) << side_m - tiny, side_m, 0.0;
  p.row(n + 5) << side_m, side_m - tiny, 0.0;
  analysis::Triangles triangles = mesh.triangles();
  triangles.push_back({n, n + 1, n + 2});
  triangles.push_back({n + 3, n + 4, n + 5});
  const analysis::ShadowMask shadow = analysis::rasterize_shadow(p, triangles, cell_m);
  render::Mask mask(size_px, size_px);
  for (int py = 0; py < size_px; ++py)
    for (int px = 0; px < size_px; ++px) {
      const int ix = px + 1, iy = size_px - py;
      if (ix < shadow.nx && iy < shadow.ny)
        mask.set(px, py, shadow.inside[static_cast<std::size_t>(iy) * shadow.nx + ix] != 0);
    }
  return mask;
}

FittedDrapeCheck check_fitted_drape(FitProblem& problem, const std::vector<double>& values) {
  const FitSpec& spec = problem.spec();
  const auto& target = std::get<DrapePhotosTarget>(spec.target);
  const Scene scene = problem.scene_at(values);
  const Settled settled = settle_to_rest(scene, spec.settle);
  const sim::Simulator& simulator = *settled.simulator;
  FittedDrapeCheck check;
  check.settled = settled.converged;
  check.fitted = measure_settled_drape(scene, simulator);
  check.top_view_mm_per_px = target.images.front().measurement.mm_per_px;
  const double cell_m = 1e-3 * check.top_view_mm_per_px;
  const auto support = scene_support(scene, simulator.mesh(), true);
  check.top_view = drape_top_view(simulator.mesh(), simulator.state().x, support->axis_m,
                                  check.top_view_mm_per_px,
                                  static_cast<int>(std::ceil(1.1 * target.specimen_m / cell_m)) + 4);
  for (const auto* list : {&target.images, &target.check_images})
    for (const DrapePhotoImage& image : *list)
      check.images.push_back({image.key, image.files.photo, list == &target.check_images,
                              image.measurement.shape.drape_coefficient, image.measurement.shape.folds,
                              drape_outline_distance_mm(target, check.fitted, image)});
  return check;
}

nlohmann::ordered_json fitted_drape_json(const FittedDrapeCheck& check) {
  nlohmann::ordered_json j;
  j["fitted"] = {{"drape_coefficient", check.fitted.drape_coefficient},
                 {"nodes", check.fitted.folds},
                 {"settled", check.settled}};
  for (const DrapePhotoComparison& c : check.images)
    j["images"].push_back({{"key", c.key}, {"file", c.file.string()}, {"held_out", c.held_out},
                           {"drape_coefficient", c.image_drape_coefficient}, {"nodes", c.image_nodes},
                           {"outline_distance_mm", c.outline_mm}});
  return j;
}

std::string write_drape_photo_outputs(const fs::path& dir, const FitSpec& spec, const FitResult& result,
                                      const FittedDrapeCheck& check) {
  const auto& target = std::get<DrapePhotosTarget>(spec.target);
  render::write_png(drape_photos_sheet(target, check), dir / "drape_photos.png");
  chart::Figure figure;
  figure.title = "weft fit " + spec.name + ": drape photos";
  figure.subtitle = "the fitted drape (thick) against the images (thin; held out: dashed)";
  figure.plots = {spectra_plot(target, check), parts_plot(result)};
  figure.columns = 2;
  figure.legend = {{"fitted", chart::Swatch::line, chart::series_colour(0)},
                   {"images", chart::Swatch::line, chart::series_colour(1)},
                   {"held out", chart::Swatch::dashed_line, chart::series_colour(2)},
                   {"outline part", chart::Swatch::disc, chart::series_colour(3)},
                   {"DC part", chart::Swatch::disc, chart::series_colour(4)},
                   {"nodes part", chart::Swatch::disc, chart::series_colour(5)}};
  chart::write_png(figure, dir / "outline_spectra.png");
  return "<h2>Drape photos</h2>\n<p>The fitted drape, settled again at the fitted values" +
         std::string(check.settled ? "" : " (NOT settled)") +
         format(": DC %.3f, ", check.fitted.drape_coefficient) + std::to_string(check.fitted.folds) +
         " nodes; the images fitted to: mean DC " + format("%.3f", target.mean_drape_coefficient) +
         ", mean " + format("%.3g", target.mean_nodes) +
         " nodes. Outline distance D: the amplitude-spectrum distance of r(θ), mm "
         "(app/fit/outline_spectrum.h); held-out images were not used in the fit, so their row "
         "is the fit's prediction.</p>\n<table>\n<tr><th>key</th><th>image</th><th></th><th>DC</th>"
         "<th>nodes</th><th>D [mm]</th></tr>\n" +
         comparison_rows(check) +
         "</table>\n<img src=\"drape_photos.png\" alt=\"fitted drape and images\">\n"
         "<img src=\"outline_spectra.png\" alt=\"outline spectra and objective parts\">\n";
}

std::string describe_comparison(const DrapePhotoComparison& c, const analysis::DrapeShape& fitted) {
  return (c.held_out ? "held out " : "") + c.file.filename().string() +
         format(": DC %.3f", c.image_drape_coefficient) + format(" (fitted %.3f), ", fitted.drape_coefficient) +
         std::to_string(c.image_nodes) + " nodes (fitted " + std::to_string(fitted.folds) +
         format("), outline distance %.2f mm", c.outline_mm);
}

}  // namespace weft::app
