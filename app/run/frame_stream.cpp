// The frame stream (see frame_stream.h).

#include "app/run/frame_stream.h"

#include <chrono>

namespace weft::app {

double frame_time_s(const Scene& scene, int frame) { return frame / scene.fps; }

FrameStreamEnd stream_frames(const Scene& scene, sim::Simulator& simulator,
                             const std::function<StreamControl(const Frame&)>& on_frame,
                             int first_frame) {
  FrameStreamEnd end;
  end.frames = first_frame - 1;
  for (int k = first_frame; k <= scene.frames; ++k) {
    const auto start = std::chrono::steady_clock::now();
    if (scene.dynamics) {
      try {
        simulator.advance(frame_time_s(scene, k) - simulator.state().time_s);
      } catch (const sim::DivergenceError& e) {
        end.divergence = FrameDivergence{k, e};
        return end;
      }
    }
    const double sim_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double time_s = scene.dynamics ? simulator.state().time_s : frame_time_s(scene, k);
    const StreamControl control =
        on_frame ? on_frame(Frame{k, time_s, sim_s, simulator}) : StreamControl::go_on;
    end.frames = k;
    if (control == StreamControl::stop) {
      end.stopped = k < scene.frames;
      break;
    }
  }
  return end;
}

}  // namespace weft::app
