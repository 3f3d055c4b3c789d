// The steady stage's shared context and the evidence its strategies return (internal to
// the run stage). run.cpp tries the strategies in order (transient.cpp, shooting.cpp,
// error_bars.cpp, slow_flow.cpp, continuation.cpp); each integrates through the context,
// writes the numbers it measured into the context's account (res: cycles, metrics,
// multipliers, costs) and returns typed evidence. Only verdict.cpp turns evidence into the
// steady cycle's label, method and the run's message.
#pragma once

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lub/run/run.hpp"
#include "lub/steady/contraction.hpp"
#include "lub/steady/periodic_orbit.hpp"
#include "lub/steady/slow_manifold.hpp"
#include "run/period_budget.hpp"
#include "run/period_map.hpp"
#include "run/segment.hpp"
#include "run/steady_tuning.hpp"

namespace lub::detail {

/// One run's steady stage: the scene, its model (built once, shared by every segment), the
/// budget of periods, and the account the strategies fill.
class SteadyContext {
 public:
  /// `budget`: the case's max_periods and what the case spent before this run.
  SteadyContext(const Scene& scene, PeriodBudget budget)
      : scene(scene), sim(scene.simulation), rm(scene), budget(std::move(budget)) {}

  const Scene& scene;
  const SimulationSpec& sim;
  const SteadyTuning tuning{};
  RunModel rm;
  RunResult res;                       ///< the account (label, method, message: verdict.cpp)
  std::vector<StartState> boundaries;  ///< the transient's cycle boundaries
  StartState end;                      ///< where the transient ended
  PeriodBudget budget;                 ///< simulation.max_periods: every strategy asks it first

