#pragma once
// The CHOLMOD back-end of SparseSpdSolver (SuiteSparse, Davis et al.) with its ordering and
// factorization kind chosen explicitly, for bench/sparse_solver_bench and tests. Everything else
// should go through make_sparse_spd_solver(SparseBackend::cholmod), which uses the defaults
// below (chosen by that benchmark; the figures are at default_sparse_backend()).

#include <memory>
#include <string>
#include <vector>

#include "sim/linear/sparse_spd_solver.h"

namespace weft::sim {

// Fill-reducing orderings (cholmod_common.method[0].ordering); `automatic` is CHOLMOD's own
// choice (AMD, then METIS when AMD's factor would be dense), each followed by a postordering.
enum class CholmodOrdering { amd, metis, nesdis, natural, automatic };
// Supernodal: dense BLAS/LAPACK kernels on blocks of columns, L Lᵀ. Simplicial: column by column,
// L D Lᵀ (the negative-pivot check reads D).
enum class CholmodFactorization { supernodal, simplicial };

// The defaults were the fastest variant on both of weft's matrices at 32², 64² and 128² grids
// (figures at default_sparse_backend()): nested dissection suits these planar-grid graphs, and
// with Debian's reference BLAS the supernodal kernels do not pay for their overhead here.
struct CholmodSettings {
  CholmodOrdering ordering = CholmodOrdering::nesdis;
  CholmodFactorization factorization = CholmodFactorization::simplicial;
};

const char* cholmod_ordering_name(CholmodOrdering ordering);
const char* cholmod_factorization_name(CholmodFactorization factorization);
// "supernodal/metis" etc.: every combination, for benchmarks and tests.
std::vector<CholmodSettings> all_cholmod_settings();
std::string cholmod_settings_name(const CholmodSettings& settings);

// Throws std::invalid_argument when weft was built without CHOLMOD.
std::unique_ptr<SparseSpdSolver> make_cholmod_solver(const CholmodSettings& settings);

}  // namespace weft::sim
