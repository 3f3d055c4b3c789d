// Steady-cycle metrics: see metrics.hpp.
#include "run/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lub/common/constants.hpp"

namespace lub {

const std::array<SteadyMetric, 12>& steady_metrics() {
  static const std::array<SteadyMetric, 12> table{{
      {"min_film_thickness_m", "m", "minimum film thickness h = c (1 - eps) over the metric cycles",
       "minimum film thickness in the cycle",
       ": change at a 100x tighter rtol (+ the transient's remaining change)", &Metrics::min_film_thickness_m,
       &Metrics::min_film_thickness_m_error, &CycleMetrics::min_film_thickness_m, false},
      {"crank_angle_at_min_film_rad", "rad", "crank angle at the minimum film thickness, in [0, 2 pi)",
       "crank angle at the minimum film thickness", "", &Metrics::crank_angle_at_min_film_rad,
       &Metrics::crank_angle_at_min_film_rad_error, &CycleMetrics::crank_angle_at_min_film_rad, true},
      {"max_eps", "1", "largest eccentricity ratio |e|/c over the metric cycles",
       "largest eccentricity ratio in the cycle", "", &Metrics::max_eps, &Metrics::max_eps_error,
       &CycleMetrics::max_eps, false},
      {"peak_reaction_N", "N", "peak force transmitted by the metric joint",
       "peak force transmitted by the metric joint", "", &Metrics::peak_reaction_N, &Metrics::peak_reaction_N_error,
       &CycleMetrics::peak_reaction_N, false},
      {"crank_angle_at_peak_reaction_rad", "rad", "crank angle at the peak joint force, in [0, 2 pi)",
       "crank angle at the peak joint force", "", &Metrics::crank_angle_at_peak_reaction_rad,
       &Metrics::crank_angle_at_peak_reaction_rad_error, &CycleMetrics::crank_angle_at_peak_reaction_rad, true},
      {"peak_acceleration_m_s2", "m s-2", "peak acceleration magnitude of the metric body",
       "peak acceleration of the metric body", "", &Metrics::peak_acceleration_m_s2,
       &Metrics::peak_acceleration_m_s2_error, &CycleMetrics::peak_acceleration_m_s2, false},
      {"peak_asperity_load_N", "N",
       "peak asperity (Greenwood-Tripp) load of the metric joint; 0 without mixed lubrication",
       "asperity load of the metric joint at the cycle's largest eccentricity", "",
       &Metrics::peak_asperity_load_N, &Metrics::peak_asperity_load_N_error, &CycleMetrics::peak_asperity_load_N,
       false},
      {"asperity_load_ratio", "1", "peak asperity load over the peak force of the metric joint",
       "peak asperity load over the peak joint force in the cycle", "", &Metrics::asperity_load_ratio,
       &Metrics::asperity_load_ratio_error, &CycleMetrics::asperity_load_ratio, false},
      {"peak_film_pressure_Pa", "Pa",
       "largest film pressure of the metric joint over the metric cycles (metrics.peak_pressure; NaN: not measured)",
       "largest film pressure of the metric joint in the cycle", "", &Metrics::peak_film_pressure_Pa,
       &Metrics::peak_film_pressure_Pa_error, &CycleMetrics::peak_film_pressure_Pa, false},
      {"crank_angle_at_peak_pressure_rad", "rad", "crank angle at the peak film pressure (NaN: not measured)",
       "crank angle at the cycle's peak film pressure", "", &Metrics::crank_angle_at_peak_pressure_rad,
       &Metrics::crank_angle_at_peak_pressure_rad_error, &CycleMetrics::crank_angle_at_peak_pressure_rad, true},
      {"peak_pressure_angle_rad", "rad",
       "angle of the peak film pressure in the bearing, from the line of maximum film thickness (NaN: not measured)",
       "angle of the cycle's peak film pressure from the line of maximum film", "", &Metrics::peak_pressure_angle_rad,
       &Metrics::peak_pressure_angle_rad_error, &CycleMetrics::peak_pressure_angle_rad, true},
      {"film_power_loss_W", "W",
       "film power loss of the metric joint (shear and pressure), mean over the metric cycles",
       "film power loss of the metric joint, mean over the cycle", "", &Metrics::film_power_loss_W,
       &Metrics::film_power_loss_W_error, &CycleMetrics::film_power_loss_W, false},
  }};
  return table;
}

double metric_distance(const SteadyMetric& metric, double a, double b) {
  return metric.angle ? std::abs(std::remainder(a - b, kTwoPi)) : std::abs(a - b);
}

}  // namespace lub

