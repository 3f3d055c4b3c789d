// The steady-cycle metrics of a run from its per-cycle extremes (internal to the run stage).
#pragma once

#include <vector>

#include "lub/run/run.hpp"
#include "lub/scene/scene.hpp"

namespace lub::detail {

/// Extremes over the last simulation.metric_cycles cycles of `cycles` (the metric joint's
/// film and reaction, the metric body's acceleration, periodicity), the safe-film check,
/// and whether and when the run became steady (the last metric_cycles cycles each repeat
/// the one before within simulation.steady_tolerance). The energy balance is not set here.
Metrics steady_cycle_metrics(const Scene& scene, const std::vector<CycleMetrics>& cycles, int cycles_run);

}  // namespace lub::detail
