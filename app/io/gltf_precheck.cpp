#include "app/io/gltf_precheck.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>

#include "app/io/mesh_file.h"
#include "app/io/mesh_precheck.h"

namespace weft::app {

namespace {

[[noreturn]] void refuse(const std::string& name, const std::string& what) {
  throw MeshFileError(name + ": glTF " + what);
}

// accessors[k]: a type and component type of glTF's, and a count of at least 1 within what
// weft reads (a face's corners: 3 per face).
void check_accessor(const nlohmann::json& a, std::size_t k, const std::string& name) {
  static const std::array<const char*, 7> types = {"SCALAR", "VEC2", "VEC3", "VEC4",
                                                   "MAT2",   "MAT3", "MAT4"};
  static const std::array<int, 6> components = {5120, 5121, 5122, 5123, 5125, 5126};
  const std::string where = "accessors[" + std::to_string(k) + "]";
  const auto type = a.find("type");
  if (type == a.end() || !type->is_string() ||
      std::find(types.begin(), types.end(), type->get<std::string>()) == types.end())
    refuse(name, where + ": type must be SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4");
  const auto component = a.find("componentType");
  if (component == a.end() || !component->is_number_integer() ||
      std::find(components.begin(), components.end(), component->get<long long>()) ==
          components.end())
    refuse(name, where + ": componentType must be 5120, 5121, 5122, 5123, 5125 or 5126");
  const auto count = a.find("count");
  if (count == a.end() || !count->is_number_integer() || count->get<long long>() < 1 ||
      count->get<long long>() > static_cast<long long>(3 * max_mesh_elements))
    refuse(name, where + ": count must be from 1 to " + std::to_string(3 * max_mesh_elements));
}

// The vertices a primitive of `mode` draws from: its indices' count, else its positions'.
void check_primitive(const nlohmann::json& p, const nlohmann::json& accessors,
                     const std::string& where, const std::string& name) {
  if (!p.is_object()) refuse(name, where + " must be an object");
  const long long mode = p.value("mode", 4LL);  // not a number: a type_error, refused below
  if (mode < 0 || mode > 6)
    refuse(name, where + ": mode must be 0 to 6, got " + std::to_string(mode));
  // assimp 5.2.5 reads a line loop through indices past its data (SIGSEGV in the Release build;
  // found by fuzzing), and weft reads no lines.
  if (mode == 2)
    refuse(name, where + ": mode 2 (a line loop): weft reads triangles and polygons, no lines");
  const auto count_of = [&](const nlohmann::json& index) -> long long {
    if (!index.is_number_unsigned() || index.get<std::size_t>() >= accessors.size())
      refuse(name, where + ": refers to accessor " + index.dump() + ", not one of the file's " +
                       std::to_string(accessors.size()));
    return accessors[index.get<std::size_t>()].value("count", 0LL);
  };
  // The accessor types glTF 2.0 allows for an attribute or the indices (its "Meshes" section):
  // assimp reads a POSITION of type VEC2 as three floats a vertex and dereferenced null (SIGSEGV
  // in the Release build; found by fuzzing).
  const auto check_type = [&](const nlohmann::json& index, const std::string& what,
                              std::initializer_list<const char*> allowed) {
    count_of(index);
    const std::string type = accessors[index.get<std::size_t>()].value("type", "");
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* t) { return type == t; }))
      refuse(name, where + ": " + what + " is accessor " + index.dump() + " of type " + type +
                       ", not one glTF allows there");
  };
  const auto attributes = p.find("attributes");
  if (attributes == p.end() || !attributes->is_object()) refuse(name, where + ": no attributes");
  for (const auto& [key, index] : attributes->items()) {
    if (key == "POSITION" || key == "NORMAL") check_type(index, key, {"VEC3"});
    else if (key == "TANGENT") check_type(index, key, {"VEC4"});
    else if (key.rfind("TEXCOORD_", 0) == 0) check_type(index, key, {"VEC2"});
    else if (key.rfind("COLOR_", 0) == 0) check_type(index, key, {"VEC3", "VEC4"});
    else count_of(index);
  }
  const auto indices = p.find("indices");
  if (indices != p.end()) check_type(*indices, "indices", {"SCALAR"});
  const long long vertices = indices != p.end() ? count_of(*indices)
                             : attributes->contains("POSITION") ? count_of((*attributes)["POSITION"])
                                                                : 0;
  // Lines need 2 corners, triangles (and their strips and fans) 3.
  const long long needed = mode == 0 ? 1 : mode <= 3 ? 2 : 3;
  if (vertices < needed)
    refuse(name, where + ": mode " + std::to_string(mode) + " needs at least " +
                     std::to_string(needed) + " vertices, got " + std::to_string(vertices));
}

// Every accessor and mesh primitive of the document.
void check_document(const nlohmann::json& doc, const std::string& name) {
  const nlohmann::json accessors = doc.value("accessors", nlohmann::json::array());
  if (!accessors.is_array()) refuse(name, "accessors must be a list");
  for (std::size_t k = 0; k < accessors.size(); ++k) {
    if (!accessors[k].is_object())
      refuse(name, "accessors[" + std::to_string(k) + "] must be an object");
    check_accessor(accessors[k], k, name);
  }
  const nlohmann::json meshes = doc.value("meshes", nlohmann::json::array());
  if (!meshes.is_array()) refuse(name, "meshes must be a list");
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const nlohmann::json primitives =
        meshes[m].is_object() ? meshes[m].value("primitives", nlohmann::json::array())
                              : nlohmann::json::array();
    for (std::size_t k = 0; k < primitives.size(); ++k) {
      const std::string where =
          "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(k) + "]";
      check_primitive(primitives[k], accessors, where, name);
    }
  }
}

}  // namespace

void check_gltf_json(std::string_view json, const std::string& name) {
  try {
    // Strictly: assimp's own JSON reader takes what JSON forbids (bytes that are not UTF-8),
    // which let an accessor of type "VEC7" through.
    const nlohmann::json doc = nlohmann::json::parse(json);
    if (!doc.is_object()) refuse(name, "document: expected a JSON object");
    check_document(doc, name);
  } catch (const nlohmann::json::exception& e) {  // not JSON, or a value of the wrong type
    refuse(name, std::string("document weft cannot read: ") + e.what());
  }
}

}  // namespace weft::app
