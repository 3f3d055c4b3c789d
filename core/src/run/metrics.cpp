// Steady-cycle metrics: see metrics.hpp.
#include "run/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lub::detail {

Metrics steady_cycle_metrics(const Scene& scene, const std::vector<CycleMetrics>& cycles, int cycles_done) {
  Metrics mt;
  mt.cycles_run = cycles_done;
  const int M = std::min<int>(scene.simulation.metric_cycles, static_cast<int>(cycles.size()));
  mt.min_film_thickness_m = std::numeric_limits<double>::infinity();
  for (int i = 0; i < M; ++i) {
    const CycleMetrics& c = cycles[cycles.size() - 1 - i];
    if (c.min_film_m < mt.min_film_thickness_m) {
      mt.min_film_thickness_m = c.min_film_m;
      mt.angle_at_min_film_rad = c.angle_at_min_film_rad;
    }
    mt.max_eps = std::max(mt.max_eps, c.max_eps);
    if (c.peak_reaction_N > mt.peak_reaction_N) {
      mt.peak_reaction_N = c.peak_reaction_N;
      mt.angle_at_peak_reaction_rad = c.angle_at_peak_reaction_rad;
    }
    mt.peak_acceleration_m_s2 = std::max(mt.peak_acceleration_m_s2, c.peak_acceleration_m_s2);
    mt.periodicity = std::max(mt.periodicity, c.periodicity);
  }
  const int mj = scene.metrics.joint;
  mt.has_film = mj >= 0 && scene.joints[mj].type == JointType::lubricated_revolute;
  if (!mt.has_film || !std::isfinite(mt.min_film_thickness_m)) mt.min_film_thickness_m = 0.0;
  if (mt.has_film) {
    mt.safe_film_m = scene.metrics.safe_film_per_diameter * 2.0 * scene.joints[mj].bearing.bearing_radius_m;
    mt.below_safe_film = mt.min_film_thickness_m < mt.safe_film_m;
  }
  return mt;
}

}  // namespace lub::detail
