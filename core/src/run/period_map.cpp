#include "run/period_map.hpp"

#include <cmath>

#include "lub/common/constants.hpp"
#include "run/integration_plan.hpp"

namespace lub::detail {

namespace {
Workspace& reset_chart_workspace(RunModel& rm) {
  rm.chart_ws.reset(rm.model);
  return rm.chart_ws;
}
}  // namespace

Chart::Chart(RunModel& rm, const StartState& x)
    : sys_(rm.model, reset_chart_workspace(rm), rm.stab, rm.scene.simulation.eps_limit, false,
           Formulation::partitioned) {
  sys_.partition(x.t, x.qv.data());
  n_ = sys_.size();
  const Eigen::VectorXd full = state_units(rm.scene, rm.model);
  units_.assign(static_cast<size_t>(n_), 0.0);
  sys_.reduce(full.data(), units_.data());
}

Eigen::VectorXd Chart::reduce(const std::vector<double>& qv) const {
  Eigen::VectorXd z(n_);
  sys_.reduce(qv.data(), z.data());
  return z;
}

bool Chart::expand(double t, const double* z, std::vector<double>& qv) {
  return sys_.expand(t, z, qv.data(), MultibodySystem::Context::observer) == 0;
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

int PeriodMap::apply(const double* z, double* Pz) {
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
  const SegmentResult period = run_segment(rm_, o);
  accumulate(stats_, period.res.stats);
  ++periods_;
  if (period.res.status != RunStatus::ok) {
    failure_ = period.res.message;
    return 1;
  }
  std::vector<double> end = period.end.qv;
  for (size_t i = 0; i < end.size(); ++i) end[i] -= winding_[i];
  chart_.reduce(end.data(), Pz);
  return 0;
}

}  // namespace lub::detail
