// Point caches (.pc2, .mdd), the rest OBJ and the animated glTF (see point_cache.h).

#include "app/io/point_cache.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "app/io/output_files.h"
#include "app/io/input_error.h"

namespace weft::app {

namespace fs = std::filesystem;

namespace {

// weft's z up → y up: (x, y, z) ↦ (x, z, −y).
Eigen::Vector3f y_up(const Eigen::Vector3f& p) { return {p.x(), p.z(), -p.y()}; }

// Appends the 4 bytes of an int32 or float32, little- or big-endian.
template <class T>
void put(std::string& bytes, T value, bool big_endian) {
  static_assert(sizeof(T) == 4);
  std::uint32_t word;
  std::memcpy(&word, &value, 4);
  for (int k = 0; k < 4; ++k) {
    const int shift = big_endian ? 24 - 8 * k : 8 * k;
    bytes.push_back(static_cast<char>((word >> shift) & 0xFFu));
  }
}

void put_points(std::string& bytes, const std::vector<Eigen::Vector3f>& points, bool big_endian) {
  for (const Eigen::Vector3f& p : points)
    for (int c = 0; c < 3; ++c) put(bytes, p[c], big_endian);
}

std::string pc2_bytes(const std::vector<std::vector<Eigen::Vector3f>>& frames) {
  std::string bytes("POINTCACHE2", 11);
  bytes.push_back('\0');
  put(bytes, std::int32_t{1}, false);  // version
  put(bytes, static_cast<std::int32_t>(frames.front().size()), false);
  put(bytes, 0.0f, false);  // start frame: weft's frame 0, the start (sample k is frame k)
  put(bytes, 1.0f, false);  // one sample per frame
  put(bytes, static_cast<std::int32_t>(frames.size()), false);
  for (const auto& frame : frames) put_points(bytes, frame, false);
  return bytes;
}

std::string mdd_bytes(const std::vector<std::vector<Eigen::Vector3f>>& frames,
                      const std::vector<double>& times_s) {
  std::string bytes;
  put(bytes, static_cast<std::int32_t>(frames.size()), true);
  put(bytes, static_cast<std::int32_t>(frames.front().size()), true);
  for (const double t : times_s) put(bytes, static_cast<float>(t), true);
  for (const auto& frame : frames) put_points(bytes, frame, true);
  return bytes;
}

std::string obj_text(const render::RenderMesh& m, const std::string& mtl_name) {
  std::ostringstream out;
  out.precision(9);
  out << "# weft: the cloth at the start (frame 0), y up; animate it with the .pc2/.mdd beside it\n"
         "mtllib " << mtl_name << "\no cloth\nusemtl cloth\n";
  for (const Eigen::Vector3f& p : m.positions) out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  const bool uvs = m.uvs.size() == m.positions.size();
  for (const Eigen::Vector2f& t : m.uvs) out << "vt " << t.x() << ' ' << t.y() << '\n';
  for (const auto& t : m.triangles) {
    out << 'f';
    for (const std::uint32_t v : t) {
      out << ' ' << v + 1;
      if (uvs) out << '/' << v + 1;
    }
    out << '\n';
  }
  return out.str();
}

// The OBJ's material: the cloth's front colour (linear), not shiny.
std::string mtl_text(const Eigen::Vector3f& colour) {
  std::ostringstream out;
  out.precision(6);
  out << "# weft: the cloth's colour (render.colors.front)\nnewmtl cloth\nKd " << colour.x() << ' '
      << colour.y() << ' ' << colour.z() << "\nKa 0 0 0\nKs 0 0 0\nNs 1\nillum 1\n";
  return out.str();
}

// The glTF's binary buffer and its JSON, built side by side: each added array gets a buffer view
// and an accessor.
class GltfBuilder {
 public:
  int add_floats(const std::vector<float>& values, int components, bool min_max = false) {
    const std::size_t offset = m_bin.size();
    for (const float v : values) put(m_bin, v, false);
    nlohmann::json accessor = {{"bufferView", add_view(offset, 0)},
                               {"componentType", 5126},
                               {"count", values.size() / components},
                               {"type", components == 1 ? "SCALAR" : components == 2 ? "VEC2" : "VEC3"}};
    if (min_max) {
      std::vector<float> lo(components, values[0]), hi(components, values[0]);
      for (std::size_t k = 0; k < values.size(); ++k) {
        lo[k % components] = std::min(lo[k % components], values[k]);
        hi[k % components] = std::max(hi[k % components], values[k]);
      }
      accessor["min"] = lo;
      accessor["max"] = hi;
    }
    m_json["accessors"].push_back(accessor);
    return static_cast<int>(m_json["accessors"].size()) - 1;
  }
  int add_indices(const std::vector<std::array<std::uint32_t, 3>>& triangles) {
    const std::size_t offset = m_bin.size();
    for (const auto& t : triangles)
      for (const std::uint32_t v : t) put(m_bin, v, false);
    m_json["accessors"].push_back({{"bufferView", add_view(offset, 34963)},
                                   {"componentType", 5125},
                                   {"count", 3 * triangles.size()},
                                   {"type", "SCALAR"}});
    return static_cast<int>(m_json["accessors"].size()) - 1;
  }
  nlohmann::json& json() { return m_json; }
  const std::string& bin() const { return m_bin; }

