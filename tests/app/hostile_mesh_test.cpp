// Hostile mesh files read by load_triangle_mesh / load_polygon_mesh (every mesh weft reads: the
// cloth's, obstacles', weft turntable's): a PLY whose face refers to a vertex it does not have,
// whose list count runs past its faces, whose header promises more than the file holds or more
// than the limit; a glTF or OBJ that refers to a file outside its folder; a device as a mesh.
// Each is a MeshFileError naming the file and what is wrong — never a crash inside assimp.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

#include "app/io/mesh_file.h"
#include "app/io/mesh_precheck.h"
#include "scene_test_support.h"
#include "tests/support/test_files.h"

namespace fs = std::filesystem;

namespace weft::app {
namespace {


fs::path dir() { return test_files::fresh_directory(::testing::TempDir(), "weft_hostile_mesh_test"); }


const std::string kPlyVertices = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";

std::string ascii_ply(const std::string& faces) {
  return "ply\nformat ascii 1.0\n" + kPlyVertices +
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0\n1 0 0\n0 1 0\n" + faces;
}

// A binary little-endian PLY of the three vertices above and one face: count, then indices.
std::string binary_ply(std::uint8_t count, const std::vector<std::int32_t>& indices, int faces = 1) {
  std::string s = "ply\nformat binary_little_endian 1.0\n" + kPlyVertices + "element face " +
                  std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  s.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  s += static_cast<char>(count);
  for (const std::int32_t i : indices) s.append(reinterpret_cast<const char*>(&i), 4);
  return s;
}

TEST(HostileMesh, AGoodPlyStillLoads) {
  const fs::path d = dir();
  test_files::write_text(d / "a.ply", ascii_ply("3 0 1 2\n"));
  test_files::write_text(d / "b.ply", binary_ply(3, {0, 1, 2}));
  for (const char* name : {"a.ply", "b.ply"})
    EXPECT_EQ(load_triangle_mesh(d / name).triangles.size(), 1u) << name;
}

TEST(HostileMesh, APlyFaceOutsideTheVerticesIsRefusedNamingTheFace) {
  const fs::path d = dir();
  test_files::write_text(d / "a.ply", ascii_ply("3 0 1 7\n"));
  test_files::write_text(d / "b.ply", binary_ply(3, {0, 1, 1000000}));
  test_files::write_text(d / "c.ply", binary_ply(3, {0, -1, 2}));
  for (const char* name : {"a.ply", "b.ply", "c.ply"}) {
    const std::string e = test::mesh_load_error(d / name);
    EXPECT_CONTAINS(e, (d / name).string() + ": face 0, vertex_indices: corner ");
    EXPECT_CONTAINS(e, "not one of the file's 3 vertices");
  }
}

TEST(HostileMesh, APlyListCountPastItsFacesOrAHeaderPastTheFileIsRefused) {
  const fs::path d = dir();
  test_files::write_text(d / "count.ply", binary_ply(255, {0, 1, 2}));
  EXPECT_CONTAINS(test::mesh_load_error(d / "count.ply"), "the file ends before it (truncated, or a bogus count)");
  test_files::write_text(d / "faces.ply", binary_ply(3, {0, 1, 2}, 1000000));
  EXPECT_CONTAINS(test::mesh_load_error(d / "faces.ply"),
                  "the PLY header says 1000000 face elements, more than its");
  test_files::write_text(d / "huge.ply", binary_ply(3, {0, 1, 2}, 10000000));
  EXPECT_CONTAINS(test::mesh_load_error(d / "huge.ply"), "the PLY header says 10000000 faces, more than 2097152");
  test_files::write_text(d / "ascii.ply", ascii_ply("3 0 1\n"));
  EXPECT_CONTAINS(test::mesh_load_error(d / "ascii.ply"), "face 0, vertex_indices: its line ends before it");
}

// Found by fuzzing: assimp's PLY reader hung on a misspelt header keyword and leaked on a NUL
// in an element's name, and weft's own walk took forever over an element of 4·10¹² items
// without properties.
TEST(HostileMesh, APlyHeaderIsReadStrictlyAndAnEmptyElementTakesNoTime) {
  const fs::path d = dir();
  std::string typo = ascii_ply("3 0 1 2\n");
  typo.replace(typo.find("property float x"), 8, "propesty");
  test_files::write_text(d / "typo.ply", typo);
  EXPECT_CONTAINS(test::mesh_load_error(d / "typo.ply"), "PLY header line 4: 'propesty float x' (expected format, "
                                              "comment, obj_info, element, property or end_header)");
  EXPECT_CONTAINS(test::mesh_load_error([&] {
                    std::string nul = ascii_ply("3 0 1 2\n");
                    nul.replace(nul.find("face"), 4, std::string("fa\1\0e", 5));
                    test_files::write_text(d / "nul.ply", nul);
                    return d / "nul.ply";
                  }()),
                  "PLY header line 7: a control character");
  EXPECT_NO_THROW(precheck_mesh_bytes("ply\nformat binary_little_endian 1.0\n"
                                      "element nothing 4444444888888\nend_header\n", ".ply", "empty.ply"));
  // A header ending the file without a line end: assimp's reader looped (found by fuzzing).
  EXPECT_CONTAINS(test::mesh_load_error([&] {
                    test_files::write_text(d / "eol.ply", "ply\nformat binary_little_endian 1.0\n"
                                                          "element foo 8\nend_header");
                    return d / "eol.ply";
                  }()),
                  "the PLY header's end_header line has no line end");
  // assimp counts no element named 'nothing' (it reads a count from the start of the name).
  EXPECT_NO_THROW(precheck_mesh_bytes("ply\nformat ascii 1.0\nelement nothing 4444444888888\n"
                                      "end_header\n\n", ".ply", "empty.ply"));
}

// Found by fuzzing (fuzz_mesh_ply): a second `element vertex` made assimp write its vertices
// past the first one's array (heap corruption: `weft turntable` aborted); faces beside tristrips
// likewise, and a face's texture coordinates were read past its corners, or through a null
// pointer without them (SIGSEGV).
TEST(HostileMesh, APlyElementTwiceOrTexcoordsPastTheCornersAreRefused) {
  const fs::path d = dir();
  test_files::write_text(d / "twice.ply",
                         "ply\nformat ascii 1.0\n" + kPlyVertices + kPlyVertices +
                             "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_CONTAINS(test::mesh_load_error(d / "twice.ply"),
                  (d / "twice.ply").string() +
                      ": PLY header line 7: element 'vertex' a second time (assimp would read it "
                      "into the first one's arrays)");
  std::string strips = ascii_ply("3 0 1 2\n3 0 1 2\n");
  strips.insert(strips.find("end_header"),
                "element tristrips 1\nproperty list int int vertex_indices\n");
  test_files::write_text(d / "strips.ply", strips);
  EXPECT_CONTAINS(test::mesh_load_error(d / "strips.ply"), "element 'tristrips' beside 'face'");
  const auto textured = [](bool corners, const std::string& uv) {
    return "ply\nformat ascii 1.0\n" + kPlyVertices + "element face 1\n" +
           (corners ? "property list uchar int vertex_indices\n" : "") +
           "property list uchar float texcoord\nend_header\n0 0 0\n1 0 0\n0 1 0\n" +
           (corners ? "3 0 1 2 " : "") + uv + "\n";
  };
  test_files::write_text(d / "uv.ply", textured(true, "6 0 0 1 0 0 1"));
  EXPECT_EQ(load_triangle_mesh(d / "uv.ply").triangles.size(), 1u);
  test_files::write_text(d / "past.ply", textured(true, "8 0 0 1 0 0 1 1 1"));
  EXPECT_CONTAINS(test::mesh_load_error(d / "past.ply"),
                  "face 0, texcoord: 8 texture coordinates for 3 corners (at most two a corner)");
  test_files::write_text(d / "none.ply", textured(false, "6 0 0 1 0 0 1"));
  EXPECT_CONTAINS(test::mesh_load_error(d / "none.ply"), "6 texture coordinates for 0 corners");
}

// Found by fuzzing (fuzz_mesh_ply): a NUL in a text body ended assimp's line there, so that it
// read a face's list count of 954 437 119 where weft's walk, word by word, had read 1 (15 GB and
// 57 s in the Release build). A text body is read a line an element, as assimp reads it.
TEST(HostileMesh, APlyTextBodyIsReadALineAnElement) {
  const fs::path d = dir();
  const auto refused = [&](const std::string& file, const std::string& body) {
    test_files::write_text(d / file, ascii_ply(body));
    return test::mesh_load_error(d / file);
  };
  EXPECT_CONTAINS(refused("nul.ply", std::string("3 0 1 2\0\n", 9)),
                  "PLY body byte 179: a control character (the body of an ASCII PLY is lines of text)");
  // The vertices' lines (ascii_ply's) hold three numbers each: a fourth is not the face's.
  std::string short_line = ascii_ply("3 0 1 2\n");
  short_line.replace(short_line.find("0 1 0\n"), 6, "0 1\n0 3 0 1 2\n");
  test_files::write_text(d / "short.ply", short_line);
  EXPECT_CONTAINS(test::mesh_load_error(d / "short.ply"), "vertex 2, z: its line ends before it");
  EXPECT_CONTAINS(refused("long.ply", "3 0 1 2 7\n"),
                  "face 0: more numbers on its line than the element's properties");
  EXPECT_CONTAINS(refused("empty.ply", "\n3 0 1 2\n"), "face 0: an empty line");
  EXPECT_CONTAINS(refused("real.ply", "3 0 1 2.5\n"), "face 0, vertex_indices: '2.5' is not an integer");
  EXPECT_CONTAINS(refused("hex.ply", "0x3 0 1 2\n"), "'0x3' is not a whole number");
  EXPECT_EQ(refused("crlf.ply", "3 0 1 2\r\n"), "no error");
}

// Found by fuzzing (fuzz_mesh_ply): `element 8888…8face 2` was some 4·10⁹ elements to assimp,
// which reads an element's count from the start of its name unless the name is one it knows;
// another name before a known one is refused (assimp would take it as empty).
TEST(HostileMesh, APlyElementAssimpCountsByItsNameIsRefused) {
  const fs::path d = dir();
  std::string digits = ascii_ply("3 0 1 2\n");
  digits.replace(digits.find("element face 1"), 14, "element 8888888888face 1");
  test_files::write_text(d / "digits.ply", digits);
  EXPECT_CONTAINS(test::mesh_load_error(d / "digits.ply"),
                  "element '8888888888face' (assimp reads a count from an element name starting "
                  "with a digit)");
  std::string camera = ascii_ply("1\n3 0 1 2\n");
  camera.replace(camera.find("element face 1"), 0, "element camera 1\nproperty uchar id\n");
  camera.replace(camera.find("1\n3 0 1 2"), 2, "");  // the camera's line is not read by assimp
  test_files::write_text(d / "camera.ply", camera);
  EXPECT_CONTAINS(test::mesh_load_error(d / "camera.ply"),
                  "element 'face' after element 'camera', which assimp takes as empty");
  std::string last = ascii_ply("3 0 1 2\n");
  last.insert(last.find("end_header"), "element camera 1\nproperty uchar id\n");
  test_files::write_text(d / "last.ply", last);
  EXPECT_EQ(load_triangle_mesh(d / "last.ply").triangles.size(), 1u);
}

TEST(HostileMesh, AnObjOverTheLimitIsRefusedBeforeItIsRead) {
  const fs::path d = dir();
  std::string obj;
  obj.reserve(8 * (max_mesh_elements + 1));
  for (std::uint64_t k = 0; k <= max_mesh_elements; ++k) obj += "v 0 0 0\n";
  test_files::write_text(d / "many.obj", obj);
  EXPECT_CONTAINS(test::mesh_load_error(d / "many.obj"), "an OBJ of 2097153 vertices, more than 2097152");
}

// A glTF whose one buffer (three corners, float32, and three uint16 indices) is at `uri`.
std::string gltf(const std::string& uri) {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
"buffers":[{"uri":")" + uri + R"(","byteLength":42}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";
}

std::string triangle_buffer() {
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t index[3] = {0, 1, 2};
  std::string s(reinterpret_cast<const char*>(xyz), sizeof xyz);
  return s.append(reinterpret_cast<const char*>(index), sizeof index);
}

TEST(HostileMesh, AGltfOrObjReferringOutsideItsFolderIsRefused) {
  const fs::path d = dir();
  fs::create_directories(d / "mesh" / "sub");
  test_files::write_text(d / "secret.bin", triangle_buffer());
  test_files::write_text(d / "mesh" / "sub" / "tri.bin", triangle_buffer());
  test_files::write_text(d / "mesh" / "inside.gltf", gltf("sub/tri.bin"));
  EXPECT_EQ(load_triangle_mesh(d / "mesh" / "inside.gltf").triangles.size(), 1u);
  test_files::write_text(d / "mesh" / "up.gltf", gltf("../secret.bin"));
  test_files::write_text(d / "mesh" / "absolute.gltf", gltf((d / "secret.bin").string()));
  fs::create_symlink(d / "secret.bin", d / "mesh" / "link.bin");
  test_files::write_text(d / "mesh" / "link.gltf", gltf("link.bin"));
  test_files::write_text(d / "secret.mtl", "newmtl m\nKd 1 0 0\n");
  test_files::write_text(d / "mesh" / "up.obj", "mtllib ../secret.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n");
  for (const char* name : {"up.gltf", "link.gltf", "up.obj"}) {
    const std::string e = test::mesh_load_error(d / "mesh" / name);
    EXPECT_CONTAINS(e, (d / "mesh" / name).string() + ": cannot read mesh file: it refers to ");
    EXPECT_CONTAINS(e, "outside the mesh file's folder " + fs::canonical(d / "mesh").string());
  }
  // assimp reads an absolute uri below the file's folder, where there is no such file.
  EXPECT_CONTAINS(test::mesh_load_error(d / "mesh" / "absolute.gltf"),
                  (d / "mesh" / "absolute.gltf").string() + ": cannot read mesh file: it refers to ");
}

// `vt nan 0` and `vt 1e39 0` (infinite as a float) used to give the pattern of `vt 0 0`.
TEST(HostileMesh, NonFiniteTextureCoordinatesAreRefused) {
  const fs::path d = dir();
  for (const char* vt : {"nan 0", "1e39 0"}) {
    test_files::write_text(d / "uv.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt ") + vt +
                                 "\nf 1/1 2/2 3/3\n");
    try {
      load_polygon_mesh(d / "uv.obj");
      ADD_FAILURE() << vt;
    } catch (const MeshFileError& e) {
      EXPECT_CONTAINS(std::string(e.what()), (d / "uv.obj").string() + ": line 6: texture coordinates 'vt ");
      EXPECT_CONTAINS(std::string(e.what()), "is not a finite number (as a float)");
    }
  }
}

// A GLB whose JSON chunk says 2 GB in a file of a few hundred bytes: assimp allocated the 2 GB
// and took 10 s before failing (found by fuzz_mesh_glb). Refused from its headers, at once.
TEST(HostileMesh, AGlbChunkLongerThanTheFileIsRefused) {
  const fs::path d = dir();
  const auto word = [](std::uint32_t w) {
    std::string b;
    for (int k = 0; k < 4; ++k) b += static_cast<char>(w >> (8 * k) & 0xFF);
    return b;
  };
  const std::string json = R"({"asset":{"version":"2.0"}})";
  const auto glb = [&](std::uint32_t chunk_length, std::uint32_t total) {
    return std::string("glTF") + word(2) + word(total) + word(chunk_length) + "JSON" + json;
  };
  const auto total = static_cast<std::uint32_t>(20 + json.size());
  test_files::write_text(d / "long.glb", glb(2037149844u, total));
  EXPECT_CONTAINS(test::mesh_load_error(d / "long.glb"), (d / "long.glb").string() +
                                                  ": GLB chunk 0 says 2037149844 bytes, but the "
                                                  "file holds 27 after its header");
  test_files::write_text(d / "total.glb", glb(static_cast<std::uint32_t>(json.size()), 1u << 30));
  EXPECT_CONTAINS(test::mesh_load_error(d / "total.glb"), "the GLB header says 1073741824 bytes, but the file holds 47");
  test_files::write_text(d / "magic.glb", "glTX" + word(2) + word(12));
  EXPECT_CONTAINS(test::mesh_load_error(d / "magic.glb"), "not a GLB file");
}

// glTF accessors and primitives assimp trusts: an accessor of type "VEC7" behind a triangle
// strip made it ask for 2^32 - 2 faces (64 GB), also when the JSON held bytes that are not UTF-8
// (found by fuzz_mesh_gltf and fuzz_mesh_glb). Refused from the JSON first, naming the part.
TEST(HostileMesh, AGltfAccessorOrPrimitiveAssimpWouldTripOnIsRefused) {
  const fs::path d = dir();
  const auto gltf = [](const std::string& type, int count, int mode, const std::string& extra) {
    return R"({"asset":{"version":"2.0"},"accessors":[{"componentType":5126,"count":)" +
           std::to_string(count) + R"(,"type":")" + type + R"("}],"meshes":[{"primitives":[{"mode":)" +
           std::to_string(mode) + R"(,"attributes":{"POSITION":0}}]}])" + extra + "}";
  };
  test_files::write_text(d / "type.gltf", gltf("VEC7", 9, 5, ""));
  EXPECT_CONTAINS(test::mesh_load_error(d / "type.gltf"), (d / "type.gltf").string() +
                                                   ": glTF accessors[0]: type must be SCALAR");
  test_files::write_text(d / "strip.gltf", gltf("VEC3", 2, 5, ""));
  EXPECT_CONTAINS(test::mesh_load_error(d / "strip.gltf"),
                  "glTF meshes[0].primitives[0]: mode 5 needs at least 3 vertices, got 2");
  test_files::write_text(d / "utf8.gltf", gltf("VEC3", 9, 4, ",\"x\":\"\xe5\xe5\""));
  EXPECT_CONTAINS(test::mesh_load_error(d / "utf8.gltf"), "glTF document weft cannot read: ");
  // Positions of type VEC2 (found by fuzz_mesh_glb beside a line loop: SIGSEGV inside assimp,
  // in the Release build too).
  test_files::write_text(d / "vec2.gltf", gltf("VEC2", 9, 4, ""));
  EXPECT_CONTAINS(test::mesh_load_error(d / "vec2.gltf"),
                  "glTF meshes[0].primitives[0]: POSITION is accessor 0 of type VEC2, not one "
                  "glTF allows there");
  // A line loop: assimp read one through indices past its data (SIGSEGV; fuzz_mesh_glb).
  test_files::write_text(d / "loop.gltf", gltf("VEC3", 9, 2, ""));
  EXPECT_CONTAINS(test::mesh_load_error(d / "loop.gltf"), "mode 2 (a line loop): weft reads triangles");
}

TEST(HostileMesh, ADeviceOrAFolderIsNotAMeshFile) {
  EXPECT_CONTAINS(test::mesh_load_error("/dev/zero"), "/dev/zero: cannot read mesh file: not a regular file");
  EXPECT_CONTAINS(test::mesh_load_error(dir()), "not a regular file");
}

}  // namespace
}  // namespace weft::app
