// Mesh files through assimp's exporter (see mesh_export.h).

#include "app/io/mesh_export.h"

#include <assimp/scene.h>

#include <assimp/Exporter.hpp>
#include <filesystem>
#include <stdexcept>

#include "app/io/input_error.h"
#include "app/io/output_files.h"

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

// The cloth's material: its colour (or, in a glTF, its texture), not metallic, rough.
aiMaterial* cloth_material(MeshFormat format, const MeshExportOptions& o) {
  auto* material = new aiMaterial();
  const aiString material_name("cloth");
  material->AddProperty(&material_name, AI_MATKEY_NAME);
  const bool textured = format != MeshFormat::ply && !o.texture_uri.empty();
  const aiColor4D colour = textured ? aiColor4D(1, 1, 1, 1)
                                    : aiColor4D(o.base_color.x(), o.base_color.y(), o.base_color.z(), 1);
  material->AddProperty(&colour, 1, AI_MATKEY_COLOR_DIFFUSE);
  material->AddProperty(&colour, 1, AI_MATKEY_BASE_COLOR);
  const float metallic = 0.0f, roughness = 0.9f;
  material->AddProperty(&metallic, 1, AI_MATKEY_METALLIC_FACTOR);
  material->AddProperty(&roughness, 1, AI_MATKEY_ROUGHNESS_FACTOR);
  if (textured) {
    const aiString uri(o.texture_uri);
    material->AddProperty(&uri, AI_MATKEY_TEXTURE(aiTextureType_DIFFUSE, 0));
    material->AddProperty(&uri, AI_MATKEY_TEXTURE(aiTextureType_BASE_COLOR, 0));
  }
  return material;
}

// Texture coordinates handed to assimp: metres, or for a textured OBJ or glTF the texture's
// coordinates (s, t) where `placement` puts it (render/texture.h). assimp's glTF exporter
// writes (s, 1 − t), glTF's v running down the image, so the image lies on the cloth as the
// renderers draw it.
aiVector3D file_uv(const Eigen::Vector2f& uv, MeshFormat format, const MeshExportOptions& o,
                   const render::TexturePlacement& placement) {
  if (format == MeshFormat::ply || o.texture_uri.empty()) return {uv.x(), uv.y(), 0.0f};
  const Eigen::Vector2f st = (uv - placement.origin).cwiseQuotient(placement.size);
  return {st.x(), st.y(), 0.0f};
}

// A point or direction as written: turned y-up for OBJ/PLY when asked.
aiVector3D file_vector(const Eigen::Vector3f& p, MeshFormat format, UpAxis up) {
  if (format != MeshFormat::gltf && up == UpAxis::y) return {p.x(), p.z(), -p.y()};
  return {p.x(), p.y(), p.z()};
}

// One mesh, one material, one root node: the smallest scene every exporter accepts.
// The aiScene owns and frees everything allocated here.
void fill_scene(const render::RenderMesh& mesh, MeshFormat format, const MeshExportOptions& o,
                aiScene& scene) {
  auto* out = new aiMesh();
  scene.mNumMeshes = 1;
  scene.mMeshes = new aiMesh*[1]{out};
  aiMaterial* material = cloth_material(format, o);
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
    out->mVertices[v] = file_vector(mesh.positions[v], format, o.up);
    out->mNormals[v] = file_vector(mesh.normals[v], format, o.up);
  }
  if (mesh.uvs.size() == mesh.positions.size()) {
    out->mTextureCoords[0] = new aiVector3D[n];
    out->mNumUVComponents[0] = 2;
    const render::TexturePlacement placement = render::texture_placement(
        {nullptr, o.texture_repeat_m, o.texture_mapping}, mesh.uvs);
    for (unsigned v = 0; v < n; ++v)
      out->mTextureCoords[0][v] = file_uv(mesh.uvs[v], format, o, placement);
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
  throw InputError(option + ": expected one of obj, ply, gltf, got '" + text + "'");
}

UpAxis parse_up_axis(const std::string& text, const std::string& option) {
  if (text == "y") return UpAxis::y;
  if (text == "z") return UpAxis::z;
  throw InputError(option + ": expected y or z, got '" + text + "'");
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
                 const std::filesystem::path& path, const MeshExportOptions& options) {
  if (mesh.positions.empty() || mesh.triangles.empty())
    throw std::invalid_argument(path.string() + ": cannot export an empty mesh");
  render::validate(mesh, path.string());
  render::RenderMesh storage;
  const render::RenderMesh& with = render::with_normals(mesh, storage);

  aiScene scene;
  fill_scene(with, format, options, scene);
  if (format == MeshFormat::gltf) {
    // z up → y up: (x, y, z) ↦ (x, z, −y), a −90° turn about x.
    scene.mRootNode->mTransformation =
        aiMatrix4x4(1, 0, 0, 0,  0, 0, 1, 0,  0, -1, 0, 0,  0, 0, 0, 1);
  }
  // assimp writes the file and its companions (an OBJ's .mtl, a glTF's .bin) itself: into a
  // private folder PATH.partial, whose files are then moved beside PATH, companions first, so
  // that a reader never sees a part of a mesh file, nor one without its companions.
  write_through_folder(path, [&](const fs::path& inside) {
    Assimp::Exporter exporter;
    if (exporter.Export(&scene, exporter_id(format), inside.string()) != aiReturn_SUCCESS)
      throw std::runtime_error(path.string() + ": cannot export mesh: " +
                               exporter.GetErrorString());
  });
}

}  // namespace weft::app
