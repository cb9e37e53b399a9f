#pragma once
// The states a run keeps of its frames — state_NNNN.npy, the cloth's positions after frame NNNN
// (frame 0: the initial shape), and with simulation.remesh the meshes beside them
// (app/io/cloth_mesh_states.h) — and how a frame is drawn from them: weft run --save-states
// keeps them for weft render, and weft run without a camera draws its frames from them once
// the simulation has ended and the camera that frames the whole run is known.

#include <Eigen/Core>
#include <filesystem>

#include "app/scene/scene.h"
#include "sim/grid.h"

namespace weft::app {

// The positions of dir/state_NNNN.npy, checked against the frame's cloth vertex count. Throws
// InputError naming the file when there is none or it does not fit.
sim::Matrix3X read_state(const std::filesystem::path& dir, int frame, Eigen::Index vertices);

// The time frame k is drawn at: the simulator's after frame k, which advance() leaves at exactly
// k / fps (t + (k/fps − t) with t = (k−1)/fps is exact), or 0 without dynamics (the simulator
// never advances).
double state_time_s(const Scene& scene, int frame);

}  // namespace weft::app
