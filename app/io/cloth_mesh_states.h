#pragma once
// The meshes of a remeshed run's saved states (weft run --save-states with simulation.remesh;
// docs/checkpoints.md): beside state_NNNN.npy, cloth_mesh_NNNN.weft holds the cloth's mesh of
// frame NNNN — written for frame 0, for every frame in whose steps the cloth was remeshed and
// for the first frame of a resumed run —
// so that the mesh of frame k is the newest cloth_mesh_j.weft with j ≤ k. weft render draws
// each state on its own mesh with it.
//
// A file is the line "weft cloth mesh 1\n" (the format's version) and sim::save_cloth_mesh's
// bytes (native doubles and integers: read back bit for bit on the same platform).

#include <filesystem>
#include <optional>

#include "sim/grid.h"

namespace weft::app {

inline constexpr const char* cloth_mesh_state_prefix = "cloth_mesh";
inline constexpr const char* cloth_mesh_state_extension = "weft";

// Writes dir/cloth_mesh_NNNN.weft atomically. Throws std::runtime_error naming the path.
void write_cloth_mesh_state(const std::filesystem::path& dir, int frame, const sim::ClothMesh& mesh);

// The meshes of the states in one folder, read as frames ask for them.
class ClothMeshStates {
 public:
  // `scene_mesh` gives the source name kept in the meshes read (messages).
  ClothMeshStates(std::filesystem::path dir, const sim::ClothMesh& scene_mesh);
  // The mesh of frame k: the newest cloth_mesh_j.weft, j ≤ k. Throws InputError naming the
  // folder when there is none (states of a run without --save-states' meshes), or naming the
  // file when it is not one of this format (another version, damaged).
  const sim::ClothMesh& at(int frame);

 private:
  std::filesystem::path m_dir;
  sim::ClothMesh m_mesh;
  std::optional<int> m_file_frame;  // the frame of the file m_mesh was read from
  int m_asked = -1;                 // the frame last asked for
};

}  // namespace weft::app
