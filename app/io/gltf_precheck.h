#pragma once
// The parts of a glTF 2.0 document assimp trusts (app/io/mesh_precheck.h runs this before
// assimp reads a .gltf, or a .glb's JSON chunk): every accessor's type and component type are
// glTF's own, and every primitive has the vertices its mode needs. Assimp subtracts from the
// count without looking: a triangle strip whose position accessor had the unknown type "VEC7"
// asked for 2^32 - 2 faces (64 GB; found by fuzzing).

#include <string>
#include <string_view>

namespace weft::app {

// Throws MeshFileError "NAME: glTF …" naming the accessor or mesh primitive, or the JSON
// parser's reason for a text that is not JSON (UTF-8, as glTF requires).
void check_gltf_json(std::string_view json, const std::string& name);

}  // namespace weft::app
