#pragma once
// The files assimp may open while reading a mesh file: the mesh file itself and companions in
// its folder (an OBJ's .mtl, a glTF's .bin buffers and images), each a regular file of at most
// max_mesh_file_bytes. A companion outside the mesh's folder — a glTF buffer `uri` of
// "../../secret" or "/etc/passwd", an OBJ `mtllib` with `..` — is refused, so that a mesh file
// cannot make weft read (and draw, or hash) a file elsewhere; links are followed before the
// check, so a link in the folder to a file outside is refused too.

#include <assimp/IOSystem.hpp>

#include <cstdint>
#include <filesystem>
#include <string>

namespace weft::app {

// Mesh files and their companions are at most this large (bytes): reading stops before a
// bigger file or a device (`/dev/zero`) is read. 10 M triangles held 5.75 GB inside assimp.
inline constexpr std::uint64_t max_mesh_file_bytes = std::uint64_t{256} << 20;

// Whether `path` is a regular file of at most max_bytes; if not, why not ("" when it is).
std::string why_not_a_readable_file(const std::filesystem::path& path, std::uint64_t max_bytes);

// An assimp IOSystem confined to the mesh file's folder (above). What it refused is kept in
// refused() for the error message: assimp's own error then only says a file was missing.
class ConfinedMeshIO : public Assimp::IOSystem {
 public:
  explicit ConfinedMeshIO(const std::filesystem::path& mesh_file);
  bool Exists(const char* file) const override;
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode = "rb") override;
  void Close(Assimp::IOStream* stream) override;
  // "FILE: why it was not opened", or "" when nothing was refused.
  const std::string& refused() const { return m_refused; }

 private:
  // "" when `file` may be opened, else the reason (kept in m_refused, the first one).
  std::string check(const std::filesystem::path& file) const;

  std::filesystem::path m_mesh_file, m_folder;  // canonical
  mutable std::string m_refused;  // also set by Exists(): some importers only ask that
};

}  // namespace weft::app
