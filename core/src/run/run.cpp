#include "lub/run/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "lub/common/constants.hpp"
#include "lub/integrators/integrator.hpp"
#include "lub/mechanism/film_element.hpp"
#include "lub/mechanism/builder.hpp"
#include "lub/mechanism/model.hpp"
#include "lub/formulation/multibody_system.hpp"
#include "run/metrics.hpp"
#include "run/segment.hpp"
#include "lub/steady/contraction.hpp"

namespace lub {

namespace {

constexpr int kPhasePoints = 120;
constexpr size_t kMaxBoundaries = 4096;  // cycle-boundary states a segment keeps  // orbit samples per cycle (every 3°) for the periodicity measure

// Everything measured at one instant.
struct Probe {
  double t = 0.0;
  const double* q = nullptr;
  const double* v = nullptr;
  const double* a = nullptr;
};

double channel_value(const Scene& scene, const Model& m, const Workspace& ws, const ChannelSpec& c,
                     const Probe& p) {
  if (c.source == ChannelSource::time) return p.t;
  if (c.source == ChannelSource::body) {
    const int o = 3 * c.index;
    switch (c.body_quantity) {
      case BodyQuantity::x: return p.q[o];
      case BodyQuantity::y: return p.q[o + 1];
      case BodyQuantity::angle: return p.q[o + 2];
      case BodyQuantity::vx: return p.v[o];
      case BodyQuantity::vy: return p.v[o + 1];
      case BodyQuantity::omega: return p.v[o + 2];
      case BodyQuantity::ax: return p.a[o];
      case BodyQuantity::ay: return p.a[o + 1];
      case BodyQuantity::alpha: return p.a[o + 2];
    }
    return 0.0;
  }
  const JointQuantity qn = c.joint_quantity;
  if (qn == JointQuantity::reaction) return joint_force(m, ws, c.index).norm();
  if (qn == JointQuantity::reaction_x) return joint_force(m, ws, c.index).x();
  if (qn == JointQuantity::reaction_y) return joint_force(m, ws, c.index).y();
  const int f = m.joint_film[c.index];
  const double clearance = scene.joints[c.index].bearing.clearance_m();
  if (f < 0) {  // a lubricated joint run as ideal: centred
    if (qn == JointQuantity::h_min) return clearance;
    return 0.0;
  }
  const FilmKinematics& k = ws.films[f];
  switch (qn) {
    case JointQuantity::e_x: return k.e.x();
    case JointQuantity::e_y: return k.e.y();
    case JointQuantity::eps: return k.state.eps;
    case JointQuantity::eps_dot: return k.state.eps_dot;
    case JointQuantity::gamma: return k.gamma();
    case JointQuantity::gamma_dot: return k.gamma_dot;
    case JointQuantity::wedge: return k.state.wedge;
    case JointQuantity::h_min: return clearance * (1.0 - k.state.eps);
    case JointQuantity::film_radial: return k.force.radial_N;
    case JointQuantity::film_tangential: return k.force.tangential_N;
    case JointQuantity::reaction: case JointQuantity::reaction_x: case JointQuantity::reaction_y: break;
  }
  return 0.0;
}

// The rate that scales the velocity tolerances [rad/s]: the fastest driver's speed, or
// 2π over the cycle period or the duration when no driver gives one.
double characteristic_rate(const Scene& scene) {
  double w = 0.0;
  for (const DriverSpec& d : scene.drivers) w = std::max(w, std::abs(d.speed_rad_s));
  if (w > 0.0) return w;
  if (const auto T = scene.cycle_period_s()) return kTwoPi / *T;
  if (scene.simulation.duration_s) return kTwoPi / *scene.simulation.duration_s;
  return 1.0;
}

// How a scene is integrated: the integrator's settings (t_stop aside: the run loop moves
// it), the formulation actually integrated and the absolute tolerances in each state's
// units (README "Integration").
struct IntegrationPlan {
  IntegratorSettings settings;
  Formulation formulation = Formulation::baumgarte;
  bool newton = false;              ///< the method iterates with Newton (uses a Jacobian)
  double atol = 0.0;                ///< the scalar reported in the run's statistics
  std::vector<double> atol_full;    ///< per component of the full state (q, v)
};

IntegrationPlan plan_integration(const Scene& scene, const Model& m) {
  const SolverSpec& sol = scene.solver;
  IntegrationPlan plan;
  IntegratorSettings& is = plan.settings;
  is.method = sol.method;
  is.rtol = sol.rtol;
  // Absolute tolerances in each state's own units (README "Integration", tolerances):
  // lengths from the smallest clearance, angles from it over each body's size, rates
  // from those times the driver's speed. solver.atol overrides them all with one number.
  const double length_scale = scene.min_clearance_m().value_or(1e-3);
  const Eigen::VectorXd scales = detail::state_units(scene, m);
  plan.atol = sol.atol ? *sol.atol : sol.rtol * length_scale;
  plan.atol_full.assign(static_cast<size_t>(2 * m.nq), 0.0);
  for (int i = 0; i < 2 * m.nq; ++i) plan.atol_full[static_cast<size_t>(i)] = sol.atol ? *sol.atol : sol.rtol * scales(i);
  is.max_step = sol.max_step_s;
  is.initial_step = sol.initial_step_s;
  is.max_order = sol.max_order;
  is.projection = sol.projection;
  plan.newton = is_newton(sol.method);
  // A mechanism without a degree of freedom (every coordinate fixed by joints and drivers:
  // the ideal slider-crank) leaves partitioning nothing to integrate: it runs on the
  // baumgarte formulation, whose states are all the coordinates.
  plan.formulation = sol.formulation == Formulation::partitioned && m.nq <= m.nc
                                      ? Formulation::baumgarte
                                      : sol.formulation;
  const bool partitioned = plan.formulation == Formulation::partitioned;
  is.user_jacobian = plan.newton && sol.jacobian == JacobianKind::structured;
  // Partitioned: the integrated coordinates are the mechanism's degrees of freedom (e.g. a
  // rod's angle and the slider's x), and the squeeze film's stiff mode lies almost along
  // one of them. Its Jacobian terms (∝ the journal's whirl rate and the rod's rate) change
  // by their own size within a few degrees of crank; with CVODE's Jacobian reuse the
  // modified Newton stalls in that mode and its first iterate is accepted on a stale rate
  // estimate, so accepted states carry an unconverged stiff component (f(y_n) − y'_n up to
  // ~0.1 rad/s² in the rod's angular acceleration). The error test cannot see it at large
  // h·λ; when the rod's angular velocity crosses zero (90° and 270° of crank) its weight
  // becomes 1/atol, the step is cut to h·λ ~ 1, the component shows as a transient and the
  // error test fails until CVODE gives up. Four states: a Jacobian costs four evaluations.
  // Projection (baumgarte + CVODE's projection) fails the same way at the dead centres,
  // where a step lands on a velocity's zero (the slider's at each cycle boundary) and its
  // weight becomes 1/atol: there the step's local error stays ~3e-10 m/s (~100 atol) in
  // the slider's velocity while h falls from 1e-4 to 3e-8 s, a stiff film transient that
  // no step above 1/λ resolves. Both the stale Jacobian and the projected error estimate
  // (integrator_cvode.cpp) feed it: full factorial on projection, 192 cases, 4 not ok
  // before; 1 with only the Jacobian refreshed, 2 with only the error estimate
  // unprojected, 0 with both (README "Defects", D6). 18 states: 18 evaluations a step.
  // Not with switching none: difference quotients across the printed law's jump make a
  // fresh Jacobian worse than a reused one (hard case law_pinkus_sternlicht_no_events:
  // 38518 Newton failures and the 100000-step budget at 0.8 cycle, against ok in 17795
  // steps with the reused one).
  is.jacobian_every_step = partitioned || (sol.projection && sol.switching == Switching::events);
  return plan;
}

class Runner {
 public:
  Runner(const Scene& scene, const detail::SegmentOptions& opt)
      : scene_(scene), opt_(opt), m_(build_model(scene)), ws_(m_), obs_ws_(m_), period_(scene.cycle_period_s()) {}

