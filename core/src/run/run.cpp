// run_scene, and the order in which the steady stage tries its strategies
// (docs/theory/steady-cycles.md). Each strategy returns evidence (steady_strategies.hpp);
// verdict.cpp turns it into the steady cycle's label, method and message.
//  - transient: cycle after cycle, stopped (stop_when_steady) once the contraction
//    estimate says the orbit is within steady_tolerance of its limit and the period map
//    confirms it;
//  - shooting: transient_cycles, then Newton on z = P(z) (P: one crank period, z: the
//    mechanism's independent coordinates and velocities at crank angle 0), the Floquet
//    multipliers from the monodromy at the orbit found, the metrics measured on it;
//  - auto: the transient until its contraction rate is known, then shooting when the
//    remaining transient would cost more than shooting does; where Newton finds no orbit,
//    the transient again, and the slow flow where the orbit lies along a slow manifold;
//  - continuation: a neighbour's orbit carried along a path of scenes (continuation.cpp).
#include "lub/run/run.hpp"

#include "lub/bearing/law_validity.hpp"

#include "run/steady_strategies.hpp"
#include "run/verdict.hpp"

namespace lub {

namespace detail {

namespace {

/// A transient leg, its segment's message the run's.
bool leg(SteadyContext& cx, int cycles, const CycleStop& stop) {
  const TransientLeg l = run_transient_leg(cx, cycles, stop);
  verdict::leg(cx.res, l);
  return l.ok;
}

/// A transient that says steady (`converged`): periodic if the period map confirms it
/// (or, `confirm` false, by the estimate alone), otherwise drifting or not converged.
void classify_transient(SteadyContext& cx, bool converged, bool confirm) {
  TransientConfirmation c;
  if (converged && confirm) c = confirm_transient(cx);
  verdict::transient(cx.res, converged, confirm, c, transient_drifts(cx));
}

void shoot(SteadyContext& cx) { verdict::shooting(cx.res, shoot_from_transient(cx)); }

/// simulation.max_cycles below kMinSteadyCycles: max_cycles cycles and nothing more (a
/// steady stage would cost tens of periods more than the case asked for).
void transient_only(SteadyContext& cx) {
  const bool ok = leg(cx, 0, nullptr);
  finish_transient(cx);
  if (ok) verdict::transient_only(cx.res, cx.sim.max_cycles);
}

/// simulation.steady = transient: cycle after cycle up to max_cycles, or until the
/// period map confirms the contraction estimate's stop (stop_when_steady).
void run_transient(SteadyContext& cx) {
  RunResult& res = cx.res;
  const SimulationSpec& sim = cx.sim;
  // With stop_when_steady, a stop the period map does not confirm is not the end: on a
  // slow manifold the contraction estimate says steady cycle after cycle while the film
  // still sinks. The transient goes on and asks again once it has run as many cycles
  // again (at most log2(max_cycles) confirmations), up to max_cycles.
  size_t ask_from = 0;
  CycleStop stop;
  if (sim.stop_when_steady)
    stop = [&](const std::vector<CycleMetrics>& cs) { return cs.size() >= ask_from && transient_steady(cx, cs); };
  bool ok = leg(cx, 0, stop);
  for (;;) {
    finish_transient(cx);
    if (!ok) return;
    const bool converged = transient_steady(cx, res.cycles);
    classify_transient(cx, converged, sim.stop_when_steady);
    const int left = sim.max_cycles - static_cast<int>(res.cycles.size());
    if (!sim.stop_when_steady || !converged || res.steady.kind == SteadyClass::periodic || left <= 0 ||
        !cx.budget.note().empty())
      break;
    res.steady.multipliers.clear();  // the next verdict's, if any
    res.steady.orbit_residual = kNaN;
    ask_from = 2 * res.cycles.size();
    ok = leg(cx, left, stop);
  }
  if (sim.error_bars) verdict::error_bars(res, transient_error_bars(cx));
}

/// simulation.steady = shooting or auto: a transient first, then shooting; where that
/// finds no orbit, the transient again (the direct evidence) and the slow flow.
void run_shooting(SteadyContext& cx) {
  RunResult& res = cx.res;
  const SimulationSpec& sim = cx.sim;
  const int n0 = sim.transient_cycles;
  CycleStop stop;
  if (sim.steady == SteadyMethod::shooting) {
    stop = [n0](const std::vector<CycleMetrics>& cs) { return static_cast<int>(cs.size()) >= n0; };
  } else {
    // auto: go on while the transient will be there sooner than shooting would be.
    stop = [&cx, n0](const std::vector<CycleMetrics>& cs) {
      if (static_cast<int>(cs.size()) < n0 || !transient_known(cx, cs)) return false;
      return transient_steady(cx, cs) || transient_cycles_left(cx, cs) > cx.tuning.shooting_cost;
    };
  }
  if (!leg(cx, 0, stop)) {
    finish_transient(cx);
    return;
  }
  finish_transient(cx);
  shoot(cx);
  // Shooting found no orbit from there: the transient goes on, up to max_cycles or until
  // its own test says steady, and shooting tries once more from where it ends, unless it
  // contracts slowly and the slow flow follows. A transient that converged is periodic
  // whatever shooting says; one that drifts is drifting.
  const int left = sim.max_cycles - static_cast<int>(res.cycles.size());
  const std::string first_newton = res.message;
  const int first_cycles = static_cast<int>(res.cycles.size());
  if (!verdict::is_orbit(res.steady.kind) && left > 0 &&
      leg(cx, left, [&cx](const std::vector<CycleMetrics>& cs) { return transient_steady(cx, cs); })) {
    finish_transient(cx);
    const bool converged = transient_steady(cx, res.cycles);
    const double rate = res.steady.contraction_rate;
    if (sim.slow_flow && !converged && rate >= cx.tuning.slow_contraction && rate < 1.0)
      verdict::slow_transient(res, first_newton, first_cycles, static_cast<int>(res.cycles.size()), rate);
    else
      shoot(cx);
    if (!verdict::is_orbit(res.steady.kind)) {
      if (converged) {
        // The transient's own test, confirmed by the period map at its end.
        const TransientConfirmation c = confirm_transient(cx);
        if (verdict::transient_after_shooting(res, c, transient_drifts(cx)) && sim.error_bars)
          verdict::error_bars(res, transient_error_bars(cx));
      } else if (transient_drifts(cx)) {
        verdict::drifting(res);
      }
    }
  }
  if (res.status == RunStatus::ok && !verdict::is_orbit(res.steady.kind) && cx.budget.note().empty() &&
      sim.slow_flow)
    verdict::slow_flow(res, follow_slow_flow(cx));
  verdict::no_orbit_inside(res);
}

}  // namespace

RunResult run_steady(const Scene& scene, PeriodBudget budget) {
  const auto wall0 = std::chrono::steady_clock::now();
  SteadyContext cx(scene, std::move(budget));
  const SimulationSpec& sim = scene.simulation;
  if (sim.steady != SteadyMethod::transient && sim.max_cycles < kMinSteadyCycles)
    transient_only(cx);
  else if (sim.steady == SteadyMethod::transient)
    run_transient(cx);
  else
    run_shooting(cx);
  return verdict::close(cx, wall0);
}

}  // namespace detail

namespace {

/// The run's validity notes: the scene's, and the metric joint's if its law keeps the whole
/// film and its load reversed in a metric cycle.
RunResult with_notes(const Scene& scene, RunResult r) {
  r.notes = scene.validity_notes;
  const int mj = scene.metrics.joint;
  if (mj >= 0 && r.metrics.load_reverses && scene.joints[mj].type == JointType::lubricated_revolute &&
      !scene.joints[mj].ideal && is_full_film_law(scene.joints[mj].law))
    r.notes.push_back(reversing_load_note("/joints/" + std::to_string(mj), scene.joints[mj].law));
  return r;
}

}  // namespace

RunResult run_scene(const Scene& scene) {
  if (scene.simulation.steady == SteadyMethod::continuation) return with_notes(scene, detail::run_alone(scene));
  return with_notes(scene, detail::run_steady(scene, detail::PeriodBudget(scene.simulation.max_periods, 0)));
}

RunResult run_scene(const Scene& scene, const ContinuationStart& from) {
  // Too short for a steady stage: the transient alone, whatever the neighbour.
  if (scene.simulation.max_cycles < kMinSteadyCycles) return with_notes(scene, detail::run_alone(scene));
  return with_notes(scene, detail::run_continued(scene, from));
}

}  // namespace lub
