// One adapter over SUNDIALS' integrators: the run loop sees steps, dense output and
// statistics, whatever the method. No C++ exception crosses into SUNDIALS: callbacks
// catch and return −1, and the message ends up in error_message().
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "lub/integrators/method.hpp"

namespace lub {

/// y' = f(t, y), with optional root functions and quadratures.
class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual int size() const = 0;
  /// 0: ok; > 0: recoverable (the integrator retries with a smaller step); < 0: fatal.
  virtual int rhs(double t, const double* y, double* ydot) = 0;
  virtual int num_roots() const { return 0; }
  virtual int roots(double /*t*/, const double* /*y*/, double* /*g*/) { return 0; }
  virtual int num_quadratures() const { return 0; }
  virtual int quadrature_rhs(double /*t*/, const double* /*y*/, double* /*qdot*/) { return 0; }
  /// Projection onto the constraint manifold after each step (CVODE BDF): writes the
  /// correction to `corr` and projects the error estimate `err` (may be null).
  virtual int project(double /*t*/, const double* /*y*/, double* /*corr*/, double* /*err*/) { return -1; }

  // The same system as a DAE F(t, Y, Y') = 0 (IDA), Y = (y, algebraic variables): y is what
  // the run loop sees (dense output, roots, quadratures use it alone); the algebraic
  // variables (multipliers) are the integrator's business.
  /// Number of algebraic variables appended to y (0: no DAE form).
  virtual int num_algebraic() const { return 0; }
  /// F(t, Y, Y'), size() + num_algebraic() components. Return codes as for rhs().
  virtual int residual(double /*t*/, const double* /*Y*/, const double* /*Yp*/, double* /*F*/) { return -1; }
  /// Consistent (Y, Y') from the state y at t (the algebraic variables and all derivatives).
  virtual int consistent_state(double /*t*/, const double* /*y*/, double* /*Y*/, double* /*Yp*/) { return -1; }
  /// Absolute tolerances of the algebraic variables, given those of the state.
  virtual void algebraic_tolerances(double /*rtol*/, double /*atol*/, double* /*out*/) const {}
  /// ∂f/∂y at (t, y) (fy = f(t, y)) into J, column-major size() × size(), every entry
  /// written. 0: ok; > 0: recoverable; −1: not provided (the integrator must then use
  /// difference quotients: only ask for it with IntegratorSettings::user_jacobian).
  /// Called from inside the integrator's step: no allocation.
  virtual int jacobian(double /*t*/, const double* /*y*/, const double* /*fy*/, double* /*J*/) { return -1; }
  /// The DAE's iteration matrix ∂F/∂Y + cj ∂F/∂Y' at (t, Y, Y') into J, column-major,
  /// (size() + num_algebraic())², every entry written. Return codes as for jacobian()
  /// (−1: not provided; ask for it with IntegratorSettings::user_jacobian). No allocation.
  virtual int dae_jacobian(double /*t*/, double /*cj*/, const double* /*Y*/, const double* /*Yp*/, double* /*J*/) {
    return -1;
  }
};

/// What an integrator counted (over all its restarts): the counters of a run's
/// SolverStats (lub/run/run.hpp), which adds what the model and the run loop counted.
struct IntegratorStats {
  long long steps = 0;
  long long rhs_evals = 0;          ///< right-hand-side evaluations by the integrator
  long long jacobian_evals = 0;     ///< Jacobian evaluations (BDF with dense Newton)
  long long rhs_evals_jacobian = 0; ///< right-hand sides spent on difference-quotient Jacobians
  long long linear_setups = 0;
  long long error_test_fails = 0;
  long long nonlinear_iters = 0;
  long long nonlinear_conv_fails = 0;
  long long root_evals = 0;
};

/// Adds the counters of `b` to `a` (a run of several integrations; the counters kept
/// across a restart: SUNDIALS resets its own at every reinit).
inline IntegratorStats& operator+=(IntegratorStats& a, const IntegratorStats& b) {
  using S = IntegratorStats;
  for (long long S::*c : {&S::steps, &S::rhs_evals, &S::jacobian_evals, &S::rhs_evals_jacobian, &S::linear_setups,
                          &S::error_test_fails, &S::nonlinear_iters, &S::nonlinear_conv_fails, &S::root_evals})
    a.*c += b.*c;
  return a;
}

