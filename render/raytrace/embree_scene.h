#pragma once
// RAII owners for the ray tracer's Embree 3 objects: a device with its error hook installed, a
// scene, and triangle-mesh geometries whose vertex buffers can be updated frame by frame.
// (sim/collision/mesh_obstacle.cpp has its own minimal owners: sim/ must not depend on render/.)

#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace weft::render::rt {

// An Embree device. Its BVH builds run on one thread, so the tree, and with it every ray's hit,
// does not depend on any thread count. The error hook records the first error; check() turns
// it into std::runtime_error (throwing through Embree's C API is not allowed).
class EmbreeDevice {
 public:
  EmbreeDevice();
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return m_device; }
  // Throws std::runtime_error("Embree: <what>: <message>") if an error was reported.
  void check(const std::string& what);

 private:
  static void on_error(void* self, RTCError code, const char* message);
  RTCDevice m_device = nullptr;
  std::string m_error;
};

// An Embree scene built for offline frames (RTC_BUILD_QUALITY_HIGH).
class EmbreeScene {
 public:
  explicit EmbreeScene(EmbreeDevice& device);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  RTCScene get() const { return m_scene; }
  // rtcCommitScene, then device.check().
  void commit(EmbreeDevice& device);

 private:
  RTCScene m_scene = nullptr;
};

// One triangle mesh attached to a scene. set() keeps the geometry when only the positions
// changed (copies them into Embree's vertex buffer, rtcUpdateGeometryBuffer, recommit) and
// recreates it when the topology changed. The scene must be committed afterwards.
class TriangleGeometry {
 public:
  TriangleGeometry() = default;
  ~TriangleGeometry();
  TriangleGeometry(const TriangleGeometry&) = delete;
  TriangleGeometry& operator=(const TriangleGeometry&) = delete;

  // positions: #V, metres; triangles: #F index triples (checked by the caller).
  void set(EmbreeDevice& device, EmbreeScene& scene, const std::vector<Eigen::Vector3f>& positions,
           const std::vector<std::array<std::uint32_t, 3>>& triangles);
  // Detaches and releases the geometry (no-op when there is none).
  void clear();
  bool attached() const { return m_geometry != nullptr; }
  unsigned id() const { return m_id; }  // Embree's geometry ID while attached
  // Geometries created and vertex-buffer updates since construction (for tests).
  int creations() const { return m_creations; }
  int updates() const { return m_updates; }

 private:
  RTCScene m_scene = nullptr;
  RTCGeometry m_geometry = nullptr;
  unsigned m_id = RTC_INVALID_GEOMETRY_ID;
  std::size_t m_vertex_count = 0;
  std::vector<std::array<std::uint32_t, 3>> m_triangles;  // the topology in Embree's buffer
  int m_creations = 0, m_updates = 0;
};

}  // namespace weft::render::rt