 private:
  int add_view(std::size_t offset, int target) {
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", m_bin.size() - offset}};
    if (target) view["target"] = target;
    m_json["bufferViews"].push_back(view);
    return static_cast<int>(m_json["bufferViews"].size()) - 1;
  }
  nlohmann::json m_json = nlohmann::json::object();
  std::string m_bin;
};

std::vector<float> flat(const std::vector<Eigen::Vector3f>& points,
                        const std::vector<Eigen::Vector3f>* minus = nullptr) {
  std::vector<float> out;
  out.reserve(3 * points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    for (int c = 0; c < 3; ++c) out.push_back(points[k][c] - (minus ? (*minus)[k][c] : 0.0f));
  return out;
}

// The animated glTF: frame 0 (the start) as the base mesh, frame k > 0 as morph target k − 1
// (positions and normals relative to frame 0), weights stepping from target to target at the
// frames' times; one material of the cloth's colour.
std::pair<std::string, std::string> gltf_files(const render::RenderMesh& topology,
                                               const std::vector<std::vector<Eigen::Vector3f>>& positions,
                                               const std::vector<std::vector<Eigen::Vector3f>>& normals,
                                               const std::vector<double>& times_s,
                                               const std::string& bin_name,
                                               const Eigen::Vector3f& colour) {
  GltfBuilder b;
  nlohmann::json attributes = {{"POSITION", b.add_floats(flat(positions[0]), 3, true)},
                               {"NORMAL", b.add_floats(flat(normals[0]), 3)}};
  if (topology.uvs.size() == topology.positions.size()) {
    std::vector<float> uvs;
    for (const Eigen::Vector2f& t : topology.uvs) uvs.insert(uvs.end(), {t.x(), t.y()});
    attributes["TEXCOORD_0"] = b.add_floats(uvs, 2);
  }
  nlohmann::json primitive = {{"attributes", attributes},
                               {"indices", b.add_indices(topology.triangles)},
                               {"material", 0}};
  nlohmann::json mesh = {{"name", "cloth"}};
  const std::size_t frames = positions.size(), targets = frames - 1;
  if (targets > 0) {
    std::vector<std::string> names;
    for (std::size_t k = 1; k < frames; ++k) {
      primitive["targets"].push_back(
          {{"POSITION", b.add_floats(flat(positions[k], &positions[0]), 3, true)},
           {"NORMAL", b.add_floats(flat(normals[k], &normals[0]), 3)}});
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04zu", k);
      names.emplace_back(name);
    }
    mesh["weights"] = std::vector<float>(targets, 0.0f);
    mesh["extras"] = {{"targetNames", names}};  // Blender names the shape keys after these
    std::vector<float> times, weights(frames * targets, 0.0f);
    for (std::size_t k = 0; k < frames; ++k) {
      times.push_back(static_cast<float>(times_s[k]));  // frame k at Blender frame k
      if (k > 0) weights[k * targets + (k - 1)] = 1.0f;
    }
    const int input = b.add_floats(times, 1, true);
    const int output = b.add_floats(weights, 1);
    nlohmann::json sampler = {{"input", input}, {"output", output}, {"interpolation", "STEP"}};
    nlohmann::json target = {{"node", 0}, {"path", "weights"}};
    nlohmann::json channel = {{"sampler", 0}, {"target", target}};
    nlohmann::json animation = {{"name", "simulation"}};
    animation["samplers"] = nlohmann::json::array({sampler});
    animation["channels"] = nlohmann::json::array({channel});
    b.json()["animations"] = nlohmann::json::array({animation});
  }
  mesh["primitives"] = nlohmann::json::array({primitive});
  nlohmann::json& j = b.json();
  j["asset"] = {{"version", "2.0"}, {"generator", "weft"}};
  j["scene"] = 0;
  j["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
  j["nodes"] = nlohmann::json::array({{{"name", "cloth"}, {"mesh", 0}}});
  j["meshes"] = nlohmann::json::array({mesh});
  nlohmann::json pbr = {{"baseColorFactor", {colour.x(), colour.y(), colour.z(), 1.0f}},
                        {"metallicFactor", 0.0f},
                        {"roughnessFactor", 1.0f}};
  j["materials"] = nlohmann::json::array({{{"name", "cloth"}, {"pbrMetallicRoughness", pbr}}});
  j["buffers"] = nlohmann::json::array({{{"uri", bin_name}, {"byteLength", b.bin().size()}}});
  return {j.dump(1) + "\n", b.bin()};
}

}  // namespace

std::vector<CacheFormat> parse_cache_formats(const std::string& text, const std::string& option) {
  std::vector<CacheFormat> formats;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item == "pc2") formats.push_back(CacheFormat::pc2);
    else if (item == "mdd") formats.push_back(CacheFormat::mdd);
    else if (item == "gltf") formats.push_back(CacheFormat::gltf);
    else
      throw InputError(option + ": expected pc2, mdd, gltf or a comma-separated list of them, got '" +
                       text + "'");
  }
  if (formats.empty())
    throw InputError(option + ": expected pc2, mdd, gltf or a comma-separated list of them, got ''");
  return formats;
}

void PointCache::add(const render::RenderMesh& frame, double time_s) {
  if (m_times_s.empty()) {
    m_topology.triangles = frame.triangles;
    m_topology.uvs = frame.uvs;
    for (const Eigen::Vector3f& p : frame.positions) m_topology.positions.push_back(y_up(p));
  } else if (frame.positions.size() != m_topology.positions.size()) {
    throw std::invalid_argument("PointCache: frame " + std::to_string(m_times_s.size()) +
                                " has " + std::to_string(frame.positions.size()) +
                                " vertices, frame 0 had " +
                                std::to_string(m_topology.positions.size()));
  }
  std::vector<Eigen::Vector3f> positions, normals;
  for (const Eigen::Vector3f& p : frame.positions) positions.push_back(y_up(p));
  render::RenderMesh storage;
  for (const Eigen::Vector3f& n : render::with_normals(frame, storage).normals) normals.push_back(y_up(n));
  m_positions.push_back(std::move(positions));
  m_normals.push_back(std::move(normals));
  m_times_s.push_back(time_s);
}

std::vector<fs::path> PointCache::write(const fs::path& stem, const std::vector<CacheFormat>& formats,
                                        const Eigen::Vector3f& colour) const {
  std::vector<fs::path> written;
  if (m_times_s.empty()) return written;
  const auto with = [&](const char* extension) { return fs::path(stem.string() + extension); };
  const auto emit = [&](const fs::path& path, const std::string& bytes) {
    write_text(path, bytes);
    written.push_back(path);
  };
  emit(with(".mtl"), mtl_text(colour));
  emit(with(".obj"), obj_text(m_topology, with(".mtl").filename().string()));
  for (const CacheFormat format : formats) {
    switch (format) {
      case CacheFormat::pc2: emit(with(".pc2"), pc2_bytes(m_positions)); break;
      case CacheFormat::mdd: emit(with(".mdd"), mdd_bytes(m_positions, m_times_s)); break;
      case CacheFormat::gltf: {
        const auto [json, bin] = gltf_files(m_topology, m_positions, m_normals, m_times_s,
                                            with(".bin").filename().string(), colour);
        emit(with(".bin"), bin);
        emit(with(".gltf"), json);
        break;
      }
    }
  }
  return written;
}

}  // namespace weft::app
