// The cholmod back-end of SparseSpdSolver: SuiteSparse CHOLMOD through its C API (int indices,
// real double), with cholmod_common wrapped in an RAII owner whose error hook records CHOLMOD's
// messages instead of printing them. Compiled only when weft is built with CHOLMOD;
// cholmod_unavailable.cpp stands in otherwise.

#include "sim/linear/cholmod_solver.h"

#include <cholmod.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <Eigen/Core>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/check.h"
#include "sim/linear/sparsity_pattern.h"

namespace weft::sim {

namespace {

constexpr const char* k_name = "cholmod";

class CholmodCommon;

// CHOLMOD reports errors and warnings through cholmod_common::error_handler(status, file, line,
// message), which carries no pointer back to its cholmod_common. CholmodCommon::call therefore
// names, for this thread and for the duration of one CHOLMOD call only, the owner the handler
// records into; outside a call it is null and the handler drops the report.
thread_local CholmodCommon* t_recording_common = nullptr;

// Owns a cholmod_common: cholmod_start on construction, cholmod_finish on destruction. Every
// CHOLMOD call goes through call(), which clears the last message and routes the handler here.
class CholmodCommon {
 public:
  CholmodCommon() {
    if (!cholmod_start(&m_common)) {
      throw std::runtime_error("cholmod_start failed to initialise a cholmod_common");
    }
    m_common.print = 0;  // never print: messages reach on_error and are kept in m_message
    m_common.error_handler = &CholmodCommon::on_error;
  }
  ~CholmodCommon() { cholmod_finish(&m_common); }
  CholmodCommon(const CholmodCommon&) = delete;
  CholmodCommon& operator=(const CholmodCommon&) = delete;

  // Runs f(cholmod_common*) — one CHOLMOD call — and returns what it returns.
  template <class Call>
  auto call(Call&& f) {
    m_message.clear();
    CholmodCommon* const outer = std::exchange(t_recording_common, this);
    struct Restore {
      CholmodCommon* outer;
      ~Restore() { t_recording_common = outer; }
    } restore{outer};
    return std::forward<Call>(f)(&m_common);
  }

  // Settings (ordering, supernodal switch, …) before analyse; statistics after.
  cholmod_common& settings() { return m_common; }
  int status() const { return m_common.status; }
  // "CHOLMOD warning 1 (not positive definite) at cholmod_factorize.c:121", or empty.
  const std::string& message() const { return m_message; }

 private:
  // Called from C: must not throw.
  static void on_error(int status, const char* file, int line, const char* message) noexcept {
    CholmodCommon* const owner = t_recording_common;
    if (owner == nullptr) return;
    try {
      const std::string kind = status < 0 ? "error" : "warning";
      owner->m_message = "CHOLMOD " + kind + " " + std::to_string(status) + " (" +
                         (message ? message : "") + ") at " + (file ? file : "?") + ":" +
                         std::to_string(line);
    } catch (...) {
      owner->m_message.clear();  // out of memory for the text: the status still tells
    }
  }

  cholmod_common m_common{};
  std::string m_message;
};

void free_cholmod_object(cholmod_factor*& object, cholmod_common* common) {
  cholmod_free_factor(&object, common);
}
void free_cholmod_object(cholmod_dense*& object, cholmod_common* common) {
  cholmod_free_dense(&object, common);
}

// Owns one object CHOLMOD allocated (a factor or a dense matrix) and frees it through the
// cholmod_common that allocated it, which must outlive this.
template <class Object>
class CholmodOwned {
 public:
  explicit CholmodOwned(CholmodCommon& common) : m_common(&common) {}
  ~CholmodOwned() { reset(); }
  CholmodOwned(const CholmodOwned&) = delete;
  CholmodOwned& operator=(const CholmodOwned&) = delete;

  Object* get() const { return m_object; }
  Object* operator->() const { return m_object; }
  // For CHOLMOD's in/out "handle" arguments, which allocate or reuse the object.
  Object** handle() { return &m_object; }
  void reset(Object* object = nullptr) {
    if (m_object != nullptr) {
      m_common->call([this](cholmod_common* c) { free_cholmod_object(m_object, c); });
    }
    m_object = object;
  }

 private:
  CholmodCommon* m_common;
  Object* m_object = nullptr;
};

// A cholmod_sparse that borrows A's arrays: symmetric, lower triangle used (stype −1).
cholmod_sparse lower_triangle_view(const SparseMatrix& A) {
  cholmod_sparse view{};
  view.nrow = static_cast<size_t>(A.rows());
  view.ncol = static_cast<size_t>(A.cols());
  view.nzmax = static_cast<size_t>(A.nonZeros());
  // CHOLMOD's inputs are not const-qualified but are only read.
  view.p = const_cast<int*>(A.outerIndexPtr());
  view.i = const_cast<int*>(A.innerIndexPtr());
  view.x = const_cast<double*>(A.valuePtr());
  view.stype = -1;
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;  // Eigen keeps each column's row indices sorted
  view.packed = 1;  // compressed: no per-column counts
  return view;
}

int cholmod_ordering_code(CholmodOrdering ordering) {
  switch (ordering) {
    case CholmodOrdering::amd:
      return CHOLMOD_AMD;
    case CholmodOrdering::metis:
      return CHOLMOD_METIS;
    case CholmodOrdering::nesdis:
      return CHOLMOD_NESDIS;
    case CholmodOrdering::natural:
      return CHOLMOD_NATURAL;
    case CholmodOrdering::automatic:
      break;
  }
  WEFT_CHECK(false, "cholmod_ordering_code: no single code for this CholmodOrdering");
  return CHOLMOD_AMD;  // not reached
}

// CHOLMOD 3 (Debian 12's SuiteSparse 5) runs the scatter and assembly loops of its supernodal
// factorization on CHOLMOD_OMP_NUM_THREADS = 4 OpenMP threads, fixed when it was built, whatever
// the machine. Beside the dense BLAS work those loops are short, and their threads waiting on
// two shared cores doubled a static solve's CPU time (the Cusick drape: 13.3 s against 6.9 s
// with one thread, weft measure --static). weft has no OpenMP region of its own, so no active
// level: the loops run on the calling thread; the results do not depend on it.
void run_openmp_regions_on_one_thread() {
#ifdef _OPENMP
  omp_set_max_active_levels(0);
#endif
}

class CholmodSolver final : public SparseSpdSolver {
 public:
  explicit CholmodSolver(const CholmodSettings& settings) {
    if (settings.factorization == CholmodFactorization::supernodal) run_openmp_regions_on_one_thread();
    cholmod_common& c = m_common.settings();
    if (settings.ordering != CholmodOrdering::automatic) {
      c.nmethods = 1;
      c.method[0].ordering = cholmod_ordering_code(settings.ordering);
    }
    c.postorder = 1;  // a weighted postorder of the elimination tree: larger supernodes
    c.supernodal = settings.factorization == CholmodFactorization::supernodal ? CHOLMOD_SUPERNODAL
                                                                              : CHOLMOD_SIMPLICIAL;
    c.final_asis = 1;                  // keep the factor as computed: supernodal L Lᵀ or L D Lᵀ
    c.quick_return_if_not_posdef = 1;  // stop at the first bad pivot
  }

