// The meshes beside a remeshed run's saved states (see cloth_mesh_states.h).

#include "app/io/cloth_mesh_states.h"

#include <fstream>
#include <sstream>
#include <string>

#include "app/io/output_files.h"
#include "app/io/run_checkpoint.h"
#include "base/atomic_file.h"
#include "base/file_read.h"
#include "app/io/input_error.h"
#include "sim/cloth_mesh_archive.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kClothMeshMagic = "weft cloth mesh 1\n";

fs::path cloth_mesh_state_path(const fs::path& dir, int frame) {
  return dir / numbered_file_name(cloth_mesh_state_prefix, frame, cloth_mesh_state_extension);
}

}  // namespace

void write_cloth_mesh_state(const fs::path& dir, int frame, const sim::ClothMesh& mesh) {
  sim::StateWriter out;
  sim::save_cloth_mesh(out, mesh);
  const std::string bytes = std::string(kClothMeshMagic) + out.bytes();
  base::write_file_atomically(cloth_mesh_state_path(dir, frame), bytes);
}

ClothMeshStates::ClothMeshStates(fs::path dir, const sim::ClothMesh& scene_mesh)
    : m_dir(std::move(dir)), m_mesh(scene_mesh) {}

const sim::ClothMesh& ClothMeshStates::at(int frame) {
  // The files between the last frame asked for and this one, newest first; all from this frame
  // down when going back.
  const int lowest = frame >= m_asked && m_file_frame ? m_asked + 1 : 0;
  m_asked = frame;
  for (int j = frame; j >= lowest; --j) {
    const fs::path path = cloth_mesh_state_path(m_dir, j);
    if (!fs::exists(path)) continue;
    if (m_file_frame == j) return m_mesh;
    std::string bytes;
    try {
      bytes = base::read_file_capped(path, max_checkpoint_bytes, "a saved cloth mesh");
    } catch (const base::FileReadError& e) {
      throw InputError(e.what());
    }
    if (bytes.compare(0, kClothMeshMagic.size(), kClothMeshMagic) != 0)
      throw InputError(path.string() + ": not a cloth mesh of format version 1 (weft run "
                       "--save-states writes them for a remeshed run)");
    try {
      sim::StateReader reader(std::string_view(bytes).substr(kClothMeshMagic.size()), path.string());
      sim::restore_cloth_mesh(reader, m_mesh);
      if (!reader.at_end()) reader.fail("bytes after the mesh");
    } catch (const sim::StateArchiveError& e) {
      throw InputError(std::string(e.what()) + " (a damaged cloth mesh)");
    }
    m_file_frame = j;
    return m_mesh;
  }
  if (!m_file_frame)
    throw InputError(m_dir.string() + ": no cloth_mesh_NNNN.weft at or before frame " +
                     std::to_string(frame) + ": the scene remeshes its cloth, and weft run "
                     "--save-states writes each frame's mesh beside the states");
  return m_mesh;
}

}  // namespace weft::app
