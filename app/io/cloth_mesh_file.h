#pragma once
// The cloth read from a mesh file (scene key cloth.mesh; docs/meshes.md): its flat pattern from
// the file's texture coordinates or from its own plane, its start from the file's positions
// placed in the world, and the mesh built by sim::make_pattern_cloth (a quad grid when the
// file holds one, a triangle mesh otherwise).

#include <filesystem>
#include <string>
#include <vector>

#include "base/enum_names.h"
#include "sim/grid.h"
#include "sim/types.h"

namespace weft::app {

// Where the material coordinates come from.
enum class PatternSource {
  automatic,  // uv when every mesh of the file has texture coordinates, else plane
  uv,         // (u, v) = uv_scale_m · (the vertex's texture coordinates), turned by −warp_angle
  plane,      // the vertex's coordinates in the mesh's own plane (a flat mesh), in metres
};

// The names a scene may give (cloth.pattern); automatic is the key left out.
inline constexpr base::EnumNames<PatternSource, 2> pattern_source_names{
    {{PatternSource::uv, "uv"}, {PatternSource::plane, "plane"}}};

struct ClothMeshFileSpec {
  std::filesystem::path path;
  PatternSource pattern = PatternSource::automatic;
  double uv_scale_m = 1.0;      // metres per texture-coordinate unit
  double warp_angle_rad = 0.0;  // the warp's angle from the pattern's first axis (UV u; plane: see below)
  double scale = 1.0;           // file length units → metres
  // The file's point (x, y, z) starts at origin + scale·(x·warp_axis + y·weft_axis +
  // z·warp_axis × weft_axis); the flat pattern's (u, v) rests at origin + u·warp_axis + v·weft_axis.
  sim::Vec3 origin{0.0, 0.0, 0.0};
  sim::Vec3 warp_axis{1.0, 0.0, 0.0};
  sim::Vec3 weft_axis{0.0, 1.0, 0.0};
};

// The plane of a flat mesh (PatternSource::plane): its normal is the summed (Newell) normal of
// its faces, its first axis the file's x axis projected into it (its y axis when x is within
// 60° of the normal), its second axis normal × first; coordinates are measured from the least
// corner of the pattern, so that they start at 0. A vertex farther than 1e-6 of the mesh's size
// from the plane makes the mesh not flat.
//
// Throws MeshFileError "PATH: what" (app/io/mesh_file.h) for an unreadable file and for a mesh the
// cloth cannot use: no texture coordinates when pattern is uv, a UV seam (a vertex with two
// texture coordinates), not flat when pattern is plane, and what sim::make_pattern_cloth
// rejects (zero-area or non-convex faces, non-manifold edges, overlaps in the pattern).
// `colour`, when given, receives each cloth vertex's RGB colour (0..1, the file's vertex colour
// channel 0), #V of the returned mesh, or is left empty when the file has no vertex colours.
sim::ClothMesh load_cloth_mesh(const ClothMeshFileSpec& spec,
                               std::vector<Eigen::Vector3d>* colour = nullptr);

}  // namespace weft::app
