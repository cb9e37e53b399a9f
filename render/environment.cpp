// Environment maps: reading, importance sampling and spherical-harmonic projection (see
// environment.h for the direction mapping). stb's implementation is compiled into Debian's
// libstb; only its declarations are included here, as in image.cpp.

#include "render/environment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include <stb_image.h>
#include <stb_image_write.h>

#include "base/constants.h"
#include "render/image.h"

namespace weft::render {

namespace {

// Why stb would make up pixels from a Radiance file's data, or "" when it is whole: stb reads
// past the end as zeros (a truncated file gives black rows, not an error) and loops forever on
// a run-length-encoded count of 0. Walks the data as stbi__hdr_load does; what stb refuses
// itself (a wrong layout, a run too long for its scanline) is left to it.
std::string radiance_data_problem(const std::string& bytes) {
  std::size_t at = 0;
  const auto next_line = [&](std::string& line) {
    const std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos) return false;
    line = bytes.substr(at, end - at);
    at = end + 1;
    return true;
  };
  std::string line;
  do {
    if (!next_line(line)) return "the file ends in its header (a truncated file)";
  } while (!line.empty());
  if (!next_line(line)) return "the file ends before its resolution line (a truncated file)";
  int width = 0, height = 0;
  if (std::sscanf(line.c_str(), "-Y %d +X %d", &height, &width) != 2 || width <= 0 || height <= 0)
    return "";
  const auto truncated = [&](int row) {
    return "the pixel data ends in scanline " + std::to_string(row + 1) + " of " +
           std::to_string(height) + " (a truncated file)";
  };
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(bytes[k]); };
  const std::size_t flat_bytes = static_cast<std::size_t>(width) * height * 4;
  if (width < 8 || width >= 32768)  // flat pixels, 4 bytes each
    return bytes.size() - at < flat_bytes
               ? truncated(static_cast<int>((bytes.size() - at) / 4 / static_cast<std::size_t>(width)))
               : "";
  for (int row = 0; row < height; ++row) {
    if (bytes.size() - at < 4) return truncated(row);
    if (byte(at) != 2 || byte(at + 1) != 2 || (byte(at + 2) & 0x80))  // flat pixels from here
      return bytes.size() - at < flat_bytes ? truncated(row) : "";
    if ((byte(at + 2) << 8 | byte(at + 3)) != width) return "";
    at += 4;
    for (int channel = 0; channel < 4; ++channel) {
      for (int i = 0; i < width;) {
        if (at >= bytes.size()) return truncated(row);
        int count = byte(at++);
        const bool run = count > 128;
        if (run) count -= 128;
        if (count == 0)
          return "a run-length count of 0 in scanline " + std::to_string(row + 1) + " (corrupt)";
        if (count > width - i) return "";
        const std::size_t data = run ? 1 : static_cast<std::size_t>(count);
        if (bytes.size() - at < data) return truncated(row);
        at += data;
        i += count;
      }
    }
  }
  return "";
}

}  // namespace

double luminance(const Eigen::Vector3f& c) {
  return 0.2126 * c.x() + 0.7152 * c.y() + 0.0722 * c.z();
}

