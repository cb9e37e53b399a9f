#pragma once
// weft sweep's chart: error against wall time on log–log axes, the Pareto front connected, each
// run numbered and listed in a legend with its settings. A chart::Figure (chart/chart.h).

#include <string>
#include <vector>

#include "chart/chart.h"

namespace weft::app {

struct PlotRun {
  double time_s = 0.0;   // simulation wall time, x
  double error_m = 0.0;  // RMS distance to the reference, y
  std::string label;     // its settings, e.g. "resolution=[21,21] time_step=1 ms"
  bool pareto = false;
  bool reference = false;  // error 0 by definition: drawn on the bottom edge of the plot
  bool diverged = false;   // not drawn; listed in the legend
  bool failed = false;     // no result (a Slurm task that did not finish): as diverged
};

// Runs are numbered from 1 in the order given (the rows of sweep.csv).
chart::Figure sweep_chart(const std::vector<PlotRun>& runs, const std::string& title);

}  // namespace weft::app
