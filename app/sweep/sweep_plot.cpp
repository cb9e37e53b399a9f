// The sweep chart as a chart::Figure: a log–log plot with the runs as numbered markers, the
// Pareto front as a line (dashed towards a run on the bottom edge), and a legend naming each
// run's settings.

#include "app/sweep/sweep_plot.h"

#include <algorithm>

namespace weft::app {

namespace {

using chart::LegendEntry;
using chart::Series;
using chart::Swatch;

const chart::Rgb8 kPareto = chart::okabe_ito::vermillion;
const chart::Rgb8 kDominated = chart::okabe_ito::blue;
constexpr std::size_t kMaxRunRows = 30;

// The Pareto front, fastest first: solid between runs with an error, dashed towards a run on
// the bottom edge (error 0, off the log axis).
std::vector<Series> front_lines(const std::vector<PlotRun>& runs) {
  std::vector<std::size_t> front;
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (runs[k].pareto && !runs[k].diverged && !runs[k].failed) front.push_back(k);
  std::sort(front.begin(), front.end(),
            [&](std::size_t a, std::size_t b) { return runs[a].time_s < runs[b].time_s; });
  std::vector<Series> lines;
  for (std::size_t k = 1; k < front.size(); ++k) {
    const PlotRun &a = runs[front[k - 1]], &b = runs[front[k]];
    Series s;
    s.name = "pareto_front";
    s.colour = kPareto;
    s.line_width = 2.0;
    s.dashed = !(a.error_m > 0.0 && b.error_m > 0.0);
    s.x = {a.time_s, b.time_s};
    s.y = {a.error_m, b.error_m};
    lines.push_back(s);
  }
  return lines;
}

// The runs of one kind as markers labelled with their numbers.
Series markers(const std::vector<PlotRun>& runs, const char* name, bool pareto, bool reference) {
  Series s;
  s.name = name;
  s.line_width = 0.0;
  s.marker = reference ? chart::Marker::square : pareto ? chart::Marker::disc : chart::Marker::ring;
  s.colour = reference ? chart::kInk : pareto ? kPareto : kDominated;
  s.label_colour = pareto ? kPareto : chart::kInk;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const PlotRun& r = runs[k];
    const bool on_edge = !(r.error_m > 0.0);
    if (r.diverged || r.failed || r.pareto != pareto || on_edge != reference) continue;
    s.x.push_back(r.time_s);
    s.y.push_back(r.error_m);  // ≤ 0 falls on the log axis' low end
    s.point_labels.push_back(std::to_string(k + 1));
  }
  return s;
}

std::vector<LegendEntry> legend(const std::vector<PlotRun>& runs) {
  std::vector<LegendEntry> out{
      {"Pareto-optimal (front connected; dashed to the reference)", Swatch::disc, kPareto},
      {"dominated: another run is faster and closer", Swatch::ring, kDominated},
      {"reference (error 0): on the bottom edge", Swatch::square, chart::kInk},
      {""},
      {"run   settings"}};
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (k + 1 == kMaxRunRows && runs.size() > kMaxRunRows) {
      out.push_back({"… " + std::to_string(runs.size() - k) + " more in sweep.csv"});
      break;
    }
    const PlotRun& r = runs[k];
    std::string line = std::to_string(k + 1) + (k + 1 < 10 ? "      " : "    ") + r.label;
    if (r.reference) line += " (reference)";
    if (r.diverged) line += " (diverged)";
    if (r.failed) line += " (failed: no result)";
    out.push_back({line, Swatch::none, {}, r.diverged || r.failed ? chart::kLightGrey : r.pareto ? kPareto : chart::kInk});
  }
  out.push_back({""});
  for (const char* note : {"error: RMS distance from the reference at the same",
                           "material points (bilinear), after the last frame",
                           "time: simulation steps only (no set-up, no rendering)"})
    out.push_back({note, Swatch::none, {}, chart::kGrey});
  return out;
}

}  // namespace

chart::Figure sweep_chart(const std::vector<PlotRun>& runs, const std::string& title) {
  // On the axes: finished runs with a positive error. The reference (and any run that matches
  // it exactly) sits on the bottom edge at its time.
  std::vector<double> times, errors;
  for (const PlotRun& r : runs) {
    if (r.diverged || r.failed) continue;
    times.push_back(r.time_s);
    if (r.error_m > 0.0) errors.push_back(r.error_m);
  }
  chart::Plot plot;
  plot.x = chart::Axis::log_fit("simulation wall time [s]", times);
  plot.y = chart::Axis::log_fit("RMS distance to the reference at the last frame [m]", errors);
  plot.x.grid = plot.y.grid = true;
  plot.series = front_lines(runs);
  // Dominated runs first, so that the front's markers stay on top.
  plot.series.push_back(markers(runs, "dominated", false, false));
  plot.series.push_back(markers(runs, "pareto", true, false));
  plot.series.push_back(markers(runs, "reference", false, true));
  plot.series.push_back(markers(runs, "reference", true, true));

  chart::Figure figure;
  figure.title = title;
  figure.plots = {plot};
  figure.plot_width = 520;
  figure.plot_height = 490;
  figure.legend = legend(runs);
  figure.legend_place = chart::LegendPlace::right;
  figure.legend_width = 440;
  return figure;
}

}  // namespace weft::app
