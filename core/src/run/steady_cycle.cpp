// A run's steady cycle (README "Steady cycles"): run_scene strings integration segments
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

#include <sstream>

#include "lub/common/constants.hpp"
#include "lub/formulation/multibody_system.hpp"
#include "lub/mechanism/builder.hpp"
#include "lub/run/run.hpp"
#include "lub/steady/contraction.hpp"
#include "lub/steady/periodic_orbit.hpp"
#include "run/metrics.hpp"
#include "run/segment.hpp"

namespace lub {

std::string classification(const RunResult& r) {
  return r.status == RunStatus::ok ? std::string(name_of(r.steady.kind)) : to_string(r.status);
}

namespace {

using detail::SegmentOptions;
using detail::SegmentResult;
using detail::StartState;

constexpr double kInf = std::numeric_limits<double>::infinity();
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
/// Error bars re-integrate at rtol × this.
constexpr double kTightFactor = 0.01;

std::vector<double> cycle_distances(const std::vector<CycleMetrics>& cycles) {
  std::vector<double> d;
  d.reserve(cycles.size());
  for (const CycleMetrics& c : cycles) d.push_back(c.periodicity);
  return d;
}

std::vector<double> cycle_min_films(const std::vector<CycleMetrics>& cycles) {
  std::vector<double> h;
  h.reserve(cycles.size());
  for (const CycleMetrics& c : cycles) h.push_back(c.min_film_m);
  return h;
}

/// Relative change of the minimum film thickness from each cycle to the next,
/// |h_k − h_{k−1}| / h_k (−1 for the first cycle or without a film).
std::vector<double> film_changes(const std::vector<CycleMetrics>& cycles) {
  std::vector<double> d(cycles.size(), -1.0);
  for (size_t k = 1; k < cycles.size(); ++k) {
    const double h = cycles[k].min_film_m, h0 = cycles[k - 1].min_film_m;
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
  const double floor = detail::orbit_noise_floor(scene);
  e.orbit = steady::estimate_contraction(cycle_distances(cs), kWindow, floor);
  const std::vector<double> dh = film_changes(cs);
  if (!dh.empty() && dh.back() >= 0.0) {
    // The film's noise floor: the orbit's, relative to the film.
    const double c = scene.min_clearance_m().value_or(1.0);
    e.film = steady::estimate_contraction(dh, kWindow, floor * c / std::max(cs.back().min_film_m, 1e-300));
  }
  return e;
}
bool has_film(const std::vector<CycleMetrics>& cs) { return !cs.empty() && cs.back().min_film_m > 0.0; }

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

double wrapped_angle_difference(double a, double b) {
  const double d = std::remainder(a - b, kTwoPi);
  return std::abs(d);
}

/// |metric − tight metric| for every steady metric, plus `extra` (per metric) on top.
void set_errors(Metrics& m, const Metrics& tight, const Metrics* extra = nullptr) {
  auto e = [&](double Metrics::*f) { return extra ? extra->*f : 0.0; };
  m.min_film_thickness_m_error =
      std::abs(m.min_film_thickness_m - tight.min_film_thickness_m) + e(&Metrics::min_film_thickness_m);
  m.angle_at_min_film_rad_error = wrapped_angle_difference(m.angle_at_min_film_rad, tight.angle_at_min_film_rad) +
                                  e(&Metrics::angle_at_min_film_rad);
  m.max_eps_error = std::abs(m.max_eps - tight.max_eps) + e(&Metrics::max_eps);
  m.peak_reaction_N_error = std::abs(m.peak_reaction_N - tight.peak_reaction_N) + e(&Metrics::peak_reaction_N);
  m.angle_at_peak_reaction_rad_error =
      wrapped_angle_difference(m.angle_at_peak_reaction_rad, tight.angle_at_peak_reaction_rad) +
      e(&Metrics::angle_at_peak_reaction_rad);
  m.peak_acceleration_m_s2_error =
      std::abs(m.peak_acceleration_m_s2 - tight.peak_acceleration_m_s2) + e(&Metrics::peak_acceleration_m_s2);
}

/// The coordinates shooting works in: the partitioned formulation's independent
/// coordinates and velocities, partitioned once at the state where shooting starts
/// (whatever formulation integrates the periods), each in its own unit.
struct Chart {
  Model m;
  Workspace ws;
  MultibodySystem sys;
  std::vector<double> units;
  int n = 0;
  Chart(const Scene& scene, const StartState& x)
      : m(build_model(scene)), ws(m), sys(m, ws, scene.simulation.eps_limit, false, Formulation::partitioned) {
    sys.partition(x.t, x.qv.data());
    n = sys.size();
    const Eigen::VectorXd full = detail::state_units(scene, m);
    units.assign(static_cast<size_t>(n), 0.0);
    sys.reduce(full.data(), units.data());
  }
  Eigen::VectorXd reduce(const std::vector<double>& qv) {
    Eigen::VectorXd z(n);
    sys.reduce(qv.data(), z.data());
    return z;
  }
  /// The consistent state at time t with independent part z (the observer context: its
  /// Newton starts from the partition's state every time, so the map is a function of z).
  bool expand(double t, const double* z, std::vector<double>& qv) {
    return sys.expand(t, z, qv.data(), MultibodySystem::Context::observer) == 0;
  }
};

/// P: one crank period from a state at the start's time and film modes.
class PeriodMap final : public steady::CycleMap {
 public:
  PeriodMap(const Scene& scene, Chart& chart, const StartState& base, std::vector<double> winding,
            double rtol_factor, SolverStats& stats, long long& periods)
      : scene_(scene), chart_(chart), base_(base), winding_(std::move(winding)), factor_(rtol_factor),
        stats_(stats), periods_(periods) {}

  int dim() const override { return chart_.n; }

  int apply(const double* z, double* Pz) override {
    StartState s = base_;
    if (!chart_.expand(base_.t, z, s.qv)) {
      message_ = "the dependent coordinates cannot be recovered at the period's start";
      return 1;
    }
    SegmentOptions o;
    o.start = &s;
    o.cycles = 1;
    o.observe = false;
    o.series = false;
    o.rtol_factor = factor_;
    o.max_steps = max_steps_;
    const SegmentResult r = detail::run_segment(scene_, o);
    detail::accumulate(stats_, r.res.stats);
    ++periods_;
    if (r.res.status != RunStatus::ok) {
      message_ = r.res.message;
      return 1;
    }
    std::vector<double> e = r.end.qv;
    for (size_t i = 0; i < e.size(); ++i) e[i] -= winding_[i];
    chart_.sys.reduce(e.data(), Pz);
    return 0;
  }
  const std::string& last_failure() const { return message_; }
  /// A period that takes far more steps than the transient's did has left the orbit's
  /// neighbourhood (near the wall the printed law's corrector crawls at h ~ 1e-8 s for
  /// minutes before it fails, D7): it fails instead.
  void set_step_budget(long long n) { max_steps_ = n; }

 private:
  const Scene& scene_;
  Chart& chart_;
  const StartState& base_;
  std::vector<double> winding_;
  double factor_;
  SolverStats& stats_;
  long long& periods_;
  std::string message_;
  long long max_steps_ = 0;
};

/// How much each coordinate advances over one period: 2π k for a body angle that turns
/// (the crank), 0 otherwise; from the last two cycle boundaries.
std::vector<double> winding_per_period(const Model& m, const StartState& a, const StartState& b) {
  std::vector<double> w(b.qv.size(), 0.0);
  for (int body = 0; body < m.nb; ++body) {
    const size_t i = static_cast<size_t>(3 * body + 2);
    w[i] = kTwoPi * std::round((b.qv[i] - a.qv[i]) / (kTwoPi));
  }
  return w;
}

class SteadyRun {
 public:
  explicit SteadyRun(const Scene& scene) : scene_(scene), sim_(scene.simulation) {}
  RunResult run();

 private:
  const Scene& scene_;
  const SimulationSpec& sim_;
  RunResult res_;
  std::vector<StartState> boundaries_;  // the transient's cycle boundaries
  StartState end_;                      // where the transient ended

  /// The transient: from the scene's initial state over its max_cycles, or `cycles` more
  /// from where it ended, stopped early by `stop`; appends cycles, series, boundaries.
  /// False if the run did not end ok.
  bool transient(int cycles, std::function<bool(const std::vector<CycleMetrics>&)> stop);
  steady::ContractionEstimate contraction() const {
    return steady::estimate_contraction(cycle_distances(res_.cycles), kWindow, detail::orbit_noise_floor(scene_));
  }
  void finish_transient();
  /// Error bars of a transient's metrics: its metric cycles again at rtol/100 from the
  /// state they started at, plus |Δ per cycle| ρ/(1 − ρ), what it would still change.
  void transient_error_bars();
  void shoot();
  void shoot_from_transient();
  bool transient_drifts() const;
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
  // (near the wall the printed law's corrector crawls at h ~ 1e-8 s, D7): it stops there,
  // and the run keeps what it has.
  if (before > 0)
    o.max_steps = 20 * res_.stats.steps / static_cast<long long>(before) * cycles + 1000;
  if (stop)
    o.stop_after_cycle = [&, stop](const std::vector<CycleMetrics>& cs) {
      if (before == 0) return stop(cs);  // the first segment's cycles are all there are
      std::vector<CycleMetrics> all = res_.cycles;
      all.insert(all.end(), cs.begin(), cs.end());
      return stop(all);
    };
  SegmentResult seg = detail::run_segment(scene_, o);
  if (before > 0 && seg.res.status == RunStatus::budget_exceeded && o.max_steps > 0 &&
      seg.res.stats.steps >= o.max_steps) {
    detail::accumulate(res_.stats, seg.res.stats);
    res_.steady.periods += static_cast<long long>(seg.res.cycles.size());
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
    for (size_t c = 0; c < res_.series.data.size() && c < seg.res.series.data.size(); ++c)
      res_.series.data[c].insert(res_.series.data[c].end(), seg.res.series.data[c].begin(),
                                 seg.res.series.data[c].end());
  }
  res_.steady.periods += static_cast<long long>(res_.cycles.size() - before);
  // A continuation's first boundary is where the transient ended: already there.
  const size_t skip = before == 0 || seg.boundaries.empty() ? 0 : 1;
  boundaries_.insert(boundaries_.end(), seg.boundaries.begin() + static_cast<std::ptrdiff_t>(skip),
                     seg.boundaries.end());
  end_ = seg.end;
  res_.steady.transient_cycles = static_cast<int>(res_.cycles.size());
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
  o.rtol_factor = factor;
  o.series = series;
  SegmentResult seg = detail::run_segment(scene_, o);
  detail::accumulate(res_.stats, seg.res.stats);
  res_.steady.periods += o.cycles;
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
  if (!h.empty()) sc.last_min_film_m = h.back();
  if (h.size() >= 2) sc.min_film_drift_m = steady::trend_per_cycle(h, kWindow);
}

void SteadyRun::shoot() {
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

void SteadyRun::shoot_from_transient() {
  SteadyCycle& sc = res_.steady;
  if (boundaries_.size() < 2) return;  // the transient is shorter than two cycles
  const StartState base = end_;
  Chart chart(scene_, base);
  if (chart.n == 0) {
    // Nothing moves but what the drivers move: every state is a function of the crank
    // angle, periodic from the first cycle (the periodicity column shows what the
    // integration's drift makes of it).
    sc.kind = SteadyClass::periodic;
    return;
  }
  const std::vector<double> winding =
      winding_per_period(chart.m, boundaries_[boundaries_.size() - 2], boundaries_.back());
  PeriodMap P(scene_, chart, base, winding, 1.0, res_.stats, sc.periods);
  // 20 times the transient's steps per cycle (its first cycles, from rest, included).
  const long long budget =
      20 * res_.stats.steps / std::max<long long>(1, static_cast<long long>(res_.cycles.size())) + 1000;
  P.set_step_budget(budget);
  steady::ShootingOptions so;
  so.scales = chart.units;
  so.tolerance = sim_.shooting_tolerance;
  // Near the wall a step of 1 % of the clearance would put the perturbed journal through
  // it: at most a tenth of the thinnest gap of the last cycle, 1 − ε_max (in clearances).
  const double gap = res_.cycles.empty() || !(res_.cycles.back().max_eps > 0.0) ? 1.0 : 1.0 - res_.cycles.back().max_eps;
  so.step = std::min(kDifferenceStep, 0.1 * gap);
  // Newton's steps no longer than the gap either (they are measured in the same units).
  so.max_newton_step = std::min(so.max_newton_step, gap);
  // Periods at rtol/100: the Newton Jacobians' and the monodromy's central differences
  // (the map's noise at rtol, ~1e-5 c at 1e-8, over a step of ~1e-2 c would be ~1e-3 in
  // them: Frêne long's |μ|max 0.9973 or 0.9990 with steps 1e-2 and 8.8e-3 at rtol 1e-8,
  // against 0.9966 from the transient's own decay), and the error bars.
  PeriodMap Pt(scene_, chart, base, winding, kTightFactor, res_.stats, sc.periods);
  Pt.set_step_budget(10 * budget);
  so.jacobian_map = &Pt;
  const steady::ShootingResult sh = steady::solve_periodic_orbit(P, chart.reduce(base.qv), so);
  sc.newton_iterations += static_cast<int>(sh.iterations);
  sc.orbit_residual = sh.residual;
  if (sh.outcome != steady::ShootingOutcome::converged) {
    sc.kind = sh.outcome == steady::ShootingOutcome::left_domain || transient_drifts() ? SteadyClass::drifting
                                                                                        : SteadyClass::not_converged;
    std::ostringstream msg;
    msg << "shooting did not converge (" << sh.message << ", residual " << sh.residual << " after "
        << sh.iterations << " Newton iterations)";
    if (!P.last_failure().empty()) msg << "; a period failed: " << P.last_failure();
    res_.message = msg.str();
    return;
  }
  // Floquet multipliers: central differences at the orbit (error O(h²)).
  steady::MonodromyOptions mo{chart.units, so.step, true};
  const steady::Monodromy mono = steady::monodromy_by_differences(Pt, sh.z, sh.Pz, mo);
  if (mono.failed) {
    sc.kind = SteadyClass::not_converged;
    res_.message = "shooting converged, but a perturbed period failed: " + Pt.last_failure();
    return;
  }
  sc.multipliers = steady::floquet_multipliers(mono.M);
  const double dominant = sc.multipliers.empty() ? 0.0 : std::abs(sc.multipliers.front());
  sc.kind = dominant < 1.0 ? SteadyClass::periodic : SteadyClass::periodic_unstable;
  sc.method = "shooting";

  // The metrics of the orbit itself, and its channels.
  StartState orbit = base;
  if (!chart.expand(base.t, sh.z.data(), orbit.qv)) {
    sc.kind = SteadyClass::not_converged;
    return;
  }
  SegmentResult seg = measure(orbit, 1.0, true);
  if (seg.res.status != RunStatus::ok) {
    sc.kind = SteadyClass::not_converged;
    res_.message = "the periodic orbit's measurement failed: " + seg.res.message;
    return;
  }

  res_.metrics = seg.res.metrics;
  res_.orbit = std::move(seg.res.series);

  if (!sim_.error_bars) return;
  // Error bars: the orbit re-found at rtol/100 by one Newton step with the monodromy
  // (z_t = z* − (M − I)⁻¹ (P_t(z*) − z*)) and measured there.
  Eigen::VectorXd Ptz(chart.n);
  if (Pt.apply(sh.z.data(), Ptz.data()) != 0) return;
  const Eigen::MatrixXd A = mono.M - Eigen::MatrixXd::Identity(chart.n, chart.n);
  const Eigen::VectorXd zt = sh.z - A.fullPivLu().solve(Ptz - sh.z);
  StartState tight = base;
  if (chart.expand(base.t, zt.data(), tight.qv)) {
    const SegmentResult st = measure(tight, kTightFactor, false);
    if (st.res.status == RunStatus::ok) set_errors(res_.metrics, st.res.metrics);
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
    SegmentResult st;
    if (k - 1 - m >= 0) st = measure(boundaries_[static_cast<size_t>(k - 1 - m)], kTightFactor, false, m);
    if (st.res.status == RunStatus::ok && res_.cycles.size() >= 2) {
      const CycleMetrics& a = res_.cycles[res_.cycles.size() - 1];
      const CycleMetrics& b = res_.cycles[res_.cycles.size() - 2];
      const double r = est.known ? est.rate : kInf;
      const double f = r < 1.0 ? r / (1.0 - r) : kInf;
      auto tail = [&](double d) { return d == 0.0 ? 0.0 : d * f; };
      Metrics extra;
      extra.min_film_thickness_m = tail(std::abs(a.min_film_m - b.min_film_m));
      extra.angle_at_min_film_rad = tail(wrapped_angle_difference(a.angle_at_min_film_rad, b.angle_at_min_film_rad));
      extra.max_eps = tail(std::abs(a.max_eps - b.max_eps));
      extra.peak_reaction_N = tail(std::abs(a.peak_reaction_N - b.peak_reaction_N));
      extra.angle_at_peak_reaction_rad =
          tail(wrapped_angle_difference(a.angle_at_peak_reaction_rad, b.angle_at_peak_reaction_rad));
      extra.peak_acceleration_m_s2 = tail(std::abs(a.peak_acceleration_m_s2 - b.peak_acceleration_m_s2));
      set_errors(res_.metrics, st.res.metrics, &extra);
    } else if (st.res.status == RunStatus::ok) {
      set_errors(res_.metrics, st.res.metrics);
    }
  }
}

RunResult SteadyRun::run() {
  const auto wall0 = std::chrono::steady_clock::now();
  SteadyCycle& sc = res_.steady;
  const double tol = sim_.steady_tolerance;

  if (sim_.steady == SteadyMethod::transient) {
    std::function<bool(const std::vector<CycleMetrics>&)> stop;
    if (sim_.stop_when_steady)
      stop = [&](const std::vector<CycleMetrics>& cs) { return transient_steady(scene_, cs, tol); };
    const bool ok = transient(0, stop);
    finish_transient();
    if (ok) {
      const bool converged = transient_steady(scene_, res_.cycles, tol);
      sc.kind = converged ? SteadyClass::periodic : transient_drifts() ? SteadyClass::drifting : SteadyClass::not_converged;
      if (sim_.error_bars) transient_error_bars();
    }
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
      // from where it ends. A transient that converged is periodic whatever shooting says;
      // one that drifts is drifting.
      const int left = sim_.max_cycles - static_cast<int>(res_.cycles.size());
      if (sc.kind != SteadyClass::periodic && sc.kind != SteadyClass::periodic_unstable && left > 0 &&
          transient(left, [&](const std::vector<CycleMetrics>& cs) { return transient_steady(scene_, cs, tol); })) {
        finish_transient();
        const bool converged = transient_steady(scene_, res_.cycles, tol);
        shoot();
        if (sc.kind != SteadyClass::periodic && sc.kind != SteadyClass::periodic_unstable) {
          if (converged) {
            sc.kind = SteadyClass::periodic;
            sc.method = "transient";
            res_.message = "periodic by the transient's contraction estimate; " + res_.message;
            if (sim_.error_bars) transient_error_bars();
          } else if (transient_drifts()) {
            sc.kind = SteadyClass::drifting;
          }
        }
      }
      if (res_.status == RunStatus::ok && sc.kind == SteadyClass::drifting && res_.message.empty())
        res_.message = "no periodic orbit inside the clearance";
    } else {
      finish_transient();
    }
  }
  res_.metrics.steady = res_.status == RunStatus::ok && sc.kind == SteadyClass::periodic;
  res_.metrics.cycles_to_steady = res_.metrics.steady ? static_cast<int>(sc.periods) : -1;
  res_.metrics.cycles_run = static_cast<int>(res_.cycles.size());
  res_.stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return std::move(res_);
}

}  // namespace

namespace detail {

void accumulate(SolverStats& t, const SolverStats& s) {
  static_cast<IntegratorStats&>(t) += s;
  t.film_law_evals_jac += s.film_law_evals_jac;
  t.observer_evals += s.observer_evals;
  t.repartitions += s.repartitions;
  t.mode_switches += s.mode_switches;
  t.model_evals += s.model_evals;
  t.gravity_evals += s.gravity_evals;
  t.film_law_evals += s.film_law_evals;
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

RunResult run_scene(const Scene& scene) {
  SteadyRun r(scene);
  return r.run();
}

}  // namespace lub
