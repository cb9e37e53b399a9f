#pragma once
// stats.csv: one row per written frame. The file is rewritten atomically with each row
// (app/io/output_files.h), so a run that stops (divergence, interruption) keeps the rows of the
// frames it wrote, never half a line, and a run that stops before its first frame leaves an
// earlier run's file as it was.

#include <filesystem>
#include <string>
#include <vector>

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
  long vertices = 0;  // the cloth's (used) vertices at the frame's end: changes with remeshing
};

class StatsCsv {
 public:
  explicit StatsCsv(const std::filesystem::path& path);  // writes nothing yet
  void write(const FrameStats& row);                       // throws std::runtime_error
  // Starts from the rows of a run resumed from a checkpoint (app/io/run_checkpoint.h); writes
  // them with the next row.
  void restore(const std::vector<FrameStats>& rows);
  // Writes the file anew with these rows: weft run without a camera fills in the render times
  // when it draws its frames, after the simulation.
  void rewrite(const std::vector<FrameStats>& rows);

 private:
  std::filesystem::path m_path;
  std::string m_text;  // the header and every row so far
};

}  // namespace weft::app
