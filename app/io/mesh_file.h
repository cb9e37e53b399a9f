#pragma once
// Triangle meshes read from files with assimp: OBJ, PLY, STL, glTF/GLB, FBX and whatever else
// the installed assimp reads. Used for mesh obstacles (sim/collision/mesh_obstacle.h).

#include <array>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "sim/types.h"

namespace weft::app {

// A mesh file that cannot be used. what() reads "PATH: what went wrong".
class MeshFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct TriangleMesh {
  sim::Matrix3X vertices;                              // #V×3, in the file's length units
  std::vector<std::array<sim::Index, 3>> triangles;  // #F, indices into vertices, file's order
};

// Every mesh of the file, merged into one: polygons triangulated (by assimp), each mesh's
// vertices transformed by its node's transform composed with all its parents' (a mesh used by
// several nodes appears once per node), then vertices at exactly the same position joined into
// one (so meshes and faces that share corners share vertices, whatever normals or texture
// coordinates the file gives them; first-seen order), and triangles that join collapses (two
// equal corners) dropped. Points and lines are ignored.
// Throws MeshFileError "PATH: cannot read mesh file: <assimp's reason>" when assimp cannot
// read it (missing file, unknown format, malformed content), and "PATH: no triangles in the
// mesh file (…)" when it holds none, and "PATH: vertex V of mesh M is at (…), not a finite
// position …" for a NaN or infinite coordinate (assimp reads floats: 1e39 is infinite).
// Before assimp can trip on the file (docs/reliability.md, "Hostile mesh files"): a device,
// folder or file over max_mesh_file_bytes, a PLY whose faces or counts are wrong, more than
// max_mesh_elements vertices or faces, a companion file outside the mesh's folder — each a
// MeshFileError naming the file and what is wrong.
TriangleMesh load_triangle_mesh(const std::filesystem::path& path);

// The formats weft reads, by extension (any case): OBJ, PLY, STL, glTF (.gltf, .glb) and FBX.
// A file of another extension is refused before it is read, and the importer weft uses holds
// assimp's importers of these formats alone, so that assimp's sniffing of a file's content
// reaches no other (its 40-odd other readers are not fuzzed: docs/reliability.md).
inline constexpr const char* mesh_file_extensions[] = {".obj", ".ply", ".stl", ".gltf", ".glb",
                                                       ".fbx"};

// A mesh read with its polygons as the file gives them (for the cloth: a quad grid is kept as
// quads), and each vertex's texture coordinates and colour when every mesh of the file has them.
struct PolygonMesh {
  sim::Matrix3X vertices;                          // #V×3, in the file's length units
  std::vector<std::vector<sim::Index>> faces;      // #F polygons (≥ 3 corners), file's order
  std::vector<sim::Vec2> uv;                       // #V (channel 0), or empty: none in the file
  std::vector<Eigen::Vector3d> colour;             // #V RGB 0..1 (channel 0), or empty: none
  // The first vertex whose corners carry different texture coordinates (a UV seam: the
  // pattern is cut there though the surface is joined), or −1.
  sim::Index uv_seam_vertex = -1;
};

// The same reading as load_triangle_mesh — every mesh merged, node transforms applied, equal
// positions joined in first-seen order, collapsed corners dropped (a polygon left with fewer
// than 3 is dropped), the same errors ("no polygons" for "no triangles") — without
// triangulating. A vertex's UV and colour are those of its first corner.
PolygonMesh load_polygon_mesh(const std::filesystem::path& path);

}  // namespace weft::app
