#pragma once
// A triangle-mesh cloth (ClothMesh without a grid) as a section of a StateWriter, and back: what
// a remeshed simulation's checkpoint holds besides its state (Simulator::save_state), and what
// weft run --save-states writes beside the positions of a remeshed run (app/io/cloth_mesh_states.h).
// Every array the simulator and the renderer use is saved as it is (material coordinates,
// triangles, rest and start positions, lumped areas, which vertices are used), so the mesh read
// back is the same bits as the one saved, not a remake of it. The name of the source (for
// messages) is not saved: the reader keeps the scene's.

#include "sim/grid.h"
#include "sim/state_archive.h"

namespace weft::sim {

// Saving a grid cloth is a bug (base::InternalError): a grid is remade from the scene, never saved.
void save_cloth_mesh(StateWriter& out, const ClothMesh& mesh);
// Reads what save_cloth_mesh wrote into `mesh` (its source is kept). Throws StateArchiveError
// naming the section when the bytes are not a mesh: sizes that disagree, a triangle corner out
// of range.
void restore_cloth_mesh(StateReader& in, ClothMesh& mesh);

}  // namespace weft::sim
