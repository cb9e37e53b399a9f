#include "sim/linear/grid_line_preconditioner.h"

#include <cmath>
#include <utility>
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

// The orthonormal pair nearest the directions of a and b, and as near the one as the other (the
// pair's bisectors are theirs): swapping a and b swaps the pair, so a cloth and its mirror image
// get mirrored frames, and a symmetric scene stays symmetric. Where one of them is zero (a
// vertex on the border has no coupling along one family) or they are parallel, the other is
// kept and its partner is any axis orthogonal to it.
std::pair<Eigen::Vector3d, Eigen::Vector3d> orthonormal_pair(Eigen::Vector3d a, Eigen::Vector3d b) {
  if (a.squaredNorm() == 0.0 && b.squaredNorm() == 0.0)
    return {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()};
  if (a.squaredNorm() == 0.0) {
    b.normalize();
    return {b.unitOrthogonal(), b};
  }
  a.normalize();
  if (b.squaredNorm() == 0.0) return {a, a.unitOrthogonal()};
  b.normalize();
  if (a.dot(b) < 0.0) b = -b;
  const Eigen::Vector3d u = a + b, w = a - b;
  if (w.squaredNorm() < 1e-12) return {a, a.unitOrthogonal()};
  const Eigen::Vector3d un = u.normalized(), wn = w.normalized();
  return {(un + wn) / std::sqrt(2.0), (un - wn) / std::sqrt(2.0)};
}

// A frame whose first two axes are the orthonormal pair nearest a and b.
Eigen::Matrix3d frame_of(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const auto [e1, e2] = orthonormal_pair(a, b);
  Eigen::Matrix3d f;
  f << e1, e2, e1.cross(e2);
  return f;
}

// The frame with the unit axis `kept` in place of the axis nearest it, the other two axes
// first made orthogonal to it, then the orthonormal pair nearest them: each axis keeps its role
// (along its family's lines) as far as it can.
Eigen::Matrix3d frame_keeping(Eigen::Matrix3d f, const Eigen::Vector3d& kept) {
  Eigen::Index j = 0;
  (f.transpose() * kept).cwiseAbs().maxCoeff(&j);
  const Eigen::Index k1 = (j + 1) % 3, k2 = (j + 2) % 3;
  const Eigen::Vector3d a = f.col(k1) - f.col(k1).dot(kept) * kept;
  const Eigen::Vector3d b = f.col(k2) - f.col(k2).dot(kept) * kept;
  auto [e1, e2] = orthonormal_pair(a, b);
  if (std::abs(e1.dot(kept)) > 1e-6 || std::abs(e2.dot(kept)) > 1e-6) {  // a or b was ~0
    e1 = kept.unitOrthogonal();
    e2 = kept.cross(e1);
  }
  f.col(j) = kept;
  f.col(k1) = e1;
  f.col(k2) = e2;
  return f;
}

// Block row p's own stiffness, what does not couple it to other vertices: the sum of its blocks
// (springs, tension and bending sum to zero along a row, as they do not resist translation),
// M (1 + h α) plus the penalties that hold contacts (κ n nᵀ, implicit_euler.cpp). Where that is
// far from isotropic, the axis of its penalty: the vertex's frame must keep it, or the line
// solves, which drop the coupling of a vertex's components, would drop most of the penalty.
Eigen::Vector3d penalty_axis(const BlockSparseMatrix& A, std::size_t p) {
  Eigen::Matrix3d own = Block(A.diagonal(p));
  for (int k = A.begin(p); k < A.end(p); ++k) own += Block(A.off_diagonal(k));
  const double mean = own.trace() / 3.0;
  if (!((own - mean * Eigen::Matrix3d::Identity()).norm() > mean)) return Eigen::Vector3d::Zero();
  Eigen::Index i = 0;
  own.diagonal().maxCoeff(&i);
  const Eigen::Vector3d d = own * (own * own.col(i));  // two power steps
  const double norm = d.norm();
  return norm > 0.0 && std::isfinite(norm) ? Eigen::Vector3d(d / norm) : Eigen::Vector3d::Zero();
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

// Each vertex's frame: its first two axes the orthonormal pair nearest the stiffest directions
// of its couplings along the two families of a pair (the warp and weft, or the two diagonals),
// its third their normal. The pair is the one whose couplings are the more directional (the sum of
// the deviatoric parts' norms, on a sample of vertices): the shear springs of an inextensible
// cloth, whose warp and weft carry an isotropic tension; the warp and weft springs of a
// mass-spring cloth, stiffer than its shear. A contact's penalty takes the place of the axis
// nearest it.
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
  for (Index p = 0; p < n; ++p) {
    m_frame[p] = frame_of(stiffest_direction(coupling_sum(m_family[first], p)),
                          stiffest_direction(coupling_sum(m_family[first + 1], p)));
    const Eigen::Vector3d penalty = penalty_axis(A, static_cast<std::size_t>(p));
    if (penalty.squaredNorm() > 0.0) m_frame[p] = frame_keeping(m_frame[p], penalty);
  }
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
      if (weight > best) {
        best = weight;
        m_component[c].family = f;
      }
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
