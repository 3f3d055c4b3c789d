// The transient strategy: cycle after cycle from the scene's initial state, the
// contraction estimate of how far it still is from its limit, whether its film drifts,
// and the period map's word on a stop the estimate calls steady.
#include <algorithm>
#include <cmath>

#include "lub/run/orbit.hpp"
#include "run/steady_strategies.hpp"

namespace lub::detail {

namespace {

std::vector<double> cycle_distances(const std::vector<CycleMetrics>& cycles) {
  std::vector<double> d;
  d.reserve(cycles.size());
  for (const CycleMetrics& c : cycles) d.push_back(c.periodicity);
  return d;
}

/// Relative change of the minimum film thickness from each cycle to the next,
/// |h_k − h_{k−1}| / h_k (−1 for the first cycle or without a film).
std::vector<double> film_changes(const std::vector<CycleMetrics>& cycles) {
  std::vector<double> d(cycles.size(), -1.0);
  for (size_t k = 1; k < cycles.size(); ++k) {
    const double h = cycles[k].min_film_thickness_m, h0 = cycles[k - 1].min_film_thickness_m;
    if (h > 0.0 && h0 > 0.0) d[k] = std::abs(h - h0) / h;
  }
  return d;
}

/// Whether a transient has reached its steady cycle within `tol`: the orbit (distances in
/// clearances) and, where there is a film, the minimum film thickness (relative changes)
/// are both within tol of their limits by the contraction estimate. The second matters
/// near the wall: a journal 1.6e-3 c from it can move 1e-3 c in all and still thin its
/// film four-fold.
struct TransientEstimate {
  steady::ContractionEstimate orbit, film;  ///< film: !known without a film
};
TransientEstimate estimate_transient(const SteadyContext& cx, const std::vector<CycleMetrics>& cs) {
  TransientEstimate e;
  const double floor = cx.orbit_noise_floor();
  e.orbit = steady::estimate_contraction(cycle_distances(cs), cx.tuning.window, floor);
  const std::vector<double> dh = film_changes(cs);
  if (!dh.empty() && dh.back() >= 0.0) {
    // The film's noise floor: the orbit's, relative to the film.
    const double c = cx.scene.min_clearance_m().value_or(1.0);
    e.film = steady::estimate_contraction(dh, cx.tuning.window,
                                          floor * c / std::max(cs.back().min_film_thickness_m, 1e-300));
  }
  return e;
}
bool has_film(const std::vector<CycleMetrics>& cs) { return !cs.empty() && cs.back().min_film_thickness_m > 0.0; }

}  // namespace

std::vector<double> cycle_min_films(const std::vector<CycleMetrics>& cycles) {
  std::vector<double> h;
  h.reserve(cycles.size());
  for (const CycleMetrics& c : cycles) h.push_back(c.min_film_thickness_m);
  return h;
}

bool transient_known(const SteadyContext& cx, const std::vector<CycleMetrics>& cs) {
  return estimate_transient(cx, cs).orbit.known;
}

bool transient_steady(const SteadyContext& cx, const std::vector<CycleMetrics>& cs) {
  if (static_cast<int>(cs.size()) < cx.sim.metric_cycles + 1) return false;
  const TransientEstimate e = estimate_transient(cx, cs);
  const double tol = cx.sim.steady_tolerance;
  return steady::transient_converged(e.orbit, tol) && (!has_film(cs) || steady::transient_converged(e.film, tol));
}

double transient_cycles_left(const SteadyContext& cx, const std::vector<CycleMetrics>& cs) {
  const TransientEstimate e = estimate_transient(cx, cs);
  const double tol = cx.sim.steady_tolerance;
  const double n = steady::cycles_to_converge(e.orbit, tol);
  return has_film(cs) ? std::max(n, steady::cycles_to_converge(e.film, tol)) : n;
}

steady::ContractionEstimate contraction(const SteadyContext& cx) {
  return steady::estimate_contraction(cycle_distances(cx.res.cycles), cx.tuning.window, cx.orbit_noise_floor());
}

TransientLeg run_transient_leg(SteadyContext& cx, int cycles, const CycleStop& stop) {
  RunResult& res = cx.res;
  TransientLeg leg;
  // The first segment starts from the scene's initial state and runs its max_cycles (or
  // duration); a continuation runs `cycles` more from where the last one ended.
  SegmentOptions o;
  o.start = res.cycles.empty() ? nullptr : &cx.end;
  o.cycles = res.cycles.empty() ? 0 : cycles;
  // Continuations keep the cycle count going: the stop rule sees every cycle so far.
  const size_t before = res.cycles.size();
  // A continuation that takes far more steps per cycle than the transient did is crawling
  // (near the wall the printed law's corrector crawls at h ~ 1e-8 s:
  // docs/validation/hard-cases.md): it stops there, and the run keeps what it has.
  if (before > 0)
    o.max_steps = cx.tuning.crawl_factor * res.stats.steps / static_cast<long long>(before) * cycles + 1000;
  bool stopped = false;
  if (stop)
    o.stop_after_cycle = [&, stop](const std::vector<CycleMetrics>& cs) {
      if (before == 0) return stopped = stop(cs);  // the first segment's cycles are all there are
      std::vector<CycleMetrics> all = res.cycles;
      all.insert(all.end(), cs.begin(), cs.end());
      return stopped = stop(all);
    };
  // Within simulation.max_periods: the cycles asked for, or as many as are left.
  const int asked = before == 0 ? cx.sim.max_cycles : cycles;
  const long long left = cx.budget.left(cx.spent());
  if (left <= 0) {
    cx.budget.stopped(cx.spent(), "no more transient cycles");
    return leg;
  }
  if (left < asked && cx.scene.cycle_period_s()) o.cycles = static_cast<int>(left);
  SegmentResult seg = run_segment(cx.rm, o);
  if (before > 0 && seg.res.status == RunStatus::budget_exceeded && o.max_steps > 0 &&
      seg.res.stats.steps >= o.max_steps) {
    accumulate(res.stats, seg.res.stats);
    res.steady.periods_integrated += static_cast<long long>(seg.res.cycles.size());
    return leg;  // crawling: not the user's budget, the run stays ok
  }
  if (before == 0) {
    // The run's account starts as the first segment's result (its status and message).
    const SolverStats keep = res.stats;
    res = std::move(seg.res);
    accumulate(res.stats, keep);
  } else {
    accumulate(res.stats, seg.res.stats);
    res.status = seg.res.status;
    leg.message = std::move(seg.res.message);
    // The continuation's first cycle has no previous one of its own (periodicity −1): the
    // contraction estimate looks at the continuation's cycles only.
    res.cycles.insert(res.cycles.end(), seg.res.cycles.begin(), seg.res.cycles.end());
    // The metrics describe the transient's last cycles: now the continuation's.
    res.metrics = steady_cycle_metrics(cx.scene, res.cycles, static_cast<int>(res.cycles.size()));
    append_series(res.series, seg.res.series, res.cycles, cx.scene.output.last_cycles);
  }
  res.steady.periods_integrated += static_cast<long long>(res.cycles.size() - before);
  // A continuation's first boundary is where the transient ended: already there.
  const size_t skip = before == 0 || seg.boundaries.empty() ? 0 : 1;
  cx.boundaries.insert(cx.boundaries.end(), seg.boundaries.begin() + static_cast<std::ptrdiff_t>(skip),
                       seg.boundaries.end());
  cx.end = seg.end;
  res.steady.transient_cycles = static_cast<int>(res.cycles.size());
  if (left < asked && res.status == RunStatus::ok && !stopped)
    cx.budget.stopped(cx.spent(), "the transient stopped after " + std::to_string(res.cycles.size()) + " cycles");
  leg.ok = res.status == RunStatus::ok;
  return leg;
}

bool transient_drifts(const SteadyContext& cx) {
  // The per-cycle minimum film moved the same way in every cycle of the window, and does
  // not stop inside the clearance: its changes do not contract (ρ >= 1), or, thinning,
  // their geometric sum h ρ/(1 − ρ)·|Δh| reaches the wall. A film that approaches its
  // limit from one side (most transients do) is not drifting.
  const int window = cx.tuning.window;
  const std::vector<double> h = cycle_min_films(cx.res.cycles);
  if (h.size() < static_cast<size_t>(window)) return false;
  int down = 0, up = 0;
  std::vector<double> dh;
  for (size_t i = h.size() - window + 1; i < h.size(); ++i) {
    (h[i] < h[i - 1] ? down : up) += 1;
    dh.push_back(std::abs(h[i] - h[i - 1]));
  }
  if (down != window - 1 && up != window - 1) return false;
  const steady::ContractionEstimate e = steady::estimate_contraction(dh, window, 1e-300);
  if (!e.known || e.rate >= 1.0) return true;
  return down == window - 1 && e.remaining >= h.back();
}

void finish_transient(SteadyContext& cx) {
  SteadyCycle& sc = cx.res.steady;
  const steady::ContractionEstimate est = contraction(cx);
  if (est.known) {
    sc.contraction_rate = est.rate;
    sc.remaining_distance = est.remaining;
  }
  const std::vector<double> h = cycle_min_films(cx.res.cycles);
  if (!h.empty()) sc.last_cycle_min_film_m = h.back();
  if (!cx.res.cycles.empty()) sc.last_cycle_asperity_load_ratio = cx.res.cycles.back().asperity_load_ratio;
  if (h.size() >= 2) sc.min_film_drift_m_per_cycle = steady::trend_per_cycle(h, cx.tuning.window);
}

TransientConfirmation confirm_transient(SteadyContext& cx) {
  // From the last cycle boundary z, P(z) − z at rtol and the monodromy M (central
  // differences at rtol/100, as shooting's) put the orbit at δ = (I − M)⁻¹ (P(z) − z),
  // Newton's step. Confirmed when every multiplier is inside the unit circle and
  // max_i |δ_i| / s_i is within steady_tolerance.
  using Outcome = TransientConfirmation::Outcome;
  SteadyCycle& steady = cx.res.steady;
  TransientConfirmation out;
  if (cx.boundaries.size() < 2) return out;
  const StartState base = cx.boundaries.back();
  Chart chart(cx.rm, base, ShootingCoordinates::independent);
  out.outcome = Outcome::confirmed;
  if (chart.size() == 0) return out;  // everything follows the drivers: periodic from the start
  std::optional<PeriodMap> period_map, tight_map;
  cx.period_maps(period_map, tight_map, chart, base, cx.transient_winding(), 1.0, cx.transient_step_budget());
  PeriodMap& period = *period_map;
  PeriodMap& tight = *tight_map;
  const steady::ShootingOptions options = cx.shooting_options(chart, cx.res.cycles.back().max_eps);
  const Eigen::VectorXd z = chart.reduce(base.qv);
  const PeriodAndMonodromy end = period_and_monodromy(period, tight, z, chart, options);
  if (period.refused() || end.monodromy.refused) {
    cx.budget.stopped(cx.spent(), "the transient's stop not confirmed by the period map");
    out.outcome = Outcome::refused;
    return out;
  }
  if (end.rc != 0 || end.monodromy.failed) {
    out.outcome = Outcome::period_failed;
    out.failure = end.rc != 0 ? period.last_failure() : tight.last_failure();
    return out;
  }
  steady.multipliers = steady::floquet_multipliers(end.monodromy.M);
  steady.orbit_residual = steady::scaled_distance(end.Pz, z, chart.units());
  const Eigen::MatrixXd M_minus_I = end.monodromy.M - Eigen::MatrixXd::Identity(chart.size(), chart.size());
  const Eigen::FullPivLU<Eigen::MatrixXd> newton(M_minus_I);
  const Eigen::VectorXd orbit = z + newton.solve(z - end.Pz);
  out.distance = steady::scaled_distance(orbit, z, chart.units());
  out.tolerance = cx.sim.steady_tolerance;
  steady.remaining_distance = out.distance;
  out.dominant = steady.multipliers.empty() ? 0.0 : std::abs(steady.multipliers.front());
  out.conditioning = orbit_conditioning(steady.multipliers);
  if (out.dominant >= 1.0) {
    out.outcome = Outcome::unstable;
  } else if (!(out.distance <= cx.sim.steady_tolerance)) {
    out.outcome = Outcome::far;
  } else if (out.conditioning > cx.tuning.refine_conditioning) {
    // An ill-conditioned orbit near the end: the map's error at rtol moves it κ-fold. One
    // period at rtol/100 says by how much; a stop it moves by more than steady_tolerance
    // is no evidence (near the wall: a fixed point of the map's error).
    Eigen::VectorXd Pt(chart.size());
    if (tight.apply(z.data(), Pt.data()) != 0) {
      if (tight.refused()) {
        cx.budget.stopped(cx.spent(), "the transient's stop not confirmed by the period map");
        out.outcome = Outcome::refused;
      } else {
        out.outcome = Outcome::period_failed;
        out.failure = tight.last_failure();
      }
      return out;
    }
    out.shift = steady::scaled_distance(z + newton.solve(end.Pz - Pt), z, chart.units());
    if (!(out.shift <= cx.sim.steady_tolerance)) out.outcome = Outcome::ill_posed;
  }
  return out;
}

}  // namespace lub::detail
