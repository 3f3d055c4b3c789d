#include "run/period_map.hpp"

#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "lub/common/constants.hpp"
#include "lub/mechanism/film_element.hpp"
#include "run/integration_plan.hpp"
#include "run/wall_coordinates.hpp"

namespace lub::detail {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
Workspace& reset_chart_workspace(RunModel& rm) {
  rm.chart_ws.reset(rm.model);
  return rm.chart_ws;
}
/// The joint tree's coordinates where the joint formulation integrates the periods (the
/// plan's choice, its fall-backs included), else the partitioned ones.
Formulation chart_formulation(const RunModel& rm) {
  return plan_integration(rm.scene, rm.model, 1.0).formulation == Formulation::joint ? Formulation::joint
                                                                                 : Formulation::partitioned;
}
}  // namespace

Chart::Chart(RunModel& rm, const StartState& x, ShootingCoordinates kind)
    : model_(rm.model), sys_(rm.model, reset_chart_workspace(rm), rm.stab, rm.scene.simulation.eps_limit, false,
                             chart_formulation(rm)) {
  const bool joint = sys_.formulation() == Formulation::joint;
  if (!joint) sys_.partition(x.t, x.qv.data());
  n_ = sys_.size();
  const Eigen::VectorXd full = state_units(rm.scene, rm.model);
  units_.assign(static_cast<size_t>(n_), 0.0);
  sys_.reduce_units(full.data(), units_.data());
  residual_units_ = units_;
  if (joint) {
    ids_.resize(static_cast<size_t>(n_ / 2));
    for (int i = 0; i < n_ / 2; ++i) ids_[static_cast<size_t>(i)] = kJointChart - i;
  } else {
    ids_ = sys_.independent();
  }
  if (kind != ShootingCoordinates::wall || !wall_applies(x)) return;
  // The wall chart: w in units of 1, ẇ in the driver's rate (the unit of a rate is the
  // length's times it, state_units).
  const int m = n_ / 2;
  const double rate = units_[static_cast<size_t>(m)] / units_[0];
  Eigen::VectorXd u, u_dot;
  film_state(x.qv.data(), u, u_dot);
  // One code per coordinate, as independent() has one index per coordinate (m of them).
  ids_.assign(static_cast<size_t>(m), 0);
  for (int i = 0; i < m; ++i) {
    const double stretch = wall_stretch(u.segment<2>(2 * (i / 2)).norm());
    units_[static_cast<size_t>(i)] = 1.0;
    units_[static_cast<size_t>(m + i)] = rate;
    residual_units_[static_cast<size_t>(i)] = stretch;
    residual_units_[static_cast<size_t>(m + i)] = rate * stretch;
    ids_[static_cast<size_t>(i)] = -1 - i;
  }
  wall_ = true;
}

bool Chart::wall_applies(const StartState& x) {
  const int nf = static_cast<int>(model_.films.size());
  if (nf == 0 || n_ != 4 * nf) return false;
  Eigen::VectorXd u, u_dot;
  film_state(x.qv.data(), u, u_dot);
  for (int k = 0; k < nf; ++k)
    if (!(u.segment<2>(2 * k).norm() < 1.0)) return false;
  // The eccentricities as functions of the independent coordinates: a regular map.
  y0_.assign(static_cast<size_t>(n_), 0.0);
  sys_.reduce(x.qv.data(), y0_.data());
  y_units_ = units_;
  const Eigen::MatrixXd D = eccentricity_jacobian(x.t, y0_);
  if (D.size() == 0) return false;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(D);
  return lu.rank() == D.rows() && lu.rcond() > 1e-8;
}

void Chart::film_state(const double* qv, Eigen::VectorXd& u, Eigen::VectorXd& u_dot) const {
  const int nf = static_cast<int>(model_.films.size());
  u.resize(2 * nf);
  u_dot.resize(2 * nf);
  for (int k = 0; k < nf; ++k) {
    const FilmKinematics fk = film_kinematics(model_, k, qv, qv + model_.nq);
    const double c = model_.films[static_cast<size_t>(k)].clearance;
    u.segment<2>(2 * k) = fk.e / c;
    u_dot.segment<2>(2 * k) = fk.e_dot / c;
  }
}

