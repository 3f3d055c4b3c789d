// The steady stage's verdict (internal to the run stage): the one place that turns the
// strategies' evidence into the steady cycle's label (SteadyClass), its method
// (SteadyCycleMethod) and the run's message. Each function reads evidence and the account's
// numbers, and writes only res.steady.kind, res.steady.method and res.message.
#pragma once

#include <chrono>
#include <string>

#include "run/steady_context.hpp"

namespace lub::detail::verdict {

/// A periodic orbit was found, stable or not.
bool is_orbit(SteadyClass k);

/// A continuation leg of the transient ended: its segment's message is the run's.
void leg(RunResult& res, const TransientLeg& leg);
/// simulation.max_cycles below kMinSteadyCycles: the transient alone, and why.
void transient_only(RunResult& res, int max_cycles);
/// A transient classified by its contraction estimate (`converged`), confirmed by the
/// period map where `confirm` (its word: `c`), drifting where its film drifts one way.
void transient(RunResult& res, bool converged, bool confirm, const TransientConfirmation& c, bool drifts);
/// Shooting from the transient found no orbit, the transient then converged by its own
/// estimate: periodic if the period map confirms it, with why shooting did not find it.
/// True if periodic.
bool transient_after_shooting(RunResult& res, const TransientConfirmation& c, bool drifts);
/// A transient that drifts: drifting.
void drifting(RunResult& res);
/// auto: no second Newton from a slowly contracting transient (the slow flow follows).
void slow_transient(RunResult& res, const std::string& first_newton, int first_cycles, int cycles, double rate);
/// A drifting case without a message: why.
void no_orbit_inside(RunResult& res);

/// Error bars that were not measured: the message says so, and an orbit whose accuracy is
/// unknown is no steady result (not_converged), except where a budget the user set
/// stopped the measurement (it keeps the orbit with NaN error bars).
void error_bars(RunResult& res, const ErrorBarEvidence& ev);

/// Shooting from the transient's end. True if an orbit was found and accepted.
bool shooting(RunResult& res, const ShootingEvidence& ev);
/// Newton's orbit: its label from the multipliers where final, or why it is none. True if
/// accepted (found, and where final measured, with error bars and located).
bool orbit(RunResult& res, const OrbitEvidence& ev);
/// Whether orbit() accepts the evidence.
bool accepted(const OrbitEvidence& ev);
/// The message orbit() leaves on a run without one.
std::string orbit_message(const OrbitEvidence& ev);
/// Why Newton–Picard where the slow flow stopped found no orbit.
std::string newton_picard_failure(const steady::ShootingResult& picard, bool period_failed,
                                  const std::string& failure);

/// Where the slow flow ended the case.
void slow_flow(RunResult& res, const SlowFlowEvidence& ev);

/// One step of a continuation from a neighbour's orbit. True if it found the orbit.
struct ContinuationStep {
  enum class Outcome { other_mechanism, no_freedom, orbit, error };
  Outcome outcome = Outcome::orbit;
  OrbitEvidence orbit;
  std::string error;
};
bool continuation_step(RunResult& res, const ContinuationStep& ev);
/// The scene's orbit found at the end of a continuation's path of `steps` steps.
void continued(RunResult& res, int steps);
/// Why a continuation's path was given up at `lambda`.
std::string path_stopped(double lambda, int steps, const std::string& why);
/// A case continued from its thick-film version, or what it says where that failed:
/// `own` the scene's own run, `why` what stopped.
void thick_film_continued(RunResult& res);
void thick_film_none(RunResult& own, const RunResult& seeded);
void thick_film_path_failed(RunResult& own, const std::string& why);
/// The case's budget spent before a further step (`why` its note).
void budget_spent(RunResult& res, const std::string& why);
/// A path from a neighbour that could not be followed: the scene alone, after `why`.
void path_then_alone(RunResult& res, const std::string& why);
/// A path from a neighbour given up where the budget is spent: its account is the case's.
void path_spent(RunResult& res, const std::string& why);
/// A path from a neighbour whose orbit was lost on the way (ContinuationStart::alone_if_lost
/// false): not_converged, its account the case's.
void path_lost(RunResult& res, const std::string& why);

/// The run's result: the budget's note first, the steady flag and counts, the wall time.
RunResult close(SteadyContext& cx, std::chrono::steady_clock::time_point wall0);

}  // namespace lub::detail::verdict
