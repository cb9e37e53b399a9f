// Hostile mesh files through the real `weft`, as each command reads them: the cloth's mesh
// (cloth.mesh), a mesh obstacle and `weft turntable MESH`. A PLY whose face refers to a vertex it
// does not have, whose list count runs past its faces or with a second vertex element, used to
// crash inside assimp (SIGSEGV, heap corruption), as did FBX models in a cycle; a glTF buffer
// outside the mesh's folder was read. Each is exit 1 naming the file, nothing written.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

class HostileMeshCli : public weft::app::test::CliDirectoryTest {
 protected:
  HostileMeshCli() : CliDirectoryTest("hostile_mesh_cli") {}
};

// A binary PLY of a square (4 vertices, 2 triangles); `count` is the first face's list count.
std::string square_ply(std::uint8_t count, std::int32_t last_index) {
  std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
                  "property float y\nproperty float z\nelement face 2\n"
                  "property list uchar int vertex_indices\nend_header\n";
  const float xyz[12] = {0, 0, 0, 0.2f, 0, 0, 0.2f, 0.2f, 0, 0, 0.2f, 0};
  s.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  const std::int32_t faces[2][3] = {{0, 1, 2}, {0, 2, last_index}};
  for (const auto& face : faces) {
    s += static_cast<char>(&face == &faces[0] ? count : 3);
    s.append(reinterpret_cast<const char*>(face), sizeof face);
  }
  return s;
}

TEST_F(HostileMeshCli, ABadPlyIsRefusedAsClothObstacleAndTurntableMesh) {
  const std::vector<std::pair<std::string, std::string>> files = {
      {"index.ply", square_ply(3, 1000000)}, {"count.ply", square_ply(255, 3)}};
  for (const auto& [name, bytes] : files) {
    std::ofstream(m_dir / name, std::ios::binary) << bytes;
    const fs::path cloth = write_scene(
        "cloth_" + name + ".json",
        R"({"description": "a cloth from a mesh file", "cloth": {"mesh": ")" + name + R"("},
  "output": {"frames": 2}, "render": {"size": [96, 64]}})");
    const fs::path obstacle = write_scene(
        "obstacle_" + name + ".json",
        tiny_scene("", ",\n  \"obstacles\": [{\"mesh\": {\"file\": \"" + name + "\"}}]"));
    const fs::path out = m_dir / ("out_" + name);
    for (const std::string& command :
         {"run " + cloth.string(), "run " + obstacle.string(), "turntable " + (m_dir / name).string()}) {
      const CommandResult r = run_weft(command + " --out " + out.string());
      EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.output;
      // The count of 255 reads the next face's bytes as corners: one of them is out of range.
      EXPECT_CONTAINS(r.output, (m_dir / name).string() + ": face ");
      EXPECT_CONTAINS(r.output, "not one of the file's 4 vertices");
      EXPECT_FALSE(fs::exists(out)) << command;
    }
  }
}

TEST_F(HostileMeshCli, AGltfBufferOutsideTheMeshFolderIsNotRead) {
  fs::create_directories(m_dir / "mesh");
  std::ofstream(m_dir / "secret.bin") << std::string(42, '\0');
  std::ofstream(m_dir / "mesh" / "up.gltf")
      << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
"buffers":[{"uri":"../secret.bin","byteLength":42}],
"bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[0,0,0]},
{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";
  const CommandResult r = run_weft("turntable " + (m_dir / "mesh" / "up.gltf").string() +
                                   " --out " + (m_dir / "out").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, "outside the mesh file's folder");
}

// A PLY with a second vertex element: assimp wrote its vertices past the first one's array and
// `weft turntable` aborted (heap corruption; found by fuzz_mesh_ply).
TEST_F(HostileMeshCli, APlyElementTwiceIsRefused) {
  std::ofstream ply(m_dir / "twice.ply");
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  ply << "ply\nformat ascii 1.0\nelement vertex 3\n" << xyz << "element vertex 1000\n" << xyz
      << "end_header\n0 0 0\n1 0 0\n0 1 0\n";
  for (int k = 0; k < 1000; ++k) ply << "0.5 0.5 0\n";
  ply.close();
  const CommandResult r = run_weft("turntable " + (m_dir / "twice.ply").string() + " --out " +
                                   (m_dir / "out").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, (m_dir / "twice.ply").string() +
                                ": PLY header line 7: element 'vertex' a second time");
  EXPECT_FALSE(fs::exists(m_dir / "out"));
}

// FBX files assimp recursed through until `weft turntable` and `weft run` died (SIGSEGV): a model
// under the root and under itself (found by fuzz_mesh_fbx), scopes nested a million deep.
TEST_F(HostileMeshCli, AnFbxAssimpWouldRecurseThroughWithoutEndIsRefused) {
  std::ofstream(m_dir / "self.fbx")
      << "FBXHeaderExtension:  {\n\tFBXVersion: 7500\n}\nObjects:  {\n\tModel: 21, \"Model::b\", "
         "\"Null\" {\n\t}\n}\nConnections:  {\n\tC: \"OO\",21,0\n\tC: \"OO\",21,21\n}\n";
  std::ofstream deep(m_dir / "deep.fbx");
  for (int k = 0; k < 1000000; ++k) deep << "A: {";
  deep.close();
  const std::vector<std::pair<std::string, std::string>> files = {
      {"self.fbx", "FBX model 21 has 2 parent connections (to 0, 21)"},
      {"deep.fbx", "FBX scopes nested deeper than 64 at line 1"}};
  for (const auto& [name, why] : files) {
    const fs::path cloth = write_scene(
        "cloth_" + name + ".json",
        R"({"description": "a cloth from a mesh file", "cloth": {"mesh": ")" + name + R"("},
  "output": {"frames": 2}, "render": {"size": [96, 64]}})");
    const fs::path out = m_dir / ("out_" + name);
    for (const std::string& command :
         {"run " + cloth.string(), "turntable " + (m_dir / name).string()}) {
      const CommandResult r = run_weft(command + " --out " + out.string());
      EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.output;
      EXPECT_CONTAINS(r.output, (m_dir / name).string() + ": " + why);
      EXPECT_FALSE(fs::exists(out)) << command;
    }
  }
}

}  // namespace
