// Mesh files through assimp (see mesh_file.h).

#include "app/mesh_file.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <map>
#include <string>
#include <utility>

namespace weft::app {
namespace {

using Position = std::array<double, 3>;

// A node and the transform from its coordinates to the file's root coordinates.
struct PlacedNode {
  const aiNode* node;
  aiMatrix4x4 to_root;
};

Position transformed(const aiMatrix4x4& m, const aiVector3D& v) {
  const double x = v.x, y = v.y, z = v.z;
  return {m.a1 * x + m.a2 * y + m.a3 * z + m.a4, m.b1 * x + m.b2 * y + m.b3 * z + m.b4,
          m.c1 * x + m.c2 * y + m.c3 * z + m.c4};
}

// What both readers share: the file's meshes merged (mesh_file.h), polygons triangulated or not.
PolygonMesh read_mesh(const std::filesystem::path& path, bool triangulate) {
  const std::string name = path.string();
  Assimp::Importer importer;
  // Join identical vertices within each mesh (positions are joined across meshes below, where
  // normals and texture coordinates no longer matter). No aiProcess_ValidateDataStructure: it
  // rejects a mesh without faces as "Validation failed", where we say "no triangles"; the
  // indices are checked below instead.
  const aiScene* scene = importer.ReadFile(
      name, (triangulate ? aiProcess_Triangulate : 0u) | aiProcess_JoinIdenticalVertices);
  if (!scene) {
    throw MeshFileError(name + ": cannot read mesh file: " + importer.GetErrorString());
  }

  PolygonMesh out;
  std::vector<Position> positions;
  std::map<Position, sim::Index> index_of;  // exact position → merged vertex
  bool all_uv = true, all_colour = true;
  std::vector<sim::Vec2> uv;
  std::vector<Eigen::Vector3d> colour;
  long dropped = 0, points_and_lines = 0;
  std::vector<PlacedNode> stack;
  if (scene->mRootNode) stack.push_back({scene->mRootNode, scene->mRootNode->mTransformation});
  while (!stack.empty()) {
    const PlacedNode placed = stack.back();
    stack.pop_back();
    const aiNode* node = placed.node;
    // Children pushed in reverse, so that they are visited in the file's order.
    for (unsigned c = node->mNumChildren; c-- > 0;) {
      const aiNode* child = node->mChildren[c];
      stack.push_back({child, placed.to_root * child->mTransformation});
    }
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const aiMesh* mesh = scene->mMeshes[node->mMeshes[k]];
      all_uv = all_uv && mesh->HasTextureCoords(0);
      all_colour = all_colour && mesh->HasVertexColors(0);
      std::vector<sim::Index> merged(mesh->mNumVertices);
      for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
        const Position p = transformed(placed.to_root, mesh->mVertices[v]);
        // A NaN would also break the map's ordering and join the vertex to an arbitrary one.
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
          throw MeshFileError(name + ": vertex " + std::to_string(v) + " of mesh " +
                              std::to_string(node->mMeshes[k]) + " is at (" +
                              std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " +
                              std::to_string(p[2]) +
                              "), not a finite position (or beyond the range of assimp's "
                              "single-precision floats)");
        const auto [it, inserted] = index_of.emplace(p, static_cast<sim::Index>(positions.size()));
        const sim::Vec2 t = mesh->HasTextureCoords(0)
                                ? sim::Vec2(mesh->mTextureCoords[0][v].x, mesh->mTextureCoords[0][v].y)
                                : sim::Vec2::Zero();
        if (inserted) {
          positions.push_back(p);
          uv.push_back(t);
          colour.push_back(mesh->HasVertexColors(0)
                               ? Eigen::Vector3d(mesh->mColors[0][v].r, mesh->mColors[0][v].g,
                                                 mesh->mColors[0][v].b)
                               : Eigen::Vector3d::Zero());
        } else if (mesh->HasTextureCoords(0) && uv[static_cast<std::size_t>(it->second)] != t &&
                   out.uv_seam_vertex < 0) {
          out.uv_seam_vertex = it->second;
        }
        merged[v] = it->second;
      }
      for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const aiFace& face = mesh->mFaces[f];
        if (face.mNumIndices < 3 || (triangulate && face.mNumIndices != 3)) {
          ++points_and_lines;
          continue;
        }
        std::vector<sim::Index> corners;
        for (unsigned c = 0; c < face.mNumIndices; ++c) {
          if (face.mIndices[c] >= mesh->mNumVertices)
            throw MeshFileError(name + ": cannot read mesh file: a face refers to vertex " +
                                std::to_string(face.mIndices[c]) + " of a mesh of " +
                                std::to_string(mesh->mNumVertices));
          corners.push_back(merged[face.mIndices[c]]);
        }
        // Corners that join collapses: a triangle with two equal corners is dropped, a polygon
        // loses its repeated corners.
        if (triangulate) {
          if (corners[0] == corners[1] || corners[1] == corners[2] || corners[2] == corners[0]) {
            ++dropped;
            continue;
          }
        } else {
          std::vector<sim::Index> kept;
          for (std::size_t c = 0; c < corners.size(); ++c)
            if (corners[c] != corners[(c + 1) % corners.size()]) kept.push_back(corners[c]);
          if (kept.size() < 3) {
            ++dropped;
            continue;
          }
          corners = std::move(kept);
        }
        out.faces.push_back(std::move(corners));
      }
    }
  }
  if (out.faces.empty()) {
    throw MeshFileError(name + ": no " + (triangulate ? "triangles" : "polygons") +
                        " in the mesh file (" + std::to_string(scene->mNumMeshes) + " meshes, " +
                        std::to_string(points_and_lines) + " points or lines, " +
                        std::to_string(dropped) + " collapsed " +
                        (triangulate ? "triangles" : "polygons") + ")");
  }
  out.vertices.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (std::size_t i = 0; i < positions.size(); ++i)
    for (int k = 0; k < 3; ++k) out.vertices(static_cast<Eigen::Index>(i), k) = positions[i][k];
  if (all_uv) out.uv = std::move(uv);
  else out.uv_seam_vertex = -1;
  if (all_colour) out.colour = std::move(colour);
  return out;
}

}  // namespace

TriangleMesh load_triangle_mesh(const std::filesystem::path& path) {
  PolygonMesh read = read_mesh(path, true);
  TriangleMesh out;
  out.vertices = std::move(read.vertices);
  out.triangles.reserve(read.faces.size());
  for (const auto& f : read.faces) out.triangles.push_back({f[0], f[1], f[2]});
  return out;
}

PolygonMesh load_polygon_mesh(const std::filesystem::path& path) { return read_mesh(path, false); }

}  // namespace weft::app
