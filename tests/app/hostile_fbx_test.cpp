// FBX files assimp 5.2.5 recurses through without end (app/io/fbx_precheck.h), text and binary:
// a model connected to itself beside its link to the root (SIGSEGV in `weft turntable`, found by
// fuzz_mesh_fbx), a model connected twice to its parent at every level of a chain (a hang: 2^40
// conversions), a chain of 100 000 models or scopes nested a million deep (SIGSEGV). Each is a
// MeshFileError naming the file and the models; the same quad without them still loads.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "app/io/fbx_precheck.h"
#include "app/io/mesh_file.h"
#include "scene_test_support.h"
#include "tests/support/test_files.h"

namespace fs = std::filesystem;

namespace weft::app {
namespace {

fs::path fbx_dir() {
  return test_files::fresh_directory(::testing::TempDir(), "weft_hostile_fbx_test");
}

// A text FBX of one quad (geometry 10) in model 20, under model 21; `links` are the connections
// after the geometry's, `more` extra objects.
std::string fbx_text(const std::string& links, const std::string& more = "") {
  return "; FBX 7.5.0 project file\nFBXHeaderExtension:  {\n\tFBXVersion: 7500\n}\n"
         "Objects:  {\n\tGeometry: 10, \"Geometry::\", \"Mesh\" {\n"
         "\t\tVertices: *12 {\n\t\t\ta: 0,0,0,1,0,0,1,1,0,0,1,0\n\t\t}\n"
         "\t\tPolygonVertexIndex: *4 {\n\t\t\ta: 0,1,2,-4\n\t\t}\n\t}\n"
         "\tModel: 20, \"Model::a\", \"Mesh\" {\n\t}\n\tModel: 21, \"Model::b\", \"Null\" "
         "{\n\t}\n" +
         more + "}\nConnections:  {\n\tC: \"OO\",10,20\n" + links + "}\n";
}

// Little-endian words and binary FBX properties: a 64-bit integer, a string, arrays.
std::string fbx_le(std::uint64_t v, int bytes) {
  std::string s;
  for (int k = 0; k < bytes; ++k) s += static_cast<char>(v >> (8 * k) & 0xFF);
  return s;
}
std::string fbx_long(std::int64_t v) {
  return "L" + fbx_le(static_cast<std::uint64_t>(v), 8);
}
std::string fbx_string(const std::string& s) {
  return "S" + fbx_le(s.size(), 4) + s;
}
template <typename T>
std::string fbx_array(char type, const std::vector<T>& values) {
  std::string s =
      type + fbx_le(values.size(), 4) + fbx_le(0, 4) + fbx_le(values.size() * sizeof(T), 4);
  for (const T v : values) s.append(reinterpret_cast<const char*>(&v), sizeof v);
  return s;
}

// A binary FBX 7.5 node at byte `offset`: name, properties, nested nodes (then a NUL record).
struct FbxNode {
  std::string name;
  std::vector<std::string> properties;
  std::vector<FbxNode> children;
};
std::string fbx_node(const FbxNode& n, std::uint64_t offset) {
  std::string properties;
  for (const std::string& p : n.properties) properties += p;
  const std::string head = static_cast<char>(n.name.size()) + n.name + properties;
  std::string nested;
  for (const FbxNode& c : n.children)
    nested += fbx_node(c, offset + 24 + head.size() + nested.size());
  if (!n.children.empty()) nested += std::string(25, '\0');
  return fbx_le(offset + 24 + head.size() + nested.size(), 8) + fbx_le(n.properties.size(), 8) +
         fbx_le(properties.size(), 8) + head + nested;
}

// The quad of fbx_text as a binary FBX, with `links` (child, parent) after the geometry's.
std::string fbx_binary(const std::vector<std::pair<int, int>>& links) {
  // An object: ID, "name\0\1Type", kind; and a nested list (assimp needs one: a Version).
  const auto object = [](const char* type, int id, const char* name, const char* kind) {
    return FbxNode{
        type,
        {fbx_long(id), fbx_string(name + std::string("\0\1", 2) + type), fbx_string(kind)},
        {{"Version", {"I" + fbx_le(232, 4)}, {}}}};
  };
  FbxNode geometry = object("Geometry", 10, "", "Mesh");
  geometry.children = {
      {"Vertices", {fbx_array<double>('d', {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0})}, {}},
      {"PolygonVertexIndex", {fbx_array<std::int32_t>('i', {0, 1, 2, -4})}, {}}};
  FbxNode connections{
      "Connections", {}, {{"C", {fbx_string("OO"), fbx_long(10), fbx_long(20)}, {}}}};
  for (const auto& [child, parent] : links)
    connections.children.push_back(
        {"C", {fbx_string("OO"), fbx_long(child), fbx_long(parent)}, {}});
  const std::vector<FbxNode> top = {
      {"FBXHeaderExtension", {}, {{"FBXVersion", {"I" + fbx_le(7500, 4)}, {}}}},
      {"Objects",
       {},
       {geometry, object("Model", 20, "a", "Mesh"), object("Model", 21, "b", "Null")}},
      connections};
  std::string s = std::string("Kaydara FBX Binary  \0\x1a\0", 23) + fbx_le(7500, 4);
  for (const FbxNode& n : top) s += fbx_node(n, s.size());
  return s + std::string(25, '\0');
}

TEST(HostileFbx, AQuadInTwoModelsLoadsAsTextAndBinary) {
  const fs::path d = fbx_dir();
  test_files::write_text(d / "text.fbx", fbx_text("\tC: \"OO\",20,21\n\tC: \"OO\",21,0\n"));
  test_files::write_text(d / "binary.fbx", fbx_binary({{20, 21}, {21, 0}}));
  for (const char* name : {"text.fbx", "binary.fbx"}) {
    const PolygonMesh m = load_polygon_mesh(d / name);
    EXPECT_EQ(m.vertices.rows(), 4) << name;
    ASSERT_EQ(m.faces.size(), 1u) << name;
    EXPECT_EQ(m.faces[0].size(), 4u) << name;
  }
}

TEST(HostileFbx, AModelLinkedToItselfOrInACycleIsRefused) {
  const fs::path d = fbx_dir();
  // Model 21 under the root and under itself: assimp recursed until SIGSEGV.
  test_files::write_text(d / "self.fbx",
                         fbx_text("\tC: \"OO\",20,21\n\tC: \"OO\",21,0\n\tC: \"OO\",21,21\n"));
  test_files::write_text(d / "self_binary.fbx", fbx_binary({{20, 21}, {21, 0}, {21, 21}}));
  for (const char* name : {"self.fbx", "self_binary.fbx"})
    EXPECT_CONTAINS(test::mesh_load_error(d / name),
                    (d / name).string() +
                        ": FBX model 21 has 2 parent connections (to 0, 21); a "
                        "model has one parent");
  test_files::write_text(d / "cycle.fbx", fbx_text("\tC: \"OO\",20,21\n\tC: \"OO\",21,20\n"));
  EXPECT_CONTAINS(
      test::mesh_load_error(d / "cycle.fbx"),
      ": FBX models connected in a cycle (20 → 21 → 20): a model cannot be its own ancestor");
  // An overflowing ID is 0 to assimp: the root.
  test_files::write_text(
      d / "overflow.fbx",
      fbx_text("\tC: \"OO\",20,21\n\tC: \"OO\",21,0\n\tC: \"OO\",21,99999999999999999999\n"));
  EXPECT_CONTAINS(test::mesh_load_error(d / "overflow.fbx"),
                  "model 21 has 2 parent connections (to 0, 0)");
}

// A model is a child of the one before it, twice: assimp converted 2^40 copies (a hang).
TEST(HostileFbx, AModelLinkedTwiceToItsParentIsRefused) {
  const fs::path d = fbx_dir();
  std::string models, links = "\tC: \"OO\",100,0\n";
  for (int k = 0; k < 40; ++k) {
    models += "\tModel: " + std::to_string(100 + k) + ", \"Model::m\", \"Null\" {\n\t}\n";
    if (k > 0)
      for (int twice = 0; twice < 2; ++twice)
        links += "\tC: \"OO\"," + std::to_string(100 + k) + "," + std::to_string(99 + k) + "\n";
  }
  test_files::write_text(d / "twice.fbx",
                         fbx_text(links + "\tC: \"OO\",21,0\n\tC: \"OO\",20,21\n", models));
  EXPECT_CONTAINS(test::mesh_load_error(d / "twice.fbx"),
                  "FBX model 101 has 2 parent connections (to 100, 100)");
}

TEST(HostileFbx, DeepModelsOrScopesAreRefused) {
  const fs::path d = fbx_dir();
  std::string models, links = "\tC: \"OO\",1000,0\n";
  for (int k = 0; k <= max_fbx_model_depth; ++k) {
    models += "\tModel: " + std::to_string(1000 + k) + ", \"Model::m\", \"Null\" {\n\t}\n";
    if (k > 0)
      links += "\tC: \"OO\"," + std::to_string(1000 + k) + "," + std::to_string(999 + k) + "\n";
  }
  test_files::write_text(d / "chain.fbx",
                         fbx_text(links + "\tC: \"OO\",21,0\n\tC: \"OO\",20,21\n", models));
  EXPECT_CONTAINS(test::mesh_load_error(d / "chain.fbx"),
                  "FBX model " + std::to_string(1000 + max_fbx_model_depth) + " is nested " +
                      std::to_string(max_fbx_model_depth + 1) + " models deep, more than " +
                      std::to_string(max_fbx_model_depth));
  std::string deep;
  for (int k = 0; k <= max_fbx_scope_depth; ++k) deep += "A: {\n";
  test_files::write_text(d / "deep.fbx", fbx_text("\tC: \"OO\",20,21\n\tC: \"OO\",21,0\n") + deep);
  EXPECT_CONTAINS(
      test::mesh_load_error(d / "deep.fbx"),
      "FBX scopes nested deeper than " + std::to_string(max_fbx_scope_depth) + " at line ");
}

// What assimp's tokenizers refuse is refused here, naming the line or byte.
TEST(HostileFbx, TokensAssimpWouldNotReadAreRefused) {
  const auto error = [](const std::string& bytes, const std::string& name) -> std::string {
    try {
      check_fbx(bytes, name);
    } catch (const MeshFileError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_CONTAINS(error("A: \"open\nB:", "q.fbx"),
                  "q.fbx: FBX file weft cannot read: unexpected end of file");
  EXPECT_CONTAINS(error("A: 1 :", "c.fbx"),
                  "c.fbx: FBX text weft cannot read: line 1: unexpected colon");
  std::string binary = fbx_binary({{20, 21}, {21, 0}});
  EXPECT_EQ(error(binary, "b.fbx"), "no error");
  binary[34] = '\x7f';  // the first node's end offset (its high byte): past the file
  EXPECT_CONTAINS(error(binary, "b.fbx"),
                  "b.fbx: FBX binary weft cannot read: byte 35: block offset is out of range");
}

}  // namespace
}  // namespace weft::app
