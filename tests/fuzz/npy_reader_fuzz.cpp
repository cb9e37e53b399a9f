// libFuzzer target: any bytes as a .npy file (parse_npy, app/io/npy_file.h). It must give an
// array or throw NpyError; any other exception (std::bad_alloc from a shape too large), a
// crash, a hang or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "app/io/npy_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)weft::app::parse_npy(std::string(reinterpret_cast<const char*>(data), size), "fuzz.npy");
  } catch (const weft::app::NpyError&) {
    // bad input, reported as such
  }
  return 0;
}
