// libFuzzer target: any bytes as a scene file's text. The scene reader must
// return a Scene or throw InputError; any other exception, a crash, a hang or a sanitizer report
// is a finding. Built with -DWEFT_FUZZ=ON (docs/reliability.md).
#include <cstddef>
#include <cstdint>
#include <string>

#include "app/scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)weft::app::parse_scene(text, "fuzz.json");
  } catch (const weft::app::InputError&) {
    // bad input, reported as such: the expected outcome for most inputs
  }
  return 0;
}
