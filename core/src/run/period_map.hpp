// The period map of shooting (internal to the run stage): P takes the mechanism's state at
// crank angle 0, in the chart's independent coordinates, once round the crank.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lub/formulation/multibody_system.hpp"
#include "lub/scene/scene.hpp"
#include "lub/steady/periodic_orbit.hpp"
#include "run/segment.hpp"

namespace lub::detail {

/// The coordinates shooting works in (simulation.shooting_coordinates), each in its own unit:
///  - independent: the mechanism's own degrees of freedom and their rates. Where the joint
///    formulation integrates the periods, its tree's coordinates (a revolute's body angle,
///    a slide's travel): every z is a consistent state by forward kinematics, no chart to
///    fix. Otherwise the partitioned formulation's independent coordinates and velocities,
///    partitioned once at the state where shooting starts, the dependent ones recovered by
///    Newton;
///  - wall: each lubricated joint's wall coordinates w and their rates ẇ
///    (wall_coordinates.hpp), where the journals' eccentricities are a complete set of
///    coordinates (the drivers move everything else: 2 per film, a regular map from the
///    independent coordinates); elsewhere the independent ones.
class Chart {
 public:
  Chart(RunModel& rm, const StartState& x, ShootingCoordinates kind = ShootingCoordinates::independent);
  int size() const { return n_; }
  /// Each coordinate's unit (state_units reduced to the chart; wall: 1 and the driver's rate).
  const std::vector<double>& units() const { return units_; }
  /// The units a residual is measured in: `units`, in the wall chart × 1/(1 − ε²) of each
  /// journal at the start, so that a tolerance means what it means in the independent
  /// coordinates (an eccentricity change in clearances), however thin the film.
  const std::vector<double>& residual_units() const { return residual_units_; }
  /// The chart coordinates of a full state (q, v).
  Eigen::VectorXd reduce(const std::vector<double>& qv) const;
  void reduce(const double* qv, double* z) const;
  /// The consistent state at time t with chart coordinates z (the observer context: its
  /// Newton starts from the partition's state every time, so the map is a function of z).
  bool expand(double t, const double* z, std::vector<double>& qv);
  /// The chart's coordinates, which a seed's monodromy must share: the independent
  /// coordinates (indices of q) the chart was partitioned with, −1, −2, … (wall), or
  /// kJointChart − i for the joint tree's coordinate i.
  const std::vector<int>& independent() const { return ids_; }
  /// Whether the chart is the wall-safe one.
  bool wall() const { return wall_; }
  /// independent()'s code for the joint tree's coordinate 0 (then −1 for each next one).
  static constexpr int kJointChart = -1000;

 private:
  /// The wall chart applies at x: 2 coordinates per film, every ε < 1, a regular map.
  bool wall_applies(const StartState& x);
  /// Wall: the eccentricities u = e/c and rates of every film at qv (2 nf each).
  void film_state(const double* qv, Eigen::VectorXd& u, Eigen::VectorXd& u_dot) const;
  /// Wall: ∂u/∂y at the partition's coordinates y (empty if the state cannot be recovered).
  Eigen::MatrixXd eccentricity_jacobian(double t, const std::vector<double>& y);
  /// Wall: the partition's coordinates y whose state has eccentricities u* and rates u̇*.
  bool solve_partition(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& u_dot, std::vector<double>& qv);

  const Model& model_;
  MultibodySystem sys_;
  std::vector<double> units_, residual_units_;
  std::vector<int> ids_;
  int n_ = 0;
  bool wall_ = false;
  std::vector<double> y0_;       ///< wall: the partition's coordinates at the start
  std::vector<double> y_units_;  ///< wall: their units
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
  /// The period with its forward sensitivities (SegmentOptions::sensitivities): on the joint
  /// formulation's chart, whose coordinates are the integrated ones, M is their sensitivity
  /// over the period; elsewhere (the wall chart, the partitioned formulation, a method
  /// without sensitivities, a film's mode switch) kNoDerivative, `last_failure` saying why.
  int apply_with_derivative(const double* z, double* Pz, double* M) override;
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
  /// Its rtol over the scene's.
  double rtol_factor() const { return rtol_factor_; }
  /// The same map at `factor` times its rtol (and `step_factor` times its step budget),
  /// sharing its run's costs and budget of periods.
  PeriodMap tighter(double factor, long long step_factor) const {
    PeriodMap twin(rm_, chart_, base_, winding_, rtol_factor_ * factor, stats_, periods_);
    twin.max_steps_ = max_steps_ * step_factor;
    twin.max_periods_ = max_periods_;
    return twin;
  }

 private:
  RunModel& rm_;
  Chart& chart_;
  const StartState& base_;
  std::vector<double> winding_;
  double rtol_factor_;
  SolverStats& stats_;
  long long& periods_;
  /// One period from z into Pz (with its sensitivities into `S` if asked); as apply().
  int period(const double* z, double* Pz, bool sensitivities, std::vector<double>* S);

  std::string failure_;
  /// Why this map has no derivative, once a period has said so for good (a film's mode
  /// switched in it: its later periods would switch too, and each try costs a period).
  std::string no_derivative_;
  long long max_steps_ = 0;
  long long max_periods_ = std::numeric_limits<long long>::max();
  bool refused_ = false;
};

}  // namespace lub::detail
