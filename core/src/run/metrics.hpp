// The steady-cycle metrics of a run from its per-cycle extremes (internal to the run stage).
#pragma once

#include <vector>

#include "lub/run/run.hpp"
#include "lub/scene/scene.hpp"

namespace lub::detail {

/// Extremes over the last simulation.metric_cycles cycles of `cycles` (the metric joint's
/// film and reaction, the metric body's acceleration, periodicity) and the safe-film
/// check. Whether they describe a steady cycle (verdict.cpp) and the energy balance
/// are not set here.
Metrics steady_cycle_metrics(const Scene& scene, const std::vector<CycleMetrics>& cycles, int cycles_run);

/// The maximum inside [t0, t1] of the cubic Hermite interpolant of a function with values
/// x0, x1 and rates r0 > 0 > r1 at the ends (so one interior maximum): its time and value.
/// Used for the largest eccentricity ratio between two observations, whose ε and ε̇ the
/// observer has evaluated: the step ends alone locate the peak to O(h²), this to O(h⁴)
/// where ε is smooth, with no further evaluation and whatever the output rate.
struct InteriorMax {
  double t = 0.0, value = 0.0;
};
InteriorMax hermite_interior_max(double t0, double x0, double r0, double t1, double x1, double r1);

}  // namespace lub::detail
