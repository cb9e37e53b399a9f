// Per-pixel light transport of the ray tracer (see integrator.h and, for the shading model and
// its units, shading.h). Per camera sample:
//   1. the camera ray through a sub-pixel point (the pixel centre for 1 sample per pixel);
//      a miss shows the background,
//   2. at each hit: the sun, its visibility from one shadow ray into the sun's cone, times the
//      cosine with the shading normal; diffuse reflectance plus, on the cloth, the sheen lobe
//      (a textured cloth's front takes its reflectance from the texture at the hit's material
//      coordinates),
//   3. bounces left: continue along a cosine-weighted direction (the sky's radiance where it
//      escapes); none left: the sky times the unoccluded fraction of ao_samples cosine-weighted
//      rays of length ao_distance_m (ambient occlusion),
//   4. a camera ray's ground hit gets the grid lines and fades into the background at its rim.
// Under an environment map (render/environment.h) the sky and ambient occlusion give way to the
// map: at each hit, after the sun, one direction drawn from the map (luminance × sin θ) and one
// cosine-weighted direction, combined by multiple importance sampling (Veach's power heuristic,
// β = 2); the cosine direction also continues the path while bounces are left, else it is an
// occlusion ray to infinity. At the first hit both directions are stratified over the pixel's
// samples (stratified_dimensions, sampling.h). Camera rays that miss show the map when it is the background.


#include "render/raytrace/integrator.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "base/constants.h"
#include "render/raytrace/adaptive_sampling.h"
#include "render/raytrace/sampling.h"
#include "render/raytrace/shading.h"

