// The error-bar strategy: a steady cycle re-found and re-measured at rtol × tight_factor
// (100 times tighter), each metric's bar the distance between the two (plus, for a
// transient, what it would still change).
#include <algorithm>
#include <limits>
#include <sstream>

#include "lub/run/orbit.hpp"
#include "run/steady_strategies.hpp"

namespace lub::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Error bars that cannot be had at this rtol: their integrations would not be ten times
/// tighter than the run's (SteadyContext::finer). A limit the user set, like a budget: the
/// metrics keep NaN bars and the label stands.
bool no_room(const SteadyContext& cx, ErrorBarEvidence& ev) {
  if (cx.error_bars_have_room()) return false;
  std::ostringstream why;
  why << "solver.rtol = " << cx.scene.solver.rtol << " leaves no room below it (they integrate "
      << 1.0 / cx.tuning.tight_factor << " times tighter, and the finest rtol the integrator reaches is "
      << cx.tuning.finest_rtol << ")";
  ev.outcome = ErrorBarEvidence::Outcome::failed;
  ev.failure = why.str();
  ev.budget = true;
  return true;
}

/// Each steady metric's error bar: |metric − tight metric| (on the circle for an angle),
/// plus `extra` (per metric: a transient's remaining change) on top.
void set_errors(Metrics& m, const Metrics& tight, const Metrics* extra = nullptr) {
  for (const SteadyMetric& sm : steady_metrics())
    m.*sm.error = metric_distance(sm, m.*sm.value, tight.*sm.value) + (extra ? extra->*sm.value : 0.0);
}

/// The orbit at rtol/100 re-solved from z* by Newton–Picard on the monodromy's M − I
/// (chords, then KINSOL from their best iterate where they do not contract).
steady::ShootingResult resolve_tight(const SteadyContext& cx, PeriodMap& tight_period, const Eigen::VectorXd& z,
                                     const Eigen::MatrixXd& M_minus_I, const steady::ShootingOptions& options) {
  const SteadyTuning& t = cx.tuning;
  steady::ShootingOptions tight = options;
  tight.jacobian_map = nullptr;
  tight.initial_jacobian = &M_minus_I;
  tight.max_iterations = t.error_bar_iterations;
  // Its residual tolerance scaled with the map's error, like its rtol: at the loose
  // tolerance z* would pass at once, however far the tight orbit lies.
  tight.tolerance = options.tolerance * t.tight_factor;
  steady::NewtonPicardOptions np = newton_picard_options(tight, t.error_bar_iterations);
  np.relative_tolerance = t.error_bar_accuracy;
  steady::ShootingResult resolved = steady::newton_picard(tight_period, z, M_minus_I, np);
  if (resolved.outcome == steady::ShootingOutcome::not_converged && resolved.residual >= 0.0 &&
      !(resolved.residual <= t.error_bar_stall * resolved.first_residual)) {
    // Chord steps that do not contract (a monodromy too far from the tight map's at its
    // orbit): KINSOL's Newton from their best iterate, with the same M − I first, and the
    // better of the two. Chords that stalled at the tight map's noise well below their
    // first residual have located the orbit as well as the bar needs.
    steady::ShootingResult again = steady::solve_periodic_orbit(tight_period, resolved.z, tight);
    again.iterations += resolved.iterations;
    again.maps += resolved.maps;
    if (again.outcome == steady::ShootingOutcome::converged || again.outcome == steady::ShootingOutcome::refused ||
        (again.residual >= 0.0 && again.residual < resolved.residual))
      resolved = std::move(again);
  }
  return resolved;
}

