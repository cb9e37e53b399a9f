#pragma once
// What the renderers draw: a triangle mesh in world coordinates (metres, z up).
// render/ knows nothing of simulation; app/ fills this from a cloth frame.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace weft::render {

struct RenderMesh {
  std::vector<Eigen::Vector3f> positions;  // #V, metres
  std::vector<Eigen::Vector3f> normals;    // #V unit vertex normals (compute_vertex_normals)
  std::vector<Eigen::Vector2f> uvs;        // #V material coordinates (warp, weft), may be empty
  std::vector<float> strain;  // #V length/rest − 1 about each vertex (Shading::strain), may be empty
  std::vector<std::array<std::uint32_t, 3>> triangles;  // #F, counter-clockwise seen from the front
  // #E lines of the simulation mesh (vertex index pairs, each a side of a triangle) that the
  // wireframe overlay draws (ClothSurface::wireframe): a grid's warp and weft edges without
  // the quads' diagonals. May be empty: then every triangle side (triangle_edges). Loop
  // subdivision and the thickness shell carry them onto the surface they build.
  std::vector<std::array<std::uint32_t, 2>> edges;
};

// Every side of the mesh's triangles once, as (smaller, larger) index pairs in the order first
// met.
std::vector<std::array<std::uint32_t, 2>> triangle_edges(const RenderMesh& mesh);

// Area-weighted vertex normals from the triangles (zero-area triangles contribute nothing;
// an isolated vertex gets +z).
void compute_vertex_normals(RenderMesh& mesh);

// Bad input: throws std::invalid_argument, the message starting with `name` ("RenderMesh",
// "object 2"), unless every position is finite and every triangle's and edge's indices are in
// range.
void validate(const RenderMesh& mesh, const std::string& name = "RenderMesh");

// `mesh`, or a copy with vertex normals computed into `storage` when they are missing or stale
// in size (the renderers shade with smooth vertex normals).
const RenderMesh& with_normals(const RenderMesh& mesh, RenderMesh& storage);

}  // namespace weft::render
