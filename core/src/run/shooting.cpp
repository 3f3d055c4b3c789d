// The shooting strategy: Newton on the period map z ↦ P(z) from a start (the transient's
// end, where the slow flow stops, a neighbour's orbit), the Floquet multipliers from the
// monodromy at the orbit found, and the orbit's measurement and error bars.
#include <algorithm>
#include <sstream>
#include <cmath>

#include "lub/run/orbit.hpp"
#include "run/orbit_seed.hpp"
#include "run/steady_strategies.hpp"

namespace lub::detail {

PeriodAndMonodromy period_and_monodromy(PeriodMap& period, PeriodMap& tight, const Eigen::VectorXd& z,
                                        const Chart& chart, const steady::ShootingOptions& options) {
  PeriodAndMonodromy out;
  out.Pz.resize(z.size());
  out.rc = period.apply(z.data(), out.Pz.data());
  if (out.rc == 0)
    out.monodromy = steady::monodromy(
        tight, z, out.Pz, steady::MonodromyOptions{chart.units(), options.step, true, 0, options.map_derivative});
  return out;
}

steady::NewtonPicardOptions newton_picard_options(const steady::ShootingOptions& o, int iterations) {
  steady::NewtonPicardOptions np;
  np.residual_scales = o.residual_units();
  np.tolerance = o.tolerance;
  np.noise_factor = o.noise_factor;
  np.max_iterations = iterations;
  return np;
}

namespace {

/// A second Newton after `first` failed: it, with first's iterations and maps (and `extra`
/// maps spent between them) counted in, if it converged or got closer; else first.
steady::ShootingResult better_of(steady::ShootingResult first, steady::ShootingResult again, long long extra = 0) {
  again.iterations += first.iterations;
  again.maps += first.maps + extra;
  return again.outcome == steady::ShootingOutcome::converged || again.residual < first.residual ? again : first;
}

/// Newton on the period map from z0; if that fails and `accelerate` (the Anderson
/// fallback), Anderson-accelerated periods from z0 and Newton again from where they got to.
steady::ShootingResult find_orbit(const SteadyTuning& t, PeriodMap& period, const Eigen::VectorXd& z0,
                                  const steady::ShootingOptions& options, bool accelerate) {
  steady::ShootingResult found = steady::solve_periodic_orbit(period, z0, options);
  if (found.outcome == steady::ShootingOutcome::converged || found.outcome == steady::ShootingOutcome::refused ||
      !accelerate)
    return found;
  // The orbit may lie far along a slow manifold: Anderson-accelerated periods from the
  // same start (one period a step, following the flow), then Newton again from there.
  steady::AndersonOptions ao;
  ao.residual_scales = options.residual_units();
  ao.max_maps = t.anderson_periods;
  ao.tolerance = t.anderson_hand_over;
  const steady::ShootingResult accelerated = steady::anderson_fixed_point(period, z0, ao);
  if (accelerated.residual < 0 || accelerated.residual >= found.residual) return found;
  steady::ShootingOptions again = options;
  again.initial_jacobian = nullptr;  // z0's, not the accelerated point's
  return better_of(std::move(found), steady::solve_periodic_orbit(period, accelerated.z, again), accelerated.maps);
}

/// How a Newton from a start went before KINSOL: where it was not run, the estimate that
/// said so.
struct StartEstimate {
  double predicted_shift = kNaN;  ///< how far the map's error at rtol moves the orbit [clearances]
  double dominant = kNaN;         ///< |μ|max of the start's monodromy
};

/// How far a residual r of P(z) = z moves the fixed point, to first order J⁻¹ r (J = M − I),
/// in the residual's units: the map's error over a slow direction, magnified by 1/|1 − μ|.
double fixed_point_shift(const Eigen::MatrixXd& J, const Eigen::VectorXd& r, const steady::ShootingOptions& options) {
  const Eigen::VectorXd shift = J.fullPivLu().solve(r);
  return steady::scaled_distance(shift, Eigen::VectorXd::Zero(shift.size()), options.residual_units());
}

/// A Newton stalled at the map's noise, taken as located there (the error bars then measure
/// how far the orbit really is).
void accept_at_noise_floor(steady::ShootingResult& found) {
  found.outcome = steady::ShootingOutcome::converged;
  found.at_noise_floor = true;
  found.message.clear();
}

/// find_orbit from z0, its first Jacobian options.initial_jacobian (a neighbour's
/// monodromy) or, if none, the monodromy at z0 (central differences of `tight`); where
/// that contracts every direction below chord_contraction, Newton–Picard chord steps on
/// it first.
steady::ShootingResult newton_from_start(const SteadyContext& cx, PeriodMap& period, PeriodMap& tight,
                                         const Eigen::VectorXd& z0, steady::ShootingOptions options, bool accelerate,
                                         StartEstimate& estimate) {
  const SteadyTuning& t = cx.tuning;
  // The start's monodromy: a neighbour's (its M − I is options.initial_jacobian), or at
  // the transient's end Newton's first Jacobian ahead of it (the same central differences
  // of the rtol/100 map KINSOL's first setup takes, then a fresh one every iteration).
  Eigen::MatrixXd J0;
  long long start_maps = 0;
  if (!options.initial_jacobian) {
    if (!options.central_jacobian) return find_orbit(t, period, z0, options, accelerate);
    const steady::Monodromy M0 = steady::monodromy(tight, z0, z0, options.monodromy_options(true));
    if (M0.failed) return find_orbit(t, period, z0, options, accelerate);
    J0 = M0.M - Eigen::MatrixXd::Identity(z0.size(), z0.size());
    start_maps = M0.maps;
    options.initial_jacobian = &J0;
    options.chord_iterations = 1;
  }
  const Eigen::MatrixXd& J = *options.initial_jacobian;
  const std::vector<std::complex<double>> mu =
      steady::floquet_multipliers(J + Eigen::MatrixXd::Identity(z0.size(), z0.size()));
  if (!mu.empty() && std::abs(mu.front()) < t.chord_contraction) {
    // A map that contracts every direction strongly changes its Jacobian little between
    // the start and its orbit: chord steps on J, two periods at rtol each, where KINSOL
    // takes a fresh Jacobian every iteration and line searches on the map's noise.
    steady::ShootingResult chords = steady::newton_picard(period, z0, J, newton_picard_options(options, t.chord_iterations));
    chords.maps += start_maps;
    // Stalled at the map's own noise (the printed law's switches), where no Newton at rtol
    // gets further: located to its residual over 1 − |μ|max, accepted within a share of
    // steady_tolerance. The error bars' re-solve measures how far the orbit really is.
    const double located = chords.residual / (1.0 - std::abs(mu.front()));
    if (chords.outcome == steady::ShootingOutcome::not_converged && chords.residual >= 0.0 &&
        located <= t.chord_located * cx.sim.steady_tolerance)
      accept_at_noise_floor(chords);
    if (chords.outcome == steady::ShootingOutcome::converged || chords.outcome == steady::ShootingOutcome::refused)
      return chords;
  }
  if (start_maps > 0 && !accelerate && cx.sim.slow_flow) {
    // A start with no neighbour (the transient's end, where the slow flow stops): how far
    // the map's error at rtol moves its fixed point, to first order (I − M)⁻¹ (P(z0) −
    // P_tight(z0)), two periods. Beyond `unlocatable` × steady_tolerance the orbit Newton
    // would find could not be located, and Newton does not run. Only where the slow flow
    // follows: without it, Newton walking into the wall is the evidence that it drifts.
    Eigen::VectorXd P0(z0.size()), T0(z0.size());
    if (period.apply(z0.data(), P0.data()) == 0 && tight.apply(z0.data(), T0.data()) == 0) {
      estimate.predicted_shift = fixed_point_shift(J, P0 - T0, options);
      start_maps += 2;
      if (estimate.predicted_shift > t.unlocatable * cx.sim.steady_tolerance) {
        steady::ShootingResult out;
        out.skipped = true;
        out.z = z0;
        out.Pz = P0;
        out.residual = steady::scaled_distance(P0, z0, options.residual_units());
        out.maps = start_maps;
        estimate.dominant = std::abs(mu.front());
        return out;
      }
    }
  }
  // KINSOL from the start, J its first Jacobian.
  steady::ShootingResult found = find_orbit(t, period, z0, options, accelerate);
  found.maps += start_maps;
  return found;
}

/// Whether a Newton stalled at the map's noise, from a neighbour's orbit whose monodromy
/// gave its first Jacobian J = M − I, has located the orbit anyway: its residual moves the
/// fixed point by no more than `within` (fixed_point_shift). Marks `found` so if it has.
bool accept_at_noise(steady::ShootingResult& found, const steady::ShootingOptions& options, double below,
                     double within) {
  if (!options.initial_jacobian || found.outcome != steady::ShootingOutcome::not_converged || found.residual < 0.0 ||
      found.residual > below || found.z.size() != found.Pz.size())
    return false;
  if (!(fixed_point_shift(*options.initial_jacobian, found.Pz - found.z, options) <= within)) return false;
  accept_at_noise_floor(found);
  return true;
}

/// The orbit's metrics and channels at chart coordinates z (evidence: measured or why not).
void measure_orbit(SteadyContext& cx, Chart& chart, const StartState& base, const Eigen::VectorXd& z,
                   OrbitEvidence& ev) {
  StartState orbit = base;
  if (!chart.expand(base.t, z.data(), orbit.qv)) {
    ev.outside_chart = true;
    return;
  }
  SegmentResult measured = cx.measure(orbit, 1.0, true);
  if (measured.res.status != RunStatus::ok) {
    ev.measure_failure = measured.res.message;
    return;
  }
  cx.res.metrics = measured.res.metrics;
  cx.res.orbit = std::move(measured.res.series);
  ev.measured = true;
}

/// The orbit's error bars where the scene asks for them (ev.bars). Without them, an
/// ill-conditioned orbit cannot be told from a fixed point of the map's error (near the
/// wall Newton converges to those): not located, saying why. False where the orbit is not
/// accepted for it.
bool take_error_bars(SteadyContext& cx, Chart& chart, const StartState& base, PeriodMap& tight_period,
                     const Eigen::VectorXd& z, const Eigen::MatrixXd& monodromy, const steady::ShootingOptions& options,
                     OrbitEvidence& ev) {
  if (cx.sim.error_bars) {
    ev.bars = orbit_error_bars(cx, chart, base, tight_period, z, monodromy, options);
    return !(ev.bars.outcome == ErrorBarEvidence::Outcome::failed && !ev.bars.budget);
  }
  const double kappa = orbit_conditioning(cx.res.steady.multipliers);
  if (!(kappa > cx.tuning.refine_conditioning)) return true;
  std::ostringstream why;
  why << "simulation.error_bars = false, and an orbit with kappa " << kappa
      << " is located only where it stops moving under refinement";
  ev.bars.outcome = ErrorBarEvidence::Outcome::failed;
  ev.bars.conditioning = kappa;
  ev.bars.failure = why.str();
  return false;
}

}  // namespace

OrbitEvidence solve_orbit(SteadyContext& cx, Chart& chart, const StartState& base, const std::vector<double>& winding,
                          long long budget, steady::ShootingOptions options, bool final, const OrbitSeed& from,
                          bool tighten_stalled) {
  using Outcome = OrbitEvidence::Outcome;
  const SteadyTuning& t = cx.tuning;
  SteadyCycle& steady = cx.res.steady;
  OrbitEvidence ev;
  ev.final = final;
  ev.steady_tolerance = cx.sim.steady_tolerance;
  ev.film_resolution = cx.tuning.film_resolution;
  // The period map at rtol × factor, and at rtol/100 of that: the Newton Jacobians' and
  // the monodromy's central differences (the map's noise at rtol over the difference step
  // would be ~1e-3 in them), and the error bars.
  std::optional<PeriodMap> period, tight_period;
  auto maps_at = [&](double factor) {
    cx.period_maps(period, tight_period, chart, base, winding, factor, budget);
    options.jacobian_map = &*tight_period;
  };
  maps_at(1.0);
  // The fallback (simulation.shooting_fallback) serves a start from the transient only.
  const bool fallback = !from.valid() && cx.sim.shooting_fallback == ShootingFallback::anderson;
  if (!from.valid()) {  // from the transient: a Newton that stops making progress is stopped
    options.stagnation_maps = t.stagnation_maps;
    options.stagnation_floor = t.tighten_below;
  }
  const Eigen::VectorXd z0 = chart.reduce(base.qv);
  StartEstimate estimate;
  steady::ShootingResult found = newton_from_start(cx, *period, *tight_period, z0, options, fallback, estimate);
  ev.predicted_shift = estimate.predicted_shift;
  ev.start_dominant = estimate.dominant;
  ev.unlocatable = t.unlocatable;
  // A single continuation step stalled at the noise: located where the neighbour's
  // monodromy says the residual moves the orbit by little; else tighter periods, below.
  const auto accept_single = [&](steady::ShootingResult& stalled) {
    if (tighten_stalled) accept_at_noise(stalled, options, t.tighten_below, t.chord_located * cx.sim.steady_tolerance);
  };
  accept_single(found);
  if ((!from.valid() || tighten_stalled) && found.outcome != steady::ShootingOutcome::converged &&
      found.outcome != steady::ShootingOutcome::refused && found.residual >= 0 && found.residual <= t.tighten_below &&
      !(estimate.predicted_shift * t.tighten_factor > t.unlocatable * cx.sim.steady_tolerance)) {
    // Stalled at the map's own noise (near |μ| = 1 its fixed point moves by that noise
    // over 1 − |μ|): Newton again on periods at rtol × tighten_factor (a start from the
    // transient, or a continuation's single step).
    maps_at(t.tighten_factor);
    const Eigen::VectorXd z = found.z;
    found = better_of(std::move(found), steady::solve_periodic_orbit(*period, z, options));
    accept_single(found);  // a single step's retry stalled at the tighter map's noise
  }
  steady.newton_iterations += static_cast<int>(found.iterations);
  steady.orbit_residual = found.residual;
  ev.newton = found;
  if (found.outcome != steady::ShootingOutcome::converged) {
    if (found.outcome == steady::ShootingOutcome::refused) {
      // Stopped by simulation.max_periods: Newton was not done, so nothing is concluded.
      std::ostringstream what;
      what << "shooting stopped after " << found.iterations << " Newton iterations (residual " << found.residual
           << ")";
      cx.budget.stopped(cx.spent(), what.str());
      ev.outcome = Outcome::refused;
      return ev;
    }
    ev.period_failure = period->last_failure();
    ev.drifts = found.outcome != steady::ShootingOutcome::left_domain && transient_drifts(cx);
    return ev;
  }
  // Floquet multipliers: the map's own derivative (simulation.monodromy = sensitivities) or
  // central differences at the orbit (error O(h²)). A step of a continuation's path needs
  // only a Jacobian for the next step: forward differences.
  const steady::Monodromy monodromy =
      steady::monodromy(final ? *tight_period : *period, found.z, found.Pz, options.monodromy_options(final));
  if (monodromy.failed) {
    ev.failure = final ? tight_period->last_failure() : period->last_failure();
    ev.outcome = Outcome::multipliers_failed;
    if (monodromy.refused) {
      cx.budget.stopped(cx.spent(), "an orbit found, its multipliers not computed");
      ev.outcome = Outcome::multipliers_refused;
    }
    return ev;
  }
  ev.outcome = Outcome::found;
  double max_eps = from.max_eps;
  double steps_per_period = from.steps_per_period;
  steady.multipliers = steady::floquet_multipliers(monodromy.M);
  ev.dominant = steady.multipliers.empty() ? 0.0 : std::abs(steady.multipliers.front());
  if (final) {
    const long long steps0 = cx.res.stats.steps;
    measure_orbit(cx, chart, base, found.z, ev);
    if (!ev.measured) return ev;
    max_eps = cx.res.metrics.max_eps;
    steps_per_period = static_cast<double>(cx.res.stats.steps - steps0) / std::max(1, cx.sim.metric_cycles);
    if (!take_error_bars(cx, chart, base, *tight_period, found.z, monodromy.M, options, ev)) return ev;
    ev.orbit_error = steady.orbit_error;
    // Located no better than the tolerance a cycle is steady by: near |μ| = 1 a fixed
    // point of the map's error.
    if (ev.orbit_error > ev.steady_tolerance || ev.bars.keeps_moving()) return ev;
  }
  StartState orbit = base;
  if (!chart.expand(base.t, found.z.data(), orbit.qv)) return ev;
  cx.res.orbit_seed = make_seed(cx.rm, chart, orbit, monodromy.M, winding, max_eps, steps_per_period);
  ev.seeded = true;
  return ev;
}

ShootingEvidence shoot_from_transient(SteadyContext& cx) {
  using Outcome = ShootingEvidence::Outcome;
  ShootingEvidence ev;
  if (cx.budget.left(cx.spent()) <= 0) {
    cx.budget.stopped(cx.spent(), "no shooting");
    ev.outcome = Outcome::no_budget;
    return ev;
  }
  // A case that cannot be shot (a rank-deficient constraint Jacobian where shooting would
  // start, KINSOL out of memory) is not converged, with the reason: never an exception
  // out of run_scene.
  try {
    if (cx.boundaries.size() < 2) return ev;  // the transient is shorter than two cycles
    const StartState base = cx.end;
    Chart chart(cx.rm, base, cx.sim.shooting_coordinates);
    if (chart.size() == 0) {
      // Nothing moves but what the drivers move: every state is a function of the crank
      // angle, periodic from the first cycle.
      ev.outcome = Outcome::no_freedom;
      return ev;
    }
    const double max_eps = cx.res.cycles.empty() ? kNaN : cx.res.cycles.back().max_eps;
    ev.orbit = solve_orbit(cx, chart, base, cx.transient_winding(), cx.transient_step_budget(),
                           cx.shooting_options(chart, max_eps), true, OrbitSeed{});
    ev.outcome = Outcome::orbit;
  } catch (const std::exception& e) {
    ev.outcome = Outcome::error;
    ev.error = e.what();
  }
  return ev;
}

}  // namespace lub::detail
