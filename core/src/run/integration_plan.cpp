#include "run/integration_plan.hpp"

#include <algorithm>
#include <cmath>

#include "lub/common/constants.hpp"
#include "lub/formulation/joint_tree.hpp"

namespace lub::detail {

namespace {

// The rate that scales the velocity tolerances [rad/s]: the fastest driver's speed, or
// 2π over the cycle period or the duration when no driver gives one.
double characteristic_rate(const Scene& scene) {
  double w = 0.0;
  for (const DriverSpec& d : scene.drivers) w = std::max(w, std::abs(d.speed_rad_s));
  if (w > 0.0) return w;
  if (const auto T = scene.cycle_period_s()) return kTwoPi / *T;
  if (scene.simulation.duration_s) return kTwoPi / *scene.simulation.duration_s;
  return 1.0;
}

}  // namespace

Eigen::VectorXd state_units(const Scene& scene, const Model& m) {
  return state_scales(m, scene.min_clearance_m().value_or(1e-3), characteristic_rate(scene));
}

Tolerances::Tolerances(const Scene& scene, const Model& m, double factor) {
  const SolverSpec& sol = scene.solver;
  const Eigen::VectorXd units = state_units(scene, m);
  rtol_ = sol.rtol * factor;
  reported_atol_ = (sol.atol ? *sol.atol : sol.rtol * scene.min_clearance_m().value_or(1e-3)) * factor;
  atol_full_.assign(static_cast<size_t>(2 * m.nq), 0.0);
  for (int i = 0; i < 2 * m.nq; ++i)
    atol_full_[static_cast<size_t>(i)] = (sol.atol ? *sol.atol : sol.rtol * units(i)) * factor;
}

std::vector<double> Tolerances::integrated_atol(const MultibodySystem& sys) const {
  std::vector<double> atol(static_cast<size_t>(sys.size()), 0.0);
  sys.reduce_units(atol_full_.data(), atol.data());
  return atol;
}

std::vector<double> Tolerances::difference_scales(const std::vector<double>& atol, double rtol) {
  std::vector<double> scales(atol.size());
  for (size_t i = 0; i < scales.size(); ++i) scales[i] = atol[i] / rtol;
  return scales;
}

std::optional<JacobianKind> IntegrationPlan::jacobian() const {
  if (!newton) return std::nullopt;
  return settings.user_jacobian ? JacobianKind::structured : JacobianKind::difference_quotients;
}

IntegrationPlan plan_integration(const Scene& scene, const Model& m, double factor) {
  const SolverSpec& sol = scene.solver;
  IntegrationPlan plan;
  IntegratorSettings& is = plan.settings;
  is.method = sol.method;
  is.rtol = sol.rtol * factor;
  is.max_step = sol.max_step_s;
  is.initial_step = sol.initial_step_s;
  is.max_order = sol.max_order;
  is.projection = sol.projection;
  plan.newton = is_newton(sol.method);
  // A mechanism without a degree of freedom (every coordinate fixed by joints and drivers:
  // the ideal slider-crank) leaves partitioning nothing to integrate: it runs on the
  // baumgarte formulation, whose states are all the coordinates.
  // The joint formulation applies where the ideal joints form a tree rooted at the ground
  // (lub/formulation/joint_tree.hpp); a loop of ideal joints runs on the partitioned one.
  plan.formulation = sol.formulation;
  if (plan.formulation == Formulation::joint && !build_joint_tree(m)) plan.formulation = Formulation::partitioned;
  if (plan.formulation == Formulation::partitioned && m.nq <= m.nc) plan.formulation = Formulation::baumgarte;
  is.user_jacobian = plan.newton && sol.jacobian == JacobianKind::structured;
  // A fresh Jacobian every step where a reused one fails. Partitioned: the squeeze film's
  // stiff mode lies almost along a degree of freedom and changes within a few degrees of
  // crank, so a stale Jacobian lets an unconverged stiff component through the error test
  // until CVODE gives up at the dead centres. Projection with event switching fails the
  // same way at the dead centres (measured on the full factorial: 4 of 192 cases not ok
  // with reuse, none with a fresh Jacobian). Not with switching none: difference quotients
  // across the printed law's jump make a fresh Jacobian worse than a reused one (the hard
  // case law_pinkus_sternlicht_no_events, tests/test_stress_hard_cases.cpp).
  // Joint coordinates: a fresh Jacobian every kJointJacobianSteps steps, a new iteration
  // matrix every step (integration_plan.hpp).
  if (plan.formulation == Formulation::partitioned || (sol.projection && sol.switching == Switching::events))
    is.jacobian_steps = 1;
  else if (plan.formulation == Formulation::joint)
    is.jacobian_steps = kJointJacobianSteps;
  return plan;
}

}  // namespace lub::detail
