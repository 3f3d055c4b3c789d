// One integration of a scene over a span of time, from its initial state or from a given
// state (internal to the run stage). run_scene strings segments together: the transient,
// the period maps of shooting, the steady cycle's measurement, the error bars' reruns.
#pragma once

#include <functional>
#include <vector>

#include "lub/mechanism/model.hpp"
#include "lub/run/run.hpp"
#include "lub/scene/scene.hpp"

namespace lub::detail {

/// A consistent state of the mechanism: time, (q, v) (2 nq) and the film modes.
struct StartState {
  double t = 0.0;
  std::vector<double> qv;
  std::vector<FilmMode> modes;
  std::vector<double> slide_radius;
};

struct SegmentOptions {
  const StartState* start = nullptr;  ///< nullptr: the scene's initial state at t = 0
  int cycles = 0;                     ///< > 0: exactly this many crank cycles from the start
  double rtol_factor = 1.0;           ///< every tolerance × this (error bars: 0.01)
  bool observe = true;                ///< per-step extremes and phase points (cycle metrics)
  bool series = true;                 ///< record the scene's channels (needs observe)
  long long max_steps = 0;            ///< > 0: budget_exceeded after this many steps
  /// Called after every completed cycle with the cycles so far: true stops the run there.
  std::function<bool(const std::vector<CycleMetrics>&)> stop_after_cycle;
};

struct SegmentResult {
  RunResult res;                    ///< status, stats, cycles, series; metrics over the last cycles
  StartState end;                   ///< the state where the segment ended (a cycle boundary if ok)
  /// The state at each cycle boundary (observe only): the start, then each cycle's end
  std::vector<StartState> boundaries;
};

SegmentResult run_segment(const Scene& scene, const SegmentOptions& opt);

/// Adds the counters and costs of `s` to `total` (drift: the larger).
void accumulate(SolverStats& total, const SolverStats& s);

/// Each state's unit (2 nq, (q, v)): lengths in the smallest clearance (1 mm without a
/// film), angles in that over the body's size, rates in those times the driver's speed.
/// The absolute tolerances are rtol times these; shooting measures residuals in them.
Eigen::VectorXd state_units(const Scene& scene, const Model& m);

/// The orbit distance between two cycles' phase points is measured in the clearance; below
/// this it is noise (the contraction estimate's floor): max(10 rtol, 1e-3 steady_tolerance).
double orbit_noise_floor(const Scene& scene, double rtol_factor = 1.0);

}  // namespace lub::detail
