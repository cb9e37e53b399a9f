// What `weft fit` writes (see fit_report.h).

#include "app/fit/fit_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "app/report/contact_sheet.h"
#include "app/io/finite_outputs.h"
#include "app/io/output_files.h"
#include "app/io/version.h"
#include "base/html_escape.h"
#include "chart/chart.h"
#include "render/photo_compare/photo_compare.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

std::string g(double v, int digits = 4) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*g", digits, v);
  return text;
}

std::string value_text(const FitParameter& p, double v) {
  return g(v) + (p.unit.empty() ? "" : " " + p.unit);
}

std::string band_text(const FitParameter& p, const FittedParameter& f) {
  return (f.low_open ? "≤ " : "") + g(f.band_low, 3) + " … " + (f.high_open ? "≥ " : "") +
         g(f.band_high, 3) + (p.unit.empty() ? "" : " " + p.unit);
}

chart::Figure convergence_figure(const FitSpec& spec, const FitResult& r) {
  std::vector<double> n, f, best;
  for (std::size_t k = 0; k < r.evaluations.size(); ++k) {
    n.push_back(static_cast<double>(k + 1));
    f.push_back(r.evaluations[k].objective);
    best.push_back(k == 0 ? f[0] : std::min(best.back(), f[k]));
  }
  chart::Plot plot;
  plot.x = chart::Axis::linear_fit("evaluation", n);
  const bool positive = *std::min_element(f.begin(), f.end()) > 0.0;
  plot.y = positive ? chart::Axis::log_fit(objective_label(spec.target), f)
                    : chart::Axis::linear_fit(objective_label(spec.target), f);
  plot.y.grid = true;
  chart::Series each("objective", chart::series_colour(1), n, f, 0.0);
  each.marker = chart::Marker::disc;
  each.marker_radius = 3.0;
  plot.series = {each, chart::Series("best so far", chart::series_colour(0), n, best)};
  chart::Figure figure;
  figure.title = "weft fit " + spec.name + ": convergence";
  figure.subtitle = std::to_string(r.evaluations.size()) + " evaluations, " + r.stop_reason;
  figure.plots = {plot};
  figure.legend = {{"objective of each evaluation", chart::Swatch::disc, chart::series_colour(1)},
                   {"best so far", chart::Swatch::line, chart::series_colour(0)}};
  figure.plot_width = 480;
  figure.plot_height = 240;
  return figure;
}

chart::Figure profile_figure(const FitSpec& spec, const FitResult& r) {
  chart::Figure figure;
  figure.title = "weft fit " + spec.name + ": objective along each parameter";
  figure.subtitle = "the others at the optimum; band: objective ≤ optimum + " + g(r.band, 3);
  figure.columns = std::min<int>(2, static_cast<int>(r.profiles.size()));
  for (std::size_t i = 0; i < r.profiles.size(); ++i) {
    const Profile& p = r.profiles[i];
    const FitParameter& param = spec.parameters[i];
    const FittedParameter& f = r.fitted[i];
    chart::Plot plot;
    plot.title = param.name;
    plot.note = "fitted " + value_text(param, f.value);
    plot.x = chart::Axis::log_fit(param.name + (param.unit.empty() ? "" : " [" + param.unit + "]"), p.values);
    std::vector<double> ys = p.objective;
    ys.push_back(r.best.objective + r.band);
    plot.y = chart::Axis::linear_fit(objective_label(spec.target), ys);
    plot.y.grid = true;
    chart::Series curve("profile", chart::series_colour(1), p.values, p.objective);
    curve.marker = chart::Marker::disc;
    curve.marker_radius = 3.0;
    const double level = r.best.objective + r.band;
    chart::Series threshold("band level", chart::series_colour(2),
                            {p.values.front(), p.values.back()}, {level, level}, 1.0);
    threshold.dashed = true;
    chart::Series band("band", chart::series_colour(0), {f.band_low, f.band_high}, {level, level}, 3.0);
    chart::Series best("optimum", chart::series_colour(0), {f.value}, {r.best.objective}, 0.0);
    best.marker = chart::Marker::ring;
    best.marker_radius = 5.0;
    plot.series = {threshold, band, curve, best};
    figure.plots.push_back(plot);
  }
  figure.legend = {{"objective", chart::Swatch::disc, chart::series_colour(1)},
                   {"optimum", chart::Swatch::ring, chart::series_colour(0)},
                   {"band", chart::Swatch::line, chart::series_colour(0)},
                   {"optimum + band", chart::Swatch::dashed_line, chart::series_colour(2)}};
  return figure;
}

