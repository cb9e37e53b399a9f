// Stand-in for egl_context.cpp when weft is configured with WEFT_WITH_EGL=OFF or without EGL.

#include <stdexcept>

#include "render/gl_context.h"

namespace weft::render {

std::unique_ptr<GlContext> make_egl_context(int /*width*/, int /*height*/) {
  throw std::runtime_error(
      "make_egl_context: weft was built without EGL (install libegl-dev and libegl-mesa0, and "
      "configure with -DWEFT_WITH_EGL=ON)");
}

}  // namespace weft::render
