#pragma once
// The cloth's animation as one file set that Blender, Houdini and glTF viewers read without
// add-ons (weft run --export-cache): the topology once, as an OBJ at the start (frame 0) with
// an MTL of the cloth's colour, and the vertex positions of frame 0 (the start) and of every
// simulated frame as
// - a point cache, .pc2 (Blender's Mesh Cache modifier, Houdini, 3ds Max) and/or .mdd
//   (Blender's Mesh Cache modifier, LightWave, Houdini), in the OBJ's vertex order;
// - an animated glTF 2.0 (.gltf + .bin): one mesh whose morph targets are the frames, its
//   weights animated so that frame k shows target k − 1 (step interpolation), and a material of
//   the cloth's colour.
// Sample k of every file is weft's frame k, so that Blender's Mesh Cache modifier on its defaults
// (frame start 0) shows frame k at Blender's frame k; a cache starting at frame 1 showed frame
// k + 1 there.
// All in glTF's and Blender's OBJ import convention, y up: weft's (x, y, z) is written
// (x, z, −y). Formats:
//   .pc2 (little-endian): "POINTCACHE2\0", int32 version 1, int32 points, float32 start frame,
//        float32 sample rate (frames per sample), int32 samples; then samples × points × 3 float32.
//   .mdd (big-endian): int32 frames, int32 points, frames × float32 time (s); then
//        frames × points × 3 float32.

#include <filesystem>
#include <string>
#include <vector>

#include "render/render_mesh.h"

namespace weft::app {

enum class CacheFormat { pc2, mdd, gltf };

// "pc2", "mdd", "gltf" or a comma-separated list of them; anything else throws InputError
// naming `option` and the choices.
std::vector<CacheFormat> parse_cache_formats(const std::string& text, const std::string& option);

// Frames collected as the run writes them, written when asked.
class PointCache {
 public:
  // The first frame added (frame 0, the start) fixes the topology (triangles, UVs) and the
  // vertex count; each frame's time in seconds. Throws std::invalid_argument when a frame's
  // vertex count differs.
  void add(const render::RenderMesh& frame, double time_s);
  int frame_count() const { return static_cast<int>(m_times_s.size()); }

  // Writes `stem`.obj (the first frame's positions, UVs and triangles, with the material of
  // `stem`.mtl: `colour`, linear 0..1) and, per format, `stem`.pc2, `stem`.mdd or `stem`.gltf +
  // `stem`.bin (its material the same colour), each atomically; returns the files written.
  // Throws std::runtime_error naming a file it cannot write; nothing to write without frames.
  std::vector<std::filesystem::path> write(const std::filesystem::path& stem,
                                           const std::vector<CacheFormat>& formats,
                                           const Eigen::Vector3f& colour) const;

 private:
  render::RenderMesh m_topology;                     // frame 0, y up
  std::vector<std::vector<Eigen::Vector3f>> m_positions;  // per frame, y up
  std::vector<std::vector<Eigen::Vector3f>> m_normals;    // per frame, y up
  std::vector<double> m_times_s;
};

}  // namespace weft::app
