// The steady stage's tuning constants, in one place (internal to the run stage). Each has
// a one-line reason; the measurements behind them are in docs/validation/steady-tuning.md.
#pragma once

namespace lub::detail {

struct SteadyTuning {
  // --- the transient ---
  /// Cycles the contraction estimate and the drift fit look back on: a few turns of a
  /// complex dominant pair, few enough to follow a rate that changes as the orbit closes in.
  int window = 10;
  /// A continuation of the transient (and a period map) may take this many times the
  /// transient's steps per cycle before it counts as crawling near the wall.
  long long crawl_factor = 20;
  /// The orbit-distance noise floor: this × rtol (the dense output's accuracy, in clearances) …
  double noise_per_rtol = 10.0;
  /// … or this fraction of steady_tolerance, whichever is larger (1e-6 c a cycle is 1e-3 c
  /// in 1000 cycles).
  double noise_per_tolerance = 1e-3;
  /// auto: the periods shooting costs (a Newton iteration ~n + 1 periods, the monodromy 2 n,
  /// n ~ 4–8); the transient goes on while it needs fewer cycles than this.
  double shooting_cost = 30.0;

  // --- shooting ---
  /// Difference step of Newton's Jacobians and the monodromy, in each state's unit: far
  /// above the period map's noise (~1e-6 c at rtol 1e-8), small against its curvature.
  double difference_step = 1e-2;
  /// Anderson acceleration (the shooting fallback): periods at most, and the residual at
  /// which it hands over to Newton (the map's noise floor at rtol 1e-8 is ~1e-7–1e-6).
  int anderson_periods = 60;
  double anderson_hand_over = 1e-6;
  /// A Newton from the transient that stalls below this residual is at the map's noise: it
  /// runs again on periods at rtol × tighten_factor.
  double tighten_below = 1e-4;
  double tighten_factor = 0.1;
  /// A Newton from the transient stops where its best residual, above tighten_below, has
  /// not halved in this many trial periods (ShootingOptions::stagnation_maps): about two
  /// iterations with their line searches. Inside Newton's region of convergence every
  /// iteration halves it; the Newtons that did not (walking along a slow manifold or into
  /// the wall) spent a seventh of the full factorial's periods and located no orbit.
  int stagnation_maps = 5;
  /// Chord (Newton–Picard) steps first where the start's monodromy has |μ|max below this …
  double chord_contraction = 0.5;
  /// … at most this many, the orbit located when their residual over 1 − |μ|max is within
  /// chord_located × steady_tolerance.
  int chord_iterations = 8;
  double chord_located = 0.1;
  /// Newton does not run where the map's error at rtol would move its orbit by more than
  /// this × steady_tolerance (it could not be located); only where the slow flow follows.
  double unlocatable = 10.0;

  // --- error bars ---
  /// Error bars re-integrate at rtol × this.
  double tight_factor = 0.01;
  /// The tight map's step budget: this × the map's at rtol.
  long long tight_step_factor = 10;
  /// The re-solve at rtol/100: at most this many Newton–Picard iterations (1–3 where the map
  /// is smooth), stopped at this fraction of its first residual (the tight orbit located
  /// to 1 % of its distance from the orbit at rtol) …
  int error_bar_iterations = 6;
  double error_bar_accuracy = 1e-2;
  /// An orbit with κ = 1/min|1 − μ| above this is re-solved once more, at rtol/1e4: its map's
  /// error is amplified κ-fold, and near the wall that error is a bias whose fixed points
  /// move with rtol (docs/theory/steady-cycles.md). Well-conditioned orbits (κ ≤ 57 on the
  /// full factorial) never pay for it …
  double refine_conditioning = 100.0;
  /// … and it is located only where the second move is below this fraction of the first
  /// (an error of order rtol^q, q ≥ ½, shrinks 10–100-fold from one refinement to the next;
  /// a fixed point of a bias moves about as far again) or below refine_floor × steady_tolerance.
  double refine_ratio = 0.3;
  double refine_floor = 0.1;
  /// An orbit whose minimum film's error bar exceeds this fraction of the film is not
  /// located: where the journal sits against the wall is not resolved at this rtol, the mark
  /// of a fixed point of the map's error near the wall (κ × the map's error beyond the gap).
  /// On the full factorial the located orbits' bars are at most 0.13 % of their films; the
  /// near-wall fixed points a smooth Jacobian lets Newton reach, 65–89 %.
  double film_resolution = 0.1;
  /// The finest rtol a refinement integrates at: below it the steps crawl at round-off
  /// near the wall (300 cycles at 1e-13 take minutes where 1e-12 takes seconds).
  double finest_rtol = 1e-12;
  /// … and chords that stall below this fraction of their first residual are enough (at
  /// the tight map's noise; no KINSOL line search on that noise after them).
  double error_bar_stall = 0.1;

  // --- the slow flow ---
  /// Periods its projective steps may spend.
  long long slow_periods = 200;
  /// Newton where the flow stops: at most this many tries, of at most this many iterations.
  int slow_newton_tries = 1;
  int slow_newton_iterations = 10;
  /// Beyond this eccentricity ratio only a flow that has stopped (not one that only seems
  /// near an orbit) is a start for Newton: an estimate there is no evidence of an orbit.
  double slow_near_wall = 1.0 - 1e-3;
  /// After Newton from the first cycles found nothing, a transient contracting at this
  /// rate or slower (but contracting) is followed by the slow flow, not a second Newton.
  double slow_contraction = 0.9;
  /// Where the flow got to, its cycles must repeat to this (clearances), or the state is on
  /// no slow manifold and the flow is not reported.
  double slow_periodicity = 1e-2;

  // --- continuation ---
  /// Newton iterations of one path step before it counts as failed (and the step halves).
  int continuation_iterations = 8;
  /// The smallest step along a path before it is given up (five halvings).
  double min_path_step = 1.0 / 32.0;
  /// A path step's period map may take this many times the neighbour's steps per period
  /// (a thinner film's smaller steps).
  double path_step_factor = 50.0;
  /// A scene's thick-film version: its viscosity × this (the journal well inside the
  /// clearance, where shooting converges from the transient).
  double thick_film = 16.0;
};

}  // namespace lub::detail
