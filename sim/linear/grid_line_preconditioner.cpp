#include "sim/linear/grid_line_preconditioner.h"

#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "base/check.h"

namespace weft::sim {

namespace {

using Block = Eigen::Map<const Eigen::Matrix3d>;

// The grid steps of the four line families: along u, along v, and the two diagonals.
constexpr int kStep[GridLinePreconditioner::kFamilies][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};

// The axis of the springs whose coupling blocks sum to `sum` (each −h² k d dᵀ at rest, plus
// tension across): −sum's column of largest diagonal entry, normalized; zero if none.
Eigen::Vector3d stiffest_direction(const Eigen::Matrix3d& sum) {
  const Eigen::Matrix3d s = -sum;
  Eigen::Index i = 0;
  if (!(s.diagonal().maxCoeff(&i) > 0.0)) return Eigen::Vector3d::Zero();
  Eigen::Vector3d d = s.col(i);
  const double norm = d.norm();
  return norm > 0.0 && std::isfinite(norm) ? Eigen::Vector3d(d / norm) : Eigen::Vector3d::Zero();
}

// An orthonormal frame whose first axis is a and second b made orthogonal to it; where one of
// them is zero (a vertex on the border has no coupling along one family), the other keeps its
// place and the zero one takes an axis orthogonal to it.
Eigen::Matrix3d frame_of(Eigen::Vector3d a, Eigen::Vector3d b) {
  if (a.squaredNorm() == 0.0 && b.squaredNorm() == 0.0) return Eigen::Matrix3d::Identity();
  if (a.squaredNorm() == 0.0) {
    b.normalize();
    a = b.unitOrthogonal();
  } else {
    a.normalize();
    b -= b.dot(a) * a;
    b = b.squaredNorm() < 1e-6 ? a.unitOrthogonal() : b.normalized();
  }
  Eigen::Matrix3d f;
  f << a, b, a.cross(b);
  return f;
}

}  // namespace

GridLinePreconditioner::GridLinePreconditioner(const BlockSparseMatrix& pattern, Index nu, Index nv)
    : m_nu(nu), m_nv(nv) {
  const auto n = static_cast<Index>(pattern.block_rows());
  WEFT_CHECK(nu > 0 && nv > 0 && nu * nv == n,
             "GridLinePreconditioner: a " + std::to_string(nu) + " × " + std::to_string(nv) +
                 " grid for " + std::to_string(n) + " block rows");
  for (int f = 0; f < kFamilies; ++f) {
    Family& fam = m_family[f];
    const int du = kStep[f][0], dv = kStep[f][1];
    fam.previous.assign(static_cast<std::size_t>(n), -1);
    fam.next.assign(static_cast<std::size_t>(n), -1);
    // Lines start where the step back leaves the grid; each is walked forward to its end.
    for (Index j = 0; j < nv; ++j)
      for (Index i = 0; i < nu; ++i) {
        const Index bi = i - du, bj = j - dv;
        if (bi >= 0 && bi < nu && bj >= 0 && bj < nv) continue;
        Index prev = -1;
        for (Index ci = i, cj = j; ci >= 0 && ci < nu && cj >= 0 && cj < nv; ci += du, cj += dv) {
          const Index p = cj * nu + ci;
          fam.order.push_back(p);
          if (prev >= 0) {
            fam.previous[p] = pattern.find(static_cast<int>(p), static_cast<int>(prev));
            fam.next[prev] = pattern.find(static_cast<int>(prev), static_cast<int>(p));
          }
          fam.previous_vertex.push_back(prev);
          prev = p;
        }
      }
    WEFT_CHECK(static_cast<Index>(fam.order.size()) == n, "GridLinePreconditioner: lines miss vertices");
  }
  m_frame.assign(static_cast<std::size_t>(n), Eigen::Matrix3d::Identity());
  for (Component& c : m_component) {
    c.inverse_pivot.assign(static_cast<std::size_t>(n), 1.0);
    c.lower.assign(static_cast<std::size_t>(n), 0.0);
  }
  m_local.resize(3 * n);
}

// Each vertex's frame: its first axis along the stiffest direction of its couplings along one
// family of a pair (the warp and weft, or the two diagonals), its second along the other's,
// made orthogonal. The pair is the one whose couplings are the more directional (the sum of
// the deviatoric parts' norms, on a sample of vertices): the shear springs of an inextensible
// cloth, whose warp and weft carry an isotropic tension; the warp and weft springs of a
// mass-spring cloth, stiffer than its shear.
void GridLinePreconditioner::update_frames(const BlockSparseMatrix& A) {
  const auto n = static_cast<Index>(m_frame.size());
  const auto coupling_sum = [&](const Family& fam, Index p) {
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    if (fam.previous[p] >= 0) sum += Block(A.off_diagonal(fam.previous[p]));
    if (fam.next[p] >= 0) sum += Block(A.off_diagonal(fam.next[p]));
    return sum;
  };
  const auto directional = [&](const Family& fam, Index p) {
    const Eigen::Matrix3d s = coupling_sum(fam, p);
    return (s - s.trace() / 3.0 * Eigen::Matrix3d::Identity()).norm();
  };
  double grid = 0.0, diagonals = 0.0;
  for (Index p = 0; p < n; p += sample_stride()) {
    grid += directional(m_family[0], p) + directional(m_family[1], p);
    diagonals += directional(m_family[2], p) + directional(m_family[3], p);
  }
  const int first = diagonals >= grid ? 2 : 0;
  for (Index p = 0; p < n; ++p)
    m_frame[p] = frame_of(stiffest_direction(coupling_sum(m_family[first], p)),
                          stiffest_direction(coupling_sum(m_family[first + 1], p)));
}

bool GridLinePreconditioner::update(const BlockSparseMatrix& A) {
  update_frames(A);
  for (int c = 0; c < 3; ++c) {
    // The family whose couplings of this component weigh most, judged on a sample of vertices.
    double best = -1.0;
    for (int f = 0; f < kFamilies; ++f) {
      const Family& fam = m_family[f];
      double weight = 0.0;
      for (std::size_t k = 0; k < fam.order.size(); k += static_cast<std::size_t>(sample_stride())) {
        const int b = fam.previous[fam.order[k]];
        if (b < 0) continue;
        const Index p = fam.order[k], q = fam.previous_vertex[k];
        weight += std::abs(m_frame[p].col(c).dot(Block(A.off_diagonal(b)) * m_frame[q].col(c)));
      }
      if (weight > best) best = weight, m_component[c].family = f;
    }
    if (!factor(A, c)) return false;
  }
  return true;
}

// The scalar tridiagonal system of component c along its family's lines, T = L D Lᵀ.
bool GridLinePreconditioner::factor(const BlockSparseMatrix& A, int c) {
  Component& comp = m_component[c];
  const Family& fam = m_family[comp.family];
  for (std::size_t k = 0; k < fam.order.size(); ++k) {
    const Index p = fam.order[k], q = fam.previous_vertex[k];
    const Eigen::Vector3d e = m_frame[p].col(c);
    double pivot = e.dot(Block(A.diagonal(static_cast<std::size_t>(p))) * e);
    comp.lower[k] = 0.0;
    const int b = fam.previous[p];
    if (q >= 0 && b >= 0) {
      const double t = e.dot(Block(A.off_diagonal(b)) * m_frame[q].col(c));
      comp.lower[k] = t * comp.inverse_pivot[k - 1];
      pivot -= comp.lower[k] * t;
    }
    if (!(pivot > 0.0)) return false;
    comp.inverse_pivot[k] = 1.0 / pivot;
  }
  return true;
}

void GridLinePreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  const auto n = static_cast<Index>(m_frame.size());
  for (Index p = 0; p < n; ++p) m_local.segment<3>(3 * p).noalias() = m_frame[p].transpose() * r.segment<3>(3 * p);
  for (int c = 0; c < 3; ++c) {
    const Component& comp = m_component[c];
    const Family& fam = m_family[comp.family];
    // Forward: y_k = ρ_k − l_k y_{k−1}; backward: w_k = y_k / d_k − l_{k+1} w_{k+1}. A line's
    // first vertex has l = 0, so one chain runs through all the lines.
    const Index* order = fam.order.data();
    const double* lower = comp.lower.data();
    const double* inverse_pivot = comp.inverse_pivot.data();
    double y = 0.0;
    for (std::size_t k = 0; k < fam.order.size(); ++k) {
      double& v = m_local[3 * order[k] + c];
      y = v - lower[k] * y;
      v = y;
    }
    double w = 0.0, l = 0.0;
    for (std::size_t k = fam.order.size(); k-- > 0;) {
      double& v = m_local[3 * order[k] + c];
      w = v * inverse_pivot[k] - l * w;
      v = w;
      l = lower[k];
    }
  }
  for (Index p = 0; p < n; ++p) z.segment<3>(3 * p).noalias() = m_frame[p] * m_local.segment<3>(3 * p);
}

}  // namespace weft::sim
