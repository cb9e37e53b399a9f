// Mesh files through assimp (see mesh_file.h).

#include "app/io/mesh_file.h"

#include <assimp/BaseImporter.h>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <utility>

#include "app/io/mesh_file_io.h"
#include "app/io/mesh_precheck.h"
#include "app/io/output_files.h"

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

// The file's meshes merged into one PolygonMesh (mesh_file.h): vertices at the same position
// joined across meshes, polygons triangulated or not, corners that the join collapses dropped.
class MeshMerger {
 public:
  MeshMerger(std::string name, bool triangulate) : m_name(std::move(name)), m_triangulate(triangulate) {}

  void add(const aiMesh& mesh, unsigned mesh_index, const aiMatrix4x4& to_root) {
    m_all_uv = m_all_uv && mesh.HasTextureCoords(0);
    m_all_colour = m_all_colour && mesh.HasVertexColors(0);
    const std::vector<sim::Index> merged = add_vertices(mesh, mesh_index, to_root);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) add_face(mesh, mesh.mFaces[f], merged);
  }

  PolygonMesh finish(unsigned mesh_count) {
    const char* what = m_triangulate ? "triangles" : "polygons";
    if (m_out.faces.empty()) {
      throw MeshFileError(m_name + ": no " + what + " in the mesh file (" +
                          std::to_string(mesh_count) + " meshes, " +
                          std::to_string(m_points_and_lines) + " points or lines, " +
                          std::to_string(m_dropped) + " collapsed " + what + ")");
    }
    m_out.vertices.resize(static_cast<Eigen::Index>(m_positions.size()), 3);
    for (std::size_t i = 0; i < m_positions.size(); ++i)
      for (int k = 0; k < 3; ++k)
        m_out.vertices(static_cast<Eigen::Index>(i), k) = m_positions[i][k];
    if (m_all_uv) m_out.uv = std::move(m_uv);
    else m_out.uv_seam_vertex = -1;
    if (m_all_colour) m_out.colour = std::move(m_colour);
    return std::move(m_out);
  }

 private:
  // The merged vertex of each of the mesh's vertices.
  std::vector<sim::Index> add_vertices(const aiMesh& mesh, unsigned mesh_index,
                                       const aiMatrix4x4& to_root) {
    std::vector<sim::Index> merged(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const Position p = transformed(to_root, mesh.mVertices[v]);
      // A NaN would also break the map's ordering and join the vertex to an arbitrary one.
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        throw MeshFileError(m_name + ": vertex " + std::to_string(v) + " of mesh " +
                            std::to_string(mesh_index) + " is at (" + std::to_string(p[0]) +
                            ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) +
                            "), not a finite position (or beyond the range of assimp's "
                            "single-precision floats)");
      const auto [it, inserted] = m_index_of.emplace(p, static_cast<sim::Index>(m_positions.size()));
      const sim::Vec2 t = mesh.HasTextureCoords(0)
                              ? sim::Vec2(mesh.mTextureCoords[0][v].x, mesh.mTextureCoords[0][v].y)
                              : sim::Vec2::Zero();
      // `vt nan 0` or `vt 1e39 0` (infinite as a float) used to give the pattern of `vt 0 0`.
      if (!t.allFinite())
        throw MeshFileError(m_name + ": vertex " + std::to_string(v) + " of mesh " +
                            std::to_string(mesh_index) + " has texture coordinates (" +
                            std::to_string(t.x()) + ", " + std::to_string(t.y()) +
                            "), not finite numbers");
      const Eigen::Vector3d colour =
          mesh.HasVertexColors(0)
              ? Eigen::Vector3d(mesh.mColors[0][v].r, mesh.mColors[0][v].g, mesh.mColors[0][v].b)
              : Eigen::Vector3d::Zero();
      if (!colour.allFinite())  // pins by colour compare it
        throw MeshFileError(m_name + ": vertex " + std::to_string(v) + " of mesh " +
                            std::to_string(mesh_index) + " has the colour (" +
                            std::to_string(colour.x()) + ", " + std::to_string(colour.y()) +
                            ", " + std::to_string(colour.z()) + "), not finite numbers");
      if (inserted) {
        m_positions.push_back(p);
        m_uv.push_back(t);
        m_colour.push_back(colour);
      } else if (mesh.HasTextureCoords(0) && m_uv[static_cast<std::size_t>(it->second)] != t &&
                 m_out.uv_seam_vertex < 0) {
        m_out.uv_seam_vertex = it->second;
      }
      merged[v] = it->second;
    }
    return merged;
  }

  void add_face(const aiMesh& mesh, const aiFace& face, const std::vector<sim::Index>& merged) {
    if (face.mNumIndices < 3 || (m_triangulate && face.mNumIndices != 3)) {
      ++m_points_and_lines;
      return;
    }
    std::vector<sim::Index> corners;
    for (unsigned c = 0; c < face.mNumIndices; ++c) {
      if (face.mIndices[c] >= mesh.mNumVertices)
        throw MeshFileError(m_name + ": cannot read mesh file: a face refers to vertex " +
                            std::to_string(face.mIndices[c]) + " of a mesh of " +
                            std::to_string(mesh.mNumVertices));
      corners.push_back(merged[face.mIndices[c]]);
    }
    // Corners that the join collapses: a triangle with two equal corners is dropped, a polygon
    // loses its repeated corners.
    if (m_triangulate) {
      if (corners[0] == corners[1] || corners[1] == corners[2] || corners[2] == corners[0]) {
        ++m_dropped;
        return;
      }
    } else {
      std::vector<sim::Index> kept;
      for (std::size_t c = 0; c < corners.size(); ++c)
        if (corners[c] != corners[(c + 1) % corners.size()]) kept.push_back(corners[c]);
      if (kept.size() < 3) {
        ++m_dropped;
        return;
      }
      corners = std::move(kept);
    }
    m_out.faces.push_back(std::move(corners));
  }

  std::string m_name;
  bool m_triangulate;
  PolygonMesh m_out;
  std::vector<Position> m_positions;
  std::map<Position, sim::Index> m_index_of;  // exact position → merged vertex
  bool m_all_uv = true, m_all_colour = true;
  std::vector<sim::Vec2> m_uv;
  std::vector<Eigen::Vector3d> m_colour;
  long m_dropped = 0, m_points_and_lines = 0;
};

