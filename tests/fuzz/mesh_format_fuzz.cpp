// libFuzzer target: any bytes as a mesh file of one format — WEFT_FUZZ_MESH_EXTENSION, one
// executable per format weft reads (app/io/mesh_file.h: .obj, .ply, .stl, .gltf, .glb, .fbx) —
// read the whole way weft reads meshes: its own checks, then assimp's importer of that format
// (the only ones weft's importer holds) through the confined IO, then the merge
// (load_polygon_mesh). It must give a mesh or throw MeshFileError; any other exception, a crash
// (inside assimp too, which is not instrumented) or a hang is a finding. Unlike
// mesh_file_fuzz.cpp (its first byte chooses OBJ or PLY), every byte is the file's, from small
// seeds of the format (tests/fuzz/seeds/mesh/), so that assimp's readers run thousands of times
// a second.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/io/mesh_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // One file per process, in the working folder (the fuzz build's), rewritten for each input.
  static const std::filesystem::path path =
      "fuzz_mesh_format_" + std::to_string(::getpid()) + WEFT_FUZZ_MESH_EXTENSION;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    (void)weft::app::load_polygon_mesh(path);
  } catch (const weft::app::MeshFileError&) {
    // bad input, reported as such
  }
  return 0;
}
