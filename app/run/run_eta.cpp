// Time left of a run (see run_eta.h).

#include "app/run/run_eta.h"

#include <string>

namespace weft::app {

void RunEta::add_simulated(double seconds) {
  m_simulated_s += seconds;
  ++m_simulated;
}

void RunEta::add_drawn(double seconds) {
  m_drawn_s += seconds;
  ++m_drawn;
}

double RunEta::seconds_left(int simulate, int draw, double drawing_done, double drawing_s) const {
  // A frame's drawing cost: the mean of those drawn, else what the one being drawn predicts.
  double draw_s = -1.0;
  if (m_drawn > 0)
    draw_s = m_drawn_s / m_drawn;
  else if (drawing_done > 0.0)
    draw_s = drawing_s / drawing_done;
  double left = 0.0;
  if (simulate > 0) {
    if (m_simulated == 0) return -1.0;
    left += simulate * (m_simulated_s / m_simulated);
  }
  if (drawing_done > 0.0) {
    // The frame being drawn: its own rate, once a tenth of it is done, predicts its rest best.
    const double current_s = drawing_done >= 0.1 || m_drawn == 0 ? drawing_s / drawing_done : draw_s;
    left += current_s > drawing_s ? current_s - drawing_s : 0.0;
  }
  if (draw > 0) {
    if (draw_s < 0.0) return -1.0;
    left += draw * draw_s;
  }
  return left;
}

FrameDrawingReport::FrameDrawingReport(render::Renderer& renderer, Progress& progress,
                                       const RunEta& eta, int done, int frame, int simulate,
                                       int draw)
    : m_renderer(renderer) {
  m_renderer.set_frame_progress([this, &progress, &eta, done, frame, simulate, draw,
                                 percent = -1](double share) mutable {
    const int now = static_cast<int>(100.0 * share);
    if (now == percent) return;
    percent = now;
    progress.update(done, "drawing frame " + std::to_string(frame) + ": " + std::to_string(now) + " %",
                    eta.seconds_left(simulate, draw, share, m_watch.seconds()));
  });
}

FrameDrawingReport::~FrameDrawingReport() {
  m_renderer.set_frame_progress({});
}

}  // namespace weft::app
