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

// What the callback says after each frame: go on to the next one, or end the stream there
// (weft measure --until-settled once the cloth has settled; weft run when a frame fails a check
// the scene makes an error, simulation.self_collision.crossings).
enum class StreamControl { go_on, stop };

struct FrameStreamEnd {
  int frames = 0;  // frames handed to the callback
  std::optional<FrameDivergence> divergence;  // none: every frame the stream was to make was made
  bool stopped = false;  // the callback ended the stream after `frames` (before the scene's last)
};

// Simulates frames first_frame..scene.frames on `simulator` (made by make_simulator(scene), at
// its start) and calls on_frame, if given, for each; when on_frame returns StreamControl::stop
// the stream ends after that frame. A divergence stops the stream and is returned; what on_frame
// throws propagates. A simulator restored from a checkpoint of frame k (weft run --resume), or
// one a stream stopped after frame k, streams on from first_frame = k + 1.
[[nodiscard]] FrameStreamEnd stream_frames(
    const Scene& scene, sim::Simulator& simulator,
    const std::function<StreamControl(const Frame&)>& on_frame, int first_frame = 1);

// The time of frame k of the scene, seconds: k / fps.
double frame_time_s(const Scene& scene, int frame);

}  // namespace weft::app
