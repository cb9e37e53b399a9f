#include "sim/linear/grid_multigrid.h"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "base/check.h"

namespace weft::sim {
namespace {

// Fine couplings reaching farther than this many grid steps are not a grid operator's.
constexpr int kMaxFineRadius = 3;

// How far apart two vertices of an nu-wide grid are, in grid steps (the larger of the two axes).
int grid_distance(Index a, Index b, Index nu) {
  return static_cast<int>(std::max(std::abs(a % nu - b % nu), std::abs(a / nu - b / nu)));
}

// Each off-diagonal block's column offset from its row, (du, dv) in grid steps.
void block_offsets(const BlockSparseMatrix& A, Index nu, std::vector<std::int8_t>& du,
                   std::vector<std::int8_t>& dv) {
  du.resize(A.off_diagonal_blocks());
  dv.resize(A.off_diagonal_blocks());
  for (std::size_t p = 0; p < A.block_rows(); ++p)
    for (int k = A.begin(p); k < A.end(p); ++k) {
      const Index q = A.column()[static_cast<std::size_t>(k)];
      du[static_cast<std::size_t>(k)] = static_cast<std::int8_t>(q % nu - static_cast<Index>(p) % nu);
      dv[static_cast<std::size_t>(k)] = static_cast<std::int8_t>(q / nu - static_cast<Index>(p) / nu);
    }
}

// The coarse pattern of an nu × nv grid: every vertex within `radius` steps of a row's vertex.
std::vector<std::vector<int>> stencil_pattern(Index nu, Index nv, int radius, std::vector<int>& slot) {
  const int width = 2 * radius + 1;
  std::vector<std::vector<int>> columns(static_cast<std::size_t>(nu * nv));
  slot.assign(columns.size() * static_cast<std::size_t>(width * width), -1);
  int block = 0;
  for (Index j = 0; j < nv; ++j)
    for (Index i = 0; i < nu; ++i) {
      const std::size_t row = static_cast<std::size_t>(j * nu + i);
      for (int dv = -radius; dv <= radius; ++dv)
        for (int du = -radius; du <= radius; ++du) {
          const Index ci = i + du, cj = j + dv;
          if ((du == 0 && dv == 0) || ci < 0 || cj < 0 || ci >= nu || cj >= nv) continue;
          columns[row].push_back(static_cast<int>(cj * nu + ci));
          slot[row * static_cast<std::size_t>(width * width) +
               static_cast<std::size_t>((dv + radius) * width + du + radius)] = block++;
        }
    }
  return columns;
}

}  // namespace

std::optional<GridMultigrid> GridMultigrid::make(const BlockSparseMatrix& fine, Index nu, Index nv) {
  if (nu < 3 || nv < 3 || static_cast<Index>(fine.block_rows()) != nu * nv || nu * nv <= kCoarsestRows)
    return std::nullopt;
  int radius = 0;
  for (std::size_t p = 0; p < fine.block_rows(); ++p)
    for (int k = fine.begin(p); k < fine.end(p); ++k)
      radius = std::max(radius, grid_distance(static_cast<Index>(p), fine.column()[static_cast<std::size_t>(k)], nu));
  if (radius > kMaxFineRadius) return std::nullopt;
  GridMultigrid mg;
  mg.m_fine_nu = nu;
  mg.m_fine_nv = nv;
  Index level_nu = nu, level_nv = nv;
  while (level_nu * level_nv > kCoarsestRows && level_nu >= 3 && level_nv >= 3) {
    Level level;
    block_offsets(mg.m_levels.empty() ? fine : mg.m_levels.back().A, level_nu, level.above_du,
                  level.above_dv);
    level.nu = level_nu / 2 + 1;
    level.nv = level_nv / 2 + 1;
    level.radius = (radius + 2) / 2;
    level.A = BlockSparseMatrix(stencil_pattern(level.nu, level.nv, level.radius, level.slot));
    const std::size_t n = static_cast<std::size_t>(level.nu * level.nv);
    level.b.resize(static_cast<Eigen::Index>(3 * n));
    level.x.resize(level.b.size());
    level.t.resize(level.b.size());
    mg.m_levels.push_back(std::move(level));
    level_nu = mg.m_levels.back().nu;
    level_nv = mg.m_levels.back().nv;
    radius = mg.m_levels.back().radius;
  }
  return mg;
}

int GridMultigrid::parents(Index i, Index j, Index coarse_nu, Parent* out) {
  const Index ci[2] = {i / 2, i / 2 + 1}, cj[2] = {j / 2, j / 2 + 1};
  const int ni = (i & 1) == 0 ? 1 : 2, nj = (j & 1) == 0 ? 1 : 2;
  const double weight = 1.0 / (ni * nj);
  int count = 0;
  for (int b = 0; b < nj; ++b)
    for (int a = 0; a < ni; ++a) out[count++] = {ci[a], cj[b], cj[b] * coarse_nu + ci[a], weight};
  return count;
}

void GridMultigrid::accumulate_galerkin(const BlockSparseMatrix& A, Index nu, std::size_t into) {
  Level& level = m_levels[into];
  const int width = 2 * level.radius + 1;
  const std::size_t row_slots = static_cast<std::size_t>(width * width);
  const auto add = [&](const Parent* rows, int row_count, const Parent* cols, int col_count,
                       const double* block) {
    for (int a = 0; a < row_count; ++a) {
      const std::size_t table = static_cast<std::size_t>(rows[a].vertex) * row_slots;
      for (int b = 0; b < col_count; ++b) {
        if (cols[b].vertex < rows[a].vertex) continue;  // the lower triangle: mirrored below
        double* target;
        if (rows[a].vertex == cols[b].vertex) {
          target = level.A.diagonal(static_cast<std::size_t>(rows[a].vertex));
        } else {
          const Index du = cols[b].i - rows[a].i, dv = cols[b].j - rows[a].j;
          target = level.A.off_diagonal(
              level.slot[table + static_cast<std::size_t>((dv + level.radius) * width + du + level.radius)]);
        }
        Eigen::Map<Eigen::Matrix<double, 9, 1>>(target) +=
            (rows[a].weight * cols[b].weight) * Eigen::Map<const Eigen::Matrix<double, 9, 1>>(block);
      }
    }
  };
  Parent row_parents[4], column_parents[4];
  std::size_t p = 0;
  for (Index j = 0; j < static_cast<Index>(A.block_rows()) / nu; ++j)
    for (Index i = 0; i < nu; ++i, ++p) {
      const int np = parents(i, j, level.nu, row_parents);
      add(row_parents, np, row_parents, np, A.diagonal(p));
      for (int k = A.begin(p); k < A.end(p); ++k) {
        const auto b = static_cast<std::size_t>(k);
        const int nq = parents(i + level.above_du[b], j + level.above_dv[b], level.nu, column_parents);
        add(row_parents, np, column_parents, nq, A.off_diagonal(k));
      }
    }
  // Block (I, J) below the diagonal is block (J, I) transposed.
  for (Index J = 0; J < level.nu * level.nv; ++J) {
    const Index ci = J % level.nu, cj = J / level.nu;
    for (int k = level.A.begin(static_cast<std::size_t>(J)); k < level.A.end(static_cast<std::size_t>(J)); ++k) {
      const Index I = level.A.column()[static_cast<std::size_t>(k)];
      if (I < J) continue;
      const Index du = I % level.nu - ci, dv = I / level.nu - cj;  // from J to I
      const int mirror = level.slot[static_cast<std::size_t>(I) * row_slots +
                                    static_cast<std::size_t>((level.radius - dv) * width + level.radius - du)];
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::ColMajor>>(level.A.off_diagonal(mirror)) =
          Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::ColMajor>>(level.A.off_diagonal(k)).transpose();
    }
  }
}

void GridMultigrid::update(const BlockSparseMatrix& fine) {
  for (std::size_t l = 0; l < m_levels.size(); ++l) {
    Level& level = m_levels[l];
    level.A.set_zero();
    accumulate_galerkin(l == 0 ? fine : m_levels[l - 1].A, l == 0 ? m_fine_nu : m_levels[l - 1].nu, l);
    for (std::size_t p = 0; p < level.A.block_rows(); ++p) {
      double* d = level.A.diagonal(p);
      if (std::all_of(d, d + 9, [](double v) { return v == 0.0; })) d[0] = d[4] = d[8] = 1.0;
    }
    level.A.invert_diagonal(level.inverse);
  }
  m_coarsest.compute(m_levels.back().A.to_dense());
  m_coarsest_ok = m_coarsest.info() == Eigen::Success;
}

void GridMultigrid::apply(const BlockSparseMatrix& fine, const std::vector<Eigen::Matrix3d>& fine_inverse,
                          const Eigen::VectorXd& r, Eigen::VectorXd& z, base::ThreadPool* pool) const {
  m_fine_residual.resize(r.size());
  z.resize(r.size());
  cycle(0, fine, fine_inverse, m_fine_nu, r, z, m_fine_residual, pool);
}

void GridMultigrid::restrict_to(const Level& coarse, Index nu, const Eigen::VectorXd& fine) const {
  coarse.b.setZero();
  Parent up[4];
  const auto nv = static_cast<Index>(fine.size() / 3 / nu);
  for (Index j = 0, v = 0; j < nv; ++j)
    for (Index i = 0; i < nu; ++i, ++v) {
      const int count = parents(i, j, coarse.nu, up);
      for (int a = 0; a < count; ++a)
        coarse.b.segment<3>(3 * up[a].vertex) += up[a].weight * fine.segment<3>(3 * v);
    }
}

void GridMultigrid::prolong_from(const Level& coarse, Index nu, Eigen::VectorXd& fine) const {
  Parent up[4];
  const auto nv = static_cast<Index>(fine.size() / 3 / nu);
  for (Index j = 0, v = 0; j < nv; ++j)
    for (Index i = 0; i < nu; ++i, ++v) {
      const int count = parents(i, j, coarse.nu, up);
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int a = 0; a < count; ++a) sum += up[a].weight * coarse.x.segment<3>(3 * up[a].vertex);
      fine.segment<3>(3 * v) += sum;
    }
}

