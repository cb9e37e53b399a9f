// weft run --report (see run_report.h).

#include "app/report/run_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "app/io/output_files.h"
#include "app/report/contact_sheet.h"
#include "base/html_escape.h"
#include "app/io/progress.h"
#include "app/scene/scene.h"
#include "chart/chart.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

const char* const kSheetName = "report_sheet.png";

std::string fixed(double v, int digits) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

// A line chart of the report: values against simulated time, the series named in a legend
// at the top right.
chart::Figure line_chart(const std::string& title, const std::string& y_label,
                         const std::vector<double>& t, std::vector<chart::Series> series) {
  std::vector<double> all_y;
  for (chart::Series& s : series) {
    s.x = t;
    all_y.insert(all_y.end(), s.y.begin(), s.y.end());
  }
  chart::Figure figure;
  figure.title = title;
  chart::Plot plot;
  plot.x = chart::Axis::linear_fit("simulated time [s]", t);
  plot.y = chart::Axis::linear_fit(y_label, all_y);
  plot.y.grid = true;
  for (const chart::Series& s : series)
    figure.legend.push_back({s.name, chart::Swatch::line, s.colour});
  plot.series = std::move(series);
  figure.plots = {plot};
  figure.legend_place = chart::LegendPlace::top_right;
  figure.plot_width = 340;
  figure.plot_height = 160;
  return figure;
}

// The charts: one column of `rows` each, against the frame's simulated time.
std::vector<chart::Figure> report_charts(const std::vector<FrameStats>& rows) {
  std::vector<double> t;
  std::vector<double> strain_pct, kinetic, elastic, gravity, sim_ms, render_ms;
  for (const FrameStats& r : rows) {
    t.push_back(r.diagnostics.time_s);
    strain_pct.push_back(100.0 * r.diagnostics.max_strain);
    kinetic.push_back(r.diagnostics.kinetic_energy_J);
    elastic.push_back(r.diagnostics.elastic_energy_J);
    gravity.push_back(r.diagnostics.gravity_energy_J);
    sim_ms.push_back(r.sim_ms);
    render_ms.push_back(r.render_ms);
  }
  const auto colour = chart::series_colour;
  return {line_chart("Largest strain", "strain [%]", t, {{"max_strain", colour(0), {}, strain_pct}}),
          line_chart("Kinetic and elastic energy", "energy [J]", t,
                     {{"kinetic", colour(1), {}, kinetic}, {"elastic", colour(2), {}, elastic}}),
          line_chart("Gravitational energy", "energy [J]", t,
                     {{"gravitational", colour(3), {}, gravity}}),
          line_chart("Wall time per frame", "time [ms]", t,
                     {{"simulation", colour(0), {}, sim_ms}, {"render", colour(1), {}, render_ms}})};
}

}  // namespace

std::string frame_file_name(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", frame);
  return name;
}

std::vector<int> evenly_spaced_frames(int frames, int count) {
  std::vector<int> out;
  if (frames < 1 || count < 1) return out;
  if (frames <= count || count == 1) {
    for (int k = frames <= count ? 1 : frames; k <= frames; ++k) out.push_back(k);
    return out;
  }
  // Frame 1 + round(k (frames − 1) / (count − 1)): distinct, since the spacing is ≥ 1.
  for (int k = 0; k < count; ++k)
    out.push_back(1 + static_cast<int>(std::lround(static_cast<double>(k) * (frames - 1) /
                                                   (count - 1))));
  return out;
}

render::Image frame_contact_sheet(const fs::path& dir, const std::vector<int>& frames, double fps,
                                  int max_width_px) {
  if (frames.empty()) throw std::runtime_error(dir.string() + ": no frames for a contact sheet");
  std::vector<render::Image> images;
  for (const int f : frames) images.push_back(render::read_image(dir / frame_file_name(f)));
  const int n = static_cast<int>(frames.size());
  const int columns = contact_sheet_columns(n, images[0].width(), images[0].height());
  const int tile_width = std::max(16, max_width_px / columns - 8);
  std::vector<render::Image> thumbnails;
  std::vector<std::string> labels;
  for (int k = 0; k < n; ++k) {
    thumbnails.push_back(thumbnail(images[static_cast<std::size_t>(k)], tile_width));
    labels.push_back("t = " + fixed(frames[static_cast<std::size_t>(k)] / fps, 2) + " s");
  }
  return contact_sheet(thumbnails, labels, columns);
}

