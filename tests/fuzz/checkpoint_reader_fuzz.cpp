// libFuzzer target: any bytes as a checkpoint's payload, behind a header with this build's hash
// and the payload's own hash (checkpoint_header), so that the reader goes past its integrity
// check into the sections (parse_checkpoint, app/io/run_checkpoint.h). It must give a
// checkpoint or throw InputError; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "app/io/input_error.h"
#include "app/io/run_checkpoint.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view payload(reinterpret_cast<const char*>(data), size);
  try {
    (void)weft::app::parse_checkpoint(weft::app::checkpoint_header(0, payload) + std::string(payload),
                                      "fuzz.weft");
  } catch (const weft::app::InputError&) {
    // bad input, reported as such
  }
  return 0;
}
