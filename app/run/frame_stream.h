#pragma once
// The frames of a scene, one way for every command (weft run, measure, turntable, sweep,
// gallery and the golden-image tests): frame k (1-based) is the simulator advanced to the time
// k / fps, one frame after another, each handed to a callback as soon as it is simulated.
// Without dynamics (simulation.dynamics: false) the simulator does not run and every frame
// shows the initial shape.

#include <functional>
#include <optional>

#include "app/scene/scene.h"
#include "sim/simulator.h"

namespace weft::app {

// One frame, valid during the callback.
struct Frame {
  int index = 0;         // 1..scene.frames
  double time_s = 0.0;   // simulated time: the simulator's, or index / fps without dynamics
  double sim_s = 0.0;    // wall time advance() took for this frame, seconds
  const sim::Simulator& simulator;  // its state is the frame's
};

// Where a stream stopped early: the frame that was being simulated and the simulator's
// divergence (its step, time and quantity). Frames before it were handed out.
struct FrameDivergence {
  int frame = 0;
  sim::DivergenceError error;
};

struct FrameStreamEnd {
  int frames = 0;  // frames handed to the callback
  std::optional<FrameDivergence> divergence;  // none: every frame of the scene was made
};

// Simulates frames 1..scene.frames on `simulator` (made by make_simulator(scene), at its start)
// and calls on_frame for each; `stop`, if given, is asked after each frame and ends the stream
// early when it says so (weft measure --until-settled). A divergence stops the stream and is
// returned; what on_frame throws propagates. A simulator restored from a checkpoint of frame
// k (weft run --resume) streams from first_frame = k + 1.
[[nodiscard]] FrameStreamEnd stream_frames(const Scene& scene, sim::Simulator& simulator,
                                           const std::function<void(const Frame&)>& on_frame,
                                           const std::function<bool()>& stop = {},
                                           int first_frame = 1);

// The time of frame k of the scene, seconds: k / fps.
double frame_time_s(const Scene& scene, int frame);

}  // namespace weft::app
