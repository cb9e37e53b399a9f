// Embree 3 triangle-geometry owners (see embree_scene.h).

#include "render/raytrace/embree_scene.h"

#include <cstring>
#include <stdexcept>

namespace weft::render::rt {

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "positions are copied as-is");
static_assert(sizeof(std::array<std::uint32_t, 3>) == 3 * sizeof(std::uint32_t),
              "triangles are copied as-is");

TriangleGeometry::~TriangleGeometry() {
  clear();
}

void TriangleGeometry::clear() {
  if (!m_geometry) return;
  rtcDetachGeometry(m_scene, m_id);
  rtcReleaseGeometry(m_geometry);
  m_geometry = nullptr;
  m_scene = nullptr;
  m_id = RTC_INVALID_GEOMETRY_ID;
  m_vertex_count = 0;
  m_triangles.clear();
}

void TriangleGeometry::set(EmbreeDevice& device, EmbreeScene& scene,
                           const std::vector<Eigen::Vector3f>& positions,
                           const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  const bool same_topology = m_geometry && m_scene == scene.get() &&
                             m_vertex_count == positions.size() && m_triangles == triangles;
  if (!same_topology) {
    clear();
    if (triangles.empty()) return;  // nothing to intersect
    RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    device.check("creating a triangle geometry");
    rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
    // Embree-owned buffers: it pads them as its SIMD loads require.
    rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                            3 * sizeof(float), positions.size());
    auto* index = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(std::uint32_t), triangles.size()));
    try {
      device.check("allocating a triangle geometry's buffers");
    } catch (...) {
      rtcReleaseGeometry(geometry);
      throw;
    }
    std::memcpy(index, triangles.data(), triangles.size() * sizeof(triangles[0]));
    m_geometry = geometry;
    m_scene = scene.get();
    m_id = rtcAttachGeometry(m_scene, m_geometry);
    m_vertex_count = positions.size();
    m_triangles = triangles;
    ++m_creations;
  } else {
    ++m_updates;
  }
  void* vertices = rtcGetGeometryBufferData(m_geometry, RTC_BUFFER_TYPE_VERTEX, 0);
  std::memcpy(vertices, positions.data(), positions.size() * sizeof(positions[0]));
  rtcUpdateGeometryBuffer(m_geometry, RTC_BUFFER_TYPE_VERTEX, 0);
  rtcCommitGeometry(m_geometry);
  device.check("committing a triangle geometry");
}

}  // namespace weft::render::rt
