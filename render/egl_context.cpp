// EGL implementation of GlContext: an OpenGL 3.3+ core context on Mesa's surfaceless platform
// (EGL_MESA_platform_surfaceless), with no surface at all (EGL_KHR_surfaceless_context). It
// stands in for OSMesa, which Mesa removed in 25.1. The rasterizer draws into its own framebuffer
// objects (raster.cpp), so no default framebuffer is needed.
//
// The EGLDisplay of the surfaceless platform is one per process (EGL returns the same handle to
// every caller), so a context never calls eglTerminate: that would destroy the contexts of every
// other renderer on the display. The display lives until the process exits.

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "render/gl_context.h"

namespace weft::render {

namespace {

const char* egl_error_name(EGLint error) {
  switch (error) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    default:
      return "unknown EGL error";
  }
}

// "make_egl_context: <what> failed (<EGL error name>)".
[[noreturn]] void fail(const std::string& what) {
  throw std::runtime_error("make_egl_context: " + what + " failed (" +
                           egl_error_name(eglGetError()) + ")");
}

bool has_extension(const char* extensions, const char* name) {
  if (extensions == nullptr) return false;
  const std::string list = std::string(" ") + extensions + " ";
  return list.find(std::string(" ") + name + " ") != std::string::npos;
}

// The surfaceless platform's display, initialised; throws with EGL's reason.
EGLDisplay surfaceless_display(EGLint& major, EGLint& minor) {
  const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client_extensions, "EGL_MESA_platform_surfaceless")) {
    throw std::runtime_error(
        "make_egl_context: EGL has no surfaceless platform (client extension "
        "EGL_MESA_platform_surfaceless missing; is Mesa's EGL driver, libegl-mesa0, installed?)");
  }
  const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_platform_display == nullptr) {
    throw std::runtime_error("make_egl_context: eglGetPlatformDisplayEXT is missing");
  }
  const EGLDisplay display =
      get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) fail("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
  if (!eglInitialize(display, &major, &minor)) fail("eglInitialize on the surfaceless display");
  return display;
}

class EglContext final : public GlContext {
 public:
  EglContext(int width, int height) {
    if (width <= 0 || height <= 0) {
      throw std::invalid_argument("make_egl_context: size must be positive, got " +
                                  std::to_string(width) + "x" + std::to_string(height));
    }
    EGLint major = 0, minor = 0;
    m_display = surfaceless_display(major, minor);
    const char* extensions = eglQueryString(m_display, EGL_EXTENSIONS);
    if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
      throw std::runtime_error(
          "make_egl_context: the surfaceless display lacks EGL_KHR_surfaceless_context");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");

    // A config is needed only to create the context; without EGL_KHR_no_config_context take
    // any RGBA8 OpenGL one (surface type 0: no surface is ever made).
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
      const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0,
                                          EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                          EGL_NONE};
      EGLint count = 0;
      if (!eglChooseConfig(m_display, config_attributes, &config, 1, &count)) {
        fail("eglChooseConfig (OpenGL, RGBA8)");
      }
      if (count < 1) {
        throw std::runtime_error("make_egl_context: no EGL config renders OpenGL in RGBA8");
      }
    }
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         3,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         3,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    m_context = eglCreateContext(m_display, config, EGL_NO_CONTEXT, context_attributes);
    if (m_context == EGL_NO_CONTEXT) fail("eglCreateContext (OpenGL 3.3 core)");
    try {
      make_current();
      m_description = "EGL " + std::to_string(major) + "." + std::to_string(minor) +
                      " surfaceless, " +
                      detail::renderer_and_version(*this, "make_egl_context");
    } catch (...) {
      destroy();
      throw;
    }
  }

  ~EglContext() override { destroy(); }

  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  void make_current() override {
    if (eglGetCurrentContext() == m_context) return;
    if (!eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, m_context)) {
      fail("eglMakeCurrent without a surface");
    }
  }

  void* proc_address(const char* name) const override {
    return detail::function_address(eglGetProcAddress(name));
  }

  std::string description() const override { return m_description; }

 private:
  void destroy() {
    if (m_context == EGL_NO_CONTEXT) return;
    if (eglGetCurrentContext() == m_context) {
      eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(m_display, m_context);
    m_context = EGL_NO_CONTEXT;
  }

  EGLDisplay m_display = EGL_NO_DISPLAY;
  EGLContext m_context = EGL_NO_CONTEXT;
  std::string m_description;
};

}  // namespace

std::unique_ptr<GlContext> make_egl_context(int width, int height) {
  return std::make_unique<EglContext>(width, height);
}

}  // namespace weft::render
