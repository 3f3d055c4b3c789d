// One integration of a scene over a span of time, from its initial state or from a given
// state (internal to the run stage). run_scene strings segments together: the transient,
// the period maps of shooting, the steady cycle's measurement, the error bars' reruns.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "lub/mechanism/model.hpp"
#include "lub/mechanism/builder.hpp"
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
  /// When the integrator gives up, restart it once from its last accepted state before
  /// ending the segment (segment.cpp, Runner::integration_failed). false: the first failure
  /// ends it, as before issue 25 (the tests compare both).
  bool restart_after_failure = true;
  /// Integrate with the state the forward sensitivities of the integrated coordinates to
  /// their start (SegmentResult::sensitivity): the variational equation on the state's own
  /// steps (Integrator::start_sensitivities), so that the derivative is that of the computed
  /// map itself. Where the integration has none (a method without them, a formulation
  /// other than joint) or a switch of the right-hand side breaks them (a film's mode
  /// change, which would need its saltation), the result says why.
  bool sensitivities = false;
  /// Called after every completed cycle with the cycles so far: true stops the run there.
  std::function<bool(const std::vector<CycleMetrics>&)> stop_after_cycle;
};

/// What a run builds once and all its segments share (Pinocchio's Model/Data split): the
/// immutable Model and a workspace for each of its users. Each segment resets the
/// workspaces it uses, so it starts from the state a fresh build would give.
struct RunModel {
  explicit RunModel(const Scene& scene);
  const Scene& scene;
  Model model;
  Stabilisation stab;       ///< the constraints' stabilisation the scene's solver asks for
  Workspace integrator_ws;  ///< the integrator's
  /// The observers' own: what they evaluate (a finite-Reynolds solver's warm start, the
  /// counters) must not reach the integrator's workspace, or how often a run samples
  /// would change its trajectory. Film modes are copied in before each observation.
  Workspace observer_ws;
  Workspace chart_ws;       ///< shooting's chart of independent coordinates (period_map.cpp)
};

struct SegmentResult {
  RunResult res;                    ///< status, stats, cycles, series; metrics over the last cycles
  StartState end;                   ///< the state where the segment ended (a cycle boundary if ok)
  /// The state at each cycle boundary (observe only): the start, then each cycle's end
  std::vector<StartState> boundaries;
  /// SegmentOptions::sensitivities: ∂y(end)/∂y(start) of the integrated coordinates
  /// (n × n, column-major), or empty with `sensitivity_note` saying why there is none.
  std::vector<double> sensitivity;
  std::string sensitivity_note;
};

SegmentResult run_segment(RunModel& rm, const SegmentOptions& opt);

/// Adds the counters and costs of `s` to `total` (drift: the larger).
void accumulate(SolverStats& total, const SolverStats& s);

}  // namespace lub::detail