// The file's bytes, read once for the checks of mesh_precheck.h (assimp then reads the file
// itself, through ConfinedMeshIO). Throws MeshFileError for a file that is not a regular file
// of at most max_mesh_file_bytes, or that the checks refuse.
void precheck_mesh_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::string why = why_not_a_readable_file(path, max_mesh_file_bytes);
  if (!why.empty()) throw MeshFileError(name + ": cannot read mesh file: " + why);
  const std::string extension = lower_extension(path);
  if (extension != ".ply" && extension != ".obj" && extension != ".glb" && extension != ".gltf" &&
      extension != ".fbx")
    return;  // STL: assimp's checks alone
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  precheck_mesh_bytes(bytes, extension, name);
}

// The scene as imported, before any post-processing may trip on it: every face's corners must
// be vertices of its mesh, every node's meshes meshes of the scene, the counts within the
// limits (assimp's own aiProcess_ValidateDataStructure then runs first of the post-processing).
void check_imported_scene(const aiScene& scene, const std::string& name) {
  std::uint64_t vertices = 0, faces = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    vertices += mesh.mNumVertices;
    faces += mesh.mNumFaces;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f)
      for (unsigned c = 0; c < mesh.mFaces[f].mNumIndices; ++c)
        if (mesh.mFaces[f].mIndices[c] >= mesh.mNumVertices)
          throw MeshFileError(name + ": cannot read mesh file: face " + std::to_string(f) +
                              " of mesh " + std::to_string(m) + " refers to vertex " +
                              std::to_string(mesh.mFaces[f].mIndices[c]) + " of a mesh of " +
                              std::to_string(mesh.mNumVertices));
  }
  if (vertices > max_mesh_elements || faces > max_mesh_elements)
    throw MeshFileError(name + ": " + std::to_string(vertices) + " vertices and " +
                        std::to_string(faces) + " faces, more than " +
                        std::to_string(max_mesh_elements) + " (the limit of weft's mesh files)");
  std::vector<const aiNode*> stack;
  if (scene.mRootNode) stack.push_back(scene.mRootNode);
  while (!stack.empty()) {
    const aiNode* node = stack.back();
    stack.pop_back();
    for (unsigned k = 0; k < node->mNumMeshes; ++k)
      if (node->mMeshes[k] >= scene.mNumMeshes)
        throw MeshFileError(name + ": cannot read mesh file: a node refers to mesh " +
                            std::to_string(node->mMeshes[k]) + " of " +
                            std::to_string(scene.mNumMeshes));
    for (unsigned c = 0; c < node->mNumChildren; ++c) stack.push_back(node->mChildren[c]);
  }
}

