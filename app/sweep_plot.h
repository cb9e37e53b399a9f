#pragma once
// weft sweep's chart: error against wall time on log–log axes, the Pareto front connected, each
// run numbered and listed in a legend with its settings.

#include <string>
#include <vector>

#include "render/image.h"

namespace weft::app {

struct PlotRun {
  double time_s = 0.0;   // simulation wall time, x
  double error_m = 0.0;  // RMS distance to the reference, y
  std::string label;     // its settings, e.g. "resolution=[21,21] time_step=1 ms"
  bool pareto = false;
  bool reference = false;  // error 0 by definition: drawn on the bottom edge of the plot
  bool diverged = false;   // not drawn; listed in the legend
};

// Runs are numbered from 1 in the order given (the rows of sweep.csv).
render::Image sweep_plot(const std::vector<PlotRun>& runs, const std::string& title);

// A tick label for a value on a log axis: "0.001" … "1000", else "2e-05" style ("2e-5").
std::string log_tick_label(double value);

}  // namespace weft::app
