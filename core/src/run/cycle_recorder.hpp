// The per-cycle measurements of a run segment (internal to the run stage): each crank
// cycle's extremes (film, reaction, acceleration) from the observations it is given, the
// journal orbit at fixed crank angles for the cycle-to-cycle distance (periodicity), and
// the metric joint's state at the cycle's end (a Poincaré section at crank angle 0).
#pragma once

#include <optional>
#include <vector>

#include "lub/mechanism/model.hpp"
#include "lub/run/run.hpp"
#include "lub/scene/scene.hpp"

namespace lub::detail {

/// Orbit samples per cycle (every 3°) for the periodicity measure.
constexpr int kPhasePoints = 120;

class CycleRecorder {
 public:
  CycleRecorder(const Scene& scene, const Model& m, double t0, std::optional<double> period);

  /// Crank angle of time t in [0, 2π) (0 without a period).
  double phase_angle(double t) const;
  /// One measuring observation at t (a step end or a phase point), after evaluate() into
  /// `ws` with accelerations `qdd`: the cycle's extremes. Where ε̇ of the metric film went
  /// from + to − since the last one, the peak between them from the cubic through both
  /// observations' ε and ε̇ (hermite_interior_max, metrics.hpp).
  /// The metric film's peak pressure and power loss too, with the body velocities `v`.
  void measure(double t, const Workspace& ws, const double* v, const double* qdd);
  /// The orbit of every film at the next phase point (the first body's position without a film).
  void phase_point(const double* q, const double* v);
  /// The metric joint's e/c and ė/c at the cycle's end, state (q, v).
  void section(const double* qv);
  /// Closes the cycle at t_end (periodicity against the previous cycle's orbit) onto
  /// `cycles`, and starts the next.
  void close(double t_end, std::vector<CycleMetrics>& cycles);
  /// No observation measured since the cycle began.
  bool empty() const { return empty_; }

 private:
  const Scene& scene_;
  const Model& m_;
  double t0_;
  std::optional<double> period_;
  CycleMetrics cur_;
  bool empty_ = true;
  /// The metric film at this cycle's last measuring observation: the other end of the
  /// interval an ε peak is interpolated on. A peak in the interval that spans a cycle
  /// boundary is not interpolated (the closed cycle cannot change).
  struct FilmObservation {
    bool valid = false;
    double t = 0.0, eps = 0.0, eps_dot = 0.0;
  } prev_film_;
  /// Orbit of every film at the phase points (e/c, 2 per film): this cycle's and the last's.
  std::vector<double> orbit_cur_, orbit_prev_;
  int phase_index_ = 0;

  /// The film power loss at the last measuring observation (trapezoidal rule over the cycle).
  struct PowerObservation {
    bool valid = false;
    double t = 0.0, power = 0.0;
  } prev_power_;
  double loss_energy_J_ = 0.0;
  /// Direction of the metric film's force at the cycle's first measuring observation, in the
  /// bearing body's frame (a load that turns by more than 90° from it reverses).
  std::optional<Eigen::Vector2d> load_direction_;

  void film_extreme(double eps, double angle);
  /// Peak pressure and power loss of the metric film f at this observation.
  void film_outputs(double t, const Workspace& ws, int f, const double* v);
};

}  // namespace lub::detail
