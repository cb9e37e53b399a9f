// Mesh files through assimp's exporter (see mesh_export.h).

#include "app/mesh_export.h"

#include <assimp/scene.h>

#include <assimp/Exporter.hpp>
#include <filesystem>
#include <stdexcept>

#include "app/scene.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

// assimp's exporter ids.
const char* exporter_id(MeshFormat format) {
  switch (format) {
    case MeshFormat::obj: return "obj";
    case MeshFormat::ply: return "plyb";  // binary little-endian PLY
    case MeshFormat::gltf: return "gltf2";
  }
  return "obj";
}

// One mesh, one (plain) material, one root node: the smallest scene every exporter accepts.
// The aiScene owns and frees everything allocated here.
void fill_scene(const render::RenderMesh& mesh, aiScene& scene) {
  auto* out = new aiMesh();
  scene.mNumMeshes = 1;
  scene.mMeshes = new aiMesh*[1]{out};
  auto* material = new aiMaterial();
  const aiString material_name("cloth");
  material->AddProperty(&material_name, AI_MATKEY_NAME);
  scene.mNumMaterials = 1;
  scene.mMaterials = new aiMaterial*[1]{material};
  scene.mRootNode = new aiNode("cloth");
  scene.mRootNode->mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned[1]{0};

  out->mName = "cloth";
  out->mMaterialIndex = 0;
  out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  const auto n = static_cast<unsigned>(mesh.positions.size());
  out->mNumVertices = n;
  out->mVertices = new aiVector3D[n];
  out->mNormals = new aiVector3D[n];
  for (unsigned v = 0; v < n; ++v) {
    const Eigen::Vector3f& p = mesh.positions[v];
    const Eigen::Vector3f& q = mesh.normals[v];
    out->mVertices[v] = aiVector3D(p.x(), p.y(), p.z());
    out->mNormals[v] = aiVector3D(q.x(), q.y(), q.z());
  }
  if (mesh.uvs.size() == mesh.positions.size()) {
    out->mTextureCoords[0] = new aiVector3D[n];
    out->mNumUVComponents[0] = 2;
    for (unsigned v = 0; v < n; ++v)
      out->mTextureCoords[0][v] = aiVector3D(mesh.uvs[v].x(), mesh.uvs[v].y(), 0.0f);
  }
  const auto f = static_cast<unsigned>(mesh.triangles.size());
  out->mNumFaces = f;
  out->mFaces = new aiFace[f];
  for (unsigned k = 0; k < f; ++k) {
    aiFace& face = out->mFaces[k];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3]{mesh.triangles[k][0], mesh.triangles[k][1], mesh.triangles[k][2]};
  }
}

}  // namespace

MeshFormat parse_mesh_format(const std::string& text, const std::string& option) {
  if (text == "obj") return MeshFormat::obj;
  if (text == "ply") return MeshFormat::ply;
  if (text == "gltf") return MeshFormat::gltf;
  throw SceneError(option + ": expected one of obj, ply, gltf, got '" + text + "'");
}

const char* mesh_extension(MeshFormat format) {
  switch (format) {
    case MeshFormat::obj: return "obj";
    case MeshFormat::ply: return "ply";
    case MeshFormat::gltf: return "gltf";
  }
  return "obj";
}

void export_mesh(const render::RenderMesh& mesh, MeshFormat format,
                 const std::filesystem::path& path) {
  if (mesh.positions.empty() || mesh.triangles.empty())
    throw std::invalid_argument(path.string() + ": cannot export an empty mesh");
  render::validate(mesh, path.string());
  render::RenderMesh storage;
  const render::RenderMesh& with = render::with_normals(mesh, storage);

  aiScene scene;
  fill_scene(with, scene);
  if (format == MeshFormat::gltf) {
    // z up → y up: (x, y, z) ↦ (x, z, −y), a −90° turn about x.
    scene.mRootNode->mTransformation =
        aiMatrix4x4(1, 0, 0, 0,  0, 0, 1, 0,  0, -1, 0, 0,  0, 0, 0, 1);
  }
  // assimp writes the file and its companions (an OBJ's .mtl, a glTF's .bin) itself: into a
  // folder PATH.partial, whose files are then moved beside PATH, companions first, so that a
  // reader never sees a part of a mesh file, nor one without its companions.
  const fs::path folder = path.string() + ".partial";
  fs::remove_all(folder);
  fs::create_directories(folder);
  Assimp::Exporter exporter;
  if (exporter.Export(&scene, exporter_id(format), (folder / path.filename()).string()) !=
      aiReturn_SUCCESS) {
    fs::remove_all(folder);
    throw std::runtime_error(path.string() + ": cannot export mesh: " +
                             exporter.GetErrorString());
  }
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().filename() != path.filename())
      fs::rename(entry.path(), path.parent_path() / entry.path().filename());
  fs::rename(folder / path.filename(), path);
  fs::remove(folder);
}

}  // namespace weft::app