  long long spent() const { return res.steady.periods_integrated; }
  /// The orbit distance below which a cycle-to-cycle change is noise [clearances]: the
  /// dense output's accuracy (noise_per_rtol × rtol) or a small share of steady_tolerance.
  double orbit_noise_floor() const;
  /// A tighter integration's rtol factor as the integrator can honour it: `factor`, or
  /// tuning.finest_rtol over the scene's rtol where `factor` would go below it (never
  /// looser than the scene's own rtol). Below ~1e-12 BDF's error test meets round-off and
  /// the steps crawl: 10 cycles of the reference case took 194 s at 1e-14.
  double finer(double factor) const;
  /// Whether the error bars have room below the scene's rtol: their integrations at least
  /// ten times tighter than it.
  bool error_bars_have_room() const { return finer(tuning.tight_factor) <= 0.1; }
  /// The metric cycles (or `cycles`) from a state at rtol × factor: their metrics and
  /// channels; refused (budget_exceeded) where the budget does not allow them.
  SegmentResult measure(const StartState& s, double factor, bool series, int cycles = 0);
  /// The period map at rtol × factor and its twin at rtol × factor × tight_factor
  /// (differences, error bars), from `base`, within `steps` integrator steps a period
  /// (tight_step_factor × that for the twin) and the run's budget of periods.
  void period_maps(std::optional<PeriodMap>& period, std::optional<PeriodMap>& tight, Chart& chart,
                   const StartState& base, const std::vector<double>& winding, double factor, long long steps);
  /// How much each coordinate advances over a period, from the transient's last two boundaries.
  std::vector<double> transient_winding() const;
  /// A period map's step budget from the transient: crawl_factor times its steps per cycle.
  long long transient_step_budget() const;
  /// Shooting's options from a cycle whose largest eccentricity ratio is `max_eps` (NaN:
  /// unknown): difference and Newton steps within the gap.
  steady::ShootingOptions shooting_options(const Chart& chart, double max_eps) const;
};

// ---------------------------------------------------------------------------------------
// Evidence

/// A transient leg (transient.cpp): whether it ended ok, and the segment's own status and
/// message where it did not.
struct TransientLeg {
  bool ok = false;
  /// A continuation leg's segment message (the run's message from then on); none for the
  /// first leg (the run's account starts as its result) or a leg that did not run.
  std::optional<std::string> message;
};

/// The period map's word on a transient its contraction estimate calls steady (transient.cpp).
struct TransientConfirmation {
  enum class Outcome {
    confirmed,     ///< within steady_tolerance of a stable orbit (or nothing moves)
    too_short,     ///< fewer than two cycle boundaries
    refused,       ///< the budget stopped it (its note says so)
    period_failed, ///< a period from the transient's end failed (`failure`)
    unstable,      ///< |μ|max >= 1 there
    far,           ///< the orbit lies `distance` from the end, beyond steady_tolerance
    ill_posed,     ///< κ amplifies the map's error a period to `shift`, beyond steady_tolerance
  };
  Outcome outcome = Outcome::too_short;
  std::string failure;
  double dominant = 0.0;  ///< |μ|max
  double distance = 0.0;  ///< |(I − M)⁻¹ (P(z) − z)| [clearances]
  double tolerance = 0.0; ///< steady_tolerance
  double conditioning = kNaN;  ///< κ = 1/min|1 − μ| there
  /// Where κ > refine_conditioning: |(I − M)⁻¹ (P − P_tight)(z)|, how far the map's error at
  /// rtol moves the orbit [clearances] (NaN: not needed).
  double shift = kNaN;
};

/// Error bars (error_bars.cpp).
struct ErrorBarEvidence {
  enum class Outcome {
    not_run,   ///< not asked for, or nothing to measure
    measured,  ///< set on the metrics
    refused,   ///< the budget stopped them (its note says so)
    failed,    ///< not measured: `failure` says why
  };
  Outcome outcome = Outcome::not_run;
  /// How the tight orbit was re-solved, where not plainly (appended to the message).
  std::string note;
  std::string failure;
  bool budget = false;  ///< the failure is a limit the user set (a budget, an rtol at the finest): NaN bars
  /// An ill-conditioned orbit (κ > refine_conditioning) re-solved once more, at rtol/1e4
  /// (or SteadyTuning::finest_rtol):
  /// how far it moved from rtol/100 [clearances] (NaN: not refined), against the first move.
  double refined_move = kNaN;  ///< +inf: not re-solved there (`refine_failure`)
  double first_move = kNaN;
  double refine_bound = kNaN;  ///< the largest second move of an orbit that stops moving
  double conditioning = kNaN;  ///< κ of the orbit's monodromy
  double refine_rtol = kNaN;   ///< the rtol it was refined at
  std::string refine_failure;
  /// Refined, and still moving (or not re-solved finer).
  bool keeps_moving() const { return !std::isnan(refined_move) && !(refined_move <= refine_bound); }
};

/// Newton on the period map from a start, and the orbit's measurement (shooting.cpp).
struct OrbitEvidence {
  enum class Outcome {
    not_found,           ///< Newton found no orbit (`newton` says why)
    refused,             ///< the budget stopped Newton (its note says so)
    multipliers_failed,  ///< converged, but a perturbed period failed (`failure`)
    multipliers_refused, ///< converged, the budget stopped the multipliers
    found,               ///< converged; measured and error bars as below where `final`
  };
  Outcome outcome = Outcome::not_found;
  bool final = false;             ///< the run's own scene: measured, classified
  steady::ShootingResult newton;  ///< Newton's result
  std::string period_failure;     ///< the period map's last failure (not_found)
  std::string failure;            ///< multipliers_failed: the perturbed period's
  bool drifts = false;            ///< not_found: the transient's film drifts one way
  double dominant = 0.0;          ///< |μ|max at the orbit
  /// Where Newton was not run (newton.skipped): how far the map's error at rtol would move
  /// the orbit [clearances], the start's |μ|max, and the factor of steady_tolerance beyond
  /// which an orbit cannot be located.
  double predicted_shift = kNaN;
  double start_dominant = kNaN;
  double unlocatable = 0.0;
  // final only:
  bool outside_chart = false;     ///< the orbit's state could not be expanded (not measured)
  bool measured = false;          ///< its metric cycles measured
  std::string measure_failure;    ///< why not (the segment's message)
  ErrorBarEvidence bars;
  double orbit_error = kNaN;      ///< how far the orbit moves at rtol/100 [clearances]
  double steady_tolerance = 0.0;
  double film_resolution = 0.0;   ///< SteadyTuning::film_resolution
  bool seeded = false;            ///< its seed made (a continuation can start from it)
};

/// Shooting from where the transient ended (shooting.cpp).
struct ShootingEvidence {
  enum class Outcome {
    no_budget,     ///< no period left (the budget's note says so)
    error,         ///< the case could not be shot (`error`: why)
    too_short,     ///< the transient is shorter than two cycles
    no_freedom,    ///< nothing moves but what the drivers move: periodic from the start
    orbit,         ///< Newton ran: `orbit`
  };
  Outcome outcome = Outcome::too_short;
  std::string error;
  OrbitEvidence orbit;
};

/// The slow flow after shooting found no orbit (slow_flow.cpp).
struct SlowFlowEvidence {
  enum class Outcome {
    not_followed,      ///< too short a transient, or nothing moves
    newton_refused,    ///< the budget stopped Newton where the flow stops
    newton,            ///< Newton where the flow stops ended the case: `orbit`
    off_manifold,      ///< where it got to is on no slow manifold: the case as shooting left it
    film_fails,        ///< the journal leaves the clearance on the way (`failure`)
    refused,           ///< the budget stopped the flow (its note says so)
    still,             ///< it stops within the map's noise, Newton finds no orbit there
    moving,            ///< its periods spent, still moving
  };
  Outcome outcome = Outcome::not_followed;
  double cycles = 0.0;          ///< cycles followed after the transient
  long long periods = 0;        ///< periods the flow spent
  steady::SlowManifoldOutcome flow = steady::SlowManifoldOutcome::budget;
  std::string shooting;         ///< why shooting from the transient found no orbit (its message)
  /// Why the last Newton where the flow stopped found no orbit (verdict.cpp's words).
  std::string newton;
  bool newton_tried = false;    ///< a Newton ran there and found no orbit
  OrbitEvidence orbit;          ///< newton: what shooting where the flow stopped found
  std::string failure;          ///< film_fails: the measurement's or the period's
  double periodicity = 0.0;     ///< off_manifold: two cycles' distance there [clearances]
  bool measured = false;        ///< the cycles where it got to measured (metrics taken)
  /// still, moving: why the cycles where it got to were not measured (the film and drift
  /// on record then stay the transient's); empty where they were
  std::string not_measured;
  /// measured: why the film's drift there was not (it is NaN); empty where it was
  std::string drift_not_measured;
  double film_at_end = kNaN;    ///< the transient's last film [m] (before the flow's metrics)
  double flow_rtol = kNaN;      ///< moving: the rtol its periods ran at (the drift's error bar's)
  /// moving: why no drift law was fitted along the flow (empty: fitted, in res.steady)
  std::string no_law;
  double law_film_low = kNaN, law_film_high = kNaN;  ///< the films the law was fitted over [m]
  bool safe_beyond_reach = false;  ///< the safe film lies beyond the law's reach (no crossing)
};

}  // namespace lub::detail
