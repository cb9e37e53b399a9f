#pragma once
// The ray tracer's triangle-mesh geometries, whose vertex buffers can be updated frame by frame,
// attached to base's Embree scene owner.

#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "base/embree.h"

namespace weft::render::rt {

// The device and scene owners are base's (base/embree.h): one device per ray tracer, its BVH
// builds on one thread; the scene is built at RTC_BUILD_QUALITY_HIGH for offline frames.
using base::EmbreeDevice;
using base::EmbreeScene;

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
