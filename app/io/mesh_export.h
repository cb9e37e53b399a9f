#pragma once
// Cloth frames written as mesh files through assimp's exporter (weft run --export-meshes): OBJ,
// binary PLY or glTF 2.0, with vertex normals and UVs = material coordinates (warp, weft), m.

#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "render/render_mesh.h"
#include "render/texture.h"

namespace weft::app {

enum class MeshFormat { obj, ply, gltf };

// "obj", "ply" or "gltf"; anything else throws InputError naming `option` and the choices.
MeshFormat parse_mesh_format(const std::string& text, const std::string& option);

// The file extension without the dot: "obj", "ply", "gltf".
const char* mesh_extension(MeshFormat format);

// Which axis of the file points up: y (Blender's OBJ import, glTF, most tools) or weft's z.
enum class UpAxis { y, z };

// "y" or "z"; anything else throws InputError naming `option`.
UpAxis parse_up_axis(const std::string& text, const std::string& option);

// What a mesh file carries beside the geometry.
struct MeshExportOptions {
  // OBJ and PLY: y writes the turn (x, y, z) ↦ (x, z, −y) into the vertex data (positions and
  // normals), z keeps weft's coordinates. A glTF is y-up whatever this says (its root node
  // carries the turn; its vertex data stays in weft's coordinates).
  UpAxis up = UpAxis::y;
  Eigen::Vector3f base_color{0.80f, 0.25f, 0.20f};  // linear 0..1: OBJ's Kd, glTF's baseColorFactor
  // OBJ and glTF: the base colour texture's file, relative to the mesh file ("" none; an OBJ's
  // MTL names it as map_Kd, a glTF as baseColorTexture). With it the UVs are texture
  // coordinates (s, t) of the texture's placement on the mesh (render/texture.h: repeats, or
  // the piece's bounding box for TextureMapping::piece), written (s, 1 − t) in a glTF (its v
  // runs down the image), and the base colour is white; without it, and in a PLY, UVs are
  // material coordinates in metres.
  std::string texture_uri;
  Eigen::Vector2d texture_repeat_m{0.1, 0.1};
  render::TextureMapping texture_mapping = render::TextureMapping::repeat;
};

// Writes the mesh's triangles, positions (m), normals and UVs to `path` (an OBJ also writes
// PATH.mtl beside it; a glTF writes its buffer to PATH's stem + .bin), with one material of
// the options' colour (and texture). Throws std::runtime_error "PATH: cannot export mesh:
// <assimp's reason>" when it cannot, and std::invalid_argument for an empty or malformed mesh
// (render::validate). The files are written whole: into a folder PATH.partial, then moved
// beside PATH (companions first).
void export_mesh(const render::RenderMesh& mesh, MeshFormat format,
                 const std::filesystem::path& path, const MeshExportOptions& options = {});

}  // namespace weft::app