  detail::SegmentResult run();

 private:
  /// One observation at (t, y), one evaluation of the model: with `record` a row of the
  /// series; with `measure` the cycle's extremes and the drift statistics. Output samples
  /// that fall at neither a step end nor a phase point only record: the metrics must not
  /// depend on the output rate.
  void observe(double t, const double* y, bool record, bool measure = true);
  void observe_phase(double t, const double* y);
  void close_cycle(double t_end);
  /// The metric joint's eccentricity and its rate at a cycle's end, into cur_.
  void section_state(const double* y);
  double phase_angle(double t) const {
    if (!period_) return 0.0;
    const double x = (t - t0_) / *period_;
    return kTwoPi * (x - std::floor(x));
  }
  /// Sampling: the observations due in the step (t_prev, t] from the integrator's dense
  /// output, in time order (series samples, orbit phase points, cycle ends). True if the
  /// run is to stop (steady).
  bool sample_step(Integrator& integ, MultibodySystem& sys, double t_prev, double t, double t_end);

  const Scene& scene_;
  const detail::SegmentOptions& opt_;
  Model m_;
  Workspace ws_;  ///< the integrator's
  /// The observers' own: what they evaluate (a finite-Reynolds solver's warm start, the
  /// counters) must not reach the integrator's workspace, or how often a run samples
  /// would change its trajectory. Film modes are copied in before each observation.
  Workspace obs_ws_;
  std::optional<double> period_;
  double t0_ = 0.0;
  RunResult res_;
  std::vector<double> qdd_, ytmp_, yfull_, yint_;
  CycleMetrics cur_;
  bool cur_empty_ = true;
  /// The metric film at this cycle's last measuring observation (step end or phase point):
  /// the other end of the interval an ε peak is interpolated on. A peak in the interval
  /// that spans a cycle boundary is not interpolated (the closed cycle cannot change).
  struct FilmObservation {
    bool valid = false;
    double t = 0.0, eps = 0.0, eps_dot = 0.0;
  } prev_film_;
  // orbit of every film at the phase points: current and previous cycle
  std::vector<double> orbit_cur_, orbit_prev_;
  int phase_index_ = 0;
  std::vector<size_t> cycle_first_sample_;  // samples recorded (ever) before each cycle end
  size_t dropped_samples_ = 0;
  // Sampling (sample_step): the next series sample and phase point, cycles closed.
  double dt_sample_ = 0.0, dt_phase_ = 0.0;
  long long sample_k_ = 0, phase_k_ = 0;
  int cycles_done_ = 0;
  std::vector<detail::StartState> boundaries_;
};

void Runner::observe(double t, const double* y, bool record, bool measure) {
  const double* q = y;
  const double* v = y + m_.nq;
  std::copy(ws_.film_mode.begin(), ws_.film_mode.end(), obs_ws_.film_mode.begin());
  std::copy(ws_.slide_radius.begin(), ws_.slide_radius.end(), obs_ws_.slide_radius.begin());
  const Workspace& ws = obs_ws_;
  if (evaluate(m_, obs_ws_, t, q, v, qdd_.data()) != 0) return;
  ++res_.stats.observer_evals;
  if (record) {
    const Probe p{t, q, v, qdd_.data()};
    auto& data = res_.series.data;
    data[0].push_back(t);
    for (size_t c = 0; c < scene_.output.channels.size(); ++c)
      data[c + 1].push_back(channel_value(scene_, m_, ws, scene_.output.channels[c], p));
  }
  if (!measure) return;
  res_.stats.max_position_drift =
      std::max(res_.stats.max_position_drift, m_.nc ? ws.Phi.head(m_.nc).lpNorm<Eigen::Infinity>() : 0.0);
  res_.stats.max_velocity_drift =
      std::max(res_.stats.max_velocity_drift, m_.nc ? ws.Phi_dot.head(m_.nc).lpNorm<Eigen::Infinity>() : 0.0);
  const double angle = phase_angle(t);
  const int mj = scene_.metrics.joint;
  if (cur_empty_) {
    cur_.min_film_m = std::numeric_limits<double>::infinity();
    cur_empty_ = false;
  }
  if (mj >= 0) {
    const double R = joint_force(m_, ws, mj).norm();
    if (R > cur_.peak_reaction_N) {
      cur_.peak_reaction_N = R;
      cur_.angle_at_peak_reaction_rad = angle;
    }
    if (scene_.joints[mj].type == JointType::lubricated_revolute) {
      const int f = m_.joint_film[mj];
      const double eps = f >= 0 ? ws.films[f].state.eps : 0.0;
      const double eps_dot = f >= 0 ? ws.films[f].state.eps_dot : 0.0;
      const double c = scene_.joints[mj].bearing.clearance_m();
      auto film_extreme = [&](double e, double at_angle) {
        // In contact (ε >= 1) the film thickness is zero: the penetration is not a film.
        const double h = std::max(0.0, c * (1.0 - e));
        cur_.max_eps = std::max(cur_.max_eps, e);
        if (h < cur_.min_film_m) {
          cur_.min_film_m = h;
          cur_.angle_at_min_film_rad = at_angle;
        }
      };
      // ε peaked since the last observation of this cycle (ε̇ from + to −): the peak from
      // the cubic through both ends' ε and ε̇ (metrics.hpp, hermite_interior_max).
      if (prev_film_.valid && t > prev_film_.t && prev_film_.eps_dot > 0.0 && eps_dot < 0.0) {
        const detail::InteriorMax mx =
            detail::hermite_interior_max(prev_film_.t, prev_film_.eps, prev_film_.eps_dot, t, eps, eps_dot);
        film_extreme(mx.value, phase_angle(mx.t));
      }
      film_extreme(eps, angle);
      prev_film_ = {true, t, eps, eps_dot};
    }
  }
  if (const int b = scene_.metrics.body; b >= 0) {
    const double a = std::hypot(qdd_[3 * b], qdd_[3 * b + 1]);
    cur_.peak_acceleration_m_s2 = std::max(cur_.peak_acceleration_m_s2, a);
  }
}

void Runner::observe_phase(double /*t*/, const double* y) {
  const double* q = y;
  const double* v = y + m_.nq;
  double* out = orbit_cur_.data() + static_cast<size_t>(phase_index_) * 2 * std::max<size_t>(1, m_.films.size());
  if (m_.films.empty()) {
    // No film: the periodicity of the mechanism itself, from the first body's position.
    out[0] = q[0];
    out[1] = q[1];
  } else {
    for (size_t k = 0; k < m_.films.size(); ++k) {
      const FilmKinematics fk = film_kinematics(m_, static_cast<int>(k), q, v);
      out[2 * k] = fk.e.x() / m_.films[k].clearance;
      out[2 * k + 1] = fk.e.y() / m_.films[k].clearance;
    }
  }
  ++phase_index_;
}

void Runner::section_state(const double* y) {
  const int mj = scene_.metrics.joint;
  const int f = mj >= 0 ? m_.joint_film[mj] : -1;
  if (f < 0) return;
  const FilmKinematics fk = film_kinematics(m_, f, y, y + m_.nq);
  const double c = m_.films[f].clearance;
  cur_.end_eccentricity_x = fk.e.x() / c;
  cur_.end_eccentricity_y = fk.e.y() / c;
  cur_.end_eccentricity_rate_x = fk.e_dot.x() / c;
  cur_.end_eccentricity_rate_y = fk.e_dot.y() / c;
}

void Runner::close_cycle(double t_end) {
  cur_.t_end_s = t_end;
  if (cur_empty_) cur_.min_film_m = 0.0;
  if (!res_.cycles.empty() && phase_index_ == kPhasePoints) {
    double d = 0.0;
    const size_t nf = std::max<size_t>(1, m_.films.size());
    for (int i = 0; i < kPhasePoints; ++i)
      for (size_t k = 0; k < nf; ++k) {
        const size_t o = (static_cast<size_t>(i) * nf + k) * 2;
        d = std::max(d, std::hypot(orbit_cur_[o] - orbit_prev_[o], orbit_cur_[o + 1] - orbit_prev_[o + 1]));
      }
    cur_.periodicity = d;
  }
  res_.cycles.push_back(cur_);
  // outputs.last_cycles: drop the samples of cycles older than the last N.
  if (!res_.series.data.empty()) {
    cycle_first_sample_.push_back(res_.series.data[0].size() + dropped_samples_);
    const int keep = scene_.output.last_cycles;
    if (keep > 0 && static_cast<int>(cycle_first_sample_.size()) > keep) {
      const size_t drop = cycle_first_sample_[cycle_first_sample_.size() - 1 - keep] - dropped_samples_;
      for (auto& ch : res_.series.data) ch.erase(ch.begin(), ch.begin() + static_cast<std::ptrdiff_t>(drop));
      dropped_samples_ += drop;
    }
  }
  std::swap(orbit_cur_, orbit_prev_);
  phase_index_ = 0;
  cur_ = CycleMetrics{};
  cur_.t_start_s = t_end;
  cur_empty_ = true;
  prev_film_ = {};
}

bool Runner::sample_step(Integrator& integ, MultibodySystem& sys, double t_prev, double t, double t_end) {
  const double inf = std::numeric_limits<double>::infinity();
  // The state at tt within the last step, as (q, v): false if it cannot be had.
  auto state_at = [&](double tt) {
    return integ.dense(tt, 0, yint_.data()) &&
           sys.expand(tt, yint_.data(), ytmp_.data(), MultibodySystem::Context::observer) == 0;
  };
  bool stop = false;
  const bool sampling = !res_.series.names.empty();
  const double t_reach = t * (1 + 1e-15);
  while (!stop) {
    const double ts = sampling ? t0_ + sample_k_ * dt_sample_ : inf;
    const double tp = period_ ? t0_ + phase_k_ * dt_phase_ : inf;
    const bool sample_due = ts <= t_reach && ts <= t_end;
    const bool phase_due = tp <= t_reach && tp <= t_end + 0.5 * dt_phase_;
    if (!sample_due && !phase_due) break;
    if (phase_due && (!sample_due || tp <= ts)) {
      ++phase_k_;
      const bool have = state_at(tp);
      if ((phase_k_ - 1) % kPhasePoints == 0) {
        // A cycle ends at tp: its end state (the Poincaré section at crank angle 0), then
        // close it before the first phase point of the next.
        if (have) {
          section_state(ytmp_.data());
          boundaries_.push_back({tp, ytmp_, ws_.film_mode, ws_.slide_radius});
          // The last kMaxBoundaries: what the steady cycle's estimates look back on.
          if (boundaries_.size() > kMaxBoundaries) boundaries_.erase(boundaries_.begin());
        }
        close_cycle(tp);
        ++cycles_done_;
        if (opt_.stop_after_cycle && opt_.stop_after_cycle(res_.cycles)) stop = true;
      }
      if (!stop && have) {
        observe_phase(tp, ytmp_.data());
        observe(tp, ytmp_.data(), sample_due && ts == tp);
        if (sample_due && ts == tp) ++sample_k_;
      }
    } else {
      ++sample_k_;
      if (ts > t_prev && state_at(ts)) observe(ts, ytmp_.data(), /*record=*/true, /*measure=*/false);
    }
  }
  return stop;
}

detail::SegmentResult Runner::run() {
  const auto wall0 = std::chrono::steady_clock::now();
  const SimulationSpec& sim = scene_.simulation;
  const SolverSpec& sol = scene_.solver;
  qdd_.assign(m_.nq, 0.0);
  ytmp_.assign(2 * m_.nq, 0.0);
  yfull_.assign(2 * m_.nq, 0.0);
  const size_t nf = std::max<size_t>(1, m_.films.size());
  orbit_cur_.assign(static_cast<size_t>(kPhasePoints) * nf * 2, 0.0);
  orbit_prev_ = orbit_cur_;

  // Series only if channels were asked for.
  if (opt_.observe && opt_.series && !scene_.output.channels.empty()) {
    res_.series.names.push_back("t");
    res_.series.units.push_back("s");
    for (const auto& c : scene_.output.channels) {
      res_.series.names.push_back(c.name);
      res_.series.units.push_back(channel_unit(c));
    }
    res_.series.data.resize(res_.series.names.size());
  }

  std::vector<double> qv0(2 * m_.nq);
  if (opt_.start) {
    // A given state (shooting's period maps, the steady cycle's measurement): its film
    // modes too. A sliding film slides at the start's own |e| (a perturbed start of a
    // difference quotient moves it).
    t0_ = opt_.start->t;
    qv0 = opt_.start->qv;
    ws_.film_mode = opt_.start->modes;
    ws_.slide_radius = opt_.start->slide_radius;
    for (size_t k = 0; k < m_.films.size(); ++k)
      if (ws_.film_mode[k] == FilmMode::sliding)
        ws_.slide_radius[k] = film_kinematics(m_, static_cast<int>(k), qv0.data(), qv0.data() + m_.nq).e.norm();
  } else {
    Eigen::VectorXd q0, v0;
    assemble_initial_state(m_, scene_, t0_, q0, v0);
    std::copy(q0.data(), q0.data() + m_.nq, qv0.begin());
    std::copy(v0.data(), v0.data() + m_.nq, qv0.begin() + m_.nq);
  }

  const double t_end = opt_.cycles > 0      ? t0_ + opt_.cycles * *period_
                       : sim.duration_s     ? *sim.duration_s
                                            : sim.max_cycles * *period_;
  IntegrationPlan plan = plan_integration(scene_, m_);
  plan.settings.rtol *= opt_.rtol_factor;
  plan.atol *= opt_.rtol_factor;
  for (double& a : plan.atol_full) a *= opt_.rtol_factor;
  IntegratorSettings is = plan.settings;
  const Formulation formulation = plan.formulation;
  const double atol = plan.atol;
  const std::vector<double>& atol_full = plan.atol_full;
  // The stop time: the next cycle boundary (never the end of the run, which would bound
  // SUNDIALS' initial-step estimates at every restart and so make the steps depend on
  // max_cycles), or the end of the run in its last cycle.
  const double eps_t = period_ ? 1e-9 * *period_ : 0.0;
  auto next_stop = [&](double tt) {
    if (!period_) return t_end;
    const double k = std::floor((tt - t0_ + eps_t) / *period_) + 1.0;
    return std::min(t0_ + k * *period_, t_end);
  };
  double t_stop = next_stop(t0_);
  is.t_stop = t_stop;
  res_.stats.rtol = is.rtol;
  res_.stats.atol = atol;
  res_.stats.method = name_of(sol.method);
  res_.stats.formulation = name_of(formulation);
  res_.stats.jacobian = !plan.newton ? std::string("none")
                                     : std::string(name_of(is.user_jacobian ? JacobianKind::structured
                                                                            : JacobianKind::difference_quotients));

  const bool energy = scene_.output.energy_balance;
  MultibodySystem sys(m_, ws_, sim.eps_limit, energy, formulation);
  sys.set_projection_tolerance(0.01 * atol);  // Newton on Φ = 0 well inside the error test
  try {
    sys.partition(t0_, qv0.data());
  } catch (const std::exception& e) {
    res_.status = RunStatus::solver_failure;
    res_.message = e.what();
    return {res_, {}, {}};
  }
  std::vector<double> y0(static_cast<size_t>(sys.size()));
  sys.reduce(qv0.data(), y0.data());
  is.atol.assign(y0.size(), 0.0);
  sys.reduce(atol_full.data(), is.atol.data());
  auto set_difference_scales = [&] {
    std::vector<double> scales(is.atol.size());
    for (size_t i = 0; i < scales.size(); ++i) scales[i] = is.atol[i] / is.rtol;
    sys.set_difference_scales(scales);
  };
  set_difference_scales();
  yint_.assign(y0.size(), 0.0);
  std::unique_ptr<Integrator> integ;
  try {
    integ = make_integrator(is, sys, t0_, y0);
  } catch (const std::exception& e) {
    res_.status = RunStatus::solver_failure;
    res_.message = e.what();
    return {res_, {}, {}};
  }
  const double E0 = energy ? mechanical_energy(m_, qv0.data(), qv0.data() + m_.nq) : 0.0;

  dt_sample_ = scene_.output.sample_interval_s;
  dt_phase_ = period_ ? *period_ / kPhasePoints : 0.0;
  if (opt_.observe) {
    observe(t0_, qv0.data(), !res_.series.names.empty());
    if (!res_.series.names.empty()) sample_k_ = 1;
    if (period_) observe_phase(t0_, qv0.data()), phase_k_ = 1;
    boundaries_.push_back({t0_, qv0, ws_.film_mode, ws_.slide_radius});  // the first cycle's start
  }

  integ->set_root_directions(sys.root_directions());
  std::vector<int> flags;
  std::optional<double> drift_limit = sim.drift_limit_m;
  if (!drift_limit && scene_.min_clearance_m()) drift_limit = 0.1 * *scene_.min_clearance_m();
  double t = t0_;
  bool stop = false;
  while (!stop) {
    const double t_prev = t;
    const StepOutcome out = integ->step(t);
    if (out == StepOutcome::failure) {
      res_.status = RunStatus::solver_failure;
      res_.message = "the integrator failed at t = " + std::to_string(t) + " s: " + integ->error_message();
      break;
    }
    // Dense output inside (t_prev, t], in time order: series samples, orbit phase points
    // and cycle ends.
    if (opt_.observe) stop = sample_step(*integ, sys, t_prev, t, t_end);
    const bool have_state = sys.expand(t, integ->y(), yfull_.data()) == 0;
    if (have_state && opt_.observe) observe(t, yfull_.data(), false);
    if (out == StepOutcome::root) {
      integ->root_flags(flags);
      bool collapse = false;
      for (size_t k = 0; k < m_.films.size(); ++k) collapse = collapse || flags[k] != 0;
      if (collapse) {
        res_.status = RunStatus::film_collapse;
        std::ostringstream msg;
        msg << "the eccentricity ratio reached simulation.eps_limit = " << sim.eps_limit << " at t = " << t
            << " s: the film cannot carry the load (no contact law in the scene)";
        res_.message = msg.str();
        break;
      }
      if (!have_state) {
        res_.status = RunStatus::solver_failure;
        res_.message = "coordinate partitioning: the dependent coordinates cannot be recovered at t = " +
                       std::to_string(t) + " s";
        break;
      }
      res_.stats.mode_switches += sys.switch_modes(flags, t, yfull_.data());
      integ->reinit(t, integ->y());
      integ->set_root_directions(sys.root_directions());
    } else if (have_state && sys.partition_degraded()) {
      // The dependent block is near-singular: choose the independent coordinates anew.
      sys.partition(t, yfull_.data());
      sys.reduce(yfull_.data(), yint_.data());
      integ->reinit(t, yint_.data());
      sys.reduce(atol_full.data(), is.atol.data());
      integ->set_abs_tolerances(is.atol);
      set_difference_scales();
      integ->set_root_directions(sys.root_directions());
      ++res_.stats.repartitions;
    } else if (int resynced = have_state && m_.n_switching > 0 ? sys.resync_modes(t, yfull_.data()) : 0;
               resynced > 0) {
      // A free mode that no longer matches the sign of ε̇: a crossing the root finder
      // could not see (ε̇ left zero from an exact zero at a restart). Restart on the
      // branch that applies.
      res_.stats.mode_switches += resynced;
      integ->reinit(t, integ->y());
      integ->set_root_directions(sys.root_directions());
    }
    if (drift_limit && res_.stats.max_position_drift > *drift_limit) {
      res_.status = RunStatus::solver_failure;
      std::ostringstream msg;
      msg << "constraint drift " << res_.stats.max_position_drift << " m exceeds simulation.drift_limit_m = "
          << *drift_limit << " m at t = " << t
          << " s: tighten solver.rtol, or use solver.projection = true or solver.formulation = partitioned";
      res_.message = msg.str();
      break;
    }
    integ->statistics(res_.stats);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    if (opt_.max_steps > 0 && res_.stats.steps >= opt_.max_steps) {
      res_.status = RunStatus::budget_exceeded;
      res_.message = "the segment's budget of " + std::to_string(opt_.max_steps) + " steps reached at t = " +
                     std::to_string(t) + " s";
      break;
    }
    if (res_.stats.steps >= sol.max_steps) {
      res_.status = RunStatus::budget_exceeded;
      res_.message = "solver.max_steps = " + std::to_string(sol.max_steps) + " steps reached at t = " +
                     std::to_string(t) + " s";
      break;
    }
    if (wall >= sol.max_wall_time_s) {
      res_.status = RunStatus::budget_exceeded;
      res_.message = "solver.max_wall_time_s = " + std::to_string(sol.max_wall_time_s) +
                     " s reached at t = " + std::to_string(t) + " s";
      break;
    }
    if (t >= t_end * (1 - 1e-15)) stop = true;
    if (!stop && t >= t_stop - eps_t) {
      t_stop = next_stop(t);
      integ->set_stop_time(t_stop);
    }
  }
  // A run without a period keeps the whole run as its one cycle; a run that ended early
  // (collapse, failure, budget) keeps its partial cycle, so the metrics see how it ended.
  if (opt_.observe && (!period_ || (!cur_empty_ && (res_.cycles.empty() || res_.status != RunStatus::ok))))
    close_cycle(t);
  detail::StartState end;
  end.t = t;
  end.qv.assign(2 * static_cast<size_t>(m_.nq), 0.0);
  if (sys.expand(t, integ->y(), end.qv.data()) != 0 && res_.status == RunStatus::ok) {
    res_.status = RunStatus::solver_failure;
    res_.message = "coordinate partitioning: the dependent coordinates cannot be recovered at t = " +
                   std::to_string(t) + " s";
  }
  end.modes = ws_.film_mode;
  end.slide_radius = ws_.slide_radius;

  integ->statistics(res_.stats);
  res_.stats.final_time_s = t;
  res_.stats.model_evals = ws_.counters.rhs + obs_ws_.counters.rhs;
  res_.stats.gravity_evals = ws_.counters.gravity + obs_ws_.counters.gravity;
  res_.stats.film_law_evals = ws_.counters.film + obs_ws_.counters.film;
  res_.stats.film_law_evals_jac = ws_.counters.film_jacobian;

  // Steady-cycle metrics over the last metric_cycles cycles (run/metrics.cpp).
  Metrics& mt = res_.metrics;
  mt = detail::steady_cycle_metrics(scene_, res_.cycles, cycles_done_);
  if (energy) {
    double Q[2] = {0, 0};
    integ->quadratures(Q);
    sys.expand(t, integ->y(), yfull_.data());
    const double* y = yfull_.data();
    mt.driver_work_J = Q[0];
    mt.film_dissipation_J = -Q[1];
    mt.energy_change_J = mechanical_energy(m_, y, y + m_.nq) - E0;
    mt.energy_residual_J = mt.driver_work_J - mt.energy_change_J - mt.film_dissipation_J;
  }
  res_.stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return {std::move(res_), std::move(end), std::move(boundaries_)};
}

}  // namespace

namespace detail {

SegmentResult run_segment(const Scene& scene, const SegmentOptions& opt) {
  Runner r(scene, opt);
  return r.run();
}

Eigen::VectorXd state_units(const Scene& scene, const Model& m) {
  return state_scales(m, scene.min_clearance_m().value_or(1e-3), characteristic_rate(scene));
}

double orbit_noise_floor(const Scene& scene, double rtol_factor) {
  // The phase points come from the dense output, accurate to about the local error
  // tolerance, rtol × c in the clearance's unit; the cycle-to-cycle distance of a
  // converged printed-law transient plateaus at 7e-7 c at rtol 1e-8 (the interpolant and
  // the restarts at every ε̇ = 0 switch). Below 1e-3 of the steady tolerance a distance
  // is noise for the question asked (1e-6 c a cycle is 1e-3 c in 1000 cycles).
  return std::max(10.0 * scene.solver.rtol * rtol_factor, 1e-3 * scene.simulation.steady_tolerance);
}

}  // namespace detail

}  // namespace lub
