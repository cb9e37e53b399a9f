#pragma once
// A small interface to an off-screen OpenGL 3.3+ core context, so that the rasterizer does not
// depend on OSMesa (gone from Mesa 25.1): an EGL surfaceless context can stand in for it.

#include <memory>
#include <string>

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

}  // namespace weft::render
