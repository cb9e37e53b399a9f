// The files assimp may open for a mesh; see mesh_file_io.h.

#include "app/io/mesh_file_io.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/IOStream.hpp>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>

namespace weft::app {

namespace fs = std::filesystem;

std::string why_not_a_readable_file(const fs::path& path, std::uint64_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::strerror(errno);
  if (!S_ISREG(st.st_mode)) return "not a regular file (a folder, device or pipe)";
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes)
    return "larger than " + std::to_string(max_bytes >> 20) + " MiB (the limit: " +
           std::to_string(st.st_size) + " bytes)";
  return "";
}

ConfinedMeshIO::ConfinedMeshIO(const fs::path& mesh_file) {
  std::error_code error;
  m_mesh_file = fs::weakly_canonical(fs::absolute(mesh_file), error);
  m_folder = m_mesh_file.parent_path();
}

std::string ConfinedMeshIO::check(const fs::path& file) const {
  std::error_code error;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(file), error);
  std::string why = error ? error.message() : "";
  if (why.empty() && resolved != m_mesh_file) {
    const fs::path inside = resolved.lexically_relative(m_folder);
    if (inside.empty() || *inside.begin() == "..")
      why = "outside the mesh file's folder " + m_folder.string() +
            " (a mesh file may refer only to files beside it or below)";
  }
  if (why.empty()) why = why_not_a_readable_file(resolved, max_mesh_file_bytes);
  if (!why.empty() && m_refused.empty()) m_refused = std::string(file) + ": " + why;
  return why;
}

bool ConfinedMeshIO::Exists(const char* file) const { return check(file).empty(); }

Assimp::IOStream* ConfinedMeshIO::Open(const char* file, const char* mode) {
  if (std::strchr(mode, 'w') || std::strchr(mode, 'a') || std::strchr(mode, '+')) {
    m_refused = std::string(file) + ": not opened for writing while reading a mesh";
    return nullptr;
  }
  if (!check(file).empty()) return nullptr;
  return Assimp::DefaultIOSystem().Open(file, mode);
}

void ConfinedMeshIO::Close(Assimp::IOStream* stream) { delete stream; }

}  // namespace weft::app