Eigen::MatrixXd Chart::eccentricity_jacobian(double t, const std::vector<double>& y) {
  // ∂u/∂y by forward differences of 1e-6 of each coordinate's unit: the map is smooth
  // (rigid-body kinematics), the error O(1e-6) only slows the Newton that uses it.
  const int m = n_ / 2;
  std::vector<double> qv(static_cast<size_t>(2 * model_.nq)), yp = y;
  Eigen::VectorXd u0, up, rate;
  if (sys_.expand(t, y.data(), qv.data(), MultibodySystem::Context::observer) != 0) return {};
  film_state(qv.data(), u0, rate);
  Eigen::MatrixXd D(m, m);
  for (int j = 0; j < m; ++j) {
    const double h = 1e-6 * y_units_[static_cast<size_t>(j)];
    yp[static_cast<size_t>(j)] = y[static_cast<size_t>(j)] + h;
    if (sys_.expand(t, yp.data(), qv.data(), MultibodySystem::Context::observer) != 0) return {};
    film_state(qv.data(), up, rate);
    D.col(j) = (up - u0) / h;
    yp[static_cast<size_t>(j)] = y[static_cast<size_t>(j)];
  }
  return D;
}

bool Chart::solve_partition(double t, const Eigen::VectorXd& u_target, const Eigen::VectorXd& u_dot_target,
                            std::vector<double>& qv) {
  // Newton on the partition's coordinates y for u(y) = u*, then on its rates for
  // u̇ = u*̇ (linear in them, with the same Jacobian: u̇ = D ẏ + ∂u/∂t), each from the
  // start's y every time: the chart is a function of z alone.
  const int m = n_ / 2;
  std::vector<double> y = y0_;
  const Eigen::MatrixXd D = eccentricity_jacobian(t, y);
  if (D.size() == 0) return false;
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(D);
  Eigen::VectorXd u, u_dot;
  // Positions, then rates: each converges linearly at the difference Jacobian's 1e-6.
  for (int part = 0; part < 2; ++part) {
    const Eigen::VectorXd& target = part == 0 ? u_target : u_dot_target;
    double last = kInf;
    for (int it = 0;; ++it) {
      if (sys_.expand(t, y.data(), qv.data(), MultibodySystem::Context::observer) != 0) return false;
      film_state(qv.data(), u, u_dot);
      const Eigen::VectorXd r = (part == 0 ? u : u_dot) - target;
      const double size = r.lpNorm<Eigen::Infinity>();
      // Converged at round-off (a position of ~1 m resolves ~1e-16 m: ~1e-12 of a clearance).
      if (size <= 1e-14 * std::max(1.0, target.lpNorm<Eigen::Infinity>())) break;
      if (it >= 8 || size >= 0.5 * last) {
        if (size <= 1e-10 * std::max(1.0, target.lpNorm<Eigen::Infinity>())) break;
        return false;
      }
      last = size;
      const Eigen::VectorXd dy = lu.solve(r);
      for (int i = 0; i < m; ++i) y[static_cast<size_t>(part * m + i)] -= dy(i);
    }
  }
  return true;
}

Eigen::VectorXd Chart::reduce(const std::vector<double>& qv) const {
  Eigen::VectorXd z(n_);
  reduce(qv.data(), z.data());
  return z;
}

void Chart::reduce(const double* qv, double* z) const {
  if (!wall_) {
    sys_.reduce(qv, z);
    return;
  }
  const int m = n_ / 2;
  Eigen::VectorXd u, u_dot;
  film_state(qv, u, u_dot);
  Eigen::Vector2d w, w_dot;
  for (int k = 0; k < m / 2; ++k) {
    to_wall_coordinates(u.segment<2>(2 * k), u_dot.segment<2>(2 * k), w, w_dot);
    z[2 * k] = w.x();
    z[2 * k + 1] = w.y();
    z[m + 2 * k] = w_dot.x();
    z[m + 2 * k + 1] = w_dot.y();
  }
}