nlohmann::ordered_json result_json(const FitSpec& spec, const FitResult& r) {
  nlohmann::ordered_json j;
  j["fit"] = spec.source;
  j["objective"] = {{"name", objective_label(spec.target)}, {"value", r.best.objective}};
  j["band"] = r.band;
  j["evaluations"] = r.evaluations.size() + r.profile_evaluations.size();
  j["stop_reason"] = r.stop_reason;
  j["settled"] = r.best.settled;
  for (std::size_t i = 0; i < spec.parameters.size(); ++i) {
    const FitParameter& p = spec.parameters[i];
    nlohmann::ordered_json q = {{"name", p.name}, {"unit", p.unit}, {"start", p.start},
                                {"value", r.best.values[i]}};
    if (i < r.profiles.size())
      q["band"] = {{"low", r.fitted[i].band_low}, {"high", r.fitted[i].band_high},
                   {"low_open", r.fitted[i].low_open}, {"high_open", r.fitted[i].high_open}};
    j["parameters"].push_back(q);
  }
  for (const auto& [name, value] : r.best.measures) j["measures"][name] = value;
  return j;
}

// The photo, the fitted render and the overlay of both silhouettes' outlines; returns the
// HTML section showing them.
std::string write_photo_images(const fs::path& dir, FitProblem& problem, const FitResult& r) {
  const auto& photo = std::get<PhotoTarget>(problem.spec().target);
  const Scene scene = problem.scene_at(r.best.values);
  const Settled settled = settle_to_rest(scene, problem.spec().settle);
  render::PhotoComparison c;
  c.photo_mask = photo.mask;
  c.render_mask = problem.silhouette(scene, *settled.simulator);
  const render::Image fitted = problem.render_look(scene, *settled.simulator);
  const render::Image overlay = render::outline_overlay(photo.photo, c);
  render::write_png(photo.photo, dir / "photo.png");
  render::write_png(fitted, dir / "fitted_render.png");
  render::write_png(overlay, dir / "overlay.png");
  // photo | fitted render | overlay, labelled with the fitted values and the measures.
  std::string measures;
  for (const auto& [name, value] : r.best.measures) measures += (measures.empty() ? "" : ", ") + name + " " + g(value, 3);
  const int width = std::min(photo.photo.width(), 560);
  render::write_png(contact_sheet({thumbnail(photo.photo, width), thumbnail(fitted, width),
                                   thumbnail(overlay, width)},
                                  {"photo", "fitted: " + describe_values(problem.spec(), r.best.values),
                                   measures},
                                  3),
                    dir / "comparison.png");
  return "<h2>Photo, fitted render, overlay</h2>\n<p>The photo (" +
         base::html_escape(photo.image_path.string()) +
         "), the fitted cloth through the scene's camera, and the outlines of the photo's "
         "silhouette (cyan) and the fitted cloth's (magenta) on the photo.</p>\n"
         "<img src=\"comparison.png\" alt=\"photo, fitted render and overlay\">\n"
         "<p>Full size: <a href=\"photo.png\">photo.png</a> · <a href=\"fitted_render.png\">"
         "fitted_render.png</a> · <a href=\"overlay.png\">overlay.png</a></p>\n";
}

