// What the GL contexts share (gl_context.h): choosing one — OSMesa or EGL surfaceless, or
// "auto" (OSMesa first, EGL when OSMesa is not built or cannot start); the environment variable
// WEFT_GL is read by app/ (app/run/renderer_choice.h), not here — and the renderer/version text of
// their descriptions.

#include <cstring>
#include <stdexcept>
#include <string>

#include "render/gl_context.h"

namespace weft::render {

std::unique_ptr<GlContext> make_gl_context(GlBackend choice, int width, int height) {
  switch (choice) {
    case GlBackend::osmesa:
      return make_osmesa_context(width, height);
    case GlBackend::egl:
      return make_egl_context(width, height);
    case GlBackend::automatic:
      break;
  }
  std::string osmesa_reason;
  try {
    return make_osmesa_context(width, height);
  } catch (const std::runtime_error& e) {
    osmesa_reason = e.what();
  }
  try {
    return make_egl_context(width, height);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("no OpenGL context for the rasterizer: " + osmesa_reason + "; " +
                             e.what());
  }
}

namespace detail {

std::string renderer_and_version(const GlContext& context, const std::string& who) {
  using GetStringFunction = const unsigned char* (*)(unsigned int);
  GetStringFunction get_string = nullptr;
  void* address = context.proc_address("glGetString");
  if (address == nullptr) throw std::runtime_error(who + ": glGetString is missing");
  std::memcpy(&get_string, &address, sizeof(address));
  const auto text = [&](unsigned int what) {
    const unsigned char* s = get_string(what);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  constexpr unsigned int gl_renderer = 0x1F01, gl_version = 0x1F02;  // GL_RENDERER, GL_VERSION
  return text(gl_renderer) + ", GL " + text(gl_version);
}

}  // namespace detail

}  // namespace weft::render
