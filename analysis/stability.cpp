#include "analysis/stability.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/check.h"
#include "sim/pins.h"

namespace weft::analysis {
namespace {

using Eigen::VectorXd;

void check_sizes(const char* where, sim::Index vertices, const VectorXd& mass_kg,
                 const VectorXd& inv_mass) {
  if (mass_kg.size() != vertices || inv_mass.size() != vertices) {
    throw std::invalid_argument(std::string(where) + ": " + std::to_string(vertices) +
                                " vertices but " + std::to_string(mass_kg.size()) + " masses and " +
                                std::to_string(inv_mass.size()) + " inverse masses");
  }
}

// y = M^{-1/2} K M^{-1/2} q with K = −∂f/∂x at x by a central difference along u = M^{-1/2} q,
// scaled so that the largest vertex displacement of a probe is fd_step_m.
class MassStiffnessProduct {
 public:
  MassStiffnessProduct(const InternalForces& forces, const sim::Matrix3X& x,
                       const VectorXd& inv_mass, double fd_step_m)
      : m_forces(forces), m_x(x), m_fd_step_m(fd_step_m) {
    m_sqrt_inv_mass = inv_mass.cwiseMax(0.0).cwiseSqrt();
  }

  void apply(const VectorXd& q, VectorXd& y) {
    const sim::Index n = static_cast<sim::Index>(m_x.rows());
    m_u.resize(n, 3);
    for (sim::Index i = 0; i < n; ++i)
      m_u.row(i) = m_sqrt_inv_mass[i] * q.segment<3>(3 * i).transpose();
    const double u_max = m_u.cwiseAbs().maxCoeff();
    y.setZero(3 * n);
    if (u_max == 0.0) return;
    const double eps = m_fd_step_m / u_max;
    m_plus = m_x + eps * m_u;
    m_minus = m_x - eps * m_u;
    m_f_plus.setZero(n, 3);
    m_f_minus.setZero(n, 3);
    m_forces(m_plus, m_f_plus);
    m_forces(m_minus, m_f_minus);
    for (sim::Index i = 0; i < n; ++i) {  // K u = −(f(x + εu) − f(x − εu)) / 2ε
      y.segment<3>(3 * i) =
          (-m_sqrt_inv_mass[i] / (2.0 * eps)) * (m_f_plus.row(i) - m_f_minus.row(i)).transpose();
    }
  }

