#pragma once
// Embree 3 ray tracer: draws the same cloth, objects and ground as RasterRenderer, seen by the
// same camera (silhouettes agree pixel for pixel), with a soft-shadowed sun, ambient occlusion
// or path-traced bounces, diffuse + cloth sheen shading, two-sided cloth. The shading model and
// its colour encoding are in render/raytrace/shading.h; the settings it adds in
// render/raytrace/raytrace_settings.h (RenderSettings::raytrace).
//
// Deterministic: each pixel sample has its own random generator seeded from its pixel and
// sample index, BVHs are built on one thread, so the bytes do not depend on the thread count.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "render/image.h"
#include "render/mask.h"
#include "render/render_mesh.h"
#include "render/render_settings.h"

namespace weft::render {

// Rays traced by the last render() (for benchmarks).
struct RayCounts {
  std::uint64_t camera = 0, shadow = 0, occlusion = 0, bounce = 0;
  std::uint64_t total() const { return camera + shadow + occlusion + bounce; }
};

class RayTracer {
 public:
  RayTracer();
  ~RayTracer();
  RayTracer(const RayTracer&) = delete;
  RayTracer& operator=(const RayTracer&) = delete;

  // The cloth and extra opaque objects (RasterRenderer's entry point). Between calls the
  // cloth's Embree geometry is kept and only its vertex buffer updated while its triangles stay
  // the same. Throws std::invalid_argument for bad settings or a bad mesh (an object's message
  // starts "object k: "), std::runtime_error for an Embree failure.
  Image render(const RenderMesh& cloth, const RenderSettings& settings,
               const std::vector<RenderObject>& objects);
  // The cloth's mask (cloth_only) or that of every surface, at the pixel centres, from the
  // geometry (Renderer::render_mask, render/renderer.h).
  Mask render_mask(const RenderMesh& cloth, const RenderSettings& settings,
                   const std::vector<RenderObject>& objects, bool cloth_only);
  std::string description() const;
  // Called after each 16×16 tile of render() with the share of tiles done (0..1, increasing),
  // from the worker threads one call at a time; empty: no reports.
  void set_frame_progress(std::function<void(double done)> progress);
  RayCounts last_ray_counts() const;
  // Embree geometries created for the cloth so far (its topology changed, or the first frame).
  int cloth_geometry_creations() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace weft::render
