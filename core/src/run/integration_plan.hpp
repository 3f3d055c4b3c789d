// How a scene is integrated (internal to the run stage): the integrator's settings, the
// formulation actually integrated, and the tolerances, each state's absolute tolerance
// derived from its unit where the integrator is set up.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lub/formulation/multibody_system.hpp"
#include "lub/integrators/integrator.hpp"
#include "lub/mechanism/model.hpp"
#include "lub/scene/scene.hpp"

namespace lub::detail {

/// Each state's unit (2 nq, (q, v)): lengths in the smallest clearance (1 mm without a
/// film), angles in that over the body's size, rates in those times the driver's speed.
/// The absolute tolerances are rtol times these; shooting measures residuals in them.
Eigen::VectorXd state_units(const Scene& scene, const Model& m);

/// The tolerances of one segment, in the full state (q, v): rtol, and each component's
/// unit s_i; atol_i = rtol_scene s_i × factor (or solver.atol × factor where the scene
/// gives one number for all).
class Tolerances {
 public:
  Tolerances(const Scene& scene, const Model& m, double factor);
  double rtol() const { return rtol_; }
  /// The scalar reported in the run's statistics (rtol × the smallest clearance, or solver.atol).
  double reported_atol() const { return reported_atol_; }
  /// Absolute tolerances of the integrated state y (the formulation's own coordinates).
  std::vector<double> integrated_atol(const MultibodySystem& sys) const;
  /// The difference quotients' scale of each integrated component: atol_i / rtol, the
  /// magnitude below which the error test is absolute rather than relative (the scale
  /// CVODE's own difference-quotient Jacobian takes from the error weights).
  static std::vector<double> difference_scales(const std::vector<double>& atol, double rtol);

 private:
  double rtol_ = 0.0;
  double reported_atol_ = 0.0;
  std::vector<double> atol_full_;  ///< per component of (q, v)
};

/// Steps a Jacobian serves in joint coordinates (IntegratorSettings::jacobian_steps). The
/// squeeze film's stiff mode turns with the crank (~1.3° a step: Frêne long at rtol 1e-8
/// takes 281 steps a cycle), so a Jacobian three steps old is a few degrees stale while
/// the iteration matrix I − γJ follows every step. Measured with the reuse varied by hand
/// (docs/theory/joint-coordinates.md): a fresh Jacobian every step, every 3 and every 5
/// steps on the printed law's reference case, 20 cycles: 0, 6 and 48 Newton convergence
/// failures in ~18 600 steps; per step (callgrind, 4 cycles) 38.7k → 32.0k instructions
/// (Frêne long), 40.2k → 33.1k (printed law with events); the full factorial with
/// "/solver/formulation": "joint" has 0 solver_failure either way (266 s → 144 s at -np 2).
/// CVODE's own reuse (up to 51 steps) doubled the reference case's steps.
constexpr int kJointJacobianSteps = 3;

struct IntegrationPlan {
  IntegratorSettings settings;  ///< t_stop and atol aside (the run loop sets them)
  Formulation formulation = Formulation::baumgarte;
  bool newton = false;          ///< the method iterates with Newton (uses a Jacobian)
  /// The Newton iteration's Jacobian (none: the method does not iterate with Newton)
  std::optional<JacobianKind> jacobian() const;
};

/// The plan for `scene` on `m` at rtol × `factor`.
IntegrationPlan plan_integration(const Scene& scene, const Model& m, double factor);

}  // namespace lub::detail
