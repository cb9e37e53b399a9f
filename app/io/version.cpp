#include "app/io/version.h"

namespace weft::app {

const char* version() { return WEFT_VERSION; }

}  // namespace weft::app
