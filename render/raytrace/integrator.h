#pragma once
// The ray tracer's per-pixel work: camera rays, hits, and the light they carry back. Pure
// functions of a read-only FrameView (built by ray_tracer.cpp once per frame), so that any
// number of threads can shade pixels at once.

#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "render/environment.h"
#include "render/raytrace/adaptive_sampling.h"
#include "render/raytrace/ray_tracer.h"
#include "render/render_mesh.h"
#include "render/render_settings.h"
#include "render/texture.h"
#include "render/weave.h"

namespace weft::render::rt {

// What shading needs to know of one Embree geometry.
struct SurfaceShading {
  const RenderMesh* mesh = nullptr;         // positions, unit vertex normals (same size), triangles
  Eigen::Vector3f front{0.0f, 0.0f, 0.0f};  // linear reflectance of the front (counter-clockwise)
  Eigen::Vector3f back{0.0f, 0.0f, 0.0f};   // and of the back side
  bool sheen = false;                       // the cloth: diffuse + sheen
  bool ground = false;                      // the ground: grid lines and fade (camera rays)
  // Replaces `front` (and `back` when texture_back) by the texture's colour at the hit's
  // material coordinates (mesh->uvs, interpolated) when set and the mesh has one UV per vertex
  // (render/texture.h).
  const Image* texture = nullptr;
  TexturePlacement texture_placement{};
  bool texture_back = false;
  // Replaces `front` and `back` (and the texture) by the vertex colours, interpolated, when
  // set (one per vertex of mesh: the strain false colour, render/strain_colour.h).
  const std::vector<Eigen::Vector3f>* vertex_colours = nullptr;
  // Tilts the shading normal by the weave's normal map (render/weave.h) when set and the mesh
  // has one UV per vertex.
  const Weave* weave = nullptr;
};

// One frame's scene and settings in the units and form the inner loop wants.
struct FrameView {
  RTCScene scene = nullptr;
  std::vector<SurfaceShading> surfaces;  // indexed by Embree geometry ID

  int width = 0, height = 0;
  // Camera: the ray through image point (px, py) (pixels, (0, 0) the top-left corner) is
  // eye + t (forward + (2 px / width − 1) right − (2 py / height − 1) up), t in [near, far]:
  // t is the depth along the view axis, as the rasterizer's clip planes. forward is the view
  // axis plus, for a calibrated camera, the shift of the image centre from the principal
  // point (perpendicular to it, so t stays the depth).
  Eigen::Vector3f eye, forward, right, up;  // right, up scaled by the half-extent at depth 1
  float near_m = 0.0f, far_m = 0.0f;
  float pixel_angle = 0.0f;  // radians per pixel at the image centre

  Shading shading = Shading::lit;
  Eigen::Vector3f sun{0.0f, 0.0f, 1.0f};         // unit, towards the sun
  float sun_cos_max = 1.0f;                      // cos of the sun's angular radius
  float sun_intensity = 0.0f;                    // see shading.h
  float sky = 0.0f;                              // sky radiance (RenderSettings::ambient)
  Eigen::Vector3f background{0.0f, 0.0f, 0.0f};  // linear radiance of camera rays that miss
  // Image-based lighting (render/environment.h): when set it replaces the sky (and, with
  // environment_background, the background colour).
  std::optional<EnvironmentLight> environment;
  bool environment_background = false;

  bool ground = false;
  Eigen::Vector3f ground_center{0.0f, 0.0f, 0.0f};
  float ground_half_size_m = 0.0f;

  int samples_per_pixel = 1, bounces = 0, ao_samples = 0;  // samples_per_pixel: the most
  AdaptiveSampling adaptive;  // when a pixel stops short of samples_per_pixel
  float ao_distance_m = 0.0f;
  float sheen = 0.0f, sheen_roughness = 0.5f;
  std::uint32_t seed = 0;
  float epsilon_m = 1e-5f;  // secondary rays start this far off the surface
};

// What the denoiser (render/denoise.h) needs of a pixel, from its camera samples: the means of
// the first hits' shading normal, reflectance (with the ground's grid lines) and distance over
// the samples that hit, the fraction that hit, and the variance of the mean of the samples'
// illumination luminance (radiance luminance / reflectance luminance; 0 with one sample);
// `mixed` when the samples' first hits are on different surfaces, or on different sides or
// colours of one (a silhouette against the ground, a fold's edge, a texture's edge).
struct PixelGuide {
  Eigen::Vector3f normal = Eigen::Vector3f::Zero(), albedo = Eigen::Vector3f::Zero();
  float depth_m = 0.0f, coverage = 0.0f, variance = 0.0f;
  bool mixed = false;
};

// What a camera sample met first, for the denoiser's guides.
struct FirstHit {
  bool hit = false;
  const SurfaceShading* surface = nullptr;
  Eigen::Vector3f normal, albedo;
  float depth_m = 0.0f;
};

// A pixel's camera samples so far (kept between adaptive sampling's passes): their radiance
// and the sums behind its PixelGuide.
struct PixelState {
  PixelSamples samples;
  PixelGuide guide_sums;  // sums over the samples that hit; `mixed` as it is
  double illumination_sum = 0.0, illumination_squares = 0.0;  // radiance / albedo luminance
  const SurfaceShading* first_surface = nullptr;  // the first sample's first hit
  Eigen::Vector3f first_albedo = Eigen::Vector3f::Zero();

  void add(const Eigen::Vector3f& radiance, const FirstHit& first);
  PixelGuide guide() const;  // the means over the samples so far
};

// Adds `count` camera samples to pixel (x, y), continuing its own sequence of samples (sample
// k of a pixel is the same whether taken in one pass or two); adds the rays it traced.
void add_pixel_samples(const FrameView& view, int x, int y, int count, PixelState& state,
                       RayCounts& counts);

// The surface the camera ray through the centre of pixel (x, y) meets first; nullptr when it
// meets none, or the ground where its rim has faded at least half into the background (the
// masks of Renderer::render_mask).
const SurfaceShading* visible_surface(const FrameView& view, int x, int y);

}  // namespace weft::render::rt
