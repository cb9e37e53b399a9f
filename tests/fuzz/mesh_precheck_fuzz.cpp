// libFuzzer target: any bytes as a PLY or an OBJ (the first byte chooses) checked by weft's own
// pre-assimp reader (app/io/mesh_precheck.h). It must pass or throw MeshFileError; any other
// exception, a crash, a hang or a sanitizer report is a finding (docs/reliability.md).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "app/io/mesh_file.h"
#include "app/io/mesh_precheck.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    weft::app::precheck_mesh_bytes(bytes, data[0] & 1 ? ".obj" : ".ply", "fuzz");
  } catch (const weft::app::MeshFileError&) {
    // bad input, reported as such
  }
  return 0;
}
