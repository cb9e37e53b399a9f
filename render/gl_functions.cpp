// Run-time loading of the GL entry points in WEFT_GL_FUNCTION_LIST.

#include "render/gl_functions.h"

#include <cstring>
#include <stdexcept>

namespace weft::render::detail {

namespace {

template <typename FunctionPointer>
void load_one(const GlContext& context, const char* gl_name, FunctionPointer& out) {
  void* address = context.proc_address(gl_name);
  if (address == nullptr) {
    throw std::runtime_error("OpenGL function " + std::string(gl_name) +
                             " is missing from the context (" + context.description() + ")");
  }
  // Object pointer → function pointer: copy the representation (POSIX guarantees they match).
  static_assert(sizeof(FunctionPointer) == sizeof(void*));
  std::memcpy(&out, &address, sizeof(void*));
}

const char* error_name(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default:
      return "unknown GL error";
  }
}

}  // namespace

GlFunctions load_gl_functions(const GlContext& context) {
  GlFunctions gl;
#define WEFT_GL_LOAD_MEMBER(type, name) load_one(context, "gl" #name, gl.name);
  WEFT_GL_FUNCTION_LIST(WEFT_GL_LOAD_MEMBER)
#undef WEFT_GL_LOAD_MEMBER
  return gl;
}

void check_gl_error(const GlFunctions& gl, const std::string& where) {
  std::string errors;
  // Bounded: a lost context may report errors forever.
  for (int i = 0; i < 16; ++i) {
    const GLenum error = gl.GetError();
    if (error == GL_NO_ERROR) break;
    if (!errors.empty()) errors += ", ";
    errors += error_name(error);
  }
  if (!errors.empty()) throw std::runtime_error(where + ": OpenGL error " + errors);
}

}  // namespace weft::render::detail
