#pragma once
// A small interface to an off-screen OpenGL 3.3+ core context, so that the rasterizer does not
// depend on OSMesa (gone from Mesa 25.1): an EGL surfaceless context can stand in for it.

#include <cstring>
#include <memory>
#include <string>

#include "render/render_settings.h"

namespace weft::render {

class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual void make_current() = 0;
  // Address of a GL entry point, or nullptr.
  virtual void* proc_address(const char* name) const = 0;
  virtual std::string description() const = 0;  // e.g. "OSMesa 22.3.6, llvmpipe, GL 4.5 core"
};

// Creates an OSMesa context with an RGBA colour buffer of width×height and a 24-bit depth
// buffer; throws std::runtime_error with OSMesa's reason when it cannot.
std::unique_ptr<GlContext> make_osmesa_context(int width, int height);

// Creates an EGL context on Mesa's surfaceless platform (no window system, no surface; the
// rasterizer draws into its own framebuffer objects): OpenGL 3.3+ core, llvmpipe unless a GPU
// render node is present. Throws std::runtime_error with EGL's reason when it cannot, or when
// weft was built without EGL (CMake option WEFT_WITH_EGL).
std::unique_ptr<GlContext> make_egl_context(int width, int height);

// The context `choice` (render_settings.h) names; automatic tries OSMesa, then EGL. Throws
// std::runtime_error (with every reason) when no context can be created.
std::unique_ptr<GlContext> make_gl_context(GlBackend choice, int width, int height);

namespace detail {

// A function pointer as the object pointer proc_address returns (POSIX guarantees they match).
template <typename Function>
void* function_address(Function function) {
  void* address = nullptr;
  static_assert(sizeof(function) == sizeof(address));
  std::memcpy(&address, &function, sizeof(address));
  return address;
}

// "<GL_RENDERER>, GL <GL_VERSION>" of a context that is current, read through its
// proc_address; throws std::runtime_error starting with `who` when glGetString is missing.
std::string renderer_and_version(const GlContext& context, const std::string& who);

}  // namespace detail

}  // namespace weft::render
