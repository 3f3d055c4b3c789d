// One run segment (segment.hpp): the integrator stepped over the segment's span, each step's
// observations (series samples, phase points, cycle ends from the dense output; extremes at
// the step end), the film modes' events, and the stops (end, steady, failure, budget).
#include "run/segment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "lub/formulation/multibody_system.hpp"
#include "lub/integrators/integrator.hpp"
#include "lub/mechanism/film_element.hpp"
#include "run/cycle_recorder.hpp"
#include "run/integration_plan.hpp"
#include "run/metrics.hpp"
#include "run/series_recorder.hpp"

namespace lub::detail {

RunModel::RunModel(const Scene& s)
    : scene(s), model(build_model(s)), stab(stabilisation(s)), integrator_ws(model), observer_ws(model), chart_ws(model) {}

namespace {

/// Cycle-boundary states a segment keeps: what the steady cycle's estimates look back on.
constexpr size_t kMaxBoundaries = 4096;

/// Why the stepping loop ends after a step.
enum class Stop { none, done, failed };

class Runner {
 public:
  Runner(RunModel& rm, const SegmentOptions& opt);
  SegmentResult run();

 private:
  const Scene& scene_;
  const SegmentOptions& opt_;
  const Model& m_;
  const Stabilisation& stab_;
  Workspace& ws_;
  Workspace& obs_ws_;
  std::optional<double> period_;
  double t0_ = 0.0, t_end_ = 0.0, t_stop_ = 0.0, eps_t_ = 0.0;
  RunResult res_;
  IntegrationPlan plan_;
  Tolerances tol_;
  std::unique_ptr<MultibodySystem> sys_;
  std::unique_ptr<Integrator> integ_;
  std::vector<double> qv0_, qdd_, ytmp_, yfull_, yint_;
  std::optional<double> drift_limit_;
  /// The observers evaluate the joint formulation's equations at the integrated state
  /// (MultibodySystem::joint_observation) instead of the absolute model: on joint, where no
  /// observation needs an ideal joint's multiplier (its reaction).
  bool joint_observer_ = false;
  CycleRecorder cycles_;
  SeriesRecorder series_;
  // Sampling (sample_step): the next series sample and phase point, cycles closed.
  double dt_sample_ = 0.0, dt_phase_ = 0.0;
  long long sample_k_ = 0, phase_k_ = 0;
  int cycles_done_ = 0;
  std::vector<StartState> boundaries_;
  std::vector<int> root_flags_;
  double E0_ = 0.0;
  double t_restarted_ = -std::numeric_limits<double>::infinity();  // the last restart after a failure
  std::string sensitivity_note_;  // why the segment has no sensitivities (empty while they run)
  std::chrono::steady_clock::time_point wall0_;

