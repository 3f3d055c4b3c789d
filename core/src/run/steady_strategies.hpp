// The steady stage's strategies (internal to the run stage): each integrates through the
// SteadyContext, writes what it measured into the account and returns evidence
// (steady_context.hpp); none decides a label or writes a message (verdict.hpp does).
#pragma once

#include <functional>
#include <vector>

#include "run/metrics.hpp"
#include "run/series_recorder.hpp"
#include "run/steady_context.hpp"

namespace lub::detail {

using CycleStop = std::function<bool(const std::vector<CycleMetrics>&)>;

// --- transient.cpp ---
/// A transient leg: from the scene's initial state over its max_cycles, or `cycles` more
/// from where it ended, stopped early by `stop`; appends cycles, series, boundaries.
TransientLeg run_transient_leg(SteadyContext& cx, int cycles, const CycleStop& stop);
/// Whether the contraction estimate of these cycles is known (enough cycles, above noise).
bool transient_known(const SteadyContext& cx, const std::vector<CycleMetrics>& cs);
/// Whether these cycles have reached their steady cycle within steady_tolerance (orbit and film).
bool transient_steady(const SteadyContext& cx, const std::vector<CycleMetrics>& cs);
/// Cycles the transient still needs by both estimates (+inf: unknown or not contracting).
double transient_cycles_left(const SteadyContext& cx, const std::vector<CycleMetrics>& cs);
/// The contraction estimate of the run's cycles so far.
steady::ContractionEstimate contraction(const SteadyContext& cx);
/// Each cycle's minimum film thickness [m].
std::vector<double> cycle_min_films(const std::vector<CycleMetrics>& cycles);
/// The film moved the same way in every cycle of the window and does not stop inside the clearance.
bool transient_drifts(const SteadyContext& cx);
/// The transient's contraction rate, distance to go, last film and its drift (numbers).
void finish_transient(SteadyContext& cx);
/// The period map's word on a transient its estimate calls steady.
TransientConfirmation confirm_transient(SteadyContext& cx);

// --- shooting.cpp ---
/// A state's period and the monodromy there: P(z) at the map's rtol, and M by central
/// differences of `tight` (its rtol/100 twin) with steps `step` in each state's unit.
/// `rc`: the period's flag (non-zero: M not computed).
struct PeriodAndMonodromy {
  int rc = 0;
  Eigen::VectorXd Pz;
  steady::Monodromy monodromy;
};
PeriodAndMonodromy period_and_monodromy(PeriodMap& period, PeriodMap& tight, const Eigen::VectorXd& z,
                                        const Chart& chart, const steady::ShootingOptions& options);
/// Newton–Picard's options for the problem `o` poses, at most `iterations` iterations.
steady::NewtonPicardOptions newton_picard_options(const steady::ShootingOptions& o, int iterations);
/// Newton on the period map from `base`, then the monodromy and the multipliers; if
/// `final`, the orbit's metrics and error bars. Sets the orbit's seed where accepted.
/// `from`: the orbit Newton started from (a continuation's), whose ε_max and steps per
/// period a path step's seed keeps (only the final step measures its own). A Newton from
/// the transient that stalls at the map's noise runs once more on periods at rtol ×
/// tighten_factor; from a continuation's orbit only where `tighten_stalled` (a single step,
/// which no shorter step can replace), and only after the stall is not accepted as located
/// through the seed's monodromy.
OrbitEvidence solve_orbit(SteadyContext& cx, Chart& chart, const StartState& base, const std::vector<double>& winding,
                          long long budget, steady::ShootingOptions options, bool final, const OrbitSeed& from,
                          bool tighten_stalled = false);
/// Shooting from where the transient ended.
ShootingEvidence shoot_from_transient(SteadyContext& cx);

// --- error_bars.cpp ---
/// The orbit re-solved at rtol/100 from z* (Newton–Picard on the monodromy's M − I) and
/// measured there; sets the metrics' error bars and the orbit's orbit_error.
ErrorBarEvidence orbit_error_bars(SteadyContext& cx, Chart& chart, const StartState& base, PeriodMap& tight_period,
                                  const Eigen::VectorXd& z, const Eigen::MatrixXd& monodromy,
                                  const steady::ShootingOptions& options);
/// A transient's metric cycles again at rtol/100 from the state they started at, plus
/// what it would still change, |Δ per cycle| ρ/(1 − ρ).
ErrorBarEvidence transient_error_bars(SteadyContext& cx);

// --- slow_flow.cpp ---
/// Shooting found no orbit from the transient's end: its slow flow followed to where the
/// journal ends up, then Newton from there where it stops near an orbit.
SlowFlowEvidence follow_slow_flow(SteadyContext& cx);

}  // namespace lub::detail

namespace lub::detail {

// --- run.cpp ---
/// The steady stage of one scene by simulation.steady (transient, shooting, auto), within
/// `budget`: the order in which the strategies are tried.
RunResult run_steady(const Scene& scene, PeriodBudget budget);

// --- continuation.cpp ---
/// simulation.steady = continuation without a neighbour: auto; where it finds no orbit,
/// the thick-film version's orbit continued back to the scene's viscosity. `before`: the
/// periods the case integrated before (a path given up).
RunResult run_alone(const Scene& scene, long long before = 0);
/// The scene from a neighbour's orbit along the path `from`; where the path cannot be
/// followed, the scene alone (run_alone), the message saying where the path ended.
RunResult run_continued(const Scene& scene, const ContinuationStart& from);

}  // namespace lub::detail