/// An ill-conditioned orbit's second refinement: re-solved from the rtol/100 orbit
/// (`z_tight`, located at `z_located`) at rtol/1e4, or as fine as the integrator reaches
/// (finest_rtol); sets the evidence's moves and bound. False: the budget refused it.
bool refine(SteadyContext& cx, const PeriodMap& tight_period, const Eigen::VectorXd& z_tight,
            const Eigen::VectorXd& z_located, const Eigen::MatrixXd& M_minus_I,
            const Eigen::FullPivLU<Eigen::MatrixXd>& newton, const steady::ShootingOptions& options,
            ErrorBarEvidence& ev) {
  const SteadyTuning& t = cx.tuning;
  const double tight_rtol = cx.scene.solver.rtol * tight_period.rtol_factor();
  const double factor = std::max(t.tight_factor, t.finest_rtol / tight_rtol);
  PeriodMap finer = tight_period.tighter(std::min(factor, 1.0), t.tight_step_factor);
  steady::ShootingOptions o = options;
  o.tolerance *= t.tight_factor;
  steady::ShootingResult again;
  ev.refine_rtol = tight_rtol * std::min(factor, 1.0);
  if (factor <= 0.5) {
    again = resolve_tight(cx, finer, z_tight, M_minus_I, o);
  } else {
    again.outcome = steady::ShootingOutcome::not_converged;
    std::ostringstream why;
    why << "rtol/100 is already " << tight_rtol << ", the finest the integrator reaches is " << t.finest_rtol;
    again.message = why.str();
  }
  if (again.outcome == steady::ShootingOutcome::refused) return false;
  ev.first_move = cx.res.steady.orbit_error;
  ev.refine_bound = std::max(t.refine_ratio * ev.first_move, t.refine_floor * cx.sim.steady_tolerance);
  if (again.Pz.size() == z_tight.size() && again.residual >= 0.0) {
    const Eigen::VectorXd z_finer = again.z - newton.solve(again.Pz - again.z);
    ev.refined_move = steady::scaled_distance(z_finer, z_located, options.residual_units());
  } else {
    // Not refined (its period failed, or no step taken): not shown to stop moving.
    ev.refined_move = kInf;
    ev.refine_failure = again.message;
    if (!finer.last_failure().empty()) ev.refine_failure += ": " + finer.last_failure();
  }
  return true;
}

}  // namespace

ErrorBarEvidence orbit_error_bars(SteadyContext& cx, Chart& chart, const StartState& base, PeriodMap& tight_period,
                                  const Eigen::VectorXd& z, const Eigen::MatrixXd& monodromy,
                                  const steady::ShootingOptions& options) {
  // Near a multiplier close to 1 the orbit moves by the map's error divided by |1 − μ|,
  // which one Newton step estimates only to first order: the re-solve locates the tight
  // orbit to 1 % of its distance from z*, not to the tight map's noise.
  using Outcome = ErrorBarEvidence::Outcome;
  ErrorBarEvidence ev;
  if (no_room(cx, ev)) {
    // An ill-conditioned orbit is located only once it stops moving under refinement:
    // without room for one, it is not (Newton stalls near the wall at residuals of the
    // film's own drift, which the map resolves at this rtol: not its noise).
    ev.conditioning = orbit_conditioning(cx.res.steady.multipliers);
    if (ev.conditioning > cx.tuning.refine_conditioning) {
      ev.budget = false;
      std::ostringstream why;
      why << "; an orbit with kappa " << ev.conditioning << " is located only where it stops moving under refinement";
      ev.failure += why.str();
    }
    return ev;
  }
  const Eigen::MatrixXd M_minus_I = monodromy - Eigen::MatrixXd::Identity(chart.size(), chart.size());
  const Eigen::FullPivLU<Eigen::MatrixXd> newton(M_minus_I);  // a Newton step: −newton.solve(P(z) − z)
  const steady::ShootingResult resolved = resolve_tight(cx, tight_period, z, M_minus_I, options);
  if (resolved.outcome == steady::ShootingOutcome::refused) {
    cx.budget.stopped(cx.spent(), "no error bars");
    ev.outcome = Outcome::refused;
    return ev;
  }
  Eigen::VectorXd z_tight;
  std::ostringstream msg;
  if (resolved.outcome == steady::ShootingOutcome::converged) {
    z_tight = resolved.z;
  } else if (resolved.outcome == steady::ShootingOutcome::not_converged && resolved.iterations >= 1 &&
             resolved.residual >= 0.0) {
    // Stalled above shooting_tolerance/100 (the tight map's own noise): its best iterate
    // is the closest the re-solve got.
    z_tight = resolved.z;
    msg << "error bars: the orbit at rtol/100 re-solved to a residual of " << resolved.residual << " ("
        << resolved.message << " after " << resolved.iterations << " iterations)";
  } else {
    // Not one step taken: one Newton step, as the first-order estimate.
    Eigen::VectorXd tight_end(chart.size());
    if (tight_period.apply(z.data(), tight_end.data()) != 0) {
      if (tight_period.refused()) {
        cx.budget.stopped(cx.spent(), "no error bars");
        ev.outcome = Outcome::refused;
      } else {
        ev.outcome = Outcome::failed;
        ev.failure = "the period at rtol/100 failed: " + tight_period.last_failure();
      }
      return ev;
    }
    z_tight = z - newton.solve(tight_end - z);
    msg << "error bars from one Newton step at rtol/100 (its re-solve: " << resolved.message << ", residual "
        << resolved.residual << " after " << resolved.iterations << " iterations)";
  }
  ev.note = msg.str();
  // How far the orbit moves: to where one more Newton step from the re-solve's best
  // iterate points (the residual left there over 1 − |μ|, no period more: a re-solve that
  // stalled at once has not moved, and is no evidence).
  Eigen::VectorXd z_located = z_tight;
  if (resolved.Pz.size() == z.size()) z_located = resolved.z - newton.solve(resolved.Pz - resolved.z);
  cx.res.steady.orbit_error = steady::scaled_distance(z_located, z, options.residual_units());
  // An ill-conditioned orbit once more, at rtol/1e4 from the rtol/100 one: an orbit stops
  // moving under refinement, a fixed point of the map's error does not.
  ev.conditioning = orbit_conditioning(cx.res.steady.multipliers);  // the monodromy's, set by shooting
  if (ev.conditioning > cx.tuning.refine_conditioning && !(cx.res.steady.orbit_error > cx.sim.steady_tolerance) &&
      !refine(cx, tight_period, z_tight, z_located, M_minus_I, newton, options, ev)) {
    cx.budget.stopped(cx.spent(), "no error bars");
    ev.outcome = Outcome::refused;
    return ev;
  }
  StartState tight_start = base;
  if (!chart.expand(base.t, z_tight.data(), tight_start.qv)) {
    ev.outcome = Outcome::failed;
    ev.failure = "the orbit at rtol/100 lies outside the coordinates' chart";
    return ev;
  }
  const SegmentResult measured = cx.measure(tight_start, cx.tuning.tight_factor, false);
  if (measured.res.status == RunStatus::ok) {
    set_errors(cx.res.metrics, measured.res.metrics);
    ev.outcome = Outcome::measured;
  } else if (cx.budget.note().empty()) {
    ev.outcome = Outcome::failed;
    ev.failure = "the orbit's measurement at rtol/100 failed (" + measured.res.message + ")";
    ev.budget = measured.res.status == RunStatus::budget_exceeded;
  } else {
    ev.outcome = Outcome::refused;
  }
  return ev;
}