bool Chart::expand(double t, const double* z, std::vector<double>& qv) {
  if (!wall_) return sys_.expand(t, z, qv.data(), MultibodySystem::Context::observer) == 0;
  const int m = n_ / 2;
  Eigen::VectorXd u(m), u_dot(m);
  Eigen::Vector2d uk, uk_dot;
  for (int k = 0; k < m / 2; ++k) {
    if (!from_wall_coordinates({z[2 * k], z[2 * k + 1]}, {z[m + 2 * k], z[m + 2 * k + 1]}, uk, uk_dot))
      return false;
    u.segment<2>(2 * k) = uk;
    u_dot.segment<2>(2 * k) = uk_dot;
  }
  return solve_partition(t, u, u_dot, qv);
}

std::vector<double> winding_per_period(const Model& m, const StartState& a, const StartState& b) {
  std::vector<double> w(b.qv.size(), 0.0);
  for (int body = 0; body < m.nb; ++body) {
    const size_t i = static_cast<size_t>(3 * body + 2);
    w[i] = kTwoPi * std::round((b.qv[i] - a.qv[i]) / (kTwoPi));
  }
  return w;
}

PeriodMap::PeriodMap(RunModel& rm, Chart& chart, const StartState& base, std::vector<double> winding,
                     double rtol_factor, SolverStats& stats, long long& periods)
    : rm_(rm), chart_(chart), base_(base), winding_(std::move(winding)), rtol_factor_(rtol_factor), stats_(stats),
      periods_(periods) {}

int PeriodMap::apply(const double* z, double* Pz) { return period(z, Pz, false, nullptr); }

int PeriodMap::apply_with_derivative(const double* z, double* Pz, double* M) {
  if (chart_.wall() || chart_.independent().empty() || chart_.independent()[0] != Chart::kJointChart)
    no_derivative_ = "the period map's derivative by sensitivities needs the joint formulation's chart";
  if (!no_derivative_.empty()) {
    failure_ = no_derivative_;
    return kNoDerivative;
  }
  std::vector<double> S;
  const int rc = period(z, Pz, true, &S);
  if (rc != 0) return rc;
  if (S.size() != static_cast<size_t>(dim()) * static_cast<size_t>(dim())) {
    no_derivative_ = failure_;  // the segment's note: why none
    return kNoDerivative;
  }
  std::copy(S.begin(), S.end(), M);
  return 0;
}

int PeriodMap::period(const double* z, double* Pz, bool sensitivities, std::vector<double>* S) {
  if (periods_ >= max_periods_) {
    failure_ = "simulation.max_periods reached";
    refused_ = true;
    return -1;
  }
  StartState start = base_;
  if (!chart_.expand(base_.t, z, start.qv)) {
    failure_ = "the dependent coordinates cannot be recovered at the period's start";
    return 1;
  }
  SegmentOptions o;
  o.start = &start;
  o.cycles = 1;
  o.observe = false;
  o.series = false;
  o.rtol_factor = rtol_factor_;
  o.max_steps = max_steps_;
  o.sensitivities = sensitivities;
  SegmentResult period = run_segment(rm_, o);
  accumulate(stats_, period.res.stats);
  ++periods_;
  if (period.res.status != RunStatus::ok) {
    failure_ = period.res.message;
    return 1;
  }
  std::vector<double> end = period.end.qv;
  for (size_t i = 0; i < end.size(); ++i) end[i] -= winding_[i];
  chart_.reduce(end.data(), Pz);
  if (S) {
    *S = std::move(period.sensitivity);
    if (S->empty()) failure_ = period.sensitivity_note;
  }
  return 0;
}

}  // namespace lub::detail
