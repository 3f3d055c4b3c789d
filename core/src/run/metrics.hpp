// The steady-cycle metrics of a run from its per-cycle extremes (internal to the run stage).
#pragma once

#include <vector>

#include "lub/run/run.hpp"
#include "lub/scene/scene.hpp"

namespace lub::detail {

/// Extremes over the last simulation.metric_cycles cycles of `cycles` (the metric joint's
/// film and reaction, the metric body's acceleration, periodicity) and the safe-film
/// check. Whether they describe a steady cycle (steady_cycle.cpp) and the energy balance
/// are not set here.
Metrics steady_cycle_metrics(const Scene& scene, const std::vector<CycleMetrics>& cycles, int cycles_run);

}  // namespace lub::detail