namespace {

using base::kPi;

// Map point (u, v) of direction d (unit), u, v ∈ [0, 1].
Eigen::Vector2f map_point(const Eigen::Vector3f& d) {
  const float theta = std::acos(std::clamp(d.z(), -1.0f, 1.0f));
  const float phi = std::atan2(d.y(), d.x());
  return {0.5f - phi / (2.0f * base::kPiF), theta / base::kPiF};
}

int texel_index(float t, int size) {
  return std::clamp(static_cast<int>(std::floor(t * static_cast<float>(size))), 0, size - 1);
}

// Turns `cdf` (values ≥ 0 in [1, n]) into a running sum scaled to end at exactly 1; entry 0 is 0.
double normalise_cdf(double* cdf, int n) {
  cdf[0] = 0.0;
  for (int i = 1; i <= n; ++i) cdf[i] += cdf[i - 1];
  const double total = cdf[n];
  for (int i = 1; i <= n; ++i) cdf[i] = total > 0.0 ? cdf[i] / total : static_cast<double>(i) / n;
  cdf[n] = 1.0;
  return total;
}

// Index i with cdf[i] ≤ t < cdf[i + 1] (a non-empty interval), and t's place within it.
int find_interval(const double* cdf, int n, double t, double& within) {
  const int i = std::clamp(static_cast<int>(std::upper_bound(cdf, cdf + n + 1, t) - cdf) - 1, 0,
                           n - 1);
  const double width = cdf[i + 1] - cdf[i];
  within = width > 0.0 ? std::clamp((t - cdf[i]) / width, 0.0, 1.0 - 1e-7) : 0.5;
  return i;
}

}  // namespace

EnvironmentMap::EnvironmentMap(int width, int height, std::vector<Eigen::Vector3f> radiance)
    : m_width(width), m_height(height), m_radiance(std::move(radiance)) {
  if (width < 2 || height < 1 ||
      m_radiance.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    throw std::invalid_argument("EnvironmentMap: expected at least 2×1 texels and width × height "
                                "radiance values, got " + std::to_string(width) + "×" +
                                std::to_string(height) + " and " +
                                std::to_string(m_radiance.size()));
  }
  for (const Eigen::Vector3f& c : m_radiance) {
    if (!c.allFinite() || c.minCoeff() < 0.0f)
      throw std::invalid_argument("EnvironmentMap: radiance must be finite and >= 0");
  }
  m_weight.resize(m_radiance.size());
  m_marginal.assign(static_cast<std::size_t>(height) + 1, 0.0);
  m_conditional.assign(static_cast<std::size_t>(height) * (width + 1), 0.0);
  for (int y = 0; y < height; ++y) {
    const double sin_theta = std::sin(kPi * (y + 0.5) / height);
    double* row = &m_conditional[static_cast<std::size_t>(y) * (width + 1)];
    for (int x = 0; x < width; ++x) {
      const std::size_t k = static_cast<std::size_t>(y) * width + x;
      m_weight[k] = luminance(m_radiance[k]) * sin_theta;
      row[x + 1] = m_weight[k];
    }
    m_marginal[y + 1] = normalise_cdf(row, width);
  }
  m_total = normalise_cdf(m_marginal.data(), height);
}

const Eigen::Vector3f& EnvironmentMap::radiance(const Eigen::Vector3f& d) const {
  const Eigen::Vector2f p = map_point(d);
  return texel(texel_index(p.x(), m_width), texel_index(p.y(), m_height));
}

EnvironmentMap::Sample EnvironmentMap::sample(float u1, float u2) const {
  double dv = 0.0, du = 0.0;
  const int y = find_interval(m_marginal.data(), m_height, u1, dv);
  const int x = find_interval(&m_conditional[static_cast<std::size_t>(y) * (m_width + 1)],
                              m_width, u2, du);
  const double u = (x + du) / m_width, v = (y + dv) / m_height;
  const double theta = kPi * v, phi = kPi * (1.0 - 2.0 * u);
  const double sin_theta = std::sin(theta);
  Sample s;
  s.direction = Eigen::Vector3d(sin_theta * std::cos(phi), sin_theta * std::sin(phi),
                                std::cos(theta)).cast<float>();
  const double p_uv = m_weight[static_cast<std::size_t>(y) * m_width + x] / m_total *
                      static_cast<double>(m_width) * m_height;
  s.pdf = sin_theta > 0.0 ? static_cast<float>(p_uv / (2.0 * kPi * kPi * sin_theta)) : 0.0f;
  return s;
}

