// A build without CGAL (sim/remesh/CMakeLists.txt): no remeshing; a scene asking for it is an
// error naming the reason (see cloth_remesh.h).

#include <stdexcept>

#include "sim/cloth_remesh.h"

namespace weft::sim {

void check_remesh_settings(const ClothMesh&, const SimSettings& settings) {
  if (settings.remesh.enabled)
    throw std::invalid_argument("simulation.remesh: this build of weft has no remesher (it was "
                                "built without CGAL: install libcgal-dev, scripts/setup)");
}

RemeshedCloth remesh_cloth(const ClothMesh&, const Matrix3X&, const Matrix3X&, const Matrix3X&,
                           const std::vector<Index>&, const RemeshSettings&) {
  throw std::invalid_argument("remesh_cloth: this build of weft has no remesher (no CGAL)");
}

double cloth_remesh_indicator_m(const ClothMesh&, const Matrix3X&, const RemeshSettings&) {
  throw std::invalid_argument("cloth_remesh_indicator_m: this build of weft has no remesher (no "
                              "CGAL)");
}

ClothRemeshCriteria cloth_remesh_criteria(const ClothMesh&, const Matrix3X&,
                                          const RemeshSettings&) {
  throw std::invalid_argument("cloth_remesh_criteria: this build of weft has no remesher (no "
                              "CGAL)");
}

}  // namespace weft::sim
