// The slow-flow strategy: where shooting from the transient found no orbit, the transient's
// slow flow followed by projective steps (steady/slow_manifold.hpp) to where the journal
// ends up; Newton–Picard, then shooting, where it stops near an orbit; the cycles where it
// got to measured.
#include <algorithm>
#include <cmath>
#include <map>

#include "lub/steady/drift_law.hpp"
#include "run/steady_strategies.hpp"
#include "run/verdict.hpp"

namespace lub::detail {

namespace {

/// The way the slow flow went: why shooting from the transient found no orbit, the last
/// Newton's failure where the flow stopped, the flow's last leg, cycles and periods in all.
struct SlowFlowWay {
  std::string shooting, newton;
  steady::SlowManifoldResult flow;
  double cycles = 0.0;
  long long maps = 0;
  bool run_budget = false;    ///< the last leg was cut short by simulation.max_periods, not slow_periods
  bool newton_tried = false;  ///< a Newton where the flow stopped found no orbit
  /// Every leg's points, at their cycles after the transient (the drift law's samples)
  std::vector<double> trail_cycles;
  std::vector<Eigen::VectorXd> trail;
  /// How far off its cycle count may be, relatively: each jump's error is held to this
  /// share of the jump (SlowManifoldOptions::jump_relative), an error in when it gets there
  double cycles_relative_error = 0.0;
  double first_cycle = 0.0;  ///< the crank cycles before the flow (its start's time over the period)
};

enum class SlowNewton {
  ended,        ///< an orbit, or a verdict of its own (budget, measurement): the case ends
  none,         ///< no orbit there (or one not located): follow the flow on
  near_wall,    ///< not tried: near the wall only a flow that has stopped counts
  unavailable,  ///< the flow's state could not be measured: stop following
};

SlowNewton newton_where_flow_stops(SteadyContext& cx, Chart& chart, const StartState& from,
                                   const std::vector<double>& winding, SlowFlowWay& way, SlowFlowEvidence& ev) {
  const SteadyTuning& t = cx.tuning;
  SteadyCycle& steady = cx.res.steady;
  StartState at = from;
  // Where the flow's state cannot be had or integrated, Newton is not run, and says why.
  if (!chart.expand(from.t, way.flow.z.data(), at.qv)) {
    way.newton = "not run: the flow's state lies outside the coordinates' chart";
    return SlowNewton::unavailable;
  }
  const SegmentResult one = cx.measure(at, 1.0, false, 1);
  if (one.res.status != RunStatus::ok || one.res.cycles.empty()) {
    way.newton = "not run: a cycle from there failed: " + one.res.message;
    return SlowNewton::unavailable;
  }
  // Near the wall an estimate of the distance to an orbit is no evidence that the journal
  // gets there: Newton converges there to "stable" orbits the transient from rest passes
  // on its way into the wall. Only a flow that has stopped is.
  if (way.flow.outcome == steady::SlowManifoldOutcome::near && one.res.cycles.back().max_eps > t.slow_near_wall)
    return SlowNewton::near_wall;
  Chart near(cx.rm, at, cx.sim.shooting_coordinates);
  steady::ShootingOptions options = cx.shooting_options(near, one.res.cycles.back().max_eps);
  options.max_iterations = t.slow_newton_iterations;
  steady.multipliers.clear();
  // Newton–Picard first: where the flow stops, its state is on the slow manifold, whose
  // fast modes settle within a period. Chord steps on the monodromy there, each followed
  // by a period, cost the monodromy's 2 n + 1 periods and two an iteration, where KINSOL
  // takes a fresh difference Jacobian each iteration. Only where they converge does
  // shooting take over from their point (its Newton, the multipliers, the metrics, the
  // error bars).
  StartState start = at;
  {
    std::optional<PeriodMap> period, tight;
    cx.period_maps(period, tight, near, at, winding, 1.0, cx.transient_step_budget());
    const Eigen::VectorXd z0 = near.reduce(at.qv);
    const PeriodAndMonodromy there = period_and_monodromy(*period, *tight, z0, near, options);
    steady::ShootingResult picard;
    if (there.rc == 0 && !there.monodromy.failed) {
      picard = steady::newton_picard(*period, z0, there.monodromy.M - Eigen::MatrixXd::Identity(near.size(), near.size()),
                                     newton_picard_options(options, t.slow_newton_iterations));
    }
    if (period->refused() || tight->refused()) {
      cx.budget.stopped(cx.spent(), "no Newton where the slow flow stops");
      steady.slow_flow_cycles = way.cycles;
      ev.outcome = SlowFlowEvidence::Outcome::newton_refused;
      return SlowNewton::ended;
    }
    if (picard.outcome != steady::ShootingOutcome::converged || !near.expand(at.t, picard.z.data(), start.qv)) {
      const bool period_failed = there.rc != 0 || there.monodromy.failed;
      way.newton = verdict::newton_picard_failure(
          picard, period_failed, period_failed ? (there.rc != 0 ? period->last_failure() : tight->last_failure()) : "");
      way.newton_tried = true;
      return SlowNewton::none;
    }
  }
  ev.orbit = solve_orbit(cx, near, start, winding, cx.transient_step_budget(), options, true, OrbitSeed{});
  const bool unlocated = steady.orbit_error > cx.sim.steady_tolerance || ev.orbit.bars.keeps_moving();
  if (verdict::accepted(ev.orbit) || (!steady.multipliers.empty() && !unlocated) || !cx.budget.note().empty()) {
    // An orbit, or one found but not measured, or the budget spent: its own verdict.
    steady.slow_flow_cycles = way.cycles;
    ev.outcome = SlowFlowEvidence::Outcome::newton;
    return SlowNewton::ended;
  }
  // No orbit, or a fixed point of the map's error (not located, near |μ| = 1): the flow at
  // rtol/10 still moves there, so it goes on.
  way.newton = verdict::orbit_message(ev.orbit);
  way.newton_tried = true;
  steady.multipliers.clear();
  steady.orbit_error = kNaN;
  return SlowNewton::none;
}

/// The evidence with the way the flow went: its cycles and periods, its last leg's outcome,
/// and what Newton said before and where it stopped.
SlowFlowEvidence& take_way(const SlowFlowWay& way, SlowFlowEvidence& ev) {
  ev.cycles = way.cycles;
  ev.periods = way.maps;
  ev.flow = way.flow.outcome;
  ev.shooting = way.shooting;
  ev.newton = way.newton;
  ev.newton_tried = way.newton_tried;
  return ev;
}

/// The metrics, channels, film and drift of the cycles measured where the flow got to.
/// Returns why the drift was not measured (it is then NaN, not the transient's), or "".
std::string take_slow_flow_metrics(SteadyContext& cx, SegmentResult& measured, Chart& chart, const StartState& from,
                                   const SlowFlowWay& way) {
  RunResult& res = cx.res;
  SteadyCycle& steady = res.steady;
  const std::vector<double> h = cycle_min_films(measured.res.cycles);
  // The run's own counts stay.
  const Metrics kept = res.metrics;
  res.metrics = measured.res.metrics;
  res.metrics.cycles_run = kept.cycles_run;
  res.metrics.cycles_to_steady = kept.cycles_to_steady;
  res.metrics.steady = false;
  res.series = std::move(measured.res.series);
  steady.last_cycle_min_film_m = h.back();
  steady.last_cycle_asperity_load_ratio = measured.res.cycles.back().asperity_load_ratio;
  // How it drifts: the film against the flow's state some tenth of its cycles before
  // (consecutive cycles differ by the flow's slow change and a wobble the jumps leave in
  // the modes that decay over tens of cycles, at times larger), on its last leg's trail;
  // where that leg is too short to have such a point (a leg after a Newton where the flow
  // stopped), on all its legs'.
  steady.min_film_drift_m_per_cycle = kNaN;  // the transient's until now
  const auto before_last_tenth = [](const std::vector<double>& c, double end) {
    size_t k = c.size();
    while (k > 0 && c[k - 1] > 0.9 * end) --k;
    return k;
  };
  const std::vector<Eigen::VectorXd>* trail = &way.flow.trail;
  const std::vector<double>* cycles = &way.flow.trail_cycles;
  double end = way.flow.cycles;
  size_t back = before_last_tenth(*cycles, end);
  if (back == 0) {
    trail = &way.trail;
    cycles = &way.trail_cycles;
    end = way.cycles;
    back = before_last_tenth(*cycles, end);
  }
  StartState earlier = from;
  if (back == 0 || !((*cycles)[back - 1] < end)) return "no point of its trail before the last tenth of its cycles";
  if (!chart.expand(from.t, (*trail)[back - 1].data(), earlier.qv))
    return "the mechanism's state at an earlier point of its trail not recovered";
  const SegmentResult then = cx.measure(earlier, 1.0, false, 1);
  if (then.res.status != RunStatus::ok || then.res.cycles.empty())
    return "a cycle from an earlier point of its trail: " +
           (then.res.message.empty() ? std::string("not measured") : then.res.message);
  steady.min_film_drift_m_per_cycle =
      (h.front() - then.res.cycles.back().min_film_thickness_m) / (end - (*cycles)[back - 1]);
  return "";
}

/// How much of the flow's drift a cycle may be its own period map's error [m/cycle]: from
/// `at`, three periods by the flow's map (rtol × tighten_factor) and three by its rtol/100
/// twin; d_k the metric film's eccentricity after k periods, apart, times its clearance.
/// d_k ≈ f + k b: f the error the fast modes forget, b the bias the slow ones keep a
/// period. Near the wall b is the method's (of one sign, not noise), and where it is as
/// large as the drift the flow's direction is the integrator's. The larger of d_1 and the
/// slope (d_3 − d_1)/2 (NaN: not measured).
double drift_error(SteadyContext& cx, const StartState& at) {
  constexpr int kPeriods = 3;
  const double f = cx.tuning.tighten_factor;
  const SegmentResult a = cx.measure(at, f, false, kPeriods);
  if (a.res.status != RunStatus::ok || a.res.cycles.size() < kPeriods) return kNaN;
  const SegmentResult b = cx.measure(at, f * cx.tuning.tight_factor, false, kPeriods);
  if (b.res.status != RunStatus::ok || b.res.cycles.size() < kPeriods) return kNaN;
  auto apart = [&](int k) {
    const CycleMetrics& x = a.res.cycles[static_cast<size_t>(k)];
    const CycleMetrics& y = b.res.cycles[static_cast<size_t>(k)];
    return Eigen::Vector2d(x.end_eccentricity_x - y.end_eccentricity_x, x.end_eccentricity_y - y.end_eccentricity_y);
  };
  const double c = cx.scene.joints[cx.scene.metrics.joint].bearing.clearance_m();
  const Eigen::Vector2d d1 = apart(0), d3 = apart(kPeriods - 1);
  return c * std::max(d1.norm(), (d3 - d1).norm() / (kPeriods - 1));
}

/// The film's drift law along the flow (steady/drift_law.hpp), where it nears the wall:
/// the film one cycle on from points of the flow's trail, a period each. First up to
/// kLawPoints evenly spaced in the trail's index (its jumps grow, so roughly evenly in the
/// logarithm of the cycles) over the whole flow; then as many over the stretch from the
/// last of them whose film is above kNearEnd × the last film (the law is the wall's, not
/// the transient's). Then the cycles until the film crosses the safe film.
void fit_flow_drift_law(SteadyContext& cx, Chart& chart, const StartState& from, const SlowFlowWay& way,
                        SlowFlowEvidence& ev) {
  constexpr size_t kLawPoints = 12;
  constexpr double kNearEnd = 2.0;
  SteadyCycle& steady = cx.res.steady;
  const size_t n = way.trail.size();
  if (n < 6) {
    ev.no_law = "fewer than 6 points along the flow";
    return;
  }
  std::map<size_t, double> film;  // by the trail's index
  auto sample = [&](size_t lo, size_t hi) {
    const size_t count = std::min(kLawPoints, hi - lo + 1);
    for (size_t k = 0; k < count; ++k) {
      const size_t i = lo + (k * (hi - lo)) / (count - 1);
      if (film.count(i)) continue;
      StartState at = from;
      double h = kNaN;
      // The law is no part of the verdict: where the run's budget has no period left for a
      // point, it is skipped, and no budget note is left.
      if (cx.budget.left(cx.spent()) >= 1 && chart.expand(from.t, way.trail[i].data(), at.qv)) {
        const SegmentResult one = cx.measure(at, 1.0, false, 1);
        if (one.res.status == RunStatus::ok && !one.res.cycles.empty()) h = one.res.cycles.back().min_film_thickness_m;
      }
      film[i] = h;
    }
  };
  // The first point (two periods into the flow) still carries the transient's wobble.
  sample(1, n - 1);
  const double last = film.rbegin()->second;
  if (!std::isfinite(last)) {
    ev.no_law = "the film where the flow stopped was not measured";
    return;
  }
  size_t lo = 1;
  for (const auto& [i, h] : film)
    if (h > kNearEnd * last) lo = i;
  sample(lo, n - 1);
  std::vector<double> cycles, films;
  for (const auto& [i, h] : film) {
    if (i < lo || !std::isfinite(h)) continue;
    cycles.push_back(way.trail_cycles[i]);
    films.push_back(h);
  }
  const steady::DriftLaw law = steady::fit_drift_law(cycles, films);
  if (!law.known) {
    ev.no_law = law.why;
    return;
  }
  steady.drift_exponent = law.exponent;
  steady.drift_exponent_error = 2.0 * std::sqrt(law.covariance(1, 1));
  ev.law_film_low = law.film_low_m;
  ev.law_film_high = law.film_high_m;
  // The drift's relative error: its period map's own a cycle, and the flow's cycle count's.
  const double drift = steady.min_film_drift_m_per_cycle, error = steady.min_film_drift_error_m_per_cycle;
  const double map_error = std::isfinite(error) ? std::abs(error / drift) : 0.0;
  const steady::DriftCrossing to_safe = steady::cycles_to_film(law, films.back(), cx.res.metrics.safe_film_thickness_m,
                                                               std::hypot(map_error, way.cycles_relative_error));
  ev.safe_beyond_reach = to_safe.beyond_reach;
  if (std::isfinite(to_safe.cycles)) {
    // The flow's own cycles carry its cycle count's error (2σ, as ΔN's).
    steady.safe_film_cycle = way.first_cycle + cycles.back() + to_safe.cycles;
    steady.safe_film_cycle_error = std::hypot(to_safe.error, 2.0 * way.cycles_relative_error * cycles.back());
  }
}

/// Where the flow got to: measured, and what it says (or, off any slow manifold, the case
/// as shooting left it: `before`).
void report_slow_flow(SteadyContext& cx, const RunResult& before, Chart& chart, const StartState& from,
                      const SlowFlowWay& way, const PeriodMap& period, SlowFlowEvidence& ev) {
  using Outcome = SlowFlowEvidence::Outcome;
  RunResult& res = cx.res;
  const steady::SlowManifoldResult& flow = way.flow;
  res.steady.slow_flow_cycles = way.cycles;
  StartState at = from;
  SegmentResult measured;
  if (flow.outcome != steady::SlowManifoldOutcome::failed && chart.expand(from.t, flow.z.data(), at.qv))
    measured = cx.measure(at, 1.0, true, cx.sim.metric_cycles + 1);  // one more: each metric cycle's periodicity known
  const bool have = measured.res.status == RunStatus::ok && !measured.res.cycles.empty();
  if (have && !(measured.res.metrics.periodicity <= cx.tuning.slow_periodicity)) {
    // Its own cycles where the flow got to are far from repeating: that state is on no slow
    // manifold, and the flow says nothing. The case's account as shooting left it (its
    // label and message untouched since), with what the flow cost.
    const long long periods = res.steady.periods_integrated;
    const SolverStats stats = res.stats;
    res = before;
    res.steady.periods_integrated = periods;
    res.stats = stats;
    ev.outcome = Outcome::off_manifold;
    ev.periodicity = measured.res.metrics.periodicity;
    return;
  }
  // Where the flow got to, its own cycles collapse the film: the film fails there.
  const bool collapses = flow.outcome != steady::SlowManifoldOutcome::failed &&
                         (measured.res.status == RunStatus::film_collapse ||
                          measured.res.status == RunStatus::solver_failure);
  // Stopped by simulation.max_periods (the user's budget, not the stage's own): refused.
  const bool refused = flow.outcome == steady::SlowManifoldOutcome::refused ||
                       (flow.outcome == steady::SlowManifoldOutcome::budget && way.run_budget) ||
                       !cx.budget.note().empty();
  if (collapses || (!refused && flow.outcome == steady::SlowManifoldOutcome::failed)) {
    ev.outcome = Outcome::film_fails;
    ev.failure = collapses ? measured.res.message : period.last_failure();
  } else if (refused) {
    cx.budget.stopped(cx.spent(), "the slow flow stopped after about " + std::to_string(std::lround(way.cycles)) +
                                      " cycles");
    ev.outcome = Outcome::refused;
    return;
  } else {
    ev.outcome = flow.outcome == steady::SlowManifoldOutcome::still ? Outcome::still : Outcome::moving;
  }
  if (!have && ev.outcome != Outcome::film_fails) {
    ev.not_measured = measured.res.message.empty() ? "the mechanism's state there not recovered"
                                                   : measured.res.message;
  }
  if (have) {
    ev.film_at_end = res.steady.last_cycle_min_film_m;
    ev.drift_not_measured = take_slow_flow_metrics(cx, measured, chart, from, way);
    ev.measured = true;
    if (ev.outcome == Outcome::moving && ev.drift_not_measured.empty()) {
      res.steady.min_film_drift_error_m_per_cycle = drift_error(cx, at);
      ev.flow_rtol = cx.scene.solver.rtol * cx.tuning.tighten_factor;
      if (res.steady.min_film_drift_m_per_cycle < 0.0)
        fit_flow_drift_law(cx, chart, from, way, ev);
    }
  }
}

}  // namespace

SlowFlowEvidence follow_slow_flow(SteadyContext& cx) {
  const SteadyTuning& t = cx.tuning;
  SlowFlowEvidence ev;
  if (cx.boundaries.size() < 2) return ev;
  const RunResult before = cx.res;  // the case as shooting left it, should the flow not hold
  const StartState from = cx.end;
  Chart chart(cx.rm, from, cx.sim.shooting_coordinates);
  if (chart.size() == 0) return ev;
  const std::vector<double> winding = cx.transient_winding();
  // The slow flow at rtol × tighten_factor: it creeps by less than the default map's
  // error per period.
  std::optional<PeriodMap> period, tight;
  cx.period_maps(period, tight, chart, from, winding, t.tighten_factor, cx.transient_step_budget());
  steady::SlowManifoldOptions o;
  o.scales = chart.residual_units();
  o.hand_over = 10.0 * cx.sim.steady_tolerance;
  // Near the wall no jump moves the journal by more than half its gap at the transient's
  // end: there the film's forces change over a fraction of the gap, and the printed law's
  // map is not smooth (ε̇ = 0 switches, sliding), so a jump's error estimate can miss a
  // jump that leaves the slow manifold.
  const double max_eps = cx.res.cycles.empty() ? kNaN : cx.res.cycles.back().max_eps;
  if (max_eps > 0.0 && max_eps < 1.0) o.max_jump = std::min(o.max_jump, 0.5 * (1.0 - max_eps));
  // The flow has stopped where it moves by less than the map's own error a period (~10 rtol
  // in the clearance's unit at rtol/10).
  o.still = 100.0 * cx.scene.solver.rtol * t.tighten_factor;
  // Each jump's error at most a share of the jump (SlowManifoldOptions::jump_relative), or
  // the map's own error where the flow barely moves: the error of a jump along the flow is
  // an error in when the journal gets there, and the flow's cycle count is its answer.
  o.jump_tolerance = o.still;
  SlowFlowWay way;
  way.shooting = before.message;
  way.cycles_relative_error = o.jump_relative;
  if (!cx.res.cycles.empty()) {
    const CycleMetrics& last = cx.res.cycles.back();
    way.first_cycle = std::round(from.t / (last.t_end_s - last.t_start_s));
  }
  Eigen::VectorXd z = chart.reduce(from.qv);
  for (int attempt = 0;; ++attempt) {
    way.run_budget = cx.budget.left(cx.spent()) < t.slow_periods - way.maps;
    o.max_maps = std::min<long long>(t.slow_periods - way.maps, cx.budget.left(cx.spent()));
    way.flow = steady::follow_slow_manifold(*period, z, o);
    for (size_t i = 0; i < way.flow.trail.size(); ++i) {
      way.trail_cycles.push_back(way.cycles + way.flow.trail_cycles[i]);
      way.trail.push_back(way.flow.trail[i]);
    }
    way.cycles += way.flow.cycles;
    way.maps += way.flow.maps;
    z = way.flow.z;
    const bool stopped = way.flow.outcome == steady::SlowManifoldOutcome::near ||
                         way.flow.outcome == steady::SlowManifoldOutcome::still;
    if (!stopped) break;
    if (attempt >= t.slow_newton_tries &&
        !(way.flow.outcome == steady::SlowManifoldOutcome::still && way.newton.empty())) {
      // Newton found no orbit where the flow seemed to stop: follow it on, without asking again.
      if (way.flow.outcome == steady::SlowManifoldOutcome::still || o.hand_over == 0.0) break;
      o.hand_over = 0.0;
      continue;
    }
    const SlowNewton tried = newton_where_flow_stops(cx, chart, from, winding, way, ev);
    if (tried == SlowNewton::ended) return take_way(way, ev);
    if (tried == SlowNewton::unavailable) break;
    // Not close enough, or too close to the wall to trust an estimate: follow it further.
    o.hand_over = tried == SlowNewton::near_wall ? 0.0 : o.hand_over / 10.0;
  }
  report_slow_flow(cx, before, chart, from, way, *period, ev);
  return take_way(way, ev);
}

}  // namespace lub::detail
