#include "sim/rft/rft_patch.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "sim/material/material.h"

namespace weft::sim {

std::vector<RftPatch> make_rft_patches(const ClothMesh& mesh) {
  const auto triangles = mesh.triangles();
  // Directed edge (a → b) of a triangle → that triangle's third vertex. A neighbour across the
  // edge runs b → a (consistent orientation).
  const auto key = [](Index a, Index b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
           static_cast<std::uint32_t>(b);
  };
  std::unordered_map<std::uint64_t, Index> third;
  third.reserve(3 * triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    for (int k = 0; k < 3; ++k) {
      const Index a = tri[static_cast<std::size_t>((k + 1) % 3)],
                  b = tri[static_cast<std::size_t>((k + 2) % 3)];
      if (!third.emplace(key(a, b), tri[static_cast<std::size_t>(k)]).second)
        throw std::invalid_argument("rotation-free triangles: edge " + std::to_string(a) + "–" +
                                    std::to_string(b) + " of triangle " + std::to_string(t) +
                                    " appears twice with the same orientation (non-manifold or "
                                    "inconsistently oriented mesh)");
    }
  }
  std::vector<RftPatch> patches(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    RftPatch& p = patches[t];
    p.triangle = t;
    for (std::size_t k = 0; k < 3; ++k) p.vertices[k] = tri[k];
    p.size = 3;
    for (int k = 0; k < 3; ++k) {
      const Index a = tri[static_cast<std::size_t>((k + 1) % 3)],
                  b = tri[static_cast<std::size_t>((k + 2) % 3)];
      const auto it = third.find(key(b, a));
      if (it == third.end()) continue;  // boundary edge
      p.opposite_slot[static_cast<std::size_t>(k)] = p.size;
      p.vertices[static_cast<std::size_t>(p.size++)] = it->second;
    }
  }
  return patches;
}

void check_rft_rigidity(double value, const char* key) {
  if (!(value >= 0.0) || !std::isfinite(value))
    throw MaterialError(std::string(key) + ": expected a finite rigidity >= 0, got " +
                                std::to_string(value));
}

}  // namespace weft::sim