std::string report_html(const FitSpec& spec, const FitResult& r, const std::string& command_line,
                        const std::string& target_section) {
  std::string html =
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>weft fit: " +
      base::html_escape(spec.name) +
      "</title>\n<style>body{font-family:sans-serif;max-width:1100px;margin:1em auto;padding:0 "
      "1em}img{max-width:100%;margin:4px 0}pre{background:#f4f4f4;padding:.5em;white-space:"
      "pre-wrap}td,th{padding:0 1em 0 0;text-align:left}</style></head><body>\n";
  html += "<h1>weft fit: " + base::html_escape(spec.name) + "</h1>\n<p>" +
          base::html_escape(spec.description) + "</p>\n";
  html += "<h2>Command</h2>\n<pre><code>" + base::html_escape(command_line) + "</code></pre>\n";
  html += "<p>Files: <a href=\"fit.csv\">fit.csv</a> · <a href=\"fit_result.json\">fit_result.json</a>"
          " · <a href=\"fitted_scene.json\">fitted_scene.json</a></p>\n";
  html += "<h2>Fitted values</h2>\n<table>\n<tr><th>parameter</th><th>start</th><th>fitted</th>"
          "<th>sensitivity band</th></tr>\n";
  for (std::size_t i = 0; i < spec.parameters.size(); ++i) {
    const FitParameter& p = spec.parameters[i];
    html += "<tr><td>" + p.name + "</td><td>" + base::html_escape(value_text(p, p.start)) +
            "</td><td>" + base::html_escape(value_text(p, r.best.values[i])) + "</td><td>" +
            (i < r.profiles.size() ? base::html_escape(band_text(p, r.fitted[i])) : "not profiled") + "</td></tr>\n";
  }
  html += "</table>\n<p>Objective (" + base::html_escape(objective_label(spec.target)) + "): " +
          g(r.best.objective) + "; band: where the profile stays ≤ optimum + " + g(r.band, 3) +
          ". " + std::to_string(r.evaluations.size()) + " evaluations (" +
          base::html_escape(r.stop_reason) + ") and " + std::to_string(r.profile_evaluations.size()) +
          " for the profiles; each a settle to rest by dynamic relaxation (" +
          std::to_string(r.best.iterations) + " iterations, ‖R‖/‖Mg‖ = " + g(r.best.residual, 2) +
          (r.best.settled ? "" : ", NOT settled") + " at the optimum).</p>\n<table>\n";
  for (const auto& [name, value] : r.best.measures)
    html += "<tr><td>" + base::html_escape(name) + "</td><td>" + g(value) + "</td></tr>\n";
  html += "</table>\n" + target_section;
  html += "<h2>Convergence and sensitivity</h2>\n<img src=\"convergence.png\" alt=\"convergence\">\n";
  if (!r.profiles.empty()) html += "<img src=\"profile.png\" alt=\"objective profiles\">\n";
  html += "</body></html>\n";
  return html;
}

}  // namespace

FitLog::FitLog(const fs::path& path, const FitSpec& spec) : m_file(path) {
  std::string header = "evaluation,phase";
  for (const FitParameter& p : spec.parameters) header += ',' + p.name;
  m_file.write(header + ",objective,settled,iterations,residual,seconds,measures\n");
}

void FitLog::write(const Evaluation& e, int number, FitPhase phase) {
  std::ostringstream m_out;
  m_out.precision(10);
  m_out << number << ',' << (phase == FitPhase::optimise ? "optimise" : "profile");
  for (const double v : e.values) m_out << ',' << v;
  m_out << ',' << e.objective << ',' << (e.settled ? 1 : 0) << ',' << e.iterations << ','
        << e.residual << ',' << e.seconds << ",\"";
  for (std::size_t k = 0; k < e.measures.size(); ++k)
    m_out << (k ? " " : "") << e.measures[k].first << '=' << e.measures[k].second;
  if (!e.failure.empty()) m_out << " failed: " << e.failure;
  m_out << "\"\n";
  m_file.write(m_out.str());
}

std::string describe_values(const FitSpec& spec, const std::vector<double>& values) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i)
    text += (i ? " " : "") + spec.parameters[i].name + "=" + value_text(spec.parameters[i], values[i]);
  return text;
}

std::string describe_measures(const Evaluation& e) {
  std::string text;
  for (const auto& [name, value] : e.measures) text += (text.empty() ? "" : " ") + name + " " + g(value);
  return text;
}

FitOutputs write_fit_outputs(const fs::path& dir, FitProblem& problem, const FitResult& r,
                             const std::string& command_line) {
  const FitSpec& spec = problem.spec();
  FitOutputs outputs;
  nlohmann::ordered_json result = result_json(spec, r);
  if (std::holds_alternative<DrapePhotosTarget>(spec.target) && r.best.failure.empty()) {
    outputs.drape_check = check_fitted_drape(problem, r.best.values);
    result["drape_photos"] = fitted_drape_json(*outputs.drape_check);
  }
  write_text(dir / "fit_result.json",
             finite_json_text(result, (dir / "fit_result.json").string()) + "\n");
  write_text(dir / "fitted_scene.json", problem.scene_at(r.best.values).text);
  write_text(dir / "fit.txt", "weft " + std::string(version()) + "\ncommand: " + command_line +
                                  "\nfit: " + spec.source + "\nscene: " + spec.base.source + "\n");
  chart::write_png(convergence_figure(spec, r), dir / "convergence.png");
  if (!r.profiles.empty()) chart::write_png(profile_figure(spec, r), dir / "profile.png");
  std::string section;
  if (std::holds_alternative<PhotoTarget>(spec.target)) section = write_photo_images(dir, problem, r);
  if (outputs.drape_check) section = write_drape_photo_outputs(dir, spec, r, *outputs.drape_check);
  outputs.report = dir / "report.html";
  write_text(outputs.report, report_html(spec, r, command_line, section));
  return outputs;
}

}  // namespace weft::app