struct IntegratorSettings {
  Method method = Method::cvode_bdf;
  double rtol = 1e-6;
  std::vector<double> atol;  ///< per component
  double max_step = 0.0;     ///< 0: none
  double initial_step = 0.0; ///< 0: automatic
  int max_order = 0;         ///< 0: default
  /// Never step past this time (moved on by Integrator::set_stop_time). It also bounds
  /// SUNDIALS' initial-step estimate after every (re)start, so the run loop keeps it at
  /// the next cycle boundary, never at the end of the run: the steps up to any time must
  /// not depend on how long the run is.
  double t_stop = 0.0;
  bool projection = false;   ///< project onto the constraints after each step (cvode_bdf)
  /// Newton methods: the system's jacobian() (cvode_bdf, arkode_dirk) or dae_jacobian()
  /// (ida) instead of SUNDIALS' dense difference quotients.
  bool user_jacobian = false;
  /// Steps a Jacobian serves (cvode_bdf): n >= 1 a fresh one every n steps (and on a
  /// convergence failure) and a new iteration matrix I − γJ every step; 0 CVODE's own
  /// reuse (a Jacobian up to 51 steps, the iteration matrix up to 20).
  int jacobian_steps = 0;
};

enum class StepOutcome { step, root, failure };

class Integrator {
 public:
  virtual ~Integrator() = default;
  /// Takes one internal step (not past t_stop); t receives the time reached.
  virtual StepOutcome step(double& t) = 0;
  /// k-th derivative of the interpolated solution at t within the last step.
  virtual bool dense(double t, int k, double* out) = 0;
  /// Quadratures at the current time.
  virtual void quadratures(double* out) = 0;
  /// The solution at the current time.
  virtual const double* y() const = 0;
  /// Fills the integrator's counters (steps, evaluations, failures) into `s`.
  virtual void statistics(IntegratorStats& s) const = 0;
  /// The steps taken so far (statistics().steps; the run loop's budget asks every step).
  virtual long long steps() const {
    IntegratorStats s;
    statistics(s);
    return s.steps;
  }
  /// SUNDIALS' message after a failure.
  virtual std::string error_message() const = 0;
  /// Forgets the message of a failure the caller recovers from (a restart after it), so a
  /// later failure reports its own.
  virtual void clear_error() = 0;
  /// Which root functions fired at the last StepOutcome::root (±1 by direction, or 0).
  virtual void root_flags(std::vector<int>& flags) = 0;
  /// Only report roots crossing in this direction (−1 decreasing, +1 increasing, 0 both).
  virtual void set_root_directions(const std::vector<int>& dirs) = 0;
  /// Restart from (t, y) after a change of the right-hand side (a mode switch): the
  /// history is discarded, the quadratures keep their values.
  virtual void reinit(double t, const double* y) = 0;
  /// Moves the stop time (ahead of the current time); it holds across reinit().
  virtual void set_stop_time(double t_stop) = 0;
  /// New absolute tolerances of the state (size() entries; the partitioned formulation's
  /// integrated coordinates change at a repartition). Call after reinit().
  virtual void set_abs_tolerances(const std::vector<double>& atol) = 0;
  /// Forward sensitivities S = ∂y(t)/∂y(t0) · S0 of the state to its initial value along the
  /// `ns` columns of S0 (size() × ns, column-major): the variational equation S' = ∂f/∂y S,
  /// its right-hand side a central difference of f along each column, solved with the state
  /// on the state's own steps (left out of the error test, so the steps are those of the
  /// state alone). They carry across reinit() unchanged (a switch of the right-hand side
  /// would need its saltation: the caller knows when). false where the method has none
  /// (only cvode_bdf has them); nothing changes then.
  virtual bool start_sensitivities(int /*ns*/, const double* /*S0*/) { return false; }
  /// The sensitivities at t within the last step (size() × ns); false if none were started
  /// or they were stopped.
  virtual bool sensitivities(double /*t*/, double* /*S*/) { return false; }
  /// Stops integrating them (they no longer apply: a switch of the right-hand side without
  /// its saltation); the state goes on as before.
  virtual void stop_sensitivities() {}
};

std::unique_ptr<Integrator> make_integrator(const IntegratorSettings& settings, OdeSystem& sys,
                                            double t0, const std::vector<double>& y0);

}  // namespace lub
