#pragma once
// The time left of a run whose frames are each simulated and only some drawn (weft run's
// --every/--last/--start/--end), drawn frames taking far longer than simulated ones (a
// ray-traced 1080p frame: tens of seconds; a simulated one: a fraction of a second). Progress's
// own estimate, elapsed × items left / items done, takes every frame to cost what the first
// did: after a first frame that was drawn, a 96-frame run drawing 4 of them was told 37 min
// instead of 1.7. Here simulation and drawing have their own mean cost per frame, measured, and
// a frame being drawn reports the share of it done (Renderer::set_frame_progress), so the
// estimate is there from the first frame's first tiles and converges as frames are done.

#include "app/io/progress.h"
#include "render/renderer.h"

namespace weft::app {

class RunEta {
 public:
  // One more frame simulated / drawn, in seconds.
  void add_simulated(double seconds);
  void add_drawn(double seconds);
  // Seconds left when `simulate` frames are still to simulate and `draw` (after the one being
  // drawn, if any) still to draw; `drawing_done` in (0, 1] is the share of the frame being
  // drawn after `drawing_s` seconds of it (0: no frame is being drawn). Negative when a part
  // that is left has no cost measured yet.
  double seconds_left(int simulate, int draw, double drawing_done = 0.0,
                      double drawing_s = 0.0) const;

 private:
  double m_simulated_s = 0.0, m_drawn_s = 0.0;
  int m_simulated = 0, m_drawn = 0;
};

// While it lives, `renderer` reports the drawing of frame `frame` on `progress`'s line (as
// item `done` of its items, "drawing frame k: p %", at most once a percent) with `eta`'s time
// left, `simulate` and `draw` frames still to come after it. `eta` is read, not changed.
class FrameDrawingReport {
 public:
  FrameDrawingReport(render::Renderer& renderer, Progress& progress, const RunEta& eta, int done,
                     int frame, int simulate, int draw);
  ~FrameDrawingReport();
  FrameDrawingReport(const FrameDrawingReport&) = delete;
  FrameDrawingReport& operator=(const FrameDrawingReport&) = delete;
  // Seconds since it began.
  double seconds() const { return m_watch.seconds(); }

 private:
  render::Renderer& m_renderer;
  base::Stopwatch m_watch;
};

}  // namespace weft::app