namespace weft::render::rt {

namespace {

constexpr float infinity = std::numeric_limits<float>::infinity();

struct Hit {
  const SurfaceShading* surface = nullptr;
  Eigen::Vector3f position;     // metres
  Eigen::Vector3f geometric;    // unit geometric normal on the side the ray came from
  Eigen::Vector3f normal;       // unit shading normal (interpolated vertex normals), same side
  Eigen::Vector3f reflectance;  // of the side that was hit
  float distance_m = 0.0f;      // from the ray origin
};

// The shading normal n of the triangle t at barycentric (u, v), tilted by the weave's normal
// map with the triangle's tangents along the warp and the weft (weave.h); n itself where the
// tilt would turn it away from the side seen (geometric) or the triangle's UVs are degenerate.
Eigen::Vector3f woven_normal(const Weave& weave, const RenderMesh& mesh,
                             const std::array<std::uint32_t, 3>& t, float u, float v,
                             const Eigen::Vector3f& n, const Eigen::Vector3f& geometric) {
  const Eigen::Vector2f &uv_a = mesh.uvs[t[0]], &uv_b = mesh.uvs[t[1]], &uv_c = mesh.uvs[t[2]];
  const Eigen::Vector2f d1 = uv_b - uv_a, d2 = uv_c - uv_a;
  const float det = d1.x() * d2.y() - d1.y() * d2.x();
  if (!(std::abs(det) > 0.0f)) return n;
  const Eigen::Vector3f p1 = mesh.positions[t[1]] - mesh.positions[t[0]];
  const Eigen::Vector3f p2 = mesh.positions[t[2]] - mesh.positions[t[0]];
  const Eigen::Vector3f t_warp = (p1 * d2.y() - p2 * d1.y()) / det;
  const Eigen::Vector3f t_weft = (p2 * d1.x() - p1 * d2.x()) / det;
  const Eigen::Vector2f uv = (1.0f - u - v) * uv_a + u * uv_b + v * uv_c;
  const Eigen::Vector3f m =
      weave_normal(*weave.normal_map, uv.x() / static_cast<float>(weave.repeat_m.x()),
                   uv.y() / static_cast<float>(weave.repeat_m.y()), static_cast<float>(weave.depth));
  const Eigen::Vector3f tilted = tilt_normal(n, t_warp, t_weft, m);
  return tilted.dot(geometric) > 0.0f ? tilted : n;
}

RTCRay make_ray(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction, float tnear,
                float tfar) {
  RTCRay ray;
  ray.org_x = origin.x();
  ray.org_y = origin.y();
  ray.org_z = origin.z();
  ray.tnear = tnear;
  ray.dir_x = direction.x();
  ray.dir_y = direction.y();
  ray.dir_z = direction.z();
  ray.time = 0.0f;
  ray.tfar = tfar;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  return ray;
}

// The closest hit along origin + t direction, t in [tnear, tfar], or false.
bool intersect(const FrameView& view, const Eigen::Vector3f& origin,
               const Eigen::Vector3f& direction, float tnear, float tfar, Hit& hit) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit ray_hit;
  ray_hit.ray = make_ray(origin, direction, tnear, tfar);
  ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  ray_hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(view.scene, &context, &ray_hit);
  if (ray_hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

  const SurfaceShading& surface = view.surfaces[ray_hit.hit.geomID];
  const RenderMesh& mesh = *surface.mesh;
  const auto& t = mesh.triangles[ray_hit.hit.primID];
  const float u = ray_hit.hit.u, v = ray_hit.hit.v, w = 1.0f - u - v;
  const Eigen::Vector3f& a = mesh.positions[t[0]];
  const Eigen::Vector3f& b = mesh.positions[t[1]];
  const Eigen::Vector3f& c = mesh.positions[t[2]];
  hit.surface = &surface;
  hit.position = w * a + u * b + v * c;  // on the triangle, more exact than origin + t dir
  hit.distance_m = ray_hit.ray.tfar * direction.norm();

  Eigen::Vector3f geometric = (b - a).cross(c - a);  // the front side's normal
  const float length = geometric.norm();
  geometric = length > 0.0f ? Eigen::Vector3f(geometric / length) : Eigen::Vector3f::UnitZ();
  const bool front = geometric.dot(direction) < 0.0f;
  if (!front) geometric = -geometric;
  Eigen::Vector3f normal = w * mesh.normals[t[0]] + u * mesh.normals[t[1]] + v * mesh.normals[t[2]];
  if (!front) normal = -normal;
  const float normal_length = normal.norm();
  // Vertex normals of opposite sign across a sharp fold can cancel or point away from the
  // side seen: the geometric normal stands in.
  hit.normal = normal_length > 1e-6f && normal.dot(geometric) > 0.0f
                   ? Eigen::Vector3f(normal / normal_length)
                   : geometric;
  hit.geometric = geometric;
  if (surface.weave && mesh.uvs.size() == mesh.positions.size())
    hit.normal = woven_normal(*surface.weave, mesh, t, u, v, hit.normal, geometric);
  hit.reflectance = front ? surface.front : surface.back;
  if ((front || surface.texture_back) && surface.texture &&
      mesh.uvs.size() == mesh.positions.size()) {
    const Eigen::Vector2f uv = w * mesh.uvs[t[0]] + u * mesh.uvs[t[1]] + v * mesh.uvs[t[2]];
    hit.reflectance = reflectance_from_color(
        sample_placed_texture(*surface.texture, surface.texture_placement, uv));
  }
  if (const std::vector<Eigen::Vector3f>* colours = surface.vertex_colours) {
    hit.reflectance = reflectance_from_color(w * (*colours)[t[0]] + u * (*colours)[t[1]] +
                                             v * (*colours)[t[2]]);
  }
  return true;
}

bool occluded(const FrameView& view, const Eigen::Vector3f& origin,
              const Eigen::Vector3f& direction, float tfar) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = make_ray(origin, direction, 0.0f, tfar);
  rtcOccluded1(view.scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to −inf when something blocks the ray
}

Eigen::Vector3f offset_origin(const FrameView& view, const Hit& hit) {
  return hit.position + view.epsilon_m * hit.geometric;
}

// Radiance leaving `hit` towards `to_viewer` (unit) by the sun: diffuse, plus sheen on cloth.
Eigen::Vector3f sun_light(const FrameView& view, const Hit& hit, const Eigen::Vector3f& to_viewer,
                          Pcg32& rng, RayCounts& counts) {
  const float cosine = hit.normal.dot(view.sun);
  const float u1 = rng.next_float(), u2 = rng.next_float();  // drawn always: fixed stream use
  if (!(view.sun_intensity > 0.0f) || !(cosine > 0.0f)) return Eigen::Vector3f::Zero();
  const Eigen::Vector3f towards =
      view.sun_cos_max < 1.0f ? uniform_cone(view.sun, view.sun_cos_max, u1, u2) : view.sun;
  if (!(towards.dot(hit.geometric) > 0.0f)) return Eigen::Vector3f::Zero();  // below the surface
  ++counts.shadow;
  if (occluded(view, offset_origin(view, hit), towards, infinity)) return Eigen::Vector3f::Zero();
  Eigen::Vector3f out = hit.reflectance * (view.sun_intensity * cosine);
  if (hit.surface->sheen && view.sheen > 0.0f) {
    out += sheen_tint(hit.reflectance) *
           (view.sheen * view.sun_intensity *
            sheen_response(hit.normal, view.sun, to_viewer, view.sheen_roughness));
  }
  return out;
}

// Unoccluded fraction of ao_samples cosine-weighted rays of length ao_distance_m.
float sky_visibility(const FrameView& view, const Hit& hit, Pcg32& rng, RayCounts& counts) {
  if (view.ao_samples <= 0) return 1.0f;
  int open = 0;
  for (int k = 0; k < view.ao_samples; ++k) {
    const float u1 = rng.next_float(), u2 = rng.next_float();
    const Eigen::Vector3f direction = cosine_hemisphere(hit.normal, u1, u2);
    if (!(direction.dot(hit.geometric) > 0.0f)) continue;  // into the surface itself
    ++counts.occlusion;
    if (!occluded(view, offset_origin(view, hit), direction, view.ao_distance_m)) ++open;
  }
  return static_cast<float>(open) / static_cast<float>(view.ao_samples);
}

// Radiance of a camera ray along `direction` that meets nothing.
Eigen::Vector3f background(const FrameView& view, const Eigen::Vector3f& direction) {
  if (view.environment && view.environment_background)
    return view.environment->radiance(direction.normalized());
  return view.background;
}

// Veach's power heuristic (β = 2): the weight of a strategy of pdf a against one of pdf b.
float power_heuristic(float a, float b) {
  return a * a / (a * a + b * b);
}

// The BRDF of `hit` for light arriving from l, seen from v (unit, on the side of the shading
// normal): diffuse ρ/π plus, on the cloth, the sheen lobe tinted as in sun_light (f_sheen =
// D·V = sheen_response / (π n·l), shading.h).
Eigen::Vector3f brdf(const FrameView& view, const Hit& hit, const Eigen::Vector3f& l,
                     const Eigen::Vector3f& v) {
  Eigen::Vector3f f = hit.reflectance / base::kPiF;
  const float n_dot_l = hit.normal.dot(l);
  if (hit.surface->sheen && view.sheen > 0.0f && n_dot_l > 0.0f) {
    f += sheen_tint(hit.reflectance) *
         (view.sheen * sheen_response(hit.normal, l, v, view.sheen_roughness) /
          (base::kPiF * n_dot_l));
  }
  return f;
}

// The environment's light sample at `hit` from u = (u1, u2) ∈ [0, 1)²: a direction drawn from
// the map, its shadow ray, weighted against cosine sampling.
Eigen::Vector3f environment_light(const FrameView& view, const Hit& hit,
                                  const Eigen::Vector3f& to_viewer, const Eigen::Vector2f& u,
                                  RayCounts& counts) {
  const EnvironmentLight& environment = *view.environment;
  if (!environment.map().samplable() || !(environment.intensity() > 0.0f))
    return Eigen::Vector3f::Zero();
  const EnvironmentMap::Sample s = environment.sample(u.x(), u.y());
  const float cosine = hit.normal.dot(s.direction);
  if (!(s.pdf > 0.0f) || !(cosine > 0.0f) || !(s.direction.dot(hit.geometric) > 0.0f))
    return Eigen::Vector3f::Zero();
  ++counts.shadow;
  if (occluded(view, offset_origin(view, hit), s.direction, infinity))
    return Eigen::Vector3f::Zero();
  const float weight = power_heuristic(s.pdf, cosine / base::kPiF) * cosine / s.pdf;
  return environment.radiance(s.direction).cwiseProduct(brdf(view, hit, s.direction, to_viewer)) *
         weight;
}

// Steps 2–3 under an environment map (see the top): radiance towards the camera from its first
// hit. The first hit's map and cosine directions come from `strata` (stratified over the
// pixel's samples, sampling.h), later hits' from `rng`; the stream's use is the same either way.
Eigen::Vector3f environment_path(const FrameView& view, Hit hit, Eigen::Vector3f to_viewer,
                                 const Eigen::Vector4f& strata, Pcg32& rng, RayCounts& counts) {
  const EnvironmentLight& environment = *view.environment;
  Eigen::Vector3f radiance = Eigen::Vector3f::Zero();
  Eigen::Vector3f throughput = Eigen::Vector3f::Ones();
  for (int depth = 0;; ++depth) {
    radiance += throughput.cwiseProduct(sun_light(view, hit, to_viewer, rng, counts));
    Eigen::Vector4f u;
    for (int i = 0; i < 4; ++i) u[i] = rng.next_float();
    if (depth == 0) u = strata;
    radiance += throughput.cwiseProduct(environment_light(view, hit, to_viewer, u.head<2>(), counts));
    const Eigen::Vector3f next = cosine_hemisphere(hit.normal, u[2], u[3]);
    const float cosine = hit.normal.dot(next);
    if (!(next.dot(hit.geometric) > 0.0f) || !(cosine > 0.0f)) break;
    // BRDF · cos / pdf, with pdf = cos / π, and the MIS weight against the map's sampling.
    const Eigen::Vector3f escaped =
        throughput.cwiseProduct(brdf(view, hit, next, to_viewer)) *
        (base::kPiF * power_heuristic(cosine / base::kPiF, environment.pdf(next)));
    const Eigen::Vector3f origin = offset_origin(view, hit);
    if (depth == view.bounces) {
      ++counts.occlusion;
      if (!occluded(view, origin, next, infinity))
        radiance += escaped.cwiseProduct(environment.radiance(next));
      break;
    }
    ++counts.bounce;
    throughput = throughput.cwiseProduct(hit.reflectance);
    if (!intersect(view, origin, next, 0.0f, infinity, hit)) {
      radiance += escaped.cwiseProduct(environment.radiance(next));
      break;
    }
    to_viewer = -next;
  }
  return radiance;
}

// Steps 2–3 under the uniform sky: radiance towards the camera from its first hit.
Eigen::Vector3f sky_path(const FrameView& view, Hit hit, Eigen::Vector3f to_viewer, Pcg32& rng,
                         RayCounts& counts) {
  Eigen::Vector3f radiance = Eigen::Vector3f::Zero();
  Eigen::Vector3f throughput = Eigen::Vector3f::Ones();
  for (int depth = 0;; ++depth) {
    radiance += throughput.cwiseProduct(sun_light(view, hit, to_viewer, rng, counts));
    if (depth == view.bounces) {
      radiance += throughput.cwiseProduct(hit.reflectance) *
                  (view.sky * sky_visibility(view, hit, rng, counts));
      break;
    }
    const float u1 = rng.next_float(), u2 = rng.next_float();
    const Eigen::Vector3f next = cosine_hemisphere(hit.normal, u1, u2);
    if (!(next.dot(hit.geometric) > 0.0f)) break;  // into the surface: absorbed
    throughput = throughput.cwiseProduct(hit.reflectance);
    ++counts.bounce;
    const Eigen::Vector3f origin = offset_origin(view, hit);
    if (!intersect(view, origin, next, 0.0f, infinity, hit)) {
      radiance += throughput * view.sky;
      break;
    }
    to_viewer = -next;
  }
  return radiance;
}

// Grid lines and rim fade of the ground seen by a camera ray: the reflectance factor (lines),
// and the weight of the background (0 inside, 1 at the rim).
void ground_pattern(const FrameView& view, const Hit& hit, const Eigen::Vector3f& direction_unit,
                    float& line_factor, float& background_weight) {
  const float incidence = std::max(std::abs(direction_unit.dot(hit.geometric)), 0.25f);
  const float pixel_m = hit.distance_m * view.pixel_angle / incidence;
  line_factor = 1.0f - ground_grid_lines(hit.position.x(), hit.position.y(), pixel_m);
  const float r =
      (hit.position.head<2>() - view.ground_center.head<2>()).norm() / view.ground_half_size_m;
  const float t = std::clamp((r - 0.6f) / 0.4f, 0.0f, 1.0f);
  background_weight = t * t * (3.0f - 2.0f * t);
}

// The camera ray's direction through image point (px, py) (FrameView's camera).
Eigen::Vector3f camera_direction(const FrameView& view, float px, float py) {
  return view.forward + (2.0f * px / static_cast<float>(view.width) - 1.0f) * view.right -
         (2.0f * py / static_cast<float>(view.height) - 1.0f) * view.up;
}

// Linear radiance of one camera sample through image point (px, py).
Eigen::Vector3f render_sample(const FrameView& view, float px, float py,
                              const Eigen::Vector4f& strata, Pcg32& rng, RayCounts& counts,
                              FirstHit& first) {
  const Eigen::Vector3f direction = camera_direction(view, px, py);
  ++counts.camera;
  Hit hit;
  if (!intersect(view, view.eye, direction, view.near_m, view.far_m, hit))
    return background(view, direction);
  Eigen::Vector3f to_viewer = -direction.normalized();
  first.hit = true;
  first.normal = hit.normal;
  first.depth_m = hit.distance_m;

  if (view.shading == Shading::normals) {  // the colour 0.5 n + 0.5, as the rasterizer
    return reflectance_from_color(0.5f * hit.normal + Eigen::Vector3f::Constant(0.5f));
  }
  float background_weight = 0.0f;
  if (hit.surface->ground) {
    float line_factor = 1.0f;
    ground_pattern(view, hit, -to_viewer, line_factor, background_weight);
    hit.reflectance *= line_factor;
  }
  first.albedo = hit.reflectance;
  first.surface = hit.surface;

  const Eigen::Vector3f radiance = view.environment
                                      ? environment_path(view, hit, to_viewer, strata, rng, counts)
                                      : sky_path(view, hit, to_viewer, rng, counts);
  if (!(background_weight > 0.0f)) return radiance;
  return (1.0f - background_weight) * radiance + background_weight * background(view, direction);
}

}  // namespace

void PixelState::add(const Eigen::Vector3f& radiance, const FirstHit& first) {
  double l = luminance(radiance);
  samples.add(radiance, l);
  if (first.hit) {
    // Another surface, or the other side or colour of it (by more than the denoiser's
    // sigma_albedo): a pixel of an edge.
    if (!first_surface) {
      first_surface = first.surface;
      first_albedo = first.albedo;
    } else if (first.surface != first_surface ||
               (first.albedo - first_albedo).cwiseAbs().maxCoeff() > 0.1f) {
      guide_sums.mixed = true;
    }
    guide_sums.normal += first.normal;
    guide_sums.albedo += first.albedo;
    guide_sums.depth_m += first.depth_m;
    guide_sums.coverage += 1.0f;
    l /= std::max(luminance(first.albedo), 1e-3);
  }
  illumination_sum += l;
  illumination_squares += l * l;
}

PixelGuide PixelState::guide() const {
  PixelGuide g = guide_sums;
  if (g.coverage > 0.0f) {
    g.normal /= g.coverage;
    g.albedo /= g.coverage;
    g.depth_m /= g.coverage;
  }
  const auto n = static_cast<double>(samples.count());
  if (n > 0.0) g.coverage /= static_cast<float>(n);
  // Variance of the mean: the samples' unbiased variance over their count.
  if (n > 1.0)
    g.variance = static_cast<float>(
        std::max(0.0, (illumination_squares - illumination_sum * illumination_sum / n) / (n - 1.0)) / n);
  return g;
}

void add_pixel_samples(const FrameView& view, int x, int y, int count, PixelState& state,
                       RayCounts& counts) {
  const std::uint64_t pixel_index =
      static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(view.width) +
      static_cast<std::uint64_t>(x);
  // The pixel's own rotations of the sub-pixel pattern and of the first hit's light samples.
  Pcg32 pixel_rng = sample_generator(pixel_index, 0xFFFFFFFFu, view.seed);
  const Eigen::Vector2f rotation(pixel_rng.next_float(), pixel_rng.next_float());
  Eigen::Vector4f strata_rotation;
  for (int i = 0; i < 4; ++i) strata_rotation[i] = pixel_rng.next_float();
  for (int r = 0; r < count; ++r) {
    const auto sample = static_cast<std::uint32_t>(state.samples.count());
    const Eigen::Vector2f offset = view.samples_per_pixel == 1 ? Eigen::Vector2f(0.5f, 0.5f)
                                                               : pixel_offset(sample, rotation);
    Pcg32 rng = sample_generator(pixel_index, sample, view.seed);
    FirstHit first;
    const Eigen::Vector3f radiance = render_sample(
        view, static_cast<float>(x) + offset.x(), static_cast<float>(y) + offset.y(),
        stratified_dimensions(sample, strata_rotation), rng, counts, first);
    state.add(radiance, first);
  }
}

const SurfaceShading* visible_surface(const FrameView& view, int x, int y) {
  const Eigen::Vector3f direction =
      camera_direction(view, static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
  Hit hit;
  if (!intersect(view, view.eye, direction, view.near_m, view.far_m, hit)) return nullptr;
  if (hit.surface->ground) {
    float line_factor = 1.0f, background_weight = 0.0f;
    ground_pattern(view, hit, direction.normalized(), line_factor, background_weight);
    if (background_weight >= 0.5f) return nullptr;
  }
  return hit.surface;
}

}  // namespace weft::render::rt
