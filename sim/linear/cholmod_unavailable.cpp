// Stand-in for cholmod_solver.cpp when weft is built without CHOLMOD (WEFT_WITH_CHOLMOD=OFF, or
// libsuitesparse-dev not installed): available_sparse_backends() then lists only eigen_ldlt.

#include <stdexcept>

#include "sim/linear/cholmod_solver.h"

namespace weft::sim {

std::unique_ptr<SparseSpdSolver> make_cholmod_solver(const CholmodSettings& /*settings*/) {
  throw std::invalid_argument(
      "sparse solver back-end \"cholmod\": weft was built without CHOLMOD (install "
      "libsuitesparse-dev and configure with -DWEFT_WITH_CHOLMOD=ON)");
}

}  // namespace weft::sim
