#pragma once
// Progress of a long run on stderr: a redrawn bar on a terminal, plain lines otherwise.

#include <cstdio>
#include <string>

#include "base/timer.h"

namespace weft::app {

class Progress {
 public:
  // `stream` is usually stderr; the bar is drawn only when it is a terminal.
  Progress(std::FILE* stream, int total, std::string label);
  // Reports that `done` of `total` items are finished; `detail` is appended (e.g. "t = 1.2 s").
  void update(int done, const std::string& detail = {});
  // The same with the caller's estimate of the seconds left (negative: not known yet), for
  // items of unequal cost (app/run/run_eta.h); may be called within an item, `done` unchanged.
  void update(int done, const std::string& detail, double eta_s);
  // Ends the bar's line (on a terminal).
  void finish();
  double elapsed_s() const;

 private:
  std::FILE* m_stream;
  int m_total;
  std::string m_label;
  bool m_terminal;
  base::Stopwatch m_watch;
  double m_last_line_s = -1e9;
};

// "1 min 05 s", "12.3 s".
std::string format_duration(double seconds);

}  // namespace weft::app
