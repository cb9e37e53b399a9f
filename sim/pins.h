#pragma once
// Pin selections: which cloth vertices are held fixed.

#include <string>
#include <variant>
#include <vector>

#include "sim/grid.h"

namespace weft::sim {

struct PinVertex { Index index; };          // flat vertex index
struct PinGrid { Index i, j; };             // grid coordinates, i along warp, j along weft (a grid only)
struct PinCorner { std::string name; };     // "u0v0", "u1v0", "u0v1", "u1v1" (a grid only)
// Fractions of the cloth size, 0..1, inclusive: of the grid's extent, or of the bounding box
// of the material coordinates on a mesh without a grid.
struct PinRegion { double u0, u1, v0, v1; };
// A box, inclusive, m: of material coordinates (u, v; the z bounds ignored), or of the start
// positions in the world (ClothMesh::start()).
struct PinBox {
  Vec3 lo, hi;
  bool world = false;
};
// Vertices the scene chose by what the mesh file gives them (app/scene/scene_cloth.cpp: a vertex
// colour); `what` names the selection in errors.
struct PinVertexSet {
  std::vector<Index> indices;
  std::string what;
};
using PinSpec = std::variant<PinVertex, PinGrid, PinCorner, PinRegion, PinBox, PinVertexSet>;

// The corner names, for error messages.
const std::vector<std::string>& corner_names();

// Sorted, unique vertex indices. Throws std::invalid_argument with a message naming the pin
// (e.g. "pin 2: vertex 5000 is outside the mesh (0..1023)") when a pin selects nothing or lies
// outside the mesh.
std::vector<Index> resolve_pins(const std::vector<PinSpec>& pins, const ClothMesh& mesh);

}  // namespace weft::sim
