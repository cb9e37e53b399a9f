#pragma once
// One interface for the renderers, chosen by RenderSettings::renderer: "raster" (OpenGL
// rasterizer, raster.h) or "raytrace" (Embree ray tracer, raytrace/ray_tracer.h, CMake option
// WEFT_WITH_EMBREE_RT). Both draw the cloth and objects of one frame from the same settings
// (the contract, render_settings.h); the cloth first goes through prepare_cloth_mesh
// (render/cloth_surface.h: subdivision, thickness shell). app/ includes this header and the
// contract only, never a back-end's.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "render/image.h"
#include "render/mask.h"
#include "render/render_mesh.h"
#include "render/render_settings.h"

namespace weft::render {

class Renderer {
 public:
  virtual ~Renderer() = default;
  // Throws std::invalid_argument for bad settings or meshes (an object's message starts
  // "object k: "), std::runtime_error when the back-end fails.
  virtual Image render(const RenderMesh& cloth, const RenderSettings& settings,
                       const std::vector<RenderObject>& objects) = 0;
  // Which pixels render_mask() sets, each decided at the pixel's centre (one sample, no
  // antialiasing) from the geometry alone, never from colour:
  // - cloth: the camera ray meets the cloth first, not hidden by an object or the ground — the
  //   cloth's mask (mask_0001.png, the silhouette objective of `weft fit`);
  // - surfaces: the ray meets any surface (cloth, object, or the ground inside the middle of
  //   its faded rim, r < 0.8 half-sizes) — the opaque part of an RGBA frame.
  enum class MaskOf { cloth, surfaces };
  // The mask of the frame render() would draw from the same arguments: same camera, cloth
  // surface aids (subdivision, thickness shell), objects and ground; the same size. Cheaper
  // than render(): no lighting, one ray or fragment per pixel. Throws as render().
  virtual Mask render_mask(const RenderMesh& cloth, const RenderSettings& settings,
                           const std::vector<RenderObject>& objects, MaskOf which) = 0;
  virtual std::string description() const = 0;
  // Called during render() with the share of the frame done so far (0..1, increasing; from the
  // renderer's worker threads, one call at a time): the ray tracer reports its tiles, the
  // rasterizer nothing. An empty function stops the reports.
  using FrameProgress = std::function<void(double done)>;
  virtual void set_frame_progress(FrameProgress progress) { (void)progress; }
};

// The renderer settings.renderer names; the rasterizer gets the GL context settings.gl names
// (OSMesa or EGL; render/ reads no environment variable) of the settings' image size. Throws
// std::runtime_error when that back-end was not built or cannot start (e.g. no OSMesa
// context), saying which.
std::unique_ptr<Renderer> make_renderer(const RenderSettings& settings);

}  // namespace weft::render
