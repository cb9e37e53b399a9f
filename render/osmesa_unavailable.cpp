// Stand-in for osmesa_context.cpp when weft is configured with WEFT_WITH_OSMESA=OFF.

#include <stdexcept>

#include "render/gl_context.h"

namespace weft::render {

std::unique_ptr<GlContext> make_osmesa_context(int /*width*/, int /*height*/) {
  throw std::runtime_error(
      "make_osmesa_context: weft was built without OSMesa (configure with -DWEFT_WITH_OSMESA=ON)");
}

}  // namespace weft::render
