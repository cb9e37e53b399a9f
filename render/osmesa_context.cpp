// OSMesa implementation of GlContext: a software (llvmpipe) OpenGL 3.3+ core context rendering
// into a buffer it owns. The rasterizer draws into its own framebuffer objects, so this buffer
// only has to exist for OSMesaMakeCurrent.

#include <GL/osmesa.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/gl_context.h"

namespace weft::render {

namespace {

class OsmesaContext final : public GlContext {
 public:
  OsmesaContext(int width, int height) : m_width(width), m_height(height) {
    if (width <= 0 || height <= 0) {
      throw std::invalid_argument("make_osmesa_context: size must be positive, got " +
                                  std::to_string(width) + "x" + std::to_string(height));
    }
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_ACCUM_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    m_context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (m_context == nullptr) {
      throw std::runtime_error(
          "make_osmesa_context: OSMesaCreateContextAttribs failed to create an OpenGL 3.3 core "
          "context (RGBA, 24-bit depth); is Mesa's OSMesa (libosmesa6, llvmpipe) installed?");
    }
    m_buffer.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    try {
      make_current();
      m_description = "OSMesa, " + detail::renderer_and_version(*this, "OSMesa");
    } catch (...) {
      destroy();
      throw;
    }
  }

  ~OsmesaContext() override { destroy(); }

  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  void make_current() override {
    if (OSMesaGetCurrentContext() == m_context) return;
    if (!OSMesaMakeCurrent(m_context, m_buffer.data(), GL_UNSIGNED_BYTE, m_width, m_height)) {
      throw std::runtime_error("OSMesaMakeCurrent failed for a " + std::to_string(m_width) + "x" +
                               std::to_string(m_height) + " RGBA buffer");
    }
  }

  void* proc_address(const char* name) const override {
    return detail::function_address(OSMesaGetProcAddress(name));
  }

  std::string description() const override { return m_description; }

 private:
  void destroy() {
    if (m_context == nullptr) return;
    // Release it first if current, so Mesa holds no pointer to our buffer.
    if (OSMesaGetCurrentContext() == m_context) {
      OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
    }
    OSMesaDestroyContext(m_context);
    m_context = nullptr;
  }

  int m_width = 0, m_height = 0;
  OSMesaContext m_context = nullptr;
  std::vector<unsigned char> m_buffer;  // width×height RGBA bytes, bottom row first (GL order)
  std::string m_description;
};

}  // namespace

std::unique_ptr<GlContext> make_osmesa_context(int width, int height) {
  return std::make_unique<OsmesaContext>(width, height);
}

}  // namespace weft::render