namespace lub::detail {

Metrics steady_cycle_metrics(const Scene& scene, const std::vector<CycleMetrics>& cycles, int cycles_done) {
  Metrics mt;
  mt.cycles_run = cycles_done;
  const int M = std::min<int>(scene.simulation.metric_cycles, static_cast<int>(cycles.size()));
  mt.min_film_thickness_m = std::numeric_limits<double>::infinity();
  for (int i = 0; i < M; ++i) {
    const CycleMetrics& c = cycles[cycles.size() - 1 - i];
    if (c.min_film_thickness_m < mt.min_film_thickness_m) {
      mt.min_film_thickness_m = c.min_film_thickness_m;
      mt.crank_angle_at_min_film_rad = c.crank_angle_at_min_film_rad;
    }
    mt.max_eps = std::max(mt.max_eps, c.max_eps);
    if (c.peak_reaction_N > mt.peak_reaction_N) {
      mt.peak_reaction_N = c.peak_reaction_N;
      mt.crank_angle_at_peak_reaction_rad = c.crank_angle_at_peak_reaction_rad;
    }
    mt.peak_acceleration_m_s2 = std::max(mt.peak_acceleration_m_s2, c.peak_acceleration_m_s2);
    mt.peak_asperity_load_N = std::max(mt.peak_asperity_load_N, c.peak_asperity_load_N);
    mt.asperity_load_ratio = std::max(mt.asperity_load_ratio, c.asperity_load_ratio);
    if (c.peak_film_pressure_Pa > mt.peak_film_pressure_Pa) {
      mt.peak_film_pressure_Pa = c.peak_film_pressure_Pa;
      mt.crank_angle_at_peak_pressure_rad = c.crank_angle_at_peak_pressure_rad;
      mt.peak_pressure_angle_rad = c.peak_pressure_angle_rad;
    }
    mt.film_power_loss_W += c.film_power_loss_W / M;
    mt.periodicity = std::max(mt.periodicity, c.periodicity);
    mt.load_reverses = mt.load_reverses || c.load_reverses;
  }
  const int mj = scene.metrics.joint;
  mt.has_film = mj >= 0 && scene.joints[mj].type == JointType::lubricated_revolute;
  if (!mt.has_film || !scene.metrics.peak_pressure) {
    mt.peak_film_pressure_Pa = std::numeric_limits<double>::quiet_NaN();
    mt.crank_angle_at_peak_pressure_rad = std::numeric_limits<double>::quiet_NaN();
    mt.peak_pressure_angle_rad = std::numeric_limits<double>::quiet_NaN();
  }
  if (!mt.has_film) mt.film_power_loss_W = std::numeric_limits<double>::quiet_NaN();
  if (!mt.has_film || !std::isfinite(mt.min_film_thickness_m)) mt.min_film_thickness_m = 0.0;
  if (mt.has_film) {
    mt.safe_film_thickness_m = scene.metrics.safe_film_per_diameter * 2.0 * scene.joints[mj].bearing.bearing_radius_m;
    mt.below_safe_film = mt.min_film_thickness_m < mt.safe_film_thickness_m;
  }
  return mt;
}

InteriorMax hermite_interior_max(double t0, double x0, double r0, double t1, double x1, double r1) {
  // On s ∈ [0, 1], h = t1 − t0, m_i = h r_i:
  //   p(s)  = (2s³ − 3s² + 1) x0 + (s³ − 2s² + s) m0 + (−2s³ + 3s²) x1 + (s³ − s²) m1,
  //   p'(s) = a s² + b s + m0,  a = 6(x0 − x1) + 3(m0 + m1),  b = 6(x1 − x0) − 4 m0 − 2 m1,
  // with p'(0) = m0 > 0 > m1 = p'(1): exactly one root in (0, 1), the maximum. The root
  // formula that does not cancel (q = −(b + sign(b)√disc)/2: roots q/a and m0/q).
  const double h = t1 - t0, m0 = h * r0, m1 = h * r1;
  const double a = 6.0 * (x0 - x1) + 3.0 * (m0 + m1), b = 6.0 * (x1 - x0) - 4.0 * m0 - 2.0 * m1;
  double s = 0.5;
  if (std::abs(a) <= 1e-14 * (std::abs(b) + std::abs(m0))) {
    s = -m0 / b;  // p' linear (b = m1 − m0 < 0 then)
  } else {
    const double disc = std::max(0.0, b * b - 4.0 * a * m0);
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    for (const double root : {q / a, q != 0.0 ? m0 / q : -1.0})
      if (root > 0.0 && root < 1.0) s = root;
  }
  s = std::clamp(s, 0.0, 1.0);
  const double s2 = s * s, s3 = s2 * s;
  const double p = (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * x1 + (s3 - s2) * m1;
  return {t0 + s * h, std::max({p, x0, x1})};
}

}  // namespace lub::detail