  void initial_state();
  bool start_integrator();
  void first_observation();
  /// One step and everything it triggers.
  Stop advance(double& t);
  /// A root: a film collapsed (stop) or a switching film changes mode (restart).
  Stop handle_root(double t, bool have_state);
  /// The dependent block is near-singular: choose the independent coordinates anew.
  void repartition(double t);
  Stop check_drift_and_budgets(double t);
  /// The integrator gave up at t: restart it there once, or end the segment.
  Stop integration_failed(double t);
  /// A fresh start of the integrator from its own state at t (after a mode switch, a
  /// resync, a failure), with the root directions of the modes now in force.
  void restart_here(double t);
  Stop fail(RunStatus status, const std::string& message);
  /// The next stop time: the next cycle boundary (never the end of the run, which would
  /// bound SUNDIALS' initial-step estimates at every restart and so make the steps depend
  /// on max_cycles), or the end of the run in its last cycle.
  double next_stop(double t) const;
  /// One observation at (t, y), one evaluation of the model: with `record` a row of the
  /// series; with `measure` the cycle's extremes and the drift statistics. Output samples
  /// that fall at neither a step end nor a phase point only record: the metrics must not
  /// depend on the output rate. `y` is the integrated state, `qv` its full (q, v).
  /// False if the model could not be evaluated there (nothing observed).
  bool observe(double t, const double* y, const double* qv, bool record, bool measure = true);
  /// Whether an observation needs an ideal joint's multiplier: a reaction of a joint
  /// without a film, as the metric joint or a recorded channel.
  bool observers_need_multipliers() const;
  void close_cycle(double t_end);
  /// Sampling: the observations due in the step (t_prev, t] from the integrator's dense
  /// output, in time order (series samples, orbit phase points, cycle ends). True if the
  /// run is to stop (steady).
  bool sample_step(double t_prev, double t);
  /// A cycle ends at tp: its end state (the Poincaré section at crank angle 0), then close it.
  bool end_cycle(double tp, bool have_state);
  SegmentResult finish(double t);
  /// SegmentOptions::sensitivities: starts them from the identity; why not, if not.
  std::string start_sensitivities();
  /// The right-hand side switched at t (a film's mode): the sensitivities stop there, as
  /// they would need the switch's saltation, and the segment's note says so.
  void end_sensitivities(double t);
};

Runner::Runner(RunModel& rm, const SegmentOptions& opt)
    : scene_(rm.scene), opt_(opt), m_(rm.model), stab_(rm.stab), ws_(rm.integrator_ws), obs_ws_(rm.observer_ws),
      period_(rm.scene.cycle_period_s()), plan_(plan_integration(rm.scene, rm.model, opt.rtol_factor)),
      tol_(rm.scene, rm.model, opt.rtol_factor), cycles_(rm.scene, rm.model, opt.start ? opt.start->t : 0.0, period_),
      series_(rm.scene, rm.model, opt.observe && opt.series) {
  ws_.reset(m_);
  obs_ws_.reset(m_);
}

Stop Runner::fail(RunStatus status, const std::string& message) {
  res_.status = status;
  res_.message = message;
  return Stop::failed;
}

double Runner::next_stop(double t) const {
  if (!period_) return t_end_;
  const double k = std::floor((t - t0_ + eps_t_) / *period_) + 1.0;
  return std::min(t0_ + k * *period_, t_end_);
}

void Runner::initial_state() {
  qv0_.assign(2 * static_cast<size_t>(m_.nq), 0.0);
  if (opt_.start) {
    // A given state (shooting's period maps, the steady cycle's measurement): its film
    // modes too. A sliding film slides at the start's own |e| (a perturbed start of a
    // difference quotient moves it).
    t0_ = opt_.start->t;
    qv0_ = opt_.start->qv;
    ws_.film_mode = opt_.start->modes;
    ws_.slide_radius = opt_.start->slide_radius;
    for (size_t k = 0; k < m_.films.size(); ++k)
      if (ws_.film_mode[k] == FilmMode::sliding)
        ws_.slide_radius[k] = film_kinematics(m_, static_cast<int>(k), qv0_.data(), qv0_.data() + m_.nq).e.norm();
  } else {
    Eigen::VectorXd q0, v0;
    assemble_initial_state(m_, scene_, t0_, q0, v0);
    std::copy(q0.data(), q0.data() + m_.nq, qv0_.begin());
    std::copy(v0.data(), v0.data() + m_.nq, qv0_.begin() + m_.nq);
  }
  const SimulationSpec& sim = scene_.simulation;
  t_end_ = opt_.cycles > 0    ? t0_ + opt_.cycles * *period_
           : sim.duration_s   ? *sim.duration_s
                              : sim.max_cycles * *period_;
  eps_t_ = period_ ? 1e-9 * *period_ : 0.0;
}

bool Runner::start_integrator() {
  const SolverSpec& sol = scene_.solver;
  IntegratorSettings is = plan_.settings;
  t_stop_ = next_stop(t0_);
  is.t_stop = t_stop_;
  res_.stats.rtol = is.rtol;
  res_.stats.atol = tol_.reported_atol();
  res_.stats.integrated = true;
  res_.stats.method = sol.method;
  res_.stats.formulation = plan_.formulation;
  res_.stats.jacobian = plan_.jacobian();
  const bool energy = scene_.output.energy_balance;
  sys_ = std::make_unique<MultibodySystem>(m_, ws_, stab_, scene_.simulation.eps_limit, energy,
                                           plan_.formulation);
  sys_->set_projection_tolerance(0.01 * tol_.reported_atol());  // Newton on Φ = 0 well inside the error test
  try {
    sys_->partition(t0_, qv0_.data());
    std::vector<double> y0(static_cast<size_t>(sys_->size()));
    sys_->reduce(qv0_.data(), y0.data());
    is.atol = tol_.integrated_atol(*sys_);
    sys_->set_difference_scales(Tolerances::difference_scales(is.atol, is.rtol));
    yint_.assign(y0.size(), 0.0);
    integ_ = make_integrator(is, *sys_, t0_, y0);
  } catch (const std::exception& e) {
    fail(RunStatus::solver_failure, e.what());
    return false;
  }
  E0_ = energy ? mechanical_energy(m_, qv0_.data(), qv0_.data() + m_.nq) : 0.0;
  integ_->set_root_directions(sys_->root_directions());
  joint_observer_ = sys_->formulation() == Formulation::joint && !observers_need_multipliers();
  drift_limit_ = scene_.simulation.drift_limit_m;
  if (!drift_limit_ && scene_.min_clearance_m()) drift_limit_ = 0.1 * *scene_.min_clearance_m();
  return true;
}

bool Runner::observers_need_multipliers() const {
  auto ideal = [&](int joint) { return joint >= 0 && m_.joint_film[joint] < 0 && m_.joint_constraint[joint] >= 0; };
  if (ideal(scene_.metrics.joint)) return true;
  if (!series_.active()) return false;
  for (const ChannelSpec& c : scene_.output.channels)
    if (c.source == ChannelSource::joint && ideal(c.index) &&
        (c.joint_quantity == JointQuantity::reaction || c.joint_quantity == JointQuantity::reaction_x ||
         c.joint_quantity == JointQuantity::reaction_y))
      return true;
  return false;
}

bool Runner::observe(double t, const double* y, const double* qv, bool record, bool measure) {
  const double* q = qv;
  const double* v = qv + m_.nq;
  std::copy(ws_.film_mode.begin(), ws_.film_mode.end(), obs_ws_.film_mode.begin());
  std::copy(ws_.slide_radius.begin(), ws_.slide_radius.end(), obs_ws_.slide_radius.begin());
  const EvalStatus s = joint_observer_ ? sys_->joint_observation(t, y, obs_ws_, qdd_.data())
                                       : evaluate(m_, obs_ws_, stab_, t, q, v, qdd_.data());
  if (s != EvalStatus::ok) return false;
  ++res_.stats.observer_evals;
  if (record) series_.record(Probe{t, q, v, qdd_.data()}, obs_ws_);
  if (!measure) return true;
  const Workspace& ws = obs_ws_;
  // In joint coordinates the ideal joints hold by construction (forward kinematics): no
  // constraint row is evaluated, and there is no drift to measure.
  if (!joint_observer_) {
    res_.stats.max_position_drift =
        std::max(res_.stats.max_position_drift, m_.nc ? ws.Phi.head(m_.nc).lpNorm<Eigen::Infinity>() : 0.0);
    res_.stats.max_velocity_drift =
        std::max(res_.stats.max_velocity_drift, m_.nc ? ws.Phi_dot.head(m_.nc).lpNorm<Eigen::Infinity>() : 0.0);
  }
  cycles_.measure(t, ws, v, qdd_.data());
  return true;
}

void Runner::close_cycle(double t_end) {
  cycles_.close(t_end, res_.cycles);
  series_.cycle_closed();
}

void Runner::first_observation() {
  dt_sample_ = scene_.output.sample_interval_s;
  dt_phase_ = period_ ? *period_ / kPhasePoints : 0.0;
  if (!opt_.observe) return;
  observe(t0_, integ_->y(), qv0_.data(), series_.active());
  if (series_.active()) sample_k_ = 1;
  if (period_) cycles_.phase_point(qv0_.data(), qv0_.data() + m_.nq), phase_k_ = 1;
  boundaries_.push_back({t0_, qv0_, ws_.film_mode, ws_.slide_radius});  // the first cycle's start
}

bool Runner::end_cycle(double tp, bool have_state) {
  if (have_state) {
    cycles_.section(ytmp_.data());
    boundaries_.push_back({tp, ytmp_, ws_.film_mode, ws_.slide_radius});
    if (boundaries_.size() > kMaxBoundaries) boundaries_.erase(boundaries_.begin());
  }
  close_cycle(tp);
  ++cycles_done_;
  return opt_.stop_after_cycle && opt_.stop_after_cycle(res_.cycles);
}

bool Runner::sample_step(double t_prev, double t) {
  const double inf = std::numeric_limits<double>::infinity();
  // The state at tt within the last step, as (q, v): false if it cannot be had.
  auto state_at = [&](double tt) {
    return integ_->dense(tt, 0, yint_.data()) &&
           sys_->expand(tt, yint_.data(), ytmp_.data(), MultibodySystem::Context::observer) == 0;
  };
  bool stop = false;
  const bool sampling = series_.active();
  const double t_reach = t * (1 + 1e-15);
  while (!stop) {
    const double ts = sampling ? t0_ + sample_k_ * dt_sample_ : inf;
    const double tp = period_ ? t0_ + phase_k_ * dt_phase_ : inf;
    const bool sample_due = ts <= t_reach && ts <= t_end_;
    const bool phase_due = tp <= t_reach && tp <= t_end_ + 0.5 * dt_phase_;
    if (!sample_due && !phase_due) break;
    if (phase_due && (!sample_due || tp <= ts)) {
      ++phase_k_;
      const bool have = state_at(tp);
      // A cycle ends at tp: close it before the first phase point of the next.
      if ((phase_k_ - 1) % kPhasePoints == 0) stop = end_cycle(tp, have);
      if (!stop && have) {
        cycles_.phase_point(ytmp_.data(), ytmp_.data() + m_.nq);
        observe(tp, yint_.data(), ytmp_.data(), sample_due && ts == tp);
        if (sample_due && ts == tp) ++sample_k_;
      }
    } else {
      ++sample_k_;
      if (ts > t_prev && state_at(ts)) observe(ts, yint_.data(), ytmp_.data(), /*record=*/true, /*measure=*/false);
    }
  }
  return stop;
}

Stop Runner::handle_root(double t, bool have_state) {
  integ_->root_flags(root_flags_);
  bool collapse = false;
  for (size_t k = 0; k < m_.films.size(); ++k) collapse = collapse || root_flags_[k] != 0;
  if (collapse) {
    std::ostringstream msg;
    msg << "the eccentricity ratio reached simulation.eps_limit = " << scene_.simulation.eps_limit << " at t = " << t
        << " s: the film cannot carry the load (no contact law in the scene)";
    return fail(RunStatus::film_collapse, msg.str());
  }
  if (!have_state)
    return fail(RunStatus::solver_failure, "coordinate partitioning: the dependent coordinates cannot be recovered at t = " +
                                               std::to_string(t) + " s");
  res_.stats.mode_switches += sys_->switch_modes(root_flags_, t, yfull_.data());
  end_sensitivities(t);
  restart_here(t);
  return Stop::none;
}

void Runner::repartition(double t) {
  sys_->partition(t, yfull_.data());
  sys_->reduce(yfull_.data(), yint_.data());
  integ_->reinit(t, yint_.data());
  const std::vector<double> atol = tol_.integrated_atol(*sys_);
  integ_->set_abs_tolerances(atol);
  sys_->set_difference_scales(Tolerances::difference_scales(atol, plan_.settings.rtol));
  integ_->set_root_directions(sys_->root_directions());
  ++res_.stats.repartitions;
}

Stop Runner::check_drift_and_budgets(double t) {
  const SolverSpec& sol = scene_.solver;
  auto at = [t] { return " reached at t = " + std::to_string(t) + " s"; };
  if (drift_limit_ && res_.stats.max_position_drift > *drift_limit_) {
    std::ostringstream msg;
    msg << "constraint drift " << res_.stats.max_position_drift << " m exceeds simulation.drift_limit_m = "
        << *drift_limit_ << " m at t = " << t
        << " s: tighten solver.rtol, or use solver.projection = true or solver.formulation = partitioned";
    return fail(RunStatus::solver_failure, msg.str());
  }
  const long long steps = integ_->steps();  // the rest of the statistics once, in finish()
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
  if (opt_.max_steps > 0 && steps >= opt_.max_steps)
    return fail(RunStatus::budget_exceeded, "the segment's budget of " + std::to_string(opt_.max_steps) + " steps" + at());
  if (steps >= sol.max_steps)
    return fail(RunStatus::budget_exceeded, "solver.max_steps = " + std::to_string(sol.max_steps) + " steps" + at());
  if (wall >= sol.max_wall_time_s)
    return fail(RunStatus::budget_exceeded, "solver.max_wall_time_s = " + std::to_string(sol.max_wall_time_s) + " s" + at());
  return Stop::none;
}

void Runner::restart_here(double t) {
  integ_->reinit(t, integ_->y());
  integ_->set_root_directions(sys_->root_directions());
}

Stop Runner::integration_failed(double t) {
  // SUNDIALS leaves (t, y) at the end of the last accepted step. Where the film is thin the
  // squeeze film's radial mode is stiff (h λ ~ 1e4–1e8) and the state a step accepts lies
  // off its slow manifold by what that step's error weights allowed, rtol |v| on the
  // independent velocities. At a dead centre an independent velocity crosses zero and its
  // weight tightens to atol within one step (by rtol |v| / atol ~ 1e2–1e3); the next step
  // relaxes the offset, a jump of the same size at any step size, so every retry fails the
  // error test down to h ~ 1e-7 s (docs/theory/long-runs.md). A fresh start from that state
  // (order 1, its own initial step) resolves the relaxation in a few short steps. Once per
  // accepted step: a failure again at the same t ends the segment, and so does one at the
  // segment's start (already a fresh start; e.g. a period map's perturbed state).
  const bool restart = opt_.restart_after_failure && t > t_restarted_ && t > t0_ &&
                       sys_->expand(t, integ_->y(), yfull_.data()) == 0;
  if (restart) {
    try {
      integ_->clear_error();
      restart_here(t);
      t_restarted_ = t;
      return Stop::none;
    } catch (const std::exception& e) {
      return fail(RunStatus::solver_failure, "the integrator failed at t = " + std::to_string(t) +
                                                 " s and could not be restarted: " + e.what());
    }
  }
  const std::string again = t == t_restarted_ ? " (again after a restart there)" : "";
  return fail(RunStatus::solver_failure,
              "the integrator failed at t = " + std::to_string(t) + " s" + again + ": " + integ_->error_message());
}

Stop Runner::advance(double& t) {
  const double t_prev = t;
  const StepOutcome out = integ_->step(t);
  if (out == StepOutcome::failure) return integration_failed(t);
  // Dense output inside (t_prev, t], in time order: series samples, orbit phase points and
  // cycle ends; then the step end itself.
  const bool steady = opt_.observe && sample_step(t_prev, t);
  const bool have_state = sys_->expand(t, integ_->y(), yfull_.data()) == 0;
  // The step end's observation, evaluated at this state with these modes: the mode check
  // below reads its films.
  const bool observed = have_state && opt_.observe && observe(t, integ_->y(), yfull_.data(), false);
  if (out == StepOutcome::root) {
    if (handle_root(t, have_state) == Stop::failed) return Stop::failed;
  } else if (have_state && sys_->partition_degraded()) {
    repartition(t);
  } else if (int resynced = have_state && m_.n_switching > 0 ? sys_->resync_modes(t, integ_->y(), yfull_.data(), observed ? &obs_ws_ : nullptr) : 0;
             resynced > 0) {
    // A free mode that no longer matches the sign of ε̇: a crossing the root finder could
    // not see (ε̇ left zero from an exact zero at a restart). Restart on the branch that applies.
    res_.stats.mode_switches += resynced;
    end_sensitivities(t);
    restart_here(t);
  }
  if (check_drift_and_budgets(t) == Stop::failed) return Stop::failed;
  if (steady || t >= t_end_ * (1 - 1e-15)) return Stop::done;
  if (t >= t_stop_ - eps_t_) {
    t_stop_ = next_stop(t);
    integ_->set_stop_time(t_stop_);
  }
  return Stop::none;
}

SegmentResult Runner::finish(double t) {
  // A run without a period keeps the whole run as its one cycle; a run that ended early
  // (collapse, failure, budget) keeps its partial cycle, so the metrics see how it ended.
  if (opt_.observe && (!period_ || (!cycles_.empty() && (res_.cycles.empty() || res_.status != RunStatus::ok))))
    close_cycle(t);
  StartState end;
  end.t = t;
  end.qv.assign(2 * static_cast<size_t>(m_.nq), 0.0);
  if (sys_->expand(t, integ_->y(), end.qv.data()) != 0 && res_.status == RunStatus::ok) {
    res_.status = RunStatus::solver_failure;
    res_.message = "coordinate partitioning: the dependent coordinates cannot be recovered at t = " +
                   std::to_string(t) + " s";
  }
  end.modes = ws_.film_mode;
  end.slide_radius = ws_.slide_radius;

  integ_->statistics(res_.stats);
  res_.stats.final_time_s = t;
  res_.stats.model_evals = ws_.counters.rhs + obs_ws_.counters.rhs;
  res_.stats.gravity_evals = ws_.counters.gravity + obs_ws_.counters.gravity;
  res_.stats.film_law_evals = ws_.counters.film + obs_ws_.counters.film;
  res_.stats.film_law_evals_jacobian = ws_.counters.film_jacobian;
  res_.stats.rhs_evals_jacobian += ws_.counters.rhs_jacobian;

  // Steady-cycle metrics over the last metric_cycles cycles (metrics.cpp).
  Metrics& mt = res_.metrics;
  mt = steady_cycle_metrics(scene_, res_.cycles, cycles_done_);
  if (scene_.output.energy_balance) {
    double Q[2] = {0, 0};
    integ_->quadratures(Q);
    sys_->expand(t, integ_->y(), yfull_.data());
    const double* y = yfull_.data();
    mt.driver_work_J = Q[0];
    mt.film_dissipation_J = -Q[1];
    mt.energy_change_J = mechanical_energy(m_, y, y + m_.nq) - E0_;
    mt.energy_residual_J = mt.driver_work_J - mt.energy_change_J - mt.film_dissipation_J;
  }
  res_.series = series_.take();
  res_.stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
  SegmentResult out;
  out.res = std::move(res_);
  out.end = std::move(end);
  out.boundaries = std::move(boundaries_);
  return out;
}

SegmentResult Runner::run() {
  wall0_ = std::chrono::steady_clock::now();
  qdd_.assign(m_.nq, 0.0);
  ytmp_.assign(2 * m_.nq, 0.0);
  yfull_.assign(2 * m_.nq, 0.0);
  initial_state();
  if (!start_integrator()) {
    res_.series = series_.take();
    SegmentResult out;
    out.res = std::move(res_);
    return out;
  }
  first_observation();
  if (opt_.sensitivities) sensitivity_note_ = start_sensitivities();
  double t = t0_;
  while (advance(t) == Stop::none) {
  }
  std::vector<double> S;
  if (opt_.sensitivities && sensitivity_note_.empty()) {
    S.assign(static_cast<size_t>(sys_->size()) * static_cast<size_t>(sys_->size()), 0.0);
    if (!integ_->sensitivities(t, S.data())) {
      sensitivity_note_ = "the sensitivities could not be read at the segment's end";
      S.clear();
    }
  }
  SegmentResult out = finish(t);
  out.sensitivity = std::move(S);
  out.sensitivity_note = std::move(sensitivity_note_);
  return out;
}

void Runner::end_sensitivities(double t) {
  if (!opt_.sensitivities || !sensitivity_note_.empty()) return;
  integ_->stop_sensitivities();
  sensitivity_note_ = "a film's mode switched at t = " + std::to_string(t) +
                      " s: the variational equation would need its saltation there";
}

std::string Runner::start_sensitivities() {
  if (sys_->formulation() != Formulation::joint)
    return "forward sensitivities need the joint formulation (its coordinates are the chart's)";
  const size_t n = static_cast<size_t>(sys_->size());
  std::vector<double> S0(n * n, 0.0);
  for (size_t i = 0; i < n; ++i) S0[i * n + i] = 1.0;
  try {
    if (!integ_->start_sensitivities(static_cast<int>(n), S0.data()))
      return "the integration method has no forward sensitivities (cvode_bdf has)";
  } catch (const std::exception& e) {
    return std::string("the forward sensitivities could not be started: ") + e.what();
  }
  return {};
}

}  // namespace

SegmentResult run_segment(RunModel& rm, const SegmentOptions& opt) {
  Runner r(rm, opt);
  return r.run();
}

void accumulate(SolverStats& t, const SolverStats& s) {
  static_cast<IntegratorStats&>(t) += s;
  using S = SolverStats;
  for (long long S::*c : {&S::film_law_evals_jacobian, &S::observer_evals, &S::repartitions, &S::mode_switches,
                          &S::model_evals, &S::gravity_evals, &S::film_law_evals})
    t.*c += s.*c;
  t.max_position_drift = std::max(t.max_position_drift, s.max_position_drift);
  t.max_velocity_drift = std::max(t.max_velocity_drift, s.max_velocity_drift);
  if (!t.integrated) {
    t.integrated = s.integrated;
    t.method = s.method;
    t.formulation = s.formulation;
    t.jacobian = s.jacobian;
    t.rtol = s.rtol;
    t.atol = s.atol;
    t.final_time_s = s.final_time_s;
  }
}

}  // namespace lub::detail
