// Saved states (see saved_states.h).

#include "app/run/saved_states.h"

#include "app/io/input_error.h"
#include "app/io/npy_file.h"
#include "app/io/output_files.h"
#include "app/run/frame_stream.h"

namespace weft::app {

namespace fs = std::filesystem;

sim::Matrix3X read_state(const fs::path& dir, int frame, Eigen::Index vertices) {
  const fs::path path = dir / numbered_file_name("state", frame, "npy");
  if (!fs::exists(path))
    throw InputError(path.string() + ": no such state (weft run --save-states writes one per "
                                     "simulated frame)");
  sim::Matrix3X x = read_npy_points(path);
  if (x.rows() != vertices)
    throw InputError(path.string() + ": " + std::to_string(x.rows()) + " vertices, the frame's "
                     "cloth mesh has " + std::to_string(vertices) + " (another scene's states?)");
  return x;
}

double state_time_s(const Scene& scene, int frame) {
  return scene.dynamics ? frame_time_s(scene, frame) : 0.0;
}

}  // namespace weft::app