float EnvironmentMap::pdf(const Eigen::Vector3f& d) const {
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - d.z() * d.z()));
  if (!(sin_theta > 0.0f) || !samplable()) return 0.0f;
  const Eigen::Vector2f p = map_point(d);
  const int x = texel_index(p.x(), m_width), y = texel_index(p.y(), m_height);
  const double p_uv = m_weight[static_cast<std::size_t>(y) * m_width + x] / m_total *
                      static_cast<double>(m_width) * m_height;
  return static_cast<float>(p_uv / (2.0 * kPi * kPi * sin_theta));
}

EnvironmentMap read_environment_map(const std::filesystem::path& path) {
  const std::string bytes = read_image_file(path, "read_environment_map");
  // stb converts an 8-bit image (a PNG named .hdr) to floats without a word: its radiance
  // would be made up, so only a Radiance file is read.
  if (!stbi_is_hdr_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()),
                               static_cast<int>(bytes.size())))
    throw std::runtime_error("read_environment_map: '" + path.string() +
                             "': not a Radiance .hdr file (expected the header \"#?RADIANCE\" "
                             "or \"#?RGBE\"; an 8-bit image holds no radiance)");
  if (const std::string why = radiance_data_problem(bytes); !why.empty())
    throw std::runtime_error("read_environment_map: '" + path.string() + "': " + why);
  int width = 0, height = 0, channels = 0;
  std::unique_ptr<float, void (*)(void*)> pixels(
      stbi_loadf_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()),
                             static_cast<int>(bytes.size()), &width, &height, &channels, 3),
      stbi_image_free);
  if (!pixels)
    throw std::runtime_error("read_environment_map: cannot read '" + path.string() +
                             "': " + stb_read_failure(path));
  std::vector<Eigen::Vector3f> radiance(static_cast<std::size_t>(width) * height);
  for (std::size_t k = 0; k < radiance.size(); ++k)
    radiance[k] = Eigen::Vector3f(pixels.get() + 3 * k).cwiseMax(0.0f);
  try {
    return EnvironmentMap(width, height, std::move(radiance));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("read_environment_map: '" + path.string() + "': " + e.what());
  }
}

void write_environment_map(const std::filesystem::path& path, const EnvironmentMap& map) {
  std::vector<float> data;
  data.reserve(static_cast<std::size_t>(map.width()) * map.height() * 3);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      for (int c = 0; c < 3; ++c) data.push_back(map.texel(x, y)[c]);
    }
  }
  if (!stbi_write_hdr(path.c_str(), map.width(), map.height(), 3, data.data()))
    throw std::runtime_error("write_environment_map: cannot write '" + path.string() + "'");
}

void validate(const Environment& e) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("RenderSettings: environment." + what);
  };
  if (!std::isfinite(e.rotation_deg)) fail("rotation_deg must be finite");
  if (!(e.intensity >= 0.0) || !std::isfinite(e.intensity))
    fail("intensity must be finite and >= 0");
}

EnvironmentLight::EnvironmentLight(const Environment& e)
    : m_map(e.map.get()),
      m_cos(static_cast<float>(std::cos(base::deg_to_rad(e.rotation_deg)))),
      m_sin(static_cast<float>(std::sin(base::deg_to_rad(e.rotation_deg)))),
      m_intensity(static_cast<float>(e.intensity)) {
  if (!m_map) throw std::invalid_argument("EnvironmentLight: no map");
}

Eigen::Vector3f EnvironmentLight::to_map(const Eigen::Vector3f& w) const {
  return {m_cos * w.x() + m_sin * w.y(), -m_sin * w.x() + m_cos * w.y(), w.z()};
}

Eigen::Vector3f EnvironmentLight::to_world(const Eigen::Vector3f& m) const {
  return {m_cos * m.x() - m_sin * m.y(), m_sin * m.x() + m_cos * m.y(), m.z()};
}

EnvironmentMap::Sample EnvironmentLight::sample(float u1, float u2) const {
  EnvironmentMap::Sample s = m_map->sample(u1, u2);
  s.direction = to_world(s.direction);
  return s;
}

}  // namespace weft::render
