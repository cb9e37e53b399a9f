// libFuzzer target: any bytes as a PLY or an OBJ file (the first byte chooses) read the whole
// way weft reads meshes: its own checks, then assimp through the confined IO, then the merge
// (load_polygon_mesh). It must give a mesh or throw MeshFileError; any other exception, a crash
// (inside assimp too, which is not instrumented) or a hang is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/io/mesh_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  // One file per process, in the working folder (the fuzz build's), rewritten for each input.
  static const std::filesystem::path stem = "fuzz_mesh_" + std::to_string(::getpid());
  const std::filesystem::path path = stem.string() + (data[0] & 1 ? ".obj" : ".ply");
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data) + 1, static_cast<std::streamsize>(size - 1));
  try {
    (void)weft::app::load_polygon_mesh(path);
  } catch (const weft::app::MeshFileError&) {
    // bad input, reported as such
  }
  return 0;
}