// Whether any face has three corners or more (a file of points or lines has none, and
// aiProcess_ValidateDataStructure would refuse its meshes as "Validation failed" where
// MeshMerger says "no triangles").
bool has_polygons(const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    for (unsigned f = 0; f < scene.mMeshes[m]->mNumFaces; ++f)
      if (scene.mMeshes[m]->mFaces[f].mNumIndices >= 3) return true;
  return false;
}

// Refuses a file whose extension is not one of mesh_file_extensions, and removes from the
// importer (and deletes: UnregisterLoader does not) every importer that reads none of them.
void keep_weft_formats_only(Assimp::Importer& importer, const std::filesystem::path& path) {
  const auto weft_reads = [](const std::string& extension) {
    return std::any_of(std::begin(mesh_file_extensions), std::end(mesh_file_extensions),
                       [&](const char* e) { return extension == e; });
  };
  const std::string extension = lower_extension(path);
  if (!weft_reads(extension))
    throw MeshFileError(path.string() + ": cannot read mesh file: expected an OBJ, PLY, STL, glTF "
                        "or FBX file (.obj, .ply, .stl, .gltf, .glb or .fbx), got '" +
                        extension + "'");
  for (std::size_t k = importer.GetImporterCount(); k-- > 0;) {
    std::istringstream words(importer.GetImporterInfo(k)->mFileExtensions);
    bool reads_one = false;
    for (std::string word; words >> word;) reads_one = reads_one || weft_reads("." + word);
    if (reads_one) continue;
    Assimp::BaseImporter* other = importer.GetImporter(k);
    importer.UnregisterLoader(other);
    delete other;
  }
}

// The file imported and post-processed: checked by precheck_mesh_file first, read through
// ConfinedMeshIO (no companion outside the file's folder), checked again as imported, then
// post-processed (validated first; polygons triangulated or not; identical vertices joined
// within each mesh — positions are joined across meshes by MeshMerger, where normals and
// texture coordinates no longer matter).
const aiScene* import_mesh(Assimp::Importer& importer, const std::filesystem::path& path,
                           bool triangulate) {
  const std::string name = path.string();
  precheck_mesh_file(path);  // a missing file, a device or a folder is named as such first
  keep_weft_formats_only(importer, path);
  auto* io = new ConfinedMeshIO(path);
  importer.SetIOHandler(io);  // the importer owns it
  const aiScene* scene = importer.ReadFile(name, 0u);
  if (!io->refused().empty())
    throw MeshFileError(name + ": cannot read mesh file: it refers to " + io->refused());
  if (!scene)
    throw MeshFileError(name + ": cannot read mesh file: " + importer.GetErrorString());
  check_imported_scene(*scene, name);
  const unsigned steps = (has_polygons(*scene) ? aiProcess_ValidateDataStructure : 0u) |
                         (triangulate ? aiProcess_Triangulate : 0u) |
                         aiProcess_JoinIdenticalVertices;
  scene = importer.ApplyPostProcessing(steps);
  if (!scene)
    throw MeshFileError(name + ": cannot read mesh file: " + importer.GetErrorString());
  return scene;
}

// What both readers share: the file's meshes merged (mesh_file.h), polygons triangulated or not.
PolygonMesh read_mesh(const std::filesystem::path& path, bool triangulate) {
  Assimp::Importer importer;
  const aiScene* scene = import_mesh(importer, path, triangulate);
  MeshMerger merger(path.string(), triangulate);
  // The node tree depth first, in the file's order (children pushed in reverse).
  std::vector<PlacedNode> stack;
  if (scene->mRootNode) stack.push_back({scene->mRootNode, scene->mRootNode->mTransformation});
  while (!stack.empty()) {
    const PlacedNode placed = stack.back();
    stack.pop_back();
    const aiNode* node = placed.node;
    for (unsigned c = node->mNumChildren; c-- > 0;) {
      const aiNode* child = node->mChildren[c];
      stack.push_back({child, placed.to_root * child->mTransformation});
    }
    for (unsigned k = 0; k < node->mNumMeshes; ++k)
      merger.add(*scene->mMeshes[node->mMeshes[k]], node->mMeshes[k], placed.to_root);
  }
  return merger.finish(scene->mNumMeshes);
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
