#pragma once
// Image-based lighting: an equirectangular environment map of linear RGB radiance (a Radiance
// .hdr file, read with stb_image), turned about the world's up axis and scaled, that lights the
// scene from all directions. Free of Embree and OpenGL: the ray tracer importance-samples it
// (render/raytrace/integrator.cpp), the rasterizer takes its 9 spherical-harmonic irradiance
// coefficients (Ramamoorthi & Hanrahan 2001).
//
// Directions. weft is z-up. Texel (x, y) of a W×H map (y = 0 the top row) spans
//     u ∈ [x/W, (x+1)/W],  v ∈ [y/H, (y+1)/H],
// and the map point (u, v) is the direction of polar angle θ = π v from +z (the top row is the
// zenith, the bottom row the nadir) and azimuth φ = π (1 − 2u) about +z, counter-clockwise from
// +x seen from above:
//     d = (sin θ cos φ, sin θ sin φ, cos θ).
// The centre column (u = ½) looks along +x, u = ¼ along +y, u = ¾ along −y and the left and
// right edges along −x: someone standing at the origin facing +x sees the map's middle ahead,
// its left half to the left, not mirrored. A rotation of α degrees turns the map by α
// counter-clockwise about +z (seen from above): world direction R_z(α) d shows the map's d.
// Radiance is the nearest texel's (piecewise constant: the function the sampler's pdf
// describes), times the intensity.

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <memory>
#include <vector>

namespace weft::render {

// Luminance of a linear RGB colour (Rec. 709 weights): the map's sampling density and the
// ray tracer's denoiser (render/denoise.h) weigh colours by it.
double luminance(const Eigen::Vector3f& linear_rgb);


// An equirectangular map (see above) with its importance-sampling tables: texel (x, y) is
// drawn with probability ∝ luminance × sin θ at its centre (Rec. 709 luminance), by a marginal
// CDF over rows and one conditional CDF per row, then uniformly in (u, v) within the texel.
class EnvironmentMap {
 public:
  // radiance: width × height linear RGB texels, row 0 the top; each channel finite and ≥ 0.
  // Throws std::invalid_argument otherwise (or for sizes below 2 × 1).
  EnvironmentMap(int width, int height, std::vector<Eigen::Vector3f> radiance);

  int width() const { return m_width; }
  int height() const { return m_height; }
  const Eigen::Vector3f& texel(int x, int y) const {
    return m_radiance[static_cast<std::size_t>(y) * m_width + x];
  }
  // The nearest texel's radiance in map direction d (unit).
  const Eigen::Vector3f& radiance(const Eigen::Vector3f& d) const;
  // False when every texel is black: nothing to sample (and nothing to light).
  bool samplable() const { return m_total > 0.0; }

  struct Sample {
    Eigen::Vector3f direction;  // map space, unit
    float pdf = 0.0f;           // per steradian
  };
  // A direction drawn from u1, u2 ∈ [0, 1) (samplable() maps only).
  Sample sample(float u1, float u2) const;
  // The pdf (per steradian) of sample() drawing map direction d (unit).
  float pdf(const Eigen::Vector3f& d) const;

 private:
  int m_width = 0, m_height = 0;
  std::vector<Eigen::Vector3f> m_radiance;
  std::vector<double> m_weight;       // luminance × sin θ per texel
  std::vector<double> m_marginal;     // H + 1 increasing values, 0 … 1
  std::vector<double> m_conditional;  // H rows of W + 1 increasing values, 0 … 1
  double m_total = 0.0;               // sum of m_weight
};

// Reads a Radiance .hdr as linear RGB. Throws std::runtime_error naming the path and stb's
// reason, or that the file is not a Radiance file (an 8-bit PNG or JPG, whatever its name).
EnvironmentMap read_environment_map(const std::filesystem::path& path);
// Writes `map` as a Radiance .hdr (tests make their maps with it). Throws std::runtime_error.
void write_environment_map(const std::filesystem::path& path, const EnvironmentMap& map);

// The environment of a scene (RenderSettings::environment).
struct Environment {
  std::shared_ptr<const EnvironmentMap> map;  // null: no environment (the uniform sky)
  double rotation_deg = 0.0;                  // about +z, counter-clockwise seen from above
  double intensity = 1.0;                     // radiance = intensity × texel
  bool background = true;                     // camera rays that miss show the map
};

// Throws std::invalid_argument ("RenderSettings: environment.…") unless rotation and
// intensity are finite and the intensity ≥ 0.
void validate(const Environment& environment);

// An Environment in world space, in floats, as the renderers read it.
class EnvironmentLight {
 public:
  explicit EnvironmentLight(const Environment& environment);
  const EnvironmentMap& map() const { return *m_map; }
  float intensity() const { return m_intensity; }
  Eigen::Vector3f to_map(const Eigen::Vector3f& world) const;
  Eigen::Vector3f to_world(const Eigen::Vector3f& map_direction) const;
  // intensity × the texel seen along world direction d (unit).
  Eigen::Vector3f radiance(const Eigen::Vector3f& d) const {
    return m_intensity * m_map->radiance(to_map(d));
  }
  EnvironmentMap::Sample sample(float u1, float u2) const;  // world direction
  float pdf(const Eigen::Vector3f& d) const { return m_map->pdf(to_map(d)); }

 private:
  const EnvironmentMap* m_map;
  float m_cos = 1.0f, m_sin = 0.0f, m_intensity = 1.0f;
};

// Spherical harmonics up to band 2, real basis, in the order (l, m) = (0,0), (1,−1), (1,0),
// (1,1), (2,−2), (2,−1), (2,0), (2,1), (2,2) (Ramamoorthi & Hanrahan 2001, eq. 3):
//   0.282095; 0.488603 (y, z, x); 1.092548 (xy, yz, xz); 0.315392 (3z² − 1); 0.546274 (x² − y²).
using ShBasis = std::array<float, 9>;
using ShCoefficients = std::array<Eigen::Vector3f, 9>;
ShBasis sh_basis(const Eigen::Vector3f& d);
// L_lm = ∫ L(d) Y_lm(d) dω of the environment's world-space radiance (rotation and intensity
// applied), integrated exactly over each texel (the map is piecewise constant): a map that is
// constant, or whose texels hold a band-≤2 function's texel means, projects exactly.
ShCoefficients project_sh(const Environment& environment);
// Irradiance E(n) = ∫ L(d) max(0, n·d) dω from the coefficients (Ramamoorthi & Hanrahan 2001,
// eq. 7, with Â0 = π, Â1 = 2π/3, Â2 = π/4): exact for band-≤2 radiance; a Lambertian surface
// of reflectance ρ then shows ρ E / π.
Eigen::Vector3f sh_irradiance(const ShCoefficients& radiance, const Eigen::Vector3f& n);
// The coefficients premultiplied by Â_l / π: Σ_k c_k Y_k(n) is E(n)/π, the radiance a white
// Lambertian surface of normal n reflects (what the rasterizer's shader sums).
ShCoefficients sh_reflected_radiance(const ShCoefficients& radiance);
// The same as a polynomial in the normal's coordinates: Σ_k p_k T_k(n) with the terms
// T = (1, y, z, x, xy, yz, 3z² − 1, xz, x² − y²), i.e. p_k = c_k × Y_k's constant. The
// rasterizer's shaders sum these (raster_shaders.cpp); sh_polynomial_value() does it here.
ShCoefficients sh_reflected_polynomial(const ShCoefficients& radiance);
Eigen::Vector3f sh_polynomial_value(const ShCoefficients& polynomial, const Eigen::Vector3f& n);

}  // namespace weft::render
