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

}  // namespace

TriangleMesh load_triangle_mesh(const std::filesystem::path& path) {
  const std::string name = path.string();
  Assimp::Importer importer;
  // Triangulate polygons; join identical vertices within each mesh (positions are joined
  // across meshes below, where normals and texture coordinates no longer matter). No
  // aiProcess_ValidateDataStructure: it rejects a mesh without faces as "Validation failed",
  // where we say "no triangles"; the indices are checked below instead.
  const aiScene* scene =
      importer.ReadFile(name, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  if (!scene) {
    throw MeshFileError(name + ": cannot read mesh file: " + importer.GetErrorString());
  }

  TriangleMesh out;
  std::vector<Position> positions;
  std::map<Position, sim::Index> index_of;  // exact position → merged vertex
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
        if (inserted) positions.push_back(p);
        merged[v] = it->second;
      }
      for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const aiFace& face = mesh->mFaces[f];
        if (face.mNumIndices != 3) {
          ++points_and_lines;
          continue;
        }
        for (unsigned c = 0; c < 3; ++c)
          if (face.mIndices[c] >= mesh->mNumVertices)
            throw MeshFileError(name + ": cannot read mesh file: a face refers to vertex " +
                                std::to_string(face.mIndices[c]) + " of a mesh of " +
                                std::to_string(mesh->mNumVertices));
        const std::array<sim::Index, 3> t{merged[face.mIndices[0]], merged[face.mIndices[1]],
                                          merged[face.mIndices[2]]};
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
          ++dropped;
          continue;
        }
        out.triangles.push_back(t);
      }
    }
  }
  if (out.triangles.empty()) {
    throw MeshFileError(name + ": no triangles in the mesh file (" +
                        std::to_string(scene->mNumMeshes) + " meshes, " +
                        std::to_string(points_and_lines) + " points or lines, " +
                        std::to_string(dropped) + " collapsed triangles)");
  }
  out.vertices.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (std::size_t i = 0; i < positions.size(); ++i)
    for (int k = 0; k < 3; ++k) out.vertices(static_cast<Eigen::Index>(i), k) = positions[i][k];
  return out;
}

}  // namespace weft::app
