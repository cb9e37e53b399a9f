#pragma once
// stats.csv: one row per written frame, flushed as it is written so that a run that stops
// (divergence, interruption) keeps the rows of the frames it wrote.

#include <filesystem>
#include <fstream>

#include "sim/diagnostics.h"
#include "sim/simulator.h"

namespace weft::app {

struct FrameStats {
  int frame = 0;          // 1-based
  double sim_ms = 0.0;    // wall time simulating this frame
  double render_ms = 0.0;  // wall time rendering and writing this frame
  sim::StepStatistics steps;  // what this frame's time steps did (count, projection, solves)
  sim::Diagnostics diagnostics;
  int self_intersections = 0;  // edge–triangle crossings of the cloth at the frame's end
};

class StatsCsv {
 public:
  explicit StatsCsv(const std::filesystem::path& path);  // throws std::runtime_error
  void write(const FrameStats& row);

 private:
  std::filesystem::path m_path;
  std::ofstream m_out;
};

}  // namespace weft::app
