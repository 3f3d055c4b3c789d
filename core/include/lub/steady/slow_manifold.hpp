// Following a transient along a slow manifold by projective steps (the steady stage: pure
// numerics on an abstract cycle map, Eigen only).
//
// Where a periodically forced system has Floquet multipliers that contract some directions
// to nothing in a period (a squeeze film's: ~1e-10) and others hardly at all (|μ| ≈ 1),
// every state reaches a slow manifold within a period and then creeps along it by a little
// each period: the slow flow
//
//   dz/dk = g(z),   g(z) = P(z) − z   on the manifold   (k: cycles, a continuous count)
//
// whose destination is where the journal ends up: a zero of g (a periodic orbit), the
// wall, or nowhere within the horizon. Integrating it period by period costs one period a
// cycle (thousands near the wall); projective integration (Gear & Kevrekidis 2003, "Projective
// methods for stiff differential equations") takes g from two periods and jumps K cycles
// along it, z ← P(P(z)) + K g, then one period settles the jumped state back onto the
// manifold (the fast directions forget the jump's error in it) and the next measures g
// again: 2 periods for K + 2 cycles. The step K is chosen by the jump's own error estimate
// (forward Euler: K/2 |g_new − g_old| in each state's unit), grown on success, cut on
// failure; a jump whose period fails (the journal put through the wall) is cut to a
// quarter, and a plain period that fails is the flow's own end.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "lub/steady/periodic_orbit.hpp"

namespace lub::steady {

struct SlowManifoldOptions {
  std::vector<double> scales;  ///< r_i: each state's unit (lengths in clearances)
  /// Largest local error of one jump, max_i |error_i| / r_i.
  double jump_tolerance = 1e-4;
  /// ... plus this fraction of the jump, max_i |K g_i| / r_i: where the flow is on its way,
  /// the path need not be followed to the tolerance the destination is measured to.
  double jump_relative = 0.05;
  /// Largest jump, max_i |K g_i| / r_i: the slow manifold curves, and the error estimate
  /// sees its curvature only after the jump.
  double max_jump = 0.05;
  double first_jump = 4.0;       ///< K of the first jump, cycles
  double horizon_cycles = 1e5;   ///< cycles followed at most
  long long max_maps = 200;      ///< periods at most
  /// Stop (near) where the slow flow is this close to a zero of g by its estimated
  /// distance |g| / λ, λ the rate at which g shrinks along the path (the slow multipliers'
  /// 1 − |μ| for a node; an algebraic approach, h ∝ k^−a, is estimated as a|h|/(a + 1):
  /// near, and wrong), on two jumps running (one estimate is fooled by a slope that still
  /// carries a faster mode's decay); 0: never. Stop (still) where |g| is below `still` a period.
  double hand_over = 0.02;
  double still = 1e-8;
};

enum class SlowManifoldOutcome {
  near,     ///< near a zero of g by its estimated distance: an orbit may be close (try Newton)
  still,    ///< |g| below `still`: the flow has stopped, within the map's own noise
  horizon,  ///< still moving after horizon_cycles
  budget,   ///< max_maps periods spent, still moving
  failed,   ///< a plain period from a state the flow reached fails: the flow's own end (the wall)
  refused,  ///< the map refused (CycleMap::apply < 0: the run's budget of periods)
};

struct SlowManifoldResult {
  SlowManifoldOutcome outcome = SlowManifoldOutcome::budget;
  Eigen::VectorXd z;   ///< the last state reached on the manifold
  Eigen::VectorXd g;   ///< P(z) − z there (per cycle)
  double cycles = 0.0; ///< cycles of the flow z stands for, after the start
  long long maps = 0;  ///< periods integrated
  int jumps = 0;       ///< accepted jumps
  int rejected = 0;    ///< jumps taken again shorter
  /// Estimated distance to the zero of g, max_i / r_i (NaN: not yet estimated).
  double distance = std::numeric_limits<double>::quiet_NaN();
  /// Accepted points: cycles after the start and the state (the first is the start's image).
  std::vector<double> trail_cycles;
  std::vector<Eigen::VectorXd> trail;
};

/// Follows the slow flow from z0 (a state on the manifold: the end of a transient).
SlowManifoldResult follow_slow_manifold(CycleMap& P, const Eigen::VectorXd& z0, const SlowManifoldOptions& opt);

const char* name_of(SlowManifoldOutcome o);

}  // namespace lub::steady
