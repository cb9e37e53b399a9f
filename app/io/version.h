#pragma once

namespace weft::app {

// The project version from CMake (WEFT_VERSION), e.g. "0.1.0".
const char* version();

}  // namespace weft::app
