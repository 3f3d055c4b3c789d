// The period map of shooting (internal to the run stage): P takes the mechanism's state at
// crank angle 0, in the chart's independent coordinates, once round the crank.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lub/formulation/multibody_system.hpp"
#include "lub/steady/periodic_orbit.hpp"
#include "run/segment.hpp"

namespace lub::detail {

/// The coordinates shooting works in: the partitioned formulation's independent
/// coordinates and velocities, partitioned once at the state where shooting starts
/// (whatever formulation integrates the periods), each in its own unit.
class Chart {
 public:
  Chart(RunModel& rm, const StartState& x);
  int size() const { return n_; }
  /// Each coordinate's unit (state_units reduced to the chart).
  const std::vector<double>& units() const { return units_; }
  /// The chart coordinates of a full state (q, v).
  Eigen::VectorXd reduce(const std::vector<double>& qv) const;
  void reduce(const double* qv, double* z) const { sys_.reduce(qv, z); }
  /// The consistent state at time t with independent part z (the observer context: its
  /// Newton starts from the partition's state every time, so the map is a function of z).
  bool expand(double t, const double* z, std::vector<double>& qv);
  /// The independent coordinates (indices of q) the chart was partitioned with.
  const std::vector<int>& independent() const { return sys_.independent(); }

 private:
  MultibodySystem sys_;
  std::vector<double> units_;
  int n_ = 0;
};

/// How much each coordinate advances over one period: 2π k for a body angle that turns
/// (the crank), 0 otherwise; from two successive cycle boundaries.
std::vector<double> winding_per_period(const Model& m, const StartState& a, const StartState& b);

/// P: one crank period from a state at the start's time and film modes, at rtol × factor;
/// the periods it integrates and their costs are added to the run's.
class PeriodMap final : public steady::CycleMap {
 public:
  PeriodMap(RunModel& rm, Chart& chart, const StartState& base, std::vector<double> winding, double rtol_factor,
            SolverStats& stats, long long& periods);

  int dim() const override { return chart_.size(); }
  int apply(const double* z, double* Pz) override;
  const std::string& last_failure() const { return failure_; }
  /// A period that takes far more steps than the transient's did has left the orbit's
  /// neighbourhood (near the wall the printed law's corrector crawls at h ~ 1e-8 s for
  /// minutes before it fails): it fails instead.
  void set_step_budget(long long n) { max_steps_ = n; }
  /// The run's budget of periods (simulation.max_periods, less what the case spent before
  /// this run): a period that would pass it is not started, and the map refuses (apply
  /// returns −1: shooting stops).
  void set_period_budget(long long n) { max_periods_ = n; }
  /// Whether the map refused for the budget.
  bool refused() const { return refused_; }

 private:
  RunModel& rm_;
  Chart& chart_;
  const StartState& base_;
  std::vector<double> winding_;
  double rtol_factor_;
  SolverStats& stats_;
  long long& periods_;
  std::string failure_;
  long long max_steps_ = 0;
  long long max_periods_ = std::numeric_limits<long long>::max();
  bool refused_ = false;
};

}  // namespace lub::detail
