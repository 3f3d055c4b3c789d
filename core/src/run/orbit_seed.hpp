// Periodic orbits carried from one scene to a neighbouring one (internal to the run
// stage): a seed made from an orbit found by shooting, and a seed placed into another
// scene as the start of its Newton. See lub/run/run.hpp (OrbitSeed).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "lub/run/run.hpp"
#include "run/period_map.hpp"
#include "run/segment.hpp"

namespace lub::detail {

/// The seed of the orbit through `orbit` (a consistent state at crank angle 0) with
/// monodromy M (chart coordinates, physical units; empty: none).
OrbitSeed make_seed(RunModel& rm, const Chart& chart, const StartState& orbit, const Eigen::MatrixXd& M,
                    const std::vector<double>& winding, double max_eps, double steps_per_period);

/// The seed placed into this run's scene: the state at t = 0 (crank angle 0) that deviates
/// from the scene's initial state by the seed's deviation in this scene's units, with the
/// seed's film modes; not yet consistent (the chart's expansion makes it so). nullopt if
/// the seed is of another mechanism (sizes differ).
std::optional<StartState> place_seed(RunModel& rm, const OrbitSeed& seed);

/// The seed's monodromy in this chart's physical units, if the chart has the seed's
/// independent coordinates: S M S⁻¹ with S the chart's units.
std::optional<Eigen::MatrixXd> seed_monodromy(const OrbitSeed& seed, const Chart& chart);

}  // namespace lub::detail
