#pragma once
// Cloth frames written as mesh files through assimp's exporter (weft run --export-meshes): OBJ,
// binary PLY or glTF 2.0, with vertex normals and UVs = material coordinates (warp, weft), m.

#include <filesystem>
#include <string>

#include "render/render_mesh.h"

namespace weft::app {

enum class MeshFormat { obj, ply, gltf };

// "obj", "ply" or "gltf"; anything else throws SceneError naming `option` and the choices.
MeshFormat parse_mesh_format(const std::string& text, const std::string& option);

// The file extension without the dot: "obj", "ply", "gltf".
const char* mesh_extension(MeshFormat format);

// Writes the mesh's triangles, positions (m), normals and UVs to `path` (an OBJ also writes
// PATH.mtl beside it; a glTF writes its buffer to PATH's stem + .bin). OBJ and PLY keep weft's
// z-up coordinates; the glTF's root node turns them to glTF's y-up (x, y, z) → (x, z, −y), so
// that viewers show the cloth upright, and the vertex data stays in weft's coordinates.
// Throws std::runtime_error "PATH: cannot export mesh: <assimp's reason>" when it cannot, and
// std::invalid_argument for an empty or malformed mesh (render::validate). The files are
// written whole: into a folder PATH.partial, then moved beside PATH (companions first).
void export_mesh(const render::RenderMesh& mesh, MeshFormat format,
                 const std::filesystem::path& path);

}  // namespace weft::app
