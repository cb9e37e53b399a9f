// Golden-image regression support; see golden.h.

#include "tests/regression/golden.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "app/run/frame_mesh.h"
#include "app/run/frame_stream.h"
#include "app/run/frame_painter.h"
#include "app/scene/scene.h"
#include "app/cli/options.h"
#include "app/run/renderer_choice.h"
#include "tests/app/coarse_scene.h"

namespace weft::test {
namespace fs = std::filesystem;

namespace {

bool update_mode() {
  const char* v = std::getenv("WEFT_REGRESSION_UPDATE");
  return v && std::string(v) == "1";
}

void write_page(const fs::path& dir, const GoldenCase& c, const render::ImageDifference& d,
                const std::string& verdict) {
  std::string overrides;
  for (const auto& [key, value] : c.settings) overrides += " --set " + key + "=" + value;
  std::ofstream html(dir / "index.html");
  html << "<!doctype html><meta charset=\"utf-8\"><title>weft regression: " << c.name
       << "</title>\n<style>body{font-family:sans-serif} img{image-rendering:pixelated;"
          "width:480px;border:1px solid #888;cursor:pointer} td{padding:6px;vertical-align:top}"
          "</style>\n<h1>" << c.name << ": " << verdict << "</h1>\n<p>scene " << c.scene << overrides << ", "
       << (c.settings.empty() ? std::to_string(c.resolution) + "² grid" : "its own mesh")
       << ", " << c.frames << " frames, " << c.renderer << ", " << c.width
       << "×" << c.height << ". PSNR " << d.psnr_db << " dB (fail below " << c.min_psnr_db
       << "), SSIM " << d.ssim << ", max difference " << d.max_abs << ", "
       << 100.0 * d.fraction_over << " % of pixels differ by more than " << d.pixel_threshold
       << " (fail above " << 100.0 * c.max_over << " %).</p>\n"
       << "<table><tr><td>actual ⇄ expected (click to swap)<br><img id=\"swap\" src=\"actual.png\""
          " onclick=\"this.src=this.src.endsWith('actual.png')?'expected.png':'actual.png';"
          "document.getElementById('which').textContent=this.src.endsWith('actual.png')?"
          "'actual':'expected'\"><br><span id=\"which\">actual</span></td>"
          "<td>difference<br><img src=\"diff.png\"></td></tr>\n"
          "<tr><td>actual<br><img src=\"actual.png\"></td><td>expected (golden: "
       << golden_path(c).string() << ")<br><img src=\"expected.png\"></td></tr></table>\n";
}

}  // namespace

render::Image render_case(const GoldenCase& c, double density_scale, long* remeshes) {
  std::vector<app::Setting> settings;
  for (const auto& [key, value] : c.settings) settings.push_back({key, value});
  app::Scene scene =
      settings.empty()
          ? app::test::coarse_scene(c.scene, c.resolution)
          : app::load_scene_with(fs::path(WEFT_SOURCE_DIR) / "assets" / "scenes" / c.scene, settings);
  scene.material.density_kg_m2 *= density_scale;
  scene.render.width = c.width;
  scene.render.height = c.height;
  scene.render.renderer = render::renderer_from_name(c.renderer, c.name);
  scene.render.raytrace.samples_per_pixel = c.samples;
  scene.frames = c.frames;
  const auto simulator = app::make_simulator(scene);
  // The frames weft run writes: the frame stream, frame by frame to the last.
  const app::FrameStreamEnd end = app::stream_frames(scene, *simulator, {});
  if (end.divergence) throw end.divergence->error;
  if (remeshes) *remeshes = simulator->remesh_count();
  const auto renderer = app::make_chosen_renderer(scene.render);
  // With what weft run draws beside the cloth: obstacles, stands, clips and rods.
  app::FramePainter painter(scene, *renderer, simulator->mesh());
  const sim::Matrix3X& x = simulator->state().x;
  return renderer->render(app::to_render_mesh(simulator->mesh(), x), scene.render,
                          painter.objects(x, simulator->state().time_s));
}

fs::path golden_path(const GoldenCase& c) {
  return fs::path(WEFT_SOURCE_DIR) / "tests" / "data" / "golden" / (c.name + ".png");
}

fs::path evidence_page(const GoldenCase& c, const std::string& evidence_folder) {
  return fs::path(WEFT_BINARY_DIR) / "regression" /
         (evidence_folder.empty() ? c.name : evidence_folder) / "index.html";
}

::testing::AssertionResult matches_golden(const GoldenCase& c, const render::Image& actual,
                                          const std::string& evidence_folder) {
  if (update_mode()) {
    render::write_png(actual, golden_path(c));
    return ::testing::AssertionSuccess() << "wrote " << golden_path(c);
  }
  if (!fs::exists(golden_path(c)))
    return ::testing::AssertionFailure()
           << "no golden image " << golden_path(c)
           << " (make it with: cmake --build build --target regress-update)";
  const render::Image expected = render::read_image(golden_path(c));
  const fs::path page = evidence_page(c, evidence_folder);
  const fs::path dir = page.parent_path();
  fs::remove_all(dir);
  if (expected.width() != actual.width() || expected.height() != actual.height()) {
    fs::create_directories(dir);
    render::write_png(actual, dir / "actual.png");
    return ::testing::AssertionFailure() << c.name << ": size " << actual.width() << "x"
                                         << actual.height() << ", golden " << expected.width()
                                         << "x" << expected.height() << "; actual.png in " << dir;
  }
  const render::ImageDifference d = render::compare_images(actual, expected, c.pixel_threshold);
  const bool ok = d.psnr_db >= c.min_psnr_db && d.fraction_over <= c.max_over;
  std::ostringstream numbers;
  numbers << "PSNR " << d.psnr_db << " dB (min " << c.min_psnr_db << "), "
          << 100.0 * d.fraction_over << " % of pixels over " << c.pixel_threshold << " (max "
          << 100.0 * c.max_over << " %), SSIM " << d.ssim << ", max " << d.max_abs;
  if (ok) return ::testing::AssertionSuccess() << c.name << ": " << numbers.str();
  fs::create_directories(dir);
  render::write_png(actual, dir / "actual.png");
  render::write_png(expected, dir / "expected.png");
  render::write_png(render::difference_heatmap(actual, expected, c.pixel_threshold), dir / "diff.png");
  write_page(dir, c, d, "FAILED");
  return ::testing::AssertionFailure() << c.name << " differs from its golden image: "
                                       << numbers.str() << "; see " << page;
}

}  // namespace weft::test
