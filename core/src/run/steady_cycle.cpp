// A run's steady cycle: run_scene strings integration segments
// (segment.hpp) together by simulation.steady:
//  - transient: cycle after cycle, stopped (stop_when_steady) once the contraction
//    estimate says the orbit is within steady_tolerance of its limit, δ ρ/(1 − ρ);
//  - shooting: transient_cycles, then Newton on z = P(z) (P: one crank period, z: the
//    mechanism's independent coordinates and velocities at crank angle 0), the Floquet
//    multipliers from the monodromy at the orbit found, the metrics measured on it;
//  - auto: transient until its contraction rate is known, then shooting when the
//    remaining transient would cost more than shooting does.
// Error bars: the steady cycle re-found and re-measured at a 100× tighter rtol.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "lub/run/run.hpp"
#include "lub/steady/contraction.hpp"
#include "lub/steady/periodic_orbit.hpp"
#include "lub/steady/slow_manifold.hpp"
#include "run/metrics.hpp"
#include "run/orbit_seed.hpp"
#include "run/period_budget.hpp"
#include "run/period_map.hpp"
#include "run/segment.hpp"
#include "run/series_recorder.hpp"

namespace lub {

std::string classification(const RunResult& r) {
  return r.status == RunStatus::ok ? std::string(name_of(r.steady.kind)) : to_string(r.status);
}

namespace {

using detail::Chart;
using detail::PeriodBudget;
using detail::PeriodMap;
using detail::RunModel;
using detail::SegmentOptions;
using detail::SegmentResult;
using detail::StartState;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A periodic orbit was found, stable or not.
bool is_orbit(SteadyClass k) { return k == SteadyClass::periodic || k == SteadyClass::periodic_unstable; }
/// Cycles the contraction estimate and the drift fit look back on: a few turns of a
/// complex dominant pair, few enough to follow a rate that changes as the orbit closes in.
constexpr int kWindow = 10;
/// Difference step of the Newton Jacobians and the monodromy, in each state's unit (1 %
/// of the clearance for the journal). The period map is not smooth below the integration's
/// own noise: two starts 1e-6 c apart take different step sequences, and their ends differ
/// by up to ~1e-6 c at rtol 1e-8 besides the flow's own change. Frêne long at the
/// reference case, dominant multiplier by central differences: step 1e-4: 1.082 (noise),
/// 1e-3: 0.9866, 1e-2: 0.99727, 3e-2: 0.99751 (truncation); the transient's own decay says
/// ≈ 0.998. Newton with 1e-3 forward differences stalled at a residual of 3.5e-9 once in
/// four starts; with 1e-2 it converged in all four.
constexpr double kDifferenceStep = 1e-2;
/// Anderson acceleration (find_orbit): periods at most, and the residual (in the residual's
/// units) at which it hands over to Newton: the map's noise floor at rtol 1e-8 is ~1e-7–1e-6.
constexpr int kAndersonPeriods = 60;
constexpr double kAndersonHandOver = 1e-6;
/// A Newton from the transient that stalls below this residual is at the map's noise: it
/// runs again on periods at rtol × kTightenFactor.
constexpr double kTightenBelow = 1e-4;
constexpr double kTightenFactor = 0.1;
/// Error bars re-integrate at rtol × this.
constexpr double kTightFactor = 0.01;
/// Newton iterations of one continuation step before it counts as failed (and the step is
/// halved): quick convergence takes 1–3 from a neighbour's orbit.
constexpr int kContinuationIterations = 8;
/// Newton iterations of the error bars' re-solve at rtol/100 (from the orbit at rtol, with
/// its monodromy: 1–3 where the map is smooth), the fraction of its first residual it
/// stops at (the tight orbit located to 1 % of its distance from the orbit at rtol), and
/// the fraction below which its chords, stalled at the tight map's noise, are enough (no
/// KINSOL after them).
constexpr int kErrorBarIterations = 6;
constexpr double kErrorBarAccuracy = 1e-2;
constexpr double kErrorBarStall = 0.1;
/// Periods the slow flow's projective steps may spend (follow_slow_flow).
constexpr long long kSlowPeriods = 200;
/// Newton from where the slow flow stops: at most this many times (each further along the
/// flow), of at most this many iterations.
constexpr int kSlowNewtonTries = 1;
constexpr int kSlowNewtonIterations = 10;
/// Beyond this eccentricity ratio Newton starts from where the slow flow stops only if it
/// has stopped (|g| within its map's noise), not where it only seems near an orbit.
constexpr double kSlowNearWall = 1.0 - 1e-3;
/// A transient that contracts this slowly or slower (but contracts) after a Newton from its
/// first cycles found no orbit: its orbit, if it has one, lies along a slow manifold, and
/// the slow flow follows it there (Newton–Picard where it stops) instead of a second
/// Newton from the transient's end. On the full factorial no second Newton from a transient
/// at 0.9 <= ρ < 1 found an orbit (131 tries, 17 948 periods); they found the two unstable
/// ones at ρ 1.013 and 1.05, and the stable one at 0.8999.
constexpr double kSlowContraction = 0.9;
/// Newton where the start's monodromy (the transient end's, or a neighbour's) has |μ|max
/// below this: chord steps on it first (newton_from_start), at most kChordIterations, an
/// orbit located when their residual over 1 − |μ|max is within kChordLocated ×
/// steady_tolerance; KINSOL after them if they stall above that.
constexpr double kChordContraction = 0.5;
constexpr int kChordIterations = 8;
constexpr double kChordLocated = 0.1;
/// With the slow flow on, Newton from the transient (or where the flow stops) does not run
/// where the map's error at rtol would move its orbit, to first order, by more than this ×
/// steady_tolerance (it could not be located: orbit_error); nor its rerun at rtol/10
/// where a tenth of that is still more. On the full factorial the located orbits'
/// estimates are 1e-5–2e-4 c; where orbit_error said "not located" the estimate was
/// 2.5–8 times below it (1.6e-3 for 1.2e-2 c).
constexpr double kUnlocatable = 10.0;
/// Where the slow flow got to, its cycles must repeat to this (clearances; the flow moves
/// by far less a cycle), or the state is on no slow manifold and the flow is not reported.
constexpr double kSlowPeriodicity = 1e-2;

/// The orbit distance between two cycles' phase points is measured in the clearance; below
/// this it is noise (the contraction estimate's floor). The phase points come from the
/// dense output, accurate to about the local error tolerance, rtol × c in the clearance's
/// unit; the cycle-to-cycle distance of a converged printed-law transient plateaus at
/// 7e-7 c at rtol 1e-8 (the interpolant and the restarts at every ε̇ = 0 switch). Below
/// 1e-3 of the steady tolerance a distance is noise for the question asked (1e-6 c a
/// cycle is 1e-3 c in 1000 cycles).
double orbit_noise_floor(const Scene& scene) {
  return std::max(10.0 * scene.solver.rtol, 1e-3 * scene.simulation.steady_tolerance);
}

std::vector<double> cycle_distances(const std::vector<CycleMetrics>& cycles) {
  std::vector<double> d;
  d.reserve(cycles.size());
  for (const CycleMetrics& c : cycles) d.push_back(c.periodicity);
  return d;
}

std::vector<double> cycle_min_films(const std::vector<CycleMetrics>& cycles) {
  std::vector<double> h;
  h.reserve(cycles.size());
  for (const CycleMetrics& c : cycles) h.push_back(c.min_film_thickness_m);
  return h;
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
/// near the wall: a journal 1.6e-3 c from it (the printed law at 50 rpm) can move 1e-3 c
/// in all and still thin its film four-fold.
struct TransientEstimate {
  steady::ContractionEstimate orbit, film;  ///< film: !known without a film
};
TransientEstimate estimate_transient(const Scene& scene, const std::vector<CycleMetrics>& cs) {
  TransientEstimate e;
  const double floor = orbit_noise_floor(scene);
  e.orbit = steady::estimate_contraction(cycle_distances(cs), kWindow, floor);
  const std::vector<double> dh = film_changes(cs);
  if (!dh.empty() && dh.back() >= 0.0) {
    // The film's noise floor: the orbit's, relative to the film.
    const double c = scene.min_clearance_m().value_or(1.0);
    e.film = steady::estimate_contraction(dh, kWindow, floor * c / std::max(cs.back().min_film_thickness_m, 1e-300));
  }
  return e;
}
bool has_film(const std::vector<CycleMetrics>& cs) { return !cs.empty() && cs.back().min_film_thickness_m > 0.0; }

bool transient_steady(const Scene& scene, const std::vector<CycleMetrics>& cs, double tol) {
  if (static_cast<int>(cs.size()) < scene.simulation.metric_cycles + 1) return false;
  const TransientEstimate e = estimate_transient(scene, cs);
  return steady::transient_converged(e.orbit, tol) && (!has_film(cs) || steady::transient_converged(e.film, tol));
}

/// Cycles the transient still needs by both estimates (+inf: unknown or not contracting).
double transient_cycles_left(const Scene& scene, const std::vector<CycleMetrics>& cs, double tol) {
  const TransientEstimate e = estimate_transient(scene, cs);
  const double n = steady::cycles_to_converge(e.orbit, tol);
  return has_film(cs) ? std::max(n, steady::cycles_to_converge(e.film, tol)) : n;
}

/// Each steady metric's error bar: |metric − tight metric| (on the circle for an angle),
/// plus `extra` (per metric: a transient's remaining change) on top.
void set_errors(Metrics& m, const Metrics& tight, const Metrics* extra = nullptr) {
  for (const SteadyMetric& sm : steady_metrics())
    m.*sm.error = metric_distance(sm, m.*sm.value, tight.*sm.value) + (extra ? extra->*sm.value : 0.0);
}

/// A state's period and the monodromy there: P(z) at the map's rtol, and M by central
/// differences of `tight` (its rtol/100 twin, 2 n periods) with steps `step` in each
/// state's unit. `rc`: the period's flag (non-zero: M not computed).
struct PeriodAndMonodromy {
  int rc = 0;
  Eigen::VectorXd Pz;
  steady::Monodromy monodromy;
};
PeriodAndMonodromy period_and_monodromy(PeriodMap& period, PeriodMap& tight, const Eigen::VectorXd& z,
                                        const Chart& chart, double step) {
  PeriodAndMonodromy out;
  out.Pz.resize(z.size());
  out.rc = period.apply(z.data(), out.Pz.data());
  if (out.rc == 0)
    out.monodromy =
        steady::monodromy_by_differences(tight, z, out.Pz, steady::MonodromyOptions{chart.units(), step, true});
  return out;
}

/// Newton–Picard's options for the problem `o` poses (its residual units, tolerance and
/// noise factor), at most `iterations` iterations.
steady::NewtonPicardOptions newton_picard_options(const steady::ShootingOptions& o, int iterations) {
  steady::NewtonPicardOptions np;
  np.residual_scales = o.residual_units();
  np.tolerance = o.tolerance;
  np.noise_factor = o.noise_factor;
  np.max_iterations = iterations;
  return np;
}

class SteadyRun {
 public:
  /// `budget`: the case's max_periods and what the case spent before this run (default:
  /// the scene's, nothing).
  explicit SteadyRun(const Scene& scene) : SteadyRun(scene, PeriodBudget(scene.simulation.max_periods, 0)) {}
  SteadyRun(const Scene& scene, PeriodBudget budget)
      : scene_(scene), sim_(scene.simulation), rm_(scene), budget_(std::move(budget)) {}
  RunResult run();
  /// One step of a continuation: Newton from a neighbour's orbit placed into this scene;
  /// `final`: this is the run's own scene (metrics, error bars). False if it failed.
  bool continue_from(const OrbitSeed& seed, bool final);
  /// Newton iterations of the last solve.
  int last_iterations() const { return last_iterations_; }
  /// The result so far (after continue_from), closed like run()'s.
  RunResult take_result(std::chrono::steady_clock::time_point wall0);

 private:
  const Scene& scene_;
  const SimulationSpec& sim_;
  RunModel rm_;  ///< built once: every segment of the run (transient, periods, measurements) shares it
  RunResult res_;
  std::vector<StartState> boundaries_;  // the transient's cycle boundaries
  StartState end_;                      // where the transient ended
  PeriodBudget budget_;                 // simulation.max_periods: every stage asks it first
  long long spent() const { return res_.steady.periods_integrated; }
  /// simulation.max_cycles below kMinSteadyCycles: the transient alone, and why.
  void transient_only();

  /// The transient: from the scene's initial state over its max_cycles, or `cycles` more
  /// from where it ended, stopped early by `stop`; appends cycles, series, boundaries.
  /// False if the run did not end ok.
  bool transient(int cycles, std::function<bool(const std::vector<CycleMetrics>&)> stop);
  steady::ContractionEstimate contraction() const {
    return steady::estimate_contraction(cycle_distances(res_.cycles), kWindow, orbit_noise_floor(scene_));
  }
  void finish_transient();
  /// Error bars of a transient's metrics: its metric cycles again at rtol/100 from the
  /// state they started at, plus |Δ per cycle| ρ/(1 − ρ), what it would still change.
  void transient_error_bars();
  void shoot();
  void shoot_from_transient();
  /// Shooting found no orbit from the transient's end: its slow flow followed by
  /// projective steps (steady/slow_manifold.hpp) to where the journal ends up, then Newton
  /// from there where it stops near an orbit.
  void follow_slow_flow();
  /// The way the slow flow went: why shooting from the transient found no orbit, the last
  /// Newton's verdict where the flow stopped, the flow's last leg, cycles and periods in all.
  struct SlowFlowWay {
    std::string shooting, newton;
    steady::SlowManifoldResult flow;
    double cycles;
    long long maps;
    bool run_budget = false;  ///< the last leg was cut short by simulation.max_periods, not kSlowPeriods
  };
  enum class SlowNewton {
    verdict,      ///< an orbit, or a verdict of its own (budget, measurement): the case ends
    none,         ///< no orbit there (or one not located): follow the flow on
    near_wall,    ///< not tried: within 1e-3 c of the wall only a flow that has stopped counts
    unavailable,  ///< the flow's state could not be measured: stop following
  };
  SlowNewton newton_where_flow_stops(Chart& chart, const StartState& from, const std::vector<double>& winding,
                                     SlowFlowWay& way);
  /// The case where the flow got to: drifting (still moving, or the film failing on the
  /// way), not_converged (stopped with no orbit), or as shooting left it (`before`) where
  /// the flow's state is on no slow manifold.
  void report_slow_flow(const RunResult& before, Chart& chart, const StartState& from, const SlowFlowWay& way,
                        const PeriodMap& period);
  /// The metrics, channels, film and drift of the cycles measured where the flow got to.
  void take_slow_flow_metrics(SegmentResult& measured, Chart& chart, const StartState& from,
                              const steady::SlowManifoldResult& flow);
  /// Newton on the period map from `base`, then the monodromy and the multipliers; if
  /// `final`, the classification, the metrics and error bars on the orbit. Sets the
  /// orbit's seed. False if no orbit was found (the message says why).
  /// `from`: the orbit Newton started from (a continuation's), whose ε_max and steps per
  /// period a path step's seed keeps (only the final step measures its own).
  bool solve_orbit(Chart& chart, const StartState& base, const std::vector<double>& winding, long long budget,
                   steady::ShootingOptions options, bool final, const OrbitSeed& from);
  int last_iterations_ = 0;
  /// Newton on the period map from z0; if that fails and `accelerate` (the Anderson
  /// fallback), Anderson-accelerated periods from z0 and Newton again from where they got to.
  steady::ShootingResult find_orbit(PeriodMap& period, const Eigen::VectorXd& z0, const steady::ShootingOptions& options,
                                    bool accelerate);
  /// find_orbit from z0, its first Jacobian options.initial_jacobian (a neighbour's
  /// monodromy) or, if none, the monodromy at z0 (central differences of `tight`); where
  /// that contracts every direction below kChordContraction, Newton–Picard chord steps on
  /// it first. `predicted_shift`: how far the map's error at rtol moves the orbit from z0
  /// (clearances; NaN where not estimated).
  steady::ShootingResult newton_from_start(PeriodMap& period, PeriodMap& tight, const Eigen::VectorXd& z0,
                                           steady::ShootingOptions options, bool accelerate, double& predicted_shift);
  /// Shooting's options from a cycle whose largest eccentricity ratio is `max_eps` (NaN:
  /// unknown): difference and Newton steps within the gap.
  steady::ShootingOptions shooting_options(const Chart& chart, double max_eps) const;
  /// Shooting found no orbit: drifting or not converged, and why.
  void shooting_failed(const steady::ShootingResult& found, const PeriodMap& period);
  /// The metrics and channels of the orbit at chart coordinates z; false if it fails.
  bool measure_orbit(Chart& chart, const StartState& base, const Eigen::VectorXd& z);
  /// Error bars: the orbit re-solved at rtol/100 (Newton from z*, chord iterations on the
  /// monodromy's M − I) and measured there.
  void orbit_error_bars(Chart& chart, const StartState& base, PeriodMap& tight_period, const Eigen::VectorXd& z,
                        const Eigen::MatrixXd& monodromy, const steady::ShootingOptions& options);
  /// The error bars could not be measured (`why`, a solver's message): the case says so.
  /// An orbit whose accuracy is unknown is no steady result: a periodic label becomes
  /// not_converged, except where a budget the user set stopped the measurement
  /// (`budget`: solver.max_steps or max_wall_time_s; simulation.max_periods says so
  /// itself), which keeps the orbit with NaN error bars, as the budget's docs say.
  void error_bars_failed(const std::string& why, bool budget);
  bool transient_drifts() const;
  /// The period map at rtol × factor and its twin at rtol × factor/100 (differences, error
  /// bars), from `base`, within `steps` integrator steps a period (10 × that for the
  /// tight one) and the run's budget of periods.
  void period_maps(std::optional<PeriodMap>& period, std::optional<PeriodMap>& tight, Chart& chart,
                   const StartState& base, const std::vector<double>& winding, double factor, long long steps);
  /// How much each coordinate advances over a period, from the transient's last two boundaries.
  std::vector<double> transient_winding() const {
    return detail::winding_per_period(rm_.model, boundaries_[boundaries_.size() - 2], boundaries_.back());
  }
  /// A period map's step budget from the transient: 20 times its steps per cycle (its first
  /// cycles, from rest, included).
  long long transient_step_budget() const {
    return 20 * res_.stats.steps / std::max<long long>(1, static_cast<long long>(res_.cycles.size())) + 1000;
  }
  /// The period map's word on a transient its contraction estimate calls steady: from the
  /// last cycle boundary z, P(z) − z at rtol and the monodromy M (central differences at
  /// rtol/100, as shooting's) put the orbit at δ = (I − M)⁻¹ (P(z) − z), Newton's step.
  /// Confirmed when every multiplier is inside the unit circle and max_i |δ_i| / s_i is
  /// within steady_tolerance. Sets the multipliers, orbit_residual and remaining_distance
  /// (the map's δ); false, the message saying why, if not confirmed.
  bool confirm_transient();
  /// simulation.steady = transient: cycle after cycle up to max_cycles, or until the
  /// period map confirms the contraction estimate's stop (stop_when_steady).
  void run_transient();
  /// A transient that says steady (`converged`): periodic if the period map confirms it
  /// (or, `confirm` false, by the estimate alone), otherwise drifting or not converged.
  void classify_transient(bool converged, bool confirm);
  /// The metric cycles (or `cycles`) from a state (rtol × factor): their metrics and channels.
  SegmentResult measure(const StartState& s, double factor, bool series, int cycles = 0);
};

bool SteadyRun::transient(int cycles, std::function<bool(const std::vector<CycleMetrics>&)> stop) {
  // The first segment starts from the scene's initial state and runs its max_cycles (or
  // duration); a continuation runs `cycles` more from where the last one ended.
  SegmentOptions o;
  o.start = res_.cycles.empty() ? nullptr : &end_;
  o.cycles = res_.cycles.empty() ? 0 : cycles;
  // Continuations keep the cycle count going: the stop rule sees every cycle so far.
  const size_t before = res_.cycles.size();
  // A continuation that takes far more steps per cycle than the transient did is crawling
  // (near the wall the printed law's corrector crawls at h ~ 1e-8 s: docs/validation/hard-cases.md): it stops there,
  // and the run keeps what it has.
  if (before > 0)
    o.max_steps = 20 * res_.stats.steps / static_cast<long long>(before) * cycles + 1000;
  bool stopped = false;
  if (stop)
    o.stop_after_cycle = [&, stop](const std::vector<CycleMetrics>& cs) {
      if (before == 0) return stopped = stop(cs);  // the first segment's cycles are all there are
      std::vector<CycleMetrics> all = res_.cycles;
      all.insert(all.end(), cs.begin(), cs.end());
      return stopped = stop(all);
    };
  // Within simulation.max_periods: the cycles asked for, or as many as are left.
  const int asked = before == 0 ? sim_.max_cycles : cycles;
  const long long left = budget_.left(spent());
  if (left <= 0) {
    budget_.stopped(spent(), "no more transient cycles");
    return false;
  }
  if (left < asked && scene_.cycle_period_s()) o.cycles = static_cast<int>(left);
  SegmentResult seg = detail::run_segment(rm_, o);
  if (before > 0 && seg.res.status == RunStatus::budget_exceeded && o.max_steps > 0 &&
      seg.res.stats.steps >= o.max_steps) {
    detail::accumulate(res_.stats, seg.res.stats);
    res_.steady.periods_integrated += static_cast<long long>(seg.res.cycles.size());
    return false;  // crawling: not the user's budget, the run stays ok
  }
  if (before == 0) {
    const SolverStats keep = res_.stats;
    res_ = std::move(seg.res);
    detail::accumulate(res_.stats, keep);
  } else {
    detail::accumulate(res_.stats, seg.res.stats);
    res_.status = seg.res.status;
    res_.message = seg.res.message;
    // The continuation's first cycle has no previous one of its own (periodicity −1): the
    // contraction estimate looks at the continuation's cycles only.
    res_.cycles.insert(res_.cycles.end(), seg.res.cycles.begin(), seg.res.cycles.end());
    // The metrics describe the transient's last cycles: now the continuation's.
    res_.metrics = detail::steady_cycle_metrics(scene_, res_.cycles, static_cast<int>(res_.cycles.size()));
    detail::append_series(res_.series, seg.res.series, res_.cycles, scene_.output.last_cycles);
  }
  res_.steady.periods_integrated += static_cast<long long>(res_.cycles.size() - before);
  // A continuation's first boundary is where the transient ended: already there.
  const size_t skip = before == 0 || seg.boundaries.empty() ? 0 : 1;
  boundaries_.insert(boundaries_.end(), seg.boundaries.begin() + static_cast<std::ptrdiff_t>(skip),
                     seg.boundaries.end());
  end_ = seg.end;
  res_.steady.transient_cycles = static_cast<int>(res_.cycles.size());
  if (left < asked && res_.status == RunStatus::ok && !stopped)
    budget_.stopped(spent(), "the transient stopped after " + std::to_string(res_.cycles.size()) + " cycles");
  return res_.status == RunStatus::ok;
}

bool SteadyRun::transient_drifts() const {
  // The per-cycle minimum film moved the same way in every cycle of the window, and does
  // not stop inside the clearance: its changes do not contract (ρ >= 1), or, thinning,
  // their geometric sum h ρ/(1 − ρ)·|Δh| reaches the wall. A film that approaches its
  // limit from one side (most transients do) is not drifting.
  const std::vector<double> h = cycle_min_films(res_.cycles);
  if (h.size() < static_cast<size_t>(kWindow)) return false;
  int down = 0, up = 0;
  std::vector<double> dh;
  for (size_t i = h.size() - kWindow + 1; i < h.size(); ++i) {
    (h[i] < h[i - 1] ? down : up) += 1;
    dh.push_back(std::abs(h[i] - h[i - 1]));
  }
  if (down != kWindow - 1 && up != kWindow - 1) return false;
  const steady::ContractionEstimate e = steady::estimate_contraction(dh, kWindow, 1e-300);
  if (!e.known || e.rate >= 1.0) return true;
  return down == kWindow - 1 && e.remaining >= h.back();
}

SegmentResult SteadyRun::measure(const StartState& s, double factor, bool series, int cycles) {
  SegmentOptions o;
  o.start = &s;
  o.cycles = cycles > 0 ? cycles : sim_.metric_cycles;
  if (!budget_.allows(o.cycles, spent(), factor == 1.0 ? "the orbit not measured" : "no error bars")) {
    SegmentResult refused;
    refused.res.status = RunStatus::budget_exceeded;
    refused.res.message = "simulation.max_periods reached";
    return refused;
  }
  o.rtol_factor = factor;
  o.series = series;
  SegmentResult seg = detail::run_segment(rm_, o);
  detail::accumulate(res_.stats, seg.res.stats);
  res_.steady.periods_integrated += o.cycles;
  return seg;
}

void SteadyRun::finish_transient() {
  SteadyCycle& sc = res_.steady;
  const steady::ContractionEstimate est = contraction();
  if (est.known) {
    sc.contraction_rate = est.rate;
    sc.remaining_distance = est.remaining;
  }
  const std::vector<double> h = cycle_min_films(res_.cycles);
  if (!h.empty()) sc.last_cycle_min_film_m = h.back();
  if (h.size() >= 2) sc.min_film_drift_m_per_cycle = steady::trend_per_cycle(h, kWindow);
}

void SteadyRun::shoot() {
  if (budget_.left(spent()) <= 0) {
    res_.steady.kind = SteadyClass::not_converged;
    budget_.stopped(spent(), "no shooting");
    return;
  }
  // A case that cannot be shot (a rank-deficient constraint Jacobian where shooting would
  // start, KINSOL out of memory) is not converged, with the reason: never an exception
  // out of run_scene.
  try {
    shoot_from_transient();
  } catch (const std::exception& e) {
    res_.steady.kind = SteadyClass::not_converged;
    res_.message = std::string("shooting: ") + e.what();
  }
}

steady::ShootingOptions SteadyRun::shooting_options(const Chart& chart, double max_eps) const {
  steady::ShootingOptions options;
  options.scales = chart.units();
  options.residual_scales = chart.residual_units();
  options.tolerance = sim_.shooting_tolerance;
  if (sim_.shooting_fallback == ShootingFallback::anderson) options.difference_retries = 2;
  // The wall chart keeps every iterate and difference step inside the clearance, and
  // its steps are relative changes of the gap.
  if (chart.wall()) {
    options.step = kDifferenceStep;
    return options;
  }
  // Near the wall a step of 1 % of the clearance would put the perturbed journal through
  // it: at most a tenth of the thinnest gap, 1 − ε_max (in clearances), of the cycle
  // shooting starts from.
  const double gap = !(max_eps > 0.0) ? 1.0 : 1.0 - max_eps;
  options.step = std::min(kDifferenceStep, 0.1 * gap);
  // Newton's steps no longer than the gap either (they are measured in the same units).
  options.max_newton_step = std::min(options.max_newton_step, gap);
  return options;
}

void SteadyRun::shooting_failed(const steady::ShootingResult& found, const PeriodMap& period) {
  res_.steady.kind = found.outcome == steady::ShootingOutcome::left_domain || transient_drifts()
                         ? SteadyClass::drifting
                         : SteadyClass::not_converged;
  std::ostringstream msg;
  if (found.outcome == steady::ShootingOutcome::refused) {
    // Stopped by simulation.max_periods: Newton was not done, so nothing is concluded.
    res_.steady.kind = SteadyClass::not_converged;
    msg << "shooting stopped after " << found.iterations << " Newton iterations (residual " << found.residual << ")";
    budget_.stopped(spent(), msg.str());
    res_.message.clear();  // the budget's note says it (take_result)
    return;
  }
  if (found.skipped)
    msg << "no shooting (" << found.message << "; residual " << found.residual << " at the start)";
  else
    msg << "shooting did not converge (" << found.message << ", residual " << found.residual << " after "
        << found.iterations << " Newton iterations)";
  if (!period.last_failure().empty()) msg << "; a period failed: " << period.last_failure();
  res_.message = msg.str();
}

bool SteadyRun::measure_orbit(Chart& chart, const StartState& base, const Eigen::VectorXd& z) {
  StartState orbit = base;
  if (!chart.expand(base.t, z.data(), orbit.qv)) {
    res_.steady.kind = SteadyClass::not_converged;
    return false;
  }
  SegmentResult measured = measure(orbit, 1.0, true);
  if (measured.res.status != RunStatus::ok) {
    res_.steady.kind = SteadyClass::not_converged;
    res_.message = "the periodic orbit's measurement failed: " + measured.res.message;
    return false;
  }
  res_.metrics = measured.res.metrics;
  res_.orbit = std::move(measured.res.series);
  return true;
}

void SteadyRun::orbit_error_bars(Chart& chart, const StartState& base, PeriodMap& tight_period,
                                 const Eigen::VectorXd& z, const Eigen::MatrixXd& monodromy,
                                 const steady::ShootingOptions& options) {
  // The orbit re-solved at rtol/100 from z*, by Newton–Picard on the monodromy's M − I:
  // near a multiplier close to 1 the orbit moves by the map's error divided by 1 − |μ|,
  // which one Newton step estimates only to first order. Located to 1 % of its distance
  // from z* (kErrorBarAccuracy), not to the tight map's noise: KINSOL's line search on that
  // noise spent 26–105 periods at rtol/100 on the printed law's orbits, where these take 3–5.
  const Eigen::MatrixXd M_minus_I = monodromy - Eigen::MatrixXd::Identity(chart.size(), chart.size());
  const Eigen::FullPivLU<Eigen::MatrixXd> newton(M_minus_I);  // a Newton step: −newton.solve(P(z) − z)
  steady::ShootingOptions tight = options;
  tight.jacobian_map = nullptr;
  tight.initial_jacobian = &M_minus_I;
  tight.max_iterations = kErrorBarIterations;
  // Its residual tolerance scaled with the map's error, like its rtol: at the loose
  // tolerance z* would pass at once, however far the tight orbit lies.
  tight.tolerance = options.tolerance * kTightFactor;
  steady::NewtonPicardOptions np = newton_picard_options(tight, kErrorBarIterations);
  np.relative_tolerance = kErrorBarAccuracy;
  steady::ShootingResult resolved = steady::newton_picard(tight_period, z, M_minus_I, np);
  if (resolved.outcome == steady::ShootingOutcome::not_converged && resolved.residual >= 0.0 &&
      !(resolved.residual <= kErrorBarStall * resolved.first_residual)) {
    // Chord steps that do not contract (a monodromy too far from the tight map's at its
    // orbit): KINSOL's Newton from their best iterate, with the same M − I first, and the
    // better of the two. Chords that stalled at the tight map's noise below a tenth of
    // their first residual have located the orbit as well as the bar needs (one more
    // chord step from there, below): KINSOL's line search on that noise spent ~100
    // periods at rtol/100 (the printed law at 0.1 mm, 100 cP, 5000 rpm, rtol 1e-9).
    steady::ShootingResult again = steady::solve_periodic_orbit(tight_period, resolved.z, tight);
    again.iterations += resolved.iterations;
    again.maps += resolved.maps;
    if (again.outcome == steady::ShootingOutcome::converged || again.outcome == steady::ShootingOutcome::refused ||
        (again.residual >= 0.0 && again.residual < resolved.residual))
      resolved = std::move(again);
  }
  if (resolved.outcome == steady::ShootingOutcome::refused) {
    budget_.stopped(spent(), "no error bars");
    return;
  }
  Eigen::VectorXd z_tight;
  std::ostringstream msg;
  if (resolved.outcome == steady::ShootingOutcome::converged) {
    z_tight = resolved.z;
  } else if (resolved.outcome == steady::ShootingOutcome::not_converged && resolved.iterations >= 1 &&
             resolved.residual >= 0.0) {
    // Stalled above shooting_tolerance/100 (the tight map's own noise: 1e-8–1e-7 on the
    // full factorial's orbits): its best iterate is the closest the re-solve got.
    z_tight = resolved.z;
    msg << "error bars: the orbit at rtol/100 re-solved to a residual of " << resolved.residual << " ("
        << resolved.message << " after " << resolved.iterations << " iterations)";
  } else {
    // Not one step taken: one Newton step, as the first-order estimate.
    Eigen::VectorXd tight_end(chart.size());
    if (tight_period.apply(z.data(), tight_end.data()) != 0) {
      if (tight_period.refused())
        budget_.stopped(spent(), "no error bars");
      else
        error_bars_failed("the period at rtol/100 failed: " + tight_period.last_failure(), false);
      return;
    }
    z_tight = z - newton.solve(tight_end - z);
    msg << "error bars from one Newton step at rtol/100 (its re-solve: " << resolved.message << ", residual "
        << resolved.residual << " after " << resolved.iterations << " iterations)";
  }
  if (!msg.str().empty()) res_.message = res_.message.empty() ? msg.str() : res_.message + "; " + msg.str();
  // How far the orbit moves: to where one more Newton step from the re-solve's best
  // iterate points (the residual left there over 1 − |μ|, no period more: a re-solve that
  // stalled at once has not moved, and is no evidence).
  Eigen::VectorXd z_located = z_tight;
  if (resolved.Pz.size() == z.size())
    z_located = resolved.z - newton.solve(resolved.Pz - resolved.z);
  res_.steady.orbit_error = steady::scaled_distance(z_located, z, options.residual_units());
  StartState tight_start = base;
  if (!chart.expand(base.t, z_tight.data(), tight_start.qv)) {
    error_bars_failed("the orbit at rtol/100 lies outside the coordinates' chart", false);
    return;
  }
  const SegmentResult measured = measure(tight_start, kTightFactor, false);
  if (measured.res.status == RunStatus::ok)
    set_errors(res_.metrics, measured.res.metrics);
  else if (budget_.note().empty())
    error_bars_failed("the orbit's measurement at rtol/100 failed (" + measured.res.message + ")",
                      measured.res.status == RunStatus::budget_exceeded);
}

void SteadyRun::error_bars_failed(const std::string& why, bool budget) {
  const std::string msg = "error bars not measured: " + why;
  res_.message = res_.message.empty() ? msg : msg + "; " + res_.message;
  if (!budget && is_orbit(res_.steady.kind))
    res_.steady.kind = SteadyClass::not_converged;
}

void SteadyRun::shoot_from_transient() {
  SteadyCycle& steady = res_.steady;
  if (boundaries_.size() < 2) return;  // the transient is shorter than two cycles
  const StartState base = end_;
  Chart chart(rm_, base, sim_.shooting_coordinates);
  if (chart.size() == 0) {
    // Nothing moves but what the drivers move: every state is a function of the crank
    // angle, periodic from the first cycle (the periodicity column shows what the
    // integration's drift makes of it).
    steady.kind = SteadyClass::periodic;
    return;
  }
  const double max_eps = res_.cycles.empty() ? kNaN : res_.cycles.back().max_eps;
  solve_orbit(chart, base, transient_winding(), transient_step_budget(), shooting_options(chart, max_eps), true,
              OrbitSeed{});
}

void SteadyRun::follow_slow_flow() {
  if (boundaries_.size() < 2) return;
  const RunResult before = res_;  // the case as shooting left it, should the flow not hold
  const StartState from = end_;
  Chart chart(rm_, from, sim_.shooting_coordinates);
  if (chart.size() == 0) return;
  const std::vector<double> winding = transient_winding();
  // The slow flow at rtol/10: it creeps by less than the default map's error per period
  // (Frêne short at 0.1 mm, 100 cP, 2500 rpm: 4.9 µm after 4400 cycles at rtol/10 in 400
  // periods, against 5.6 µm and ~5.2 µm for transients at 1e-9 and 1e-10, and 9 µm at the
  // default 1e-8 after 3000 cycles).
  std::optional<PeriodMap> period, tight;
  period_maps(period, tight, chart, from, winding, kTightenFactor, transient_step_budget());
  steady::SlowManifoldOptions o;
  o.scales = chart.residual_units();
  o.hand_over = 10.0 * sim_.steady_tolerance;
  // Near the wall no jump moves the journal by more than half its gap at the transient's
  // end: there the film's forces change over a fraction of the gap, and the printed law's
  // map is not smooth (ε̇ = 0 switches, sliding), so a jump's error estimate can miss a
  // jump that leaves the slow manifold (at 50 rpm, 200 cP a flow with 0.05 c jumps left a
  // film of 0.11 µm for one of 57 µm that the transient never reaches).
  const double max_eps = res_.cycles.empty() ? kNaN : res_.cycles.back().max_eps;
  if (max_eps > 0.0 && max_eps < 1.0) o.max_jump = std::min(o.max_jump, 0.5 * (1.0 - max_eps));
  // The flow has stopped where it moves by less than the map's own error a period (~10 rtol
  // in the clearance's unit at rtol/10).
  o.still = 100.0 * scene_.solver.rtol * kTightenFactor;
  // Each jump's error at most 5 % of the jump (SlowManifoldOptions::jump_relative), or the
  // map's own error where the flow barely moves: the error of a jump along the flow is an
  // error in when the journal gets there, and the flow's cycle count is its answer. An
  // absolute 0.1 steady_tolerance (1e-4 c) let jumps grow where g is small and the map's
  // noise low: at rtol/10 the flows counted 2.6–4.3 times the cycles of the default's for the
  // same 200 periods, and Frêne short at 0.1 mm, 40 cP, 2500 rpm had 2.13 µm "at cycle
  // 5997" where transients at rtol 1e-9 and 1e-10 have ~2.9 µm. Relative alone: 7.98 µm at
  // cycle 767 (default) and 4.61 µm at 1760 (rtol/10), the transient at 1e-10 8.13 and
  // 4.78 µm there.
  o.jump_tolerance = o.still;
  SlowFlowWay way{before.message, {}, {}, 0.0, 0};
  Eigen::VectorXd z = chart.reduce(from.qv);
  for (int attempt = 0;; ++attempt) {
    way.run_budget = budget_.left(spent()) < kSlowPeriods - way.maps;
    o.max_maps = std::min<long long>(kSlowPeriods - way.maps, budget_.left(spent()));
    way.flow = steady::follow_slow_manifold(*period, z, o);
    way.cycles += way.flow.cycles;
    way.maps += way.flow.maps;
    z = way.flow.z;
    const bool stopped = way.flow.outcome == steady::SlowManifoldOutcome::near ||
                         way.flow.outcome == steady::SlowManifoldOutcome::still;
    if (!stopped) break;
    if (attempt >= kSlowNewtonTries &&
        !(way.flow.outcome == steady::SlowManifoldOutcome::still && way.newton.empty())) {
      // Newton found no orbit where the flow seemed to stop: follow it on, without asking again.
      if (way.flow.outcome == steady::SlowManifoldOutcome::still || o.hand_over == 0.0) break;
      o.hand_over = 0.0;
      continue;
    }
    const SlowNewton tried = newton_where_flow_stops(chart, from, winding, way);
    if (tried == SlowNewton::verdict) return;
    if (tried == SlowNewton::unavailable) break;
    // Not close enough, or too close to the wall to trust an estimate: follow it further.
    o.hand_over = tried == SlowNewton::near_wall ? 0.0 : o.hand_over / 10.0;
  }
  report_slow_flow(before, chart, from, way, *period);
}

SteadyRun::SlowNewton SteadyRun::newton_where_flow_stops(Chart& chart, const StartState& from,
                                                         const std::vector<double>& winding, SlowFlowWay& way) {
  SteadyCycle& steady = res_.steady;
  StartState at = from;
  if (!chart.expand(from.t, way.flow.z.data(), at.qv)) return SlowNewton::unavailable;
  const SegmentResult one = measure(at, 1.0, false, 1);
  if (one.res.status != RunStatus::ok || one.res.cycles.empty()) return SlowNewton::unavailable;
  // Within 1e-3 c of the wall an estimate of the distance to an orbit is no evidence that
  // the journal gets there: Newton converged there to "stable" orbits the transient from
  // rest passes on its way into the wall (Frêne long, 0.5 mm, 400 cP, 50 rpm: an orbit at
  // 31 nm, |μ|max 0.991; the transient reaches eps_limit at cycle 121 at rtol 1e-8). Only a
  // flow that has stopped is.
  if (way.flow.outcome == steady::SlowManifoldOutcome::near && one.res.cycles.back().max_eps > kSlowNearWall)
    return SlowNewton::near_wall;
  Chart near(rm_, at, sim_.shooting_coordinates);
  steady::ShootingOptions options = shooting_options(near, one.res.cycles.back().max_eps);
  options.max_iterations = kSlowNewtonIterations;
  res_.message.clear();
  steady.multipliers.clear();
  // Newton–Picard first: where the flow stops, its state is on the slow manifold, whose
  // fast modes (multipliers ~1e-10) settle within a period. Chord steps on the monodromy
  // there, each followed by a period (steady::newton_picard), cost the monodromy's 2 n + 1
  // periods and two an iteration; KINSOL's Newton, a fresh difference Jacobian each
  // iteration and a rerun at rtol/10, cost ~190 a try on the full factorial and located no
  // orbit. Only where they converge does shooting take over from their point (its Newton
  // there, the multipliers, the metrics, the error bars).
  StartState start = at;
  {
    std::optional<PeriodMap> period, tight;
    period_maps(period, tight, near, at, winding, 1.0, transient_step_budget());
    const Eigen::VectorXd z0 = near.reduce(at.qv);
    const PeriodAndMonodromy there = period_and_monodromy(*period, *tight, z0, near, options.step);
    const int rc = there.rc;
    const steady::Monodromy& m = there.monodromy;
    steady::ShootingResult picard;
    if (rc == 0 && !m.failed) {
      picard = steady::newton_picard(*period, z0, m.M - Eigen::MatrixXd::Identity(near.size(), near.size()),
                                     newton_picard_options(options, kSlowNewtonIterations));
    }
    if (period->refused() || tight->refused()) {
      steady.kind = SteadyClass::not_converged;
      budget_.stopped(spent(), "no Newton where the slow flow stops");
      steady.slow_flow_cycles = way.cycles;
      return SlowNewton::verdict;
    }
    if (picard.outcome != steady::ShootingOutcome::converged || !near.expand(at.t, picard.z.data(), start.qv)) {
      std::ostringstream msg;
      if (rc != 0 || m.failed)
        msg << "Newton-Picard: a period failed: " << (rc != 0 ? period->last_failure() : tight->last_failure());
      else if (picard.outcome == steady::ShootingOutcome::converged)
        msg << "Newton-Picard's orbit lies outside the coordinates' chart";
      else
        msg << picard.message << ", residual " << picard.residual << " after " << picard.iterations << " iterations";
      way.newton = msg.str();
      steady.method = "transient";
      return SlowNewton::none;
    }
  }
  if (solve_orbit(near, start, winding, transient_step_budget(), options, true, OrbitSeed{})) {
    steady.slow_flow_cycles = way.cycles;
    std::ostringstream msg;
    msg << "found from where its slow flow stops, about " << std::lround(way.cycles) << " cycles after the transient ("
        << way.maps << " periods); from the transient: " << way.shooting;
    res_.message = res_.message.empty() ? msg.str() : msg.str() + "; " + res_.message;
    return SlowNewton::verdict;
  }
  const bool unlocated = steady.orbit_error > sim_.steady_tolerance;
  if ((!steady.multipliers.empty() && !unlocated) || !budget_.note().empty()) {
    // An orbit found but not measured, or the budget spent: its own verdict.
    steady.slow_flow_cycles = way.cycles;
    return SlowNewton::verdict;
  }
  // No orbit, or a fixed point of the map's error (not located, near |μ| = 1): the flow at
  // rtol/10 still moves there, so it goes on.
  way.newton = res_.message;
  steady.multipliers.clear();
  steady.orbit_error = kNaN;
  steady.method = "transient";
  return SlowNewton::none;
}

void SteadyRun::report_slow_flow(const RunResult& before, Chart& chart, const StartState& from,
                                 const SlowFlowWay& way, const PeriodMap& period) {
  SteadyCycle& steady = res_.steady;
  const steady::SlowManifoldResult& flow = way.flow;
  steady.slow_flow_cycles = way.cycles;
  const long long n = std::lround(way.cycles);
  StartState at = from;
  SegmentResult measured;
  if (flow.outcome != steady::SlowManifoldOutcome::failed && chart.expand(from.t, flow.z.data(), at.qv))
    measured = measure(at, 1.0, true, sim_.metric_cycles + 1);  // one more: each metric cycle's periodicity known
  const bool have = measured.res.status == RunStatus::ok && !measured.res.cycles.empty();
  if (have && !(measured.res.metrics.periodicity <= kSlowPeriodicity)) {
    // Its own cycles where the flow got to are far from repeating: that state is on no slow
    // manifold, and the flow says nothing (the printed law at 50 rpm, 0.5 mm, 400 cP: two
    // cycles 0.67 c apart, films of 10 nm and 129 µm). The case stays as shooting left it.
    const long long periods = steady.periods_integrated;
    const SolverStats stats = res_.stats;
    std::ostringstream why;
    why << "; its slow flow not followed: where it got to (about " << n << " cycles on), two cycles differ by "
        << measured.res.metrics.periodicity << " clearances, off any slow manifold";
    res_ = before;
    res_.steady.periods_integrated = periods;
    res_.stats = stats;
    res_.message += why.str();
    return;
  }
  // Where the flow got to, its own cycles collapse the film: the film fails there.
  const bool collapses = flow.outcome != steady::SlowManifoldOutcome::failed &&
                         (measured.res.status == RunStatus::film_collapse ||
                          measured.res.status == RunStatus::solver_failure);
  std::ostringstream msg;
  // Stopped by simulation.max_periods (the user's budget, not the stage's own): refused.
  const bool refused = flow.outcome == steady::SlowManifoldOutcome::refused ||
                       (flow.outcome == steady::SlowManifoldOutcome::budget && way.run_budget) ||
                       !budget_.note().empty();
  switch (collapses ? steady::SlowManifoldOutcome::failed
                    : refused ? steady::SlowManifoldOutcome::refused : flow.outcome) {
    case steady::SlowManifoldOutcome::failed:
      steady.kind = SteadyClass::drifting;
      msg << "the film fails: followed along its slow manifold, the journal leaves the clearance about " << n
          << " cycles after the transient (" << (collapses ? measured.res.message : period.last_failure()) << ")";
      break;
    case steady::SlowManifoldOutcome::refused:
      // The budget's note says it (take_result), after why shooting found no orbit.
      steady.kind = SteadyClass::not_converged;
      budget_.stopped(spent(), "the slow flow stopped after about " + std::to_string(n) + " cycles");
      res_.message = way.shooting;
      return;
    case steady::SlowManifoldOutcome::still:
      steady.kind = SteadyClass::not_converged;
      msg << "its slow flow stops within the map's noise about " << n
          << " cycles after the transient, but Newton finds no orbit there (" << way.newton << ")";
      break;
    default:  // its periods spent, still moving
      steady.kind = SteadyClass::drifting;
      msg << "still moving about " << n << " cycles after the transient, followed along its slow manifold";
      break;
  }
  if (have) {
    msg << ": minimum film " << steady.last_cycle_min_film_m << " m at the transient's end";
    take_slow_flow_metrics(measured, chart, from, flow);
    msg << ", " << steady.last_cycle_min_film_m << " m there, changing by " << steady.min_film_drift_m_per_cycle
        << " m a cycle";
  }
  msg << " (" << way.maps << " periods, " << name_of(flow.outcome) << "); from the transient: " << way.shooting;
  res_.message = msg.str();
}

void SteadyRun::take_slow_flow_metrics(SegmentResult& measured, Chart& chart, const StartState& from,
                                       const steady::SlowManifoldResult& flow) {
  SteadyCycle& steady = res_.steady;
  const std::vector<double> h = cycle_min_films(measured.res.cycles);
  // The metrics (and stored channels) of the cycles where the flow got to; the run's own
  // counts stay.
  const Metrics kept = res_.metrics;
  res_.metrics = measured.res.metrics;
  res_.metrics.cycles_run = kept.cycles_run;
  res_.metrics.cycles_to_steady = kept.cycles_to_steady;
  res_.metrics.steady = false;
  res_.series = std::move(measured.res.series);
  steady.method = "slow_flow";
  steady.last_cycle_min_film_m = h.back();
  // How it drifts: the film against the flow's state some tenth of its cycles before
  // (consecutive cycles differ by the flow's slow change and a wobble the jumps leave in
  // the modes that decay over tens of cycles, at times larger).
  size_t back = flow.trail.size();
  while (back > 0 && flow.trail_cycles[back - 1] > 0.9 * flow.cycles) --back;
  StartState earlier = from;
  if (back > 0 && flow.trail_cycles[back - 1] < flow.cycles &&
      chart.expand(from.t, flow.trail[back - 1].data(), earlier.qv)) {
    const SegmentResult then = measure(earlier, 1.0, false, 1);
    if (then.res.status == RunStatus::ok && !then.res.cycles.empty())
      steady.min_film_drift_m_per_cycle = (h.front() - then.res.cycles.back().min_film_thickness_m) /
                                          (flow.cycles - flow.trail_cycles[back - 1]);
  }
}

void SteadyRun::period_maps(std::optional<PeriodMap>& period, std::optional<PeriodMap>& tight, Chart& chart,
                            const StartState& base, const std::vector<double>& winding, double factor,
                            long long steps) {
  period.emplace(rm_, chart, base, winding, factor, res_.stats, res_.steady.periods_integrated);
  period->set_step_budget(steps);
  period->set_period_budget(budget_.run_limit());
  tight.emplace(rm_, chart, base, winding, factor * kTightFactor, res_.stats, res_.steady.periods_integrated);
  tight->set_step_budget(10 * steps);
  tight->set_period_budget(budget_.run_limit());
}

/// A second Newton after `first` failed: it, with first's iterations and maps (and `extra`
/// maps spent between them) counted in, if it converged or got closer; else first.
steady::ShootingResult better_of(steady::ShootingResult first, steady::ShootingResult again, long long extra = 0) {
  again.iterations += first.iterations;
  again.maps += first.maps + extra;
  return again.outcome == steady::ShootingOutcome::converged || again.residual < first.residual ? again : first;
}

steady::ShootingResult SteadyRun::find_orbit(PeriodMap& period, const Eigen::VectorXd& z0,
                                             const steady::ShootingOptions& options, bool accelerate) {
  steady::ShootingResult found = steady::solve_periodic_orbit(period, z0, options);
  if (found.outcome == steady::ShootingOutcome::converged || found.outcome == steady::ShootingOutcome::refused ||
      !accelerate)
    return found;
  // Newton from the transient's end found no orbit: the orbit may lie far along a slow
  // manifold. Anderson-accelerated periods from the same start (one period a step,
  // following the flow), then Newton again from where they got to.
  steady::AndersonOptions ao;
  ao.residual_scales = options.residual_units();
  ao.max_maps = kAndersonPeriods;
  ao.tolerance = kAndersonHandOver;
  const steady::ShootingResult accelerated = steady::anderson_fixed_point(period, z0, ao);
  if (accelerated.residual < 0 || accelerated.residual >= found.residual) return found;
  steady::ShootingOptions again = options;
  again.initial_jacobian = nullptr;  // z0's, not the accelerated point's
  return better_of(std::move(found), steady::solve_periodic_orbit(period, accelerated.z, again), accelerated.maps);
}

steady::ShootingResult SteadyRun::newton_from_start(PeriodMap& period, PeriodMap& tight, const Eigen::VectorXd& z0,
                                                    steady::ShootingOptions options, bool accelerate,
                                                    double& predicted_shift) {
  // The start's monodromy: a neighbour's (its M − I is options.initial_jacobian), or at
  // the transient's end Newton's first Jacobian ahead of it (the same central differences
  // of the rtol/100 map KINSOL's first setup takes, then a fresh one every iteration).
  predicted_shift = kNaN;
  Eigen::MatrixXd J0;
  long long start_maps = 0;
  if (!options.initial_jacobian) {
    if (!options.central_jacobian) return find_orbit(period, z0, options, accelerate);
    const steady::Monodromy M0 = steady::monodromy_by_differences(
        tight, z0, z0, steady::MonodromyOptions{options.scales, options.step, true, options.difference_retries});
    if (M0.failed) return find_orbit(period, z0, options, accelerate);
    J0 = M0.M - Eigen::MatrixXd::Identity(z0.size(), z0.size());
    start_maps = M0.maps;
    options.initial_jacobian = &J0;
    options.chord_iterations = 1;
  }
  const Eigen::MatrixXd& J = *options.initial_jacobian;
  const std::vector<std::complex<double>> mu =
      steady::floquet_multipliers(J + Eigen::MatrixXd::Identity(z0.size(), z0.size()));
  if (!mu.empty() && std::abs(mu.front()) < kChordContraction) {
    // A map that contracts every direction strongly changes its Jacobian little between
    // the start and its orbit: Newton–Picard chord steps on J, two periods at rtol each
    // (the printed law's orbits, |μ|max 0.014–0.47), where KINSOL took a fresh Jacobian
    // every iteration, 2 n periods at rtol/100 each, and line searches on the map's noise.
    steady::ShootingResult chords =
        steady::newton_picard(period, z0, J, newton_picard_options(options, kChordIterations));
    chords.maps += start_maps;
    // Stalled at the map's own noise (the printed law's switches: 1e-6–1e-4 c at rtol
    // 1e-8 on the full factorial's orbits), where no Newton at rtol gets further: located
    // to its residual over 1 − |μ|max, accepted within a tenth of steady_tolerance. The
    // error bars' re-solve at rtol/100 measures how far the orbit really is (orbit_error).
    const double located = chords.residual / (1.0 - std::abs(mu.front()));
    if (chords.outcome == steady::ShootingOutcome::not_converged && chords.residual >= 0.0 &&
        located <= kChordLocated * sim_.steady_tolerance) {
      chords.outcome = steady::ShootingOutcome::converged;
      chords.at_noise_floor = true;
      chords.message.clear();
    }
    if (chords.outcome == steady::ShootingOutcome::converged || chords.outcome == steady::ShootingOutcome::refused)
      return chords;
  }
  if (start_maps > 0 && !accelerate && sim_.slow_flow) {
    // A start with no neighbour (the transient's end, where the slow flow stops): how far
    // the map's error at rtol moves its fixed point, to first order (I − M)⁻¹ (P(z0) −
    // P_tight(z0)), two periods. Near |μ| = 1 the orbit Newton would find at rtol is that
    // far from the true one; beyond kUnlocatable × steady_tolerance it could not be
    // located (orbit_error), and Newton does not run: on the full factorial, in 59 of the
    // 130 cells with no orbit, 12.0k of the 25.0k periods Newton spent there. Only where
    // the slow flow follows a case with no orbit and says where the journal goes: without
    // it, Newton walking into the wall is the evidence that it drifts (with slow_flow
    // false, 22 cells would go from drifting to not_converged).
    Eigen::VectorXd P0(z0.size()), T0(z0.size());
    if (period.apply(z0.data(), P0.data()) == 0 && tight.apply(z0.data(), T0.data()) == 0) {
      const Eigen::VectorXd shift = J.fullPivLu().solve(P0 - T0);
      predicted_shift = steady::scaled_distance(shift, Eigen::VectorXd::Zero(z0.size()), options.residual_units());
      start_maps += 2;
      if (predicted_shift > kUnlocatable * sim_.steady_tolerance) {
        steady::ShootingResult out;
        out.skipped = true;
        out.z = z0;
        out.Pz = P0;
        out.residual = steady::scaled_distance(P0, z0, options.residual_units());
        out.maps = start_maps;
        std::ostringstream msg;
        msg << "the map's error at rtol would move its orbit by " << predicted_shift << " clearances (|mu|max "
            << std::abs(mu.front()) << "), more than " << kUnlocatable << " x steady_tolerance";
        out.message = msg.str();
        return out;
      }
    }
  }
  // KINSOL from the start, J its first Jacobian.
  steady::ShootingResult found = find_orbit(period, z0, options, accelerate);
  found.maps += start_maps;
  return found;
}

bool SteadyRun::solve_orbit(Chart& chart, const StartState& base, const std::vector<double>& winding,
                            long long budget, steady::ShootingOptions options, bool final, const OrbitSeed& from) {
  SteadyCycle& steady = res_.steady;
  // The period map at rtol × factor, and at rtol/100 of that: the Newton Jacobians' and
  // the monodromy's central differences (the map's noise at rtol, ~1e-5 c at 1e-8, over a
  // step of ~1e-2 c would be ~1e-3 in them: Frêne long's |μ|max 0.9973 or 0.9990 with
  // steps 1e-2 and 8.8e-3 at rtol 1e-8, against 0.9966 from the transient's own decay),
  // and the error bars.
  std::optional<PeriodMap> period, tight_period;
  auto maps_at = [&](double factor) {
    period_maps(period, tight_period, chart, base, winding, factor, budget);
    options.jacobian_map = &*tight_period;
  };
  maps_at(1.0);
  // The fallback (simulation.shooting_fallback) serves a start from the transient only.
  const bool fallback = !from.valid() && sim_.shooting_fallback == ShootingFallback::anderson;
  const Eigen::VectorXd z0 = chart.reduce(base.qv);
  double predicted_shift = kNaN;
  steady::ShootingResult found = newton_from_start(*period, *tight_period, z0, options, fallback, predicted_shift);
  if (!from.valid() && found.outcome != steady::ShootingOutcome::converged &&
      found.outcome != steady::ShootingOutcome::refused && found.residual >= 0 && found.residual <= kTightenBelow &&
      !(predicted_shift * kTightenFactor > kUnlocatable * sim_.steady_tolerance)) {
    // Stalled at the map's own noise (near |μ| = 1 its fixed point moves by that noise
    // over 1 − |μ|): Newton again on periods at rtol/10 (a start from the transient; on
    // the full factorial 19 of 52 not-converged cells get an answer, docs/theory/steady-cycles.md).
    maps_at(kTightenFactor);
    const Eigen::VectorXd z = found.z;
    found = better_of(std::move(found), steady::solve_periodic_orbit(*period, z, options));
  }
  steady.newton_iterations += static_cast<int>(found.iterations);
  steady.orbit_residual = found.residual;
  last_iterations_ = static_cast<int>(found.iterations);
  if (found.outcome != steady::ShootingOutcome::converged) {
    shooting_failed(found, *period);
    return false;
  }
  // Floquet multipliers: central differences at the orbit (error O(h²)). A step of a
  // continuation's path needs only a Jacobian for the next step: forward differences.
  const steady::Monodromy monodromy =
      final ? steady::monodromy_by_differences(*tight_period, found.z, found.Pz,
                                               steady::MonodromyOptions{chart.units(), options.step, true, options.difference_retries})
            : steady::monodromy_by_differences(*period, found.z, found.Pz,
                                               steady::MonodromyOptions{chart.units(), options.step, false, options.difference_retries});
  if (monodromy.failed) {
    steady.kind = SteadyClass::not_converged;
    res_.message = "shooting converged, but a perturbed period failed: " +
                   (final ? tight_period->last_failure() : period->last_failure());
    if (monodromy.refused) {
      budget_.stopped(spent(), "an orbit found, its multipliers not computed");
      res_.message.clear();
    }
    return false;
  }
  double max_eps = from.max_eps;
  double steps_per_period = from.steps_per_period;
  steady.multipliers = steady::floquet_multipliers(monodromy.M);
  if (final) {
    const double dominant = steady.multipliers.empty() ? 0.0 : std::abs(steady.multipliers.front());
    steady.kind = dominant < 1.0 ? SteadyClass::periodic : SteadyClass::periodic_unstable;
    steady.method = "shooting";
    const long long steps0 = res_.stats.steps;
    if (!measure_orbit(chart, base, found.z)) return false;
    max_eps = res_.metrics.max_eps;
    steps_per_period = static_cast<double>(res_.stats.steps - steps0) / std::max(1, sim_.metric_cycles);
    if (sim_.error_bars) {
      orbit_error_bars(chart, base, *tight_period, found.z, monodromy.M, options);
      if (steady.kind == SteadyClass::not_converged) return false;
    }
    if (steady.orbit_error > sim_.steady_tolerance) {
      // Located no better than the tolerance a cycle is steady by: near |μ| = 1 a fixed
      // point of the map's error (Frêne short near the wall, |μ|max 0.9999: 5e-3–1e-2 c).
      std::ostringstream msg;
      msg << "the orbit moves by " << steady.orbit_error << " clearances when its periods are integrated 100 times tighter (|mu|max "
          << dominant << "; steady_tolerance " << sim_.steady_tolerance
          << "): not located";
      res_.message = res_.message.empty() ? msg.str() : msg.str() + "; " + res_.message;
      steady.kind = SteadyClass::not_converged;
      return false;
    }
  }
  StartState orbit = base;
  if (!chart.expand(base.t, found.z.data(), orbit.qv)) return final;
  res_.orbit_seed = detail::make_seed(rm_, chart, orbit, monodromy.M, winding, max_eps, steps_per_period);
  return true;
}

bool SteadyRun::continue_from(const OrbitSeed& seed, bool final) {
  try {
    const std::optional<StartState> base = detail::place_seed(rm_, seed);
    if (!base) {
      res_.message = "the neighbour's orbit is of another mechanism";
      return false;
    }
    Chart chart(rm_, *base, sim_.shooting_coordinates);
    if (chart.size() == 0) {
      res_.steady.kind = SteadyClass::periodic;
      return true;
    }
    // Within the neighbour's gap, as from a transient.
    steady::ShootingOptions options = shooting_options(chart, seed.max_eps);
    options.max_iterations = kContinuationIterations;
    Eigen::MatrixXd J0;
    if (const std::optional<Eigen::MatrixXd> M0 = detail::seed_monodromy(seed, chart)) {
      J0 = *M0 - Eigen::MatrixXd::Identity(chart.size(), chart.size());
      options.initial_jacobian = &J0;
    }
    // The neighbour's steps per period, with room for a thinner film's smaller steps.
    const long long budget = static_cast<long long>(50.0 * seed.steps_per_period) + 1000;
    return solve_orbit(chart, *base, seed.winding, budget, options, final, seed);
  } catch (const std::exception& e) {
    res_.steady.kind = SteadyClass::not_converged;
    res_.message = std::string("continuation: ") + e.what();
    return false;
  }
}

bool SteadyRun::confirm_transient() {
  SteadyCycle& steady = res_.steady;
  if (boundaries_.size() < 2) return false;
  const StartState base = boundaries_.back();
  Chart chart(rm_, base, ShootingCoordinates::independent);
  if (chart.size() == 0) return true;  // everything follows the drivers: periodic from the start
  std::optional<PeriodMap> period_map, tight_map;
  period_maps(period_map, tight_map, chart, base, transient_winding(), 1.0, transient_step_budget());
  PeriodMap& period = *period_map;
  PeriodMap& tight = *tight_map;
  const steady::ShootingOptions options = shooting_options(chart, res_.cycles.back().max_eps);
  const Eigen::VectorXd z = chart.reduce(base.qv);
  const PeriodAndMonodromy end = period_and_monodromy(period, tight, z, chart, options.step);
  const int rc = end.rc;
  const Eigen::VectorXd& Pz = end.Pz;
  const steady::Monodromy& monodromy = end.monodromy;
  if (period.refused() || monodromy.refused) {
    budget_.stopped(spent(), "the transient's stop not confirmed by the period map");
    return false;
  }
  if (rc != 0 || monodromy.failed) {
    res_.message = "the transient's stop not confirmed: a period from its end failed: " +
                   (rc != 0 ? period.last_failure() : tight.last_failure());
    return false;
  }
  steady.multipliers = steady::floquet_multipliers(monodromy.M);
  steady.orbit_residual = steady::scaled_distance(Pz, z, chart.units());
  const Eigen::MatrixXd M_minus_I = monodromy.M - Eigen::MatrixXd::Identity(chart.size(), chart.size());
  const Eigen::VectorXd orbit = z + M_minus_I.fullPivLu().solve(z - Pz);
  const double delta = steady::scaled_distance(orbit, z, chart.units());
  steady.remaining_distance = delta;
  const double dominant = steady.multipliers.empty() ? 0.0 : std::abs(steady.multipliers.front());
  std::ostringstream msg;
  msg << "the transient's stop not confirmed by the period map: ";
  if (dominant >= 1.0) {
    msg << "|mu|max = " << dominant << " at its end, not a stable cycle";
  } else if (!(delta <= sim_.steady_tolerance)) {
    msg << "the orbit lies " << delta << " clearances from its end (|mu|max = " << dominant
        << "; steady_tolerance " << sim_.steady_tolerance << ")";
  } else {
    return true;
  }
  res_.message = msg.str();
  return false;
}

void SteadyRun::classify_transient(bool converged, bool confirm) {
  SteadyCycle& steady = res_.steady;
  if (converged && !confirm) {
    // A transient of fixed length (stop_when_steady off) was not asked for its steady cycle:
    // its verdict is the estimate's, and says so.
    steady.kind = SteadyClass::periodic;
    if (res_.message.empty())
      res_.message = "periodic by the contraction estimate alone (a transient of fixed length: stop_when_steady "
                     "or steady = auto asks the period map to confirm it)";
    return;
  }
  if (converged && confirm_transient()) {
    steady.kind = SteadyClass::periodic;
    steady.method = "transient";
    return;
  }
  steady.kind = transient_drifts() ? SteadyClass::drifting : SteadyClass::not_converged;
  if (!converged && res_.message.empty()) {
    std::ostringstream msg;
    msg << "not steady after " << res_.cycles.size() << " cycles by the contraction estimate (rate "
        << steady.contraction_rate << ", distance still to go " << steady.remaining_distance << " clearances)";
    res_.message = msg.str();
  }
}

void SteadyRun::transient_error_bars() {
  const int M = sim_.metric_cycles;
  const steady::ContractionEstimate est = contraction();
  if (scene_.cycle_period_s() && !res_.cycles.empty()) {
    // The metric cycles again at rtol/100 from the state they started at, plus what
    // the transient would still change: |Δ per cycle| ρ/(1 − ρ) (unbounded if ρ >= 1).
    // boundaries_: the initial state, then each cycle's end.
    const int k = static_cast<int>(boundaries_.size());
    const int m = std::min(M, static_cast<int>(res_.cycles.size()));
    SegmentResult tight;
    if (k - 1 - m >= 0) tight = measure(boundaries_[static_cast<size_t>(k - 1 - m)], kTightFactor, false, m);
    if (tight.res.status == RunStatus::ok && res_.cycles.size() >= 2) {
      const CycleMetrics& a = res_.cycles[res_.cycles.size() - 1];
      const CycleMetrics& b = res_.cycles[res_.cycles.size() - 2];
      const double r = est.known ? est.rate : kInf;
      const double f = r < 1.0 ? r / (1.0 - r) : kInf;
      auto tail = [&](double d) { return d == 0.0 ? 0.0 : d * f; };
      Metrics extra;
      for (const SteadyMetric& sm : steady_metrics())
        extra.*sm.value = tail(metric_distance(sm, a.*sm.per_cycle, b.*sm.per_cycle));
      set_errors(res_.metrics, tight.res.metrics, &extra);
    } else if (tight.res.status == RunStatus::ok) {
      set_errors(res_.metrics, tight.res.metrics);
    } else if (k - 1 - m >= 0 && budget_.note().empty()) {
      error_bars_failed("the metric cycles at rtol/100 failed (" + tight.res.message + ")",
                        tight.res.status == RunStatus::budget_exceeded);
    }
  }
}

void SteadyRun::run_transient() {
  const double tol = sim_.steady_tolerance;
  // With stop_when_steady, a stop the period map does not confirm is not the end: on a
  // slow manifold the contraction estimate says steady cycle after cycle (Frêne long,
  // 0.2 mm, 400 cP, 500 rpm: from cycle 1142, its film 1.1 µm still sinking to 0.23 µm).
  // The transient goes on and asks again once it has run as many cycles again (at most
  // log2(max_cycles) confirmations), up to max_cycles.
  size_t ask_from = 0;
  std::function<bool(const std::vector<CycleMetrics>&)> stop;
  if (sim_.stop_when_steady)
    stop = [&](const std::vector<CycleMetrics>& cs) { return cs.size() >= ask_from && transient_steady(scene_, cs, tol); };
  bool ok = transient(0, stop);
  for (;;) {
    finish_transient();
    if (!ok) return;
    const bool converged = transient_steady(scene_, res_.cycles, tol);
    classify_transient(converged, sim_.stop_when_steady);
    const int left = sim_.max_cycles - static_cast<int>(res_.cycles.size());
    if (!sim_.stop_when_steady || !converged || res_.steady.kind == SteadyClass::periodic || left <= 0 ||
        !budget_.note().empty())
      break;
    res_.steady.multipliers.clear();  // the next verdict's, if any
    res_.steady.orbit_residual = kNaN;
    ask_from = 2 * res_.cycles.size();
    ok = transient(left, stop);
  }
  if (sim_.error_bars) transient_error_bars();
}

void SteadyRun::transient_only() {
  // max_cycles cycles and nothing more: a steady stage would cost tens of periods more than
  // the case asked for (shooting the slider-crank from one cycle: 27–311).
  const bool ok = transient(0, nullptr);
  finish_transient();
  if (ok) {
    res_.steady.kind = SteadyClass::not_converged;
    res_.message = "simulation.max_cycles = " + std::to_string(sim_.max_cycles) +
                   ": too short for the steady stage (it needs max_cycles >= " + std::to_string(kMinSteadyCycles) +
                   "); the transient alone";
  }
}

RunResult SteadyRun::run() {
  const auto wall0 = std::chrono::steady_clock::now();
  SteadyCycle& steady = res_.steady;
  const double tol = sim_.steady_tolerance;

  if (sim_.steady != SteadyMethod::transient && sim_.max_cycles < kMinSteadyCycles) {
    transient_only();
  } else if (sim_.steady == SteadyMethod::transient) {
    run_transient();
  } else {
    // shooting / auto: a transient first.
    const int n0 = sim_.transient_cycles;
    std::function<bool(const std::vector<CycleMetrics>&)> stop;
    if (sim_.steady == SteadyMethod::shooting) {
      stop = [n0](const std::vector<CycleMetrics>& cs) { return static_cast<int>(cs.size()) >= n0; };
    } else {
      // auto: go on while the transient will be there sooner than shooting would be
      // (a Newton iteration costs about n + 1 periods, the monodromy 2 n, n ~ 4–8).
      const double shooting_cost = 30.0;
      stop = [&, n0, shooting_cost](const std::vector<CycleMetrics>& cs) {
        if (static_cast<int>(cs.size()) < n0) return false;
        const TransientEstimate e = estimate_transient(scene_, cs);
        if (!e.orbit.known) return false;
        return transient_steady(scene_, cs, tol) || transient_cycles_left(scene_, cs, tol) > shooting_cost;
      };
    }
    bool ok = transient(0, stop);
    if (ok) {
      finish_transient();
      shoot();
      // Shooting found no orbit from there: the transient goes on, up to max_cycles or
      // until its own test says steady (the direct evidence), and shooting tries once more
      // from where it ends, unless it contracts slowly and the slow flow follows
      // (kSlowContraction). A transient that converged is periodic whatever shooting says;
      // one that drifts is drifting.
      const int left = sim_.max_cycles - static_cast<int>(res_.cycles.size());
      const std::string first_newton = res_.message;
      const int first_cycles = static_cast<int>(res_.cycles.size());
      if (!is_orbit(steady.kind) && left > 0 &&
          transient(left, [&](const std::vector<CycleMetrics>& cs) { return transient_steady(scene_, cs, tol); })) {
        finish_transient();
        const bool converged = transient_steady(scene_, res_.cycles, tol);
        const double rate = steady.contraction_rate;
        if (sim_.slow_flow && !converged && rate >= kSlowContraction && rate < 1.0) {
          std::ostringstream msg;
          if (!first_newton.empty()) msg << "from cycle " << first_cycles << ": " << first_newton << "; ";
          msg << "no Newton from cycle " << res_.cycles.size() << " (the transient contracts at rate " << rate
              << ": its orbit, if any, lies along a slow manifold, where the slow flow goes)";
          res_.message = msg.str();
        } else {
          shoot();
        }
        if (!is_orbit(steady.kind)) {
          if (converged) {
            // The transient's own test, confirmed by the period map at its end.
            const std::string shooting = res_.message;
            res_.message.clear();
            classify_transient(true, true);
            if (steady.kind == SteadyClass::periodic) {
              res_.message = "periodic by the transient's contraction estimate, confirmed by the period map; " + shooting;
              if (sim_.error_bars) transient_error_bars();
            } else {
              res_.message = res_.message.empty() ? shooting : res_.message + "; " + shooting;
            }
          } else if (transient_drifts()) {
            steady.kind = SteadyClass::drifting;
          }
        }
      }
      if (res_.status == RunStatus::ok && !is_orbit(steady.kind) && budget_.note().empty() && sim_.slow_flow)
        follow_slow_flow();
      if (res_.status == RunStatus::ok && steady.kind == SteadyClass::drifting && res_.message.empty())
        res_.message = "no periodic orbit inside the clearance";
    } else {
      finish_transient();
    }
  }
  return take_result(wall0);
}

RunResult SteadyRun::take_result(std::chrono::steady_clock::time_point wall0) {
  const SteadyCycle& steady = res_.steady;
  if (!budget_.note().empty())
    res_.message = budget_.note() + (res_.message.empty() ? "" : "; " + res_.message);
  res_.metrics.steady = res_.status == RunStatus::ok && steady.kind == SteadyClass::periodic;
  res_.metrics.cycles_to_steady = res_.metrics.steady ? static_cast<int>(steady.periods_integrated) : -1;
  res_.metrics.cycles_run = static_cast<int>(res_.cycles.size());
  res_.stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return std::move(res_);
}

}  // namespace

namespace detail {

void accumulate(SolverStats& t, const SolverStats& s) {
  static_cast<IntegratorStats&>(t) += s;
  using S = SolverStats;
  for (long long S::*c : {&S::film_law_evals_jacobian, &S::observer_evals, &S::repartitions, &S::mode_switches,
                          &S::model_evals, &S::gravity_evals, &S::film_law_evals})
    t.*c += s.*c;
  t.max_position_drift = std::max(t.max_position_drift, s.max_position_drift);
  t.max_velocity_drift = std::max(t.max_velocity_drift, s.max_velocity_drift);
  if (t.method.empty()) {
    t.method = s.method;
    t.formulation = s.formulation;
    t.jacobian = s.jacobian;
    t.rtol = s.rtol;
    t.atol = s.atol;
    t.final_time_s = s.final_time_s;
  }
}

}  // namespace detail

namespace {
/// The smallest step along a continuation's path before it is given up (five halvings).
constexpr double kMinPathStep = 1.0 / 32.0;
/// A scene's thick-film version: its lubricated joints' viscosity × this (the Sommerfeld
/// number × 16: the journal well inside the clearance, where shooting converges from the
/// transient).
constexpr double kThickFilm = 16.0;

bool found_orbit(const RunResult& r) {
  return r.status == RunStatus::ok && is_orbit(r.steady.kind);
}

/// Adds what `part` cost to `total`.
void add_costs(RunResult& total, const RunResult& part) {
  detail::accumulate(total.stats, part.stats);
  total.steady.periods_integrated += part.steady.periods_integrated;
  total.steady.newton_iterations += part.steady.newton_iterations;
}

/// Whether the case has spent its simulation.max_periods, having integrated `spent`; if
/// so, `why` says so.
bool budget_spent(const Scene& scene, long long spent, std::string& why) {
  if (spent < scene.simulation.max_periods) return false;
  PeriodBudget b(scene.simulation.max_periods, spent);
  b.stopped(0, "no further step");
  why = b.note();
  return true;
}

/// Follows the path from the seed to the scene (λ = 1); the run's result there, or nullopt
/// with `why` and what the tries cost in `spent`. `before`: what the case integrated
/// before the path (its simulation.max_periods bounds both).
std::optional<RunResult> follow_path(const Scene& scene, const ContinuationStart& from, RunResult& spent,
                                     std::string& why, long long before = 0) {
  OrbitSeed seed = from.seed;
  double lambda = 0.0, step = 1.0;
  int steps = 0;
  why = seed.valid() ? "" : "the neighbour has no orbit";
  while (seed.valid() && step >= kMinPathStep) {
    const long long used = before + spent.steady.periods_integrated;
    if (budget_spent(scene, used, why)) break;
    const double next = std::min(1.0, lambda + step);
    const bool final = next >= 1.0;
    const Scene between = final ? Scene{} : from.path(next);
    SteadyRun r(final ? scene : between, PeriodBudget(scene.simulation.max_periods, used));
    const bool ok = r.continue_from(seed, final);
    ++steps;
    const int iterations = r.last_iterations();
    RunResult part = r.take_result(std::chrono::steady_clock::now());
    if (ok && final) {
      add_costs(part, spent);
      part.steady.method = "continuation";
      part.steady.continuation_steps = steps;
      return part;
    }
    add_costs(spent, part);
    if (ok) {
      seed = std::move(part.orbit_seed);
      lambda = next;
      if (iterations <= 2) step *= 2.0;  // quick: a longer step next
    } else {
      step *= 0.5;
      why = part.message;
    }
  }
  std::ostringstream msg;
  msg << "continuation stopped at λ = " << lambda << " after " << steps << " steps (" << why << ")";
  why = msg.str();
  return std::nullopt;
}

RunResult finish_wall(RunResult r, std::chrono::steady_clock::time_point wall0) {
  r.stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  r.metrics.cycles_to_steady = r.metrics.steady ? static_cast<int>(r.steady.periods_integrated) : -1;
  return r;
}

/// simulation.steady = continuation without a neighbour: auto; where it finds no orbit,
/// the thick-film version's orbit continued back to the scene's viscosity. `before`: the
/// periods the case integrated before (a path given up).
RunResult run_alone(const Scene& scene, long long before = 0) {
  const auto wall0 = std::chrono::steady_clock::now();
  const long long limit = scene.simulation.max_periods;
  RunResult own = SteadyRun(scene, PeriodBudget(limit, before)).run();
  if (own.status != RunStatus::ok || found_orbit(own) || scene.simulation.max_cycles < kMinSteadyCycles) return own;
  std::string why;
  if (budget_spent(scene, before + own.steady.periods_integrated, why)) {
    if (own.message.find("simulation.max_periods") == std::string::npos) own.message = why + "; " + own.message;
    return finish_wall(std::move(own), wall0);
  }
  auto thick_version = [&scene](double factor) {
    Scene s = scene;
    for (JointSpec& j : s.joints)
      if (j.type == JointType::lubricated_revolute) j.viscosity_Pa_s *= factor;
    return s;
  };
  const Scene thick = thick_version(kThickFilm);
  const RunResult seeded = SteadyRun(thick, PeriodBudget(limit, before + own.steady.periods_integrated)).run();
  add_costs(own, seeded);
  if (!seeded.orbit_seed.valid()) {
    own.message = "no orbit at 16 × the viscosity either (" + classification(seeded) + "); " + own.message;
    return finish_wall(std::move(own), wall0);
  }
  const ContinuationStart from{seeded.orbit_seed,
                               [&](double lambda) { return thick_version(std::pow(kThickFilm, 1.0 - lambda)); }};
  std::optional<RunResult> r = follow_path(scene, from, own, why, before);
  if (!r) {
    own.message = "from 16 × the viscosity: " + why + "; " + own.message;
    return finish_wall(std::move(own), wall0);
  }
  r->message = "continued from 16 × the viscosity";
  return finish_wall(std::move(*r), wall0);
}

}  // namespace

RunResult run_scene(const Scene& scene) {
  if (scene.simulation.steady == SteadyMethod::continuation) return run_alone(scene);
  SteadyRun r(scene);
  return r.run();
}

RunResult run_scene(const Scene& scene, const ContinuationStart& from) {
  // Too short for a steady stage: the transient alone, whatever the neighbour.
  if (scene.simulation.max_cycles < kMinSteadyCycles) return run_alone(scene);
  const auto wall0 = std::chrono::steady_clock::now();
  RunResult spent;
  std::string why;
  if (std::optional<RunResult> r = follow_path(scene, from, spent, why)) return finish_wall(std::move(*r), wall0);
  // The budget is spent: the path's account is the case's.
  std::string none;
  if (budget_spent(scene, spent.steady.periods_integrated, none)) {
    spent.message = why;
    return finish_wall(std::move(spent), wall0);
  }
  // The path could not be followed: the scene alone.
  RunResult r = run_alone(scene, spent.steady.periods_integrated);
  add_costs(r, spent);
  r.message = why + "; " + r.message;
  return finish_wall(std::move(r), wall0);
}

}  // namespace lub