fs::path write_run_report(const fs::path& dir, const Scene& scene, const std::string& command_line,
                          const std::vector<FrameStats>& rows) {
  if (rows.empty()) throw std::runtime_error(dir.string() + ": no frames to report");
  const int last = rows.back().frame;
  const std::vector<int> shown = evenly_spaced_frames(last, report_sheet_frames);
  render::write_png(frame_contact_sheet(dir, shown, scene.fps), dir / kSheetName);

  double max_strain = 0.0, sim_ms = 0.0, render_ms = 0.0;
  long unconverged = 0;
  for (const FrameStats& r : rows) {
    max_strain = std::max(max_strain, r.diagnostics.max_strain);
    sim_ms += r.sim_ms;
    render_ms += r.render_ms;
    unconverged += r.steps.unconverged_steps;
  }
  const std::string last_name = frame_file_name(last);
  std::string html;
  html += "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>weft report: " +
          base::html_escape(scene.name) + "</title>\n<style>body{font-family:sans-serif;max-width:"
          "1000px;margin:1em auto;padding:0 1em}img{max-width:100%}pre{background:#f4f4f4;"
          "padding:.5em;overflow-x:auto;white-space:pre-wrap}td{padding:0 1em 0 0}"
          ".charts svg{margin:0 8px 8px 0}</style></head><body>\n";
  html += "<h1>weft report: " + base::html_escape(scene.name) + "</h1>\n";
  html += "<p>" + base::html_escape(scene.description) + "</p>\n";
  html += "<h2>Command</h2>\n<pre><code>" + base::html_escape(command_line) + "</code></pre>\n";
  html += "<p>Files: <a href=\"scene.json\">scene.json</a> · <a href=\"stats.csv\">stats.csv</a>"
          " · <a href=\"run.txt\">run.txt</a></p>\n";
  html += "<table>\n<tr><td>frames</td><td>" + std::to_string(last) + " at " +
          fixed(scene.fps, 3 * (scene.fps != std::floor(scene.fps))) + " fps (" +
          fixed(rows.back().diagnostics.time_s, 3) + " s simulated)</td></tr>\n";
  html += "<tr><td>cloth</td><td>" +
          (scene.mesh || scene.grid.disc_edge == sim::DiscEdge::smooth
               ? cloth_size_text(scene)
               : std::to_string(scene.grid.nu) + " × " + std::to_string(scene.grid.nv) +
                     " vertices") +
          "</td></tr>\n";
  html += "<tr><td>largest strain</td><td>" + fixed(100.0 * max_strain, 3) + " %</td></tr>\n";
  html += "<tr><td>steps that missed the projection tolerance</td><td>" +
          std::to_string(unconverged) + "</td></tr>\n";
  html += "<tr><td>wall time</td><td>simulation " + base::html_escape(format_duration(sim_ms / 1e3)) +
          ", rendering " + base::html_escape(format_duration(render_ms / 1e3)) + "</td></tr>\n</table>\n";
  html += "<h2>Frames</h2>\n<p>" + std::to_string(shown.size()) +
          " frames, evenly spaced in time (<code>" + kSheetName + "</code>):</p>\n<img src=\"" +
          kSheetName + "\" alt=\"contact sheet\">\n";
  html += "<h2>Last frame</h2>\n<p>t = " + fixed(rows.back().diagnostics.time_s, 3) +
          " s (<code>" + last_name + "</code>):</p>\n<img src=\"" + last_name +
          "\" alt=\"last frame\">\n";
  html += "<h2>Per frame</h2>\n<p>The values of <a href=\"stats.csv\">stats.csv</a>, one point "
          "per frame.</p>\n<div class=\"charts\">\n";
  for (const chart::Figure& figure : report_charts(rows)) html += chart::draw_svg(figure) + "\n";
  html += "</div>\n</body></html>\n";
  const fs::path path = dir / "report.html";
  write_text(path, html);
  return path;
}

}  // namespace weft::app
