#pragma once
// Private to render/: the OpenGL 3.3 core entry points the rasterizer uses, loaded at run time
// through GlContext::proc_address so that any context (OSMesa now, EGL later) can provide them.
// Nothing in weft links GL symbols directly.

#include <GL/glcorearb.h>

#include <string>

#include "render/gl_context.h"

namespace weft::render::detail {

// X-macro: (pointer type from glcorearb.h, member name = GL name without the "gl" prefix).
#define WEFT_GL_FUNCTION_LIST(X)                                             \
  X(PFNGLGETERRORPROC, GetError)                                             \
  X(PFNGLGETSTRINGPROC, GetString)                                           \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                       \
  X(PFNGLVIEWPORTPROC, Viewport)                                             \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                         \
  X(PFNGLCLEARDEPTHPROC, ClearDepth)                                         \
  X(PFNGLCLEARPROC, Clear)                                                   \
  X(PFNGLENABLEPROC, Enable)                                                 \
  X(PFNGLDISABLEPROC, Disable)                                               \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                           \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                           \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                   \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                           \
  X(PFNGLFINISHPROC, Finish)                                                 \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                       \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                         \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                                         \
  X(PFNGLDRAWBUFFERPROC, DrawBuffer)                                         \
  X(PFNGLSCISSORPROC, Scissor)                                               \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                         \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                                     \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                               \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                         \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                               \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)               \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                     \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                 \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                               \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                             \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                       \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                             \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample) \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                       \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                 \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                       \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                   \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                         \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                   \
  X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap)                                 \
  X(PFNGLCREATESHADERPROC, CreateShader)                                     \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                     \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                   \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                       \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                             \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                     \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                   \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                     \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                       \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                     \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                           \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                   \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                         \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                         \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                           \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                           \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                           \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                           \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                             \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                               \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                         \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                               \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                         \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                   \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                         \
  X(PFNGLBUFFERDATAPROC, BufferData)                                         \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                       \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)

// One function pointer per entry of WEFT_GL_FUNCTION_LIST, e.g. gl.Clear(GL_COLOR_BUFFER_BIT).
struct GlFunctions {
#define WEFT_GL_DECLARE_MEMBER(type, name) type name = nullptr;
  WEFT_GL_FUNCTION_LIST(WEFT_GL_DECLARE_MEMBER)
#undef WEFT_GL_DECLARE_MEMBER
};

// Loads every entry point from the (current) context; throws std::runtime_error naming the
// first missing function.
GlFunctions load_gl_functions(const GlContext& context);

// Throws std::runtime_error("<where>: GL error <name>") if glGetError reports an error
// (all pending errors are drained and listed).
void check_gl_error(const GlFunctions& gl, const std::string& where);

}  // namespace weft::render::detail