ErrorBarEvidence transient_error_bars(SteadyContext& cx) {
  using Outcome = ErrorBarEvidence::Outcome;
  ErrorBarEvidence ev;
  if (no_room(cx, ev)) return ev;
  RunResult& res = cx.res;
  const int M = cx.sim.metric_cycles;
  const steady::ContractionEstimate est = contraction(cx);
  if (!cx.scene.cycle_period_s() || res.cycles.empty()) return ev;
  // The metric cycles again at rtol/100 from the state they started at, plus what
  // the transient would still change: |Δ per cycle| ρ/(1 − ρ) (unbounded if ρ >= 1).
  // boundaries: the initial state, then each cycle's end.
  const int k = static_cast<int>(cx.boundaries.size());
  const int m = std::min(M, static_cast<int>(res.cycles.size()));
  SegmentResult tight;
  if (k - 1 - m >= 0) tight = cx.measure(cx.boundaries[static_cast<size_t>(k - 1 - m)], cx.tuning.tight_factor, false, m);
  if (tight.res.status == RunStatus::ok && res.cycles.size() >= 2) {
    const CycleMetrics& a = res.cycles[res.cycles.size() - 1];
    const CycleMetrics& b = res.cycles[res.cycles.size() - 2];
    const double r = est.known ? est.rate : kInf;
    const double f = r < 1.0 ? r / (1.0 - r) : kInf;
    auto tail = [&](double d) { return d == 0.0 ? 0.0 : d * f; };
    Metrics extra;
    for (const SteadyMetric& sm : steady_metrics())
      extra.*sm.value = tail(metric_distance(sm, a.*sm.per_cycle, b.*sm.per_cycle));
    set_errors(res.metrics, tight.res.metrics, &extra);
    ev.outcome = Outcome::measured;
  } else if (tight.res.status == RunStatus::ok) {
    set_errors(res.metrics, tight.res.metrics);
    ev.outcome = Outcome::measured;
  } else if (k - 1 - m >= 0 && cx.budget.note().empty()) {
    ev.outcome = Outcome::failed;
    ev.failure = "the metric cycles at rtol/100 failed (" + tight.res.message + ")";
    ev.budget = tight.res.status == RunStatus::budget_exceeded;
  }
  return ev;
}

}  // namespace lub::detail