 private:
  const InternalForces& m_forces;
  const sim::Matrix3X& m_x;
  double m_fd_step_m;
  VectorXd m_sqrt_inv_mass;
  sim::Matrix3X m_u, m_plus, m_minus, m_f_plus, m_f_minus;
};

}  // namespace

double LargestEigenvalue::omega_rad_s() const { return std::sqrt(std::max(lambda_1_s2, 0.0)); }

LargestEigenvalue largest_eigenvalue_mass_stiffness(const InternalForces& forces,
                                                    const sim::Matrix3X& x, const VectorXd& mass_kg,
                                                    const VectorXd& inv_mass,
                                                    const EigenvalueSettings& settings) {
  const sim::Index vertices = static_cast<sim::Index>(x.rows());
  check_sizes("largest_eigenvalue_mass_stiffness", vertices, mass_kg, inv_mass);
  if (!forces) throw std::invalid_argument("largest_eigenvalue_mass_stiffness: no forces");
  if (!(settings.fd_step_m > 0.0) || settings.max_iterations < 1 ||
      !(settings.relative_tolerance > 0.0))
    throw std::invalid_argument("largest_eigenvalue_mass_stiffness: bad settings");

  const sim::Index n = 3 * vertices;
  VectorXd free_mask = VectorXd::Zero(n);
  for (sim::Index i = 0; i < vertices; ++i)
    if (inv_mass[i] > 0.0) free_mask.segment<3>(3 * i).setOnes();
  const sim::Index free_dofs = static_cast<sim::Index>(free_mask.sum());
  LargestEigenvalue result;
  if (free_dofs == 0) {
    result.converged = true;
    return result;
  }

  // Lanczos with full reorthogonalisation (Golub & Van Loan, Matrix Computations, §10.1):
  // S Q_j = Q_j T_j + β_j q_{j+1} e_jᵀ; the largest Ritz value θ of the tridiagonal T_j, with
  // Ritz vector Q_j s, has residual ‖S Q_j s − θ Q_j s‖ = β_j |s_j|.
  MassStiffnessProduct product(forces, x, inv_mass, settings.fd_step_m);
  const int max_steps = static_cast<int>(std::min<sim::Index>(settings.max_iterations, free_dofs));
  Eigen::MatrixXd Q(n, max_steps);
  VectorXd alpha(max_steps), beta(max_steps);
  std::mt19937_64 rng(settings.seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  VectorXd q(n);
  for (sim::Index r = 0; r < n; ++r) q[r] = uniform(rng) * free_mask[r];
  Q.col(0) = q.normalized();
  VectorXd w(n);
  for (int j = 0; j < max_steps; ++j) {
    product.apply(Q.col(j), w);
    alpha[j] = Q.col(j).dot(w);
    w -= alpha[j] * Q.col(j);
    if (j > 0) w -= beta[j - 1] * Q.col(j - 1);
    for (int pass = 0; pass < 2; ++pass)  // twice is enough (Kahan–Parlett)
      w -= Q.leftCols(j + 1) * (Q.leftCols(j + 1).transpose() * w);
    beta[j] = w.norm();
    result.iterations = j + 1;

    const bool last = j + 1 == max_steps;
    const double scale = alpha.head(j + 1).cwiseAbs().maxCoeff() + beta.head(j + 1).maxCoeff();
    const bool invariant = beta[j] <= 1e-13 * scale;  // Q_j spans an invariant subspace
    if (j % 4 == 3 || last || invariant) {  // Ritz values every few steps: O(j²) each
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz;
      ritz.computeFromTridiagonal(alpha.head(j + 1), beta.head(j), Eigen::ComputeEigenvectors);
      const sim::Index top = j;  // eigenvalues in increasing order
      result.lambda_1_s2 = ritz.eigenvalues()[top];
      result.residual_1_s2 = beta[j] * std::abs(ritz.eigenvectors()(j, top));
      if (invariant ||
          result.residual_1_s2 <= settings.relative_tolerance * std::abs(result.lambda_1_s2)) {
        result.converged = true;
        break;
      }
    }
    if (last || invariant) break;
    Q.col(j + 1) = w / beta[j];
  }
  return result;
}

CriticalStep predicted_critical_step(sim::Integrator method, double omega_rad_s,
                                     double damping_1_s) {
  if (!(omega_rad_s > 0.0) || !std::isfinite(omega_rad_s))
    throw std::invalid_argument("predicted_critical_step: omega " + std::to_string(omega_rad_s) +
                                " rad/s, expected > 0");
  if (!(damping_1_s >= 0.0))
    throw std::invalid_argument("predicted_critical_step: damping " + std::to_string(damping_1_s) +
                                " 1/s, expected >= 0");
  const double w = omega_rad_s, a = damping_1_s;
  switch (method) {
    case sim::Integrator::symplectic_euler:
      return {StepLimit::bounded, (std::sqrt(a * a + 4.0 * w * w) - a) / (w * w)};
    case sim::Integrator::velocity_verlet:
    case sim::Integrator::central_difference:
      return {StepLimit::bounded, 2.0 / w};
    case sim::Integrator::rk4:
      return {StepLimit::bounded, 2.0 * std::sqrt(2.0) / w};
    case sim::Integrator::explicit_euler:
      if (a == 0.0) return {StepLimit::always_unstable, 0.0};
      if (a < 2.0 * w) return {StepLimit::bounded, a / (w * w)};
      return {StepLimit::bounded, 2.0 / (0.5 * a + std::sqrt(0.25 * a * a - w * w))};
    case sim::Integrator::implicit_euler:
      return {StepLimit::always_stable, std::numeric_limits<double>::infinity()};
    case sim::Integrator::dynamic_relaxation:  // its fictitious masses are made stable for its step
      throw std::invalid_argument(
          "predicted_critical_step: dynamic_relaxation iterates in pseudo-time, not a "
          "physical-time integrator");
  }
  WEFT_CHECK(false, "predicted_critical_step: unknown integrator");
  return {};
}

StepperFactory stepper_factory(sim::Integrator method, sim::System system) {
  WEFT_CHECK(sim::integrates_physical_time(method), std::string("stepper_factory: ") +
                                                        sim::integrator_name(method) +
                                                        " does not integrate physical time");
  (void)sim::make_time_integrator(method, system);  // throws now on misuse, not in the first run
  auto shared = std::make_shared<const sim::System>(std::move(system));
  return [method, shared]() -> StepFunction {
    std::shared_ptr<sim::TimeIntegrator> integrator = sim::make_time_integrator(method, *shared);
    return [integrator, shared](sim::Matrix3X& x, sim::Matrix3X& v, double h_s) {
      return integrator->step(*shared, x, v, h_s).solved;
    };
  };
}

BlowUpResult run_blow_up_test(const StepFunction& step, const sim::Matrix3X& x_rest,
                              const VectorXd& mass_kg, const VectorXd& inv_mass, double h_s,
                              const BlowUpSettings& settings) {
  const sim::Index n = static_cast<sim::Index>(x_rest.rows());
  check_sizes("run_blow_up_test", n, mass_kg, inv_mass);
  if (!(h_s > 0.0) || settings.steps < 1 || !(settings.perturbation_m > 0.0) ||
      !(settings.growth_factor > 1.0))
    throw std::invalid_argument("run_blow_up_test: bad step " + std::to_string(h_s) +
                                " s or settings");
  std::mt19937_64 rng(settings.seed);
  std::uniform_real_distribution<double> uniform(-settings.perturbation_m,
                                                 settings.perturbation_m);
  sim::Matrix3X x = x_rest, v = sim::Matrix3X::Zero(n, 3);
  for (sim::Index i = 0; i < n; ++i)
    if (inv_mass[i] > 0.0)
      for (int c = 0; c < 3; ++c) x(i, c) += uniform(rng);
  const auto displacement = [&] {  // ‖x − x₀‖_M, kg^½·m
    double sum = 0.0;
    for (sim::Index i = 0; i < n; ++i) sum += mass_kg[i] * (x.row(i) - x_rest.row(i)).squaredNorm();
    return std::sqrt(sum);
  };
  const double start = displacement();
  if (!(start > 0.0)) throw std::invalid_argument("run_blow_up_test: no free vertex to perturb");

  BlowUpResult result;
  for (long s = 0; s < settings.steps; ++s) {
    result.steps_run = s + 1;
    if (!step(x, v, h_s) || !x.allFinite() || !v.allFinite()) {
      result.stable = false;
      result.max_growth = std::numeric_limits<double>::infinity();
      break;
    }
    const double growth = displacement() / start;
    result.max_growth = std::max(result.max_growth, growth);
    if (!(growth <= settings.growth_factor)) {
      result.stable = false;
      break;
    }
  }
  return result;
}

double CriticalStepSearch::h_s() const { return std::sqrt(stable_h_s * unstable_h_s); }

CriticalStepSearch find_critical_step(const StepperFactory& make_stepper,
                                      const sim::Matrix3X& x_rest, const VectorXd& mass_kg,
                                      const VectorXd& inv_mass, double guess_h_s,
                                      const BlowUpSettings& settings, double relative_tolerance) {
  if (!(guess_h_s > 0.0) || !std::isfinite(guess_h_s) || !(relative_tolerance > 0.0))
    throw std::invalid_argument("find_critical_step: guess " + std::to_string(guess_h_s) +
                                " s, tolerance " + std::to_string(relative_tolerance));
  CriticalStepSearch search;
  const auto stable = [&](double h_s) {
    ++search.runs;
    return run_blow_up_test(make_stepper(), x_rest, mass_kg, inv_mass, h_s, settings).stable;
  };
  constexpr int kMaxWidenings = 8;
  double lo = 0.5 * guess_h_s, hi = 2.0 * guess_h_s;
  bool hi_known_unstable = false;
  for (int k = 0; !stable(lo); ++k) {
    if (k == kMaxWidenings) return search;
    hi = lo;
    hi_known_unstable = true;
    lo *= 0.25;
  }
  if (!hi_known_unstable) {
    for (int k = 0; stable(hi); ++k) {
      if (k == kMaxWidenings) return search;
      lo = hi;
      hi *= 4.0;
    }
  }
  while (hi > lo * (1.0 + relative_tolerance)) {
    const double mid = std::sqrt(lo * hi);
    (stable(mid) ? lo : hi) = mid;
  }
  search.bracketed = true;
  search.stable_h_s = lo;
  search.unstable_h_s = hi;
  return search;
}

StabilityCloth::StabilityCloth(sim::Index n, double stiffness_scale) {
  if (n < 3) throw std::invalid_argument("StabilityCloth: " + std::to_string(n) + " vertices per side, expected >= 3");
  if (!(stiffness_scale > 0.0) || !std::isfinite(stiffness_scale))
    throw std::invalid_argument("StabilityCloth: stiffness scale " +
                                std::to_string(stiffness_scale) + ", expected > 0");
  sim::GridSpec spec;
  spec.nu = spec.nv = n;
  spec.origin = sim::Vec3::Zero();  // small coordinates: the perturbations keep their digits
  m_mesh = sim::make_grid(spec);
  m_material.stretch_warp_N_m *= stiffness_scale;
  m_material.stretch_weft_N_m *= stiffness_scale;
  m_material.shear_N_m *= stiffness_scale;
  m_material.bend_warp_Nm *= stiffness_scale;
  m_material.bend_weft_Nm *= stiffness_scale;
  m_pinned = sim::resolve_pins({sim::PinCorner{"u0v1"}, sim::PinCorner{"u1v1"}}, m_mesh);
  m_model = std::make_unique<sim::MassSpringModel>(m_mesh, m_material);
  m_mass_kg = m_material.density_kg_m2 * m_mesh.vertex_area_m2;
  m_inv_mass = m_mass_kg.cwiseInverse();
  for (sim::Index p : m_pinned) m_inv_mass[p] = 0.0;
}

InternalForces StabilityCloth::forces() const {
  const sim::MassSpringModel* model = m_model.get();
  return [model](const sim::Matrix3X& x, sim::Matrix3X& f) { model->add_forces(x, f); };
}

LargestEigenvalue StabilityCloth::largest_eigenvalue(const EigenvalueSettings& s) const {
  return largest_eigenvalue_mass_stiffness(forces(), rest_positions(), m_mass_kg, m_inv_mass, s);
}

sim::System StabilityCloth::system(double damping_1_s) const {
  sim::System system;
  system.mass_kg = m_mass_kg;
  system.inv_mass = m_inv_mass;
  system.damping_1_s = damping_1_s;
  system.terms = m_model->terms();
  return system;
}

StepperFactory StabilityCloth::stepper_factory(sim::Integrator method, double damping_1_s) const {
  return analysis::stepper_factory(method, system(damping_1_s));
}

}  // namespace weft::analysis