// x = B_k b on level k (0: the fine grid), t its scratch residual.
void GridMultigrid::cycle(std::size_t k, const BlockSparseMatrix& A,
                          const std::vector<Eigen::Matrix3d>& inverse, Index nu,
                          const Eigen::VectorXd& b, Eigen::VectorXd& x, Eigen::VectorXd& t,
                          base::ThreadPool* pool) const {
  const std::size_t n = inverse.size();
  const auto smooth = [&](const Eigen::VectorXd& residual, double weight, bool add) {
    for (std::size_t v = 0; v < n; ++v) {
      const auto i = static_cast<Eigen::Index>(3 * v);
      const Eigen::Vector3d step = weight * (inverse[v] * residual.segment<3>(i));
      if (add) {
        x.segment<3>(i) += step;
      } else {
        x.segment<3>(i) = step;
      }
    }
  };
  if (k == m_levels.size()) {  // the coarsest grid
    if (m_coarsest_ok) {
      x = m_coarsest.solve(b);
    } else {
      smooth(b, 1.0, false);
    }
    return;
  }
  smooth(b, kSmoothingWeight, false);
  A.multiply(x, t, pool);
  t = b - t;
  const Level& coarse = m_levels[k];
  restrict_to(coarse, nu, t);
  cycle(k + 1, coarse.A, coarse.inverse, coarse.nu, coarse.b, coarse.x, coarse.t, nullptr);
  prolong_from(coarse, nu, x);
  A.multiply(x, t, pool);
  t = b - t;
  smooth(t, kSmoothingWeight, true);
}

}  // namespace weft::sim