  void analyze(const SparseMatrix& A) override {
    linear_detail::require_analyzable(A, k_name);
    m_factorized = false;
    m_pattern = linear_detail::SparsityPattern();
    m_factor.reset();
    cholmod_sparse view = lower_triangle_view(A);
    cholmod_factor* const factor =
        m_common.call([&view](cholmod_common* c) { return cholmod_analyze(&view, c); });
    if (factor == nullptr) {
      throw std::runtime_error("cholmod_analyze failed on a " + std::to_string(A.rows()) + "x" +
                               std::to_string(A.cols()) + " matrix: " + m_common.message());
    }
    m_factor.reset(factor);
    m_pattern = linear_detail::SparsityPattern(A);
  }

  bool factorize(const SparseMatrix& A) override {
    linear_detail::require_analysed_pattern(m_pattern, A, k_name);
    m_factorized = false;
    m_failure.clear();
    if (const Eigen::Index bad = linear_detail::first_non_finite_entry(A); bad >= 0) {
      m_failure = linear_detail::non_finite_entry_message(A, bad);
      return false;
    }
    cholmod_sparse view = lower_triangle_view(A);
    cholmod_factor* const factor = m_factor.get();
    m_common.call(
        [&view, factor](cholmod_common* c) { return cholmod_factorize(&view, factor, c); });
    if (m_common.status() < CHOLMOD_OK) {  // out of memory or invalid input: not numerical
      throw std::runtime_error("cholmod_factorize failed: " + m_common.message());
    }
    const auto n = static_cast<Eigen::Index>(factor->n);
    if (m_common.status() == CHOLMOD_NOT_POSDEF || factor->minor < factor->n) {
      m_failure = "pivot " + std::to_string(factor->minor) + " of " + std::to_string(n) +
                  " is not positive (" + m_common.message() + ")";
      return false;
    }
    if (!factor->is_super && !factor->is_ll) {
      // Simplicial L D Lᵀ stops only at a zero pivot; D(j) is the first entry of column j.
      const auto* column_start = static_cast<const int*>(factor->p);
      const auto* values = static_cast<const double*>(factor->x);
      for (Eigen::Index j = 0; j < n; ++j) {
        const double d = values[column_start[j]];
        if (!(d > 0.0) || !std::isfinite(d)) {
          m_failure = linear_detail::pivot_message(j, n, d);
          return false;
        }
      }
    }
    m_factorized = true;
    return true;
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& b) const override {
    linear_detail::require_solvable(m_factorized, m_pattern, b, k_name);
    cholmod_dense rhs{};
    rhs.nrow = static_cast<size_t>(b.size());
    rhs.ncol = 1;
    rhs.nzmax = rhs.nrow;
    rhs.d = rhs.nrow;
    rhs.x = const_cast<double*>(b.data());  // read only
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    // cholmod_solve2 reuses X, Y and E across calls when their shapes fit.
    cholmod_factor* const factor = m_factor.get();
    const int ok = m_common.call([&](cholmod_common* c) {
      return cholmod_solve2(CHOLMOD_A, factor, &rhs, nullptr, m_x.handle(), nullptr, m_y.handle(),
                            m_e.handle(), c);
    });
    if (!ok || m_x.get() == nullptr) {
      throw std::runtime_error("cholmod_solve2 failed: " + m_common.message());
    }
    return Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(m_x->x), b.size());
  }

  SparseBackend backend() const override { return SparseBackend::cholmod; }
  std::string last_failure() const override { return m_failure; }

 private:
  // Declared first so that it is destroyed last: the owned objects below free through it.
  // Mutable: every CHOLMOD call, solves included, writes status and statistics into it.
  mutable CholmodCommon m_common;
  CholmodOwned<cholmod_factor> m_factor{m_common};
  mutable CholmodOwned<cholmod_dense> m_x{m_common}, m_y{m_common},
      m_e{m_common};  // solve workspace
  linear_detail::SparsityPattern m_pattern;
  bool m_factorized = false;
  std::string m_failure;
};

}  // namespace

std::unique_ptr<SparseSpdSolver> make_cholmod_solver(const CholmodSettings& settings) {
  return std::make_unique<CholmodSolver>(settings);
}

}  // namespace weft::sim
