#pragma once
// Checks of a mesh file's bytes made before assimp reads them, for what assimp would crash on
// or spend minutes and gigabytes on: a PLY's header and body are walked (element counts against
// the file's size and the limits, each face's list count and vertex indices), an OBJ's vertex
// and face lines are counted and its texture coordinates must be finite (assimp reads `vt nan
// 0` as `vt 0 0`), a glTF's accessors and primitives and an FBX's scopes and model hierarchy
// are checked (gltf_precheck.h, fbx_precheck.h). STL is bounded by the file size alone
// (max_mesh_file_bytes, app/io/mesh_file_io.h).

#include <cstdint>
#include <string_view>

namespace weft::app {

// At most this many vertices and faces in a mesh file (each), checked before the load where
// the file says (PLY's header, OBJ's lines) and after it for every format: 2²¹, a cloth of
// 1448² vertices, far beyond what weft simulates in a day on a workstation.
inline constexpr std::uint64_t max_mesh_elements = std::uint64_t{1} << 21;

// Throws MeshFileError "NAME: …" naming what is wrong (the element, face or line) for a PLY or
// OBJ file (by `extension`, lower case with its dot) whose content is malformed or over the
// limits, for a GLB whose header or chunk lengths run past the file, and for a glTF (.gltf, or a
// .glb's JSON chunk) whose accessors or primitives assimp would trip on (gltf_precheck.h), and
// for an FBX whose scopes or models assimp would recurse through without end (fbx_precheck.h);
// any other extension passes.
void precheck_mesh_bytes(std::string_view bytes, const std::string& extension,
                         const std::string& name);

}  // namespace weft::app
