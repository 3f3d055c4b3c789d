// The steady stage's verdict: evidence → label, method and message, in one place
// (run/verdict.hpp). Messages join their parts with "; ", the newest reason first where a
// later stage decides, the earlier stages' reasons after it.
#include "run/verdict.hpp"

#include "lub/run/orbit.hpp"

#include <cmath>
#include <sstream>

namespace lub {

std::string classification(const RunResult& r) {
  return r.status == RunStatus::ok ? std::string(name_of(r.steady.kind)) : to_string(r.status);
}

namespace detail::verdict {

namespace {

/// `part` before the message (joined by "; ").
void prepend(std::string& message, const std::string& part) {
  message = message.empty() ? part : part + "; " + message;
}
/// `part` after the message (joined by "; ").
void append(std::string& message, const std::string& part) {
  message = message.empty() ? part : message + "; " + part;
}

std::string error_bars_not_measured(const std::string& why) { return "error bars not measured: " + why; }

/// Newton found no orbit: drifting where it walked out of the clearance or the transient
/// drifts, else not converged; why.
void no_orbit(RunResult& res, const OrbitEvidence& ev) {
  const steady::ShootingResult& found = ev.newton;
  res.steady.kind = found.outcome == steady::ShootingOutcome::left_domain || ev.drifts ? SteadyClass::drifting
                                                                                      : SteadyClass::not_converged;
  std::ostringstream msg;
  if (found.skipped) {
    std::ostringstream why;
    why << "the map's error at rtol would move its orbit by " << ev.predicted_shift << " clearances (|mu|max "
        << ev.start_dominant << "), more than " << ev.unlocatable << " x steady_tolerance";
    msg << "no shooting (" << why.str() << "; residual " << found.residual << " at the start)";
  } else {
    msg << "shooting did not converge (" << found.message << ", residual " << found.residual << " after "
        << found.iterations << " Newton iterations)";
  }
  if (!ev.period_failure.empty()) msg << "; a period failed: " << ev.period_failure;
  res.message = msg.str();
}

}  // namespace

bool is_orbit(SteadyClass k) { return has_orbit(k); }

void leg(RunResult& res, const TransientLeg& leg) {
  if (leg.message) res.message = *leg.message;
}

void transient_only(RunResult& res, int max_cycles) {
  res.steady.kind = SteadyClass::not_converged;
  res.message = "simulation.max_cycles = " + std::to_string(max_cycles) +
                ": too short for the steady stage (it needs max_cycles >= " + std::to_string(kMinSteadyCycles) +
                "); the transient alone";
}

void transient(RunResult& res, bool converged, bool confirm, const TransientConfirmation& c, bool drifts) {
  using Outcome = TransientConfirmation::Outcome;
  SteadyCycle& steady = res.steady;
  if (converged && !confirm) {
    // A transient of fixed length (stop_when_steady off) was not asked for its steady cycle:
    // its verdict is the estimate's, and says so.
    steady.kind = SteadyClass::periodic;
    if (res.message.empty())
      res.message = "periodic by the contraction estimate alone (a transient of fixed length: stop_when_steady "
                    "or steady = auto asks the period map to confirm it)";
    return;
  }
  if (converged && c.outcome == Outcome::confirmed) {
    steady.kind = SteadyClass::periodic;
    steady.method = SteadyCycleMethod::transient;
    return;
  }
  if (converged) {
    std::ostringstream msg;
    switch (c.outcome) {
      case Outcome::period_failed:
        msg << "the transient's stop not confirmed: a period from its end failed: " << c.failure;
        break;
      case Outcome::unstable:
        msg << "the transient's stop not confirmed by the period map: |mu|max = " << c.dominant
            << " at its end, not a stable cycle";
        break;
      case Outcome::far:
        msg << "the transient's stop not confirmed by the period map: the orbit lies " << c.distance
            << " clearances from its end (|mu|max = " << c.dominant << "; steady_tolerance " << c.tolerance << ")";
        break;
      case Outcome::ill_posed:
        msg << "the transient's stop not confirmed by the period map: kappa " << c.conditioning
            << " amplifies its error a period at rtol to " << c.shift << " clearances (steady_tolerance "
            << c.tolerance << "), a stop there is the integrator's";
        break;
      default:  // too short, or the budget's note says it
        break;
    }
    if (!msg.str().empty()) res.message = msg.str();
  }
  steady.kind = drifts ? SteadyClass::drifting : SteadyClass::not_converged;
  if (!converged && res.message.empty()) {
    std::ostringstream msg;
    msg << "not steady after " << res.cycles.size() << " cycles by the contraction estimate (rate "
        << steady.contraction_rate << ", distance still to go " << steady.remaining_distance << " clearances)";
    res.message = msg.str();
  }
}

bool transient_after_shooting(RunResult& res, const TransientConfirmation& c, bool drifts) {
  const std::string shooting = res.message;
  res.message.clear();
  transient(res, true, true, c, drifts);
  if (res.steady.kind == SteadyClass::periodic) {
    res.message = "periodic by the transient's contraction estimate, confirmed by the period map; " + shooting;
    return true;
  }
  append(res.message, shooting);
  return false;
}

void drifting(RunResult& res) { res.steady.kind = SteadyClass::drifting; }

void slow_transient(RunResult& res, const std::string& first_newton, int first_cycles, int cycles, double rate) {
  std::ostringstream msg;
  if (!first_newton.empty()) msg << "from cycle " << first_cycles << ": " << first_newton << "; ";
  msg << "no Newton from cycle " << cycles << " (the transient contracts at rate " << rate
      << ": its orbit, if any, lies along a slow manifold, where the slow flow goes)";
  res.message = msg.str();
}

void no_orbit_inside(RunResult& res) {
  if (res.status == RunStatus::ok && res.steady.kind == SteadyClass::drifting && res.message.empty())
    res.message = "no periodic orbit inside the clearance";
}

void error_bars(RunResult& res, const ErrorBarEvidence& ev) {
  if (!ev.note.empty()) append(res.message, ev.note);
  if (ev.outcome != ErrorBarEvidence::Outcome::failed) return;
  prepend(res.message, error_bars_not_measured(ev.failure));
  if (!ev.budget && is_orbit(res.steady.kind)) res.steady.kind = SteadyClass::not_converged;
}

bool accepted(const OrbitEvidence& ev) {
  if (ev.outcome != OrbitEvidence::Outcome::found) return false;
  if (!ev.final) return ev.seeded;
  const bool bars_failed = ev.bars.outcome == ErrorBarEvidence::Outcome::failed && !ev.bars.budget;
  return ev.measured && !bars_failed && !(ev.orbit_error > ev.steady_tolerance) && !ev.bars.keeps_moving();
}

bool orbit(RunResult& res, const OrbitEvidence& ev) {
  using Outcome = OrbitEvidence::Outcome;
  SteadyCycle& steady = res.steady;
  switch (ev.outcome) {
    case Outcome::not_found:
      no_orbit(res, ev);
      return false;
    case Outcome::refused:  // the budget's note says it (close)
    case Outcome::multipliers_refused:
      steady.kind = SteadyClass::not_converged;
      res.message.clear();
      return false;
    case Outcome::multipliers_failed:
      steady.kind = SteadyClass::not_converged;
      res.message = "shooting converged, but a perturbed period failed: " + ev.failure;
      return false;
    case Outcome::found:
      break;
  }
  if (!ev.final) return ev.seeded;
  steady.kind = ev.dominant < 1.0 ? SteadyClass::periodic : SteadyClass::periodic_unstable;
  steady.method = SteadyCycleMethod::shooting;
  if (ev.outside_chart) {
    steady.kind = SteadyClass::not_converged;
    res.message = "the orbit Newton found lies outside the coordinates' chart (no consistent state there)";
    return false;
  }
  if (!ev.measured) {
    steady.kind = SteadyClass::not_converged;
    res.message = "the periodic orbit's measurement failed: " + ev.measure_failure;
    return false;
  }
  error_bars(res, ev.bars);
  if (steady.kind == SteadyClass::not_converged) return false;
  if (ev.orbit_error > ev.steady_tolerance) {
    // Located no better than the tolerance a cycle is steady by: near |μ| = 1 a fixed
    // point of the map's error.
    std::ostringstream msg;
    msg << "the orbit moves by " << ev.orbit_error
        << " clearances when its periods are integrated 100 times tighter (|mu|max " << ev.dominant
        << "; steady_tolerance " << ev.steady_tolerance << "): not located";
    prepend(res.message, msg.str());
    steady.kind = SteadyClass::not_converged;
    return false;
  }
  if (ev.bars.keeps_moving()) {
    // Ill-conditioned, and still moving as far when refined again: a fixed point of the map's
    // error, whose place is the integrator's (docs/theory/steady-cycles.md).
    std::ostringstream msg;
    msg << "the orbit (kappa " << ev.bars.conditioning << ") moves by " << ev.bars.first_move
        << " clearances from rtol to rtol/100 and ";
    if (std::isinf(ev.bars.refined_move))
      msg << "could not be re-solved at rtol " << ev.bars.refine_rtol << " (" << ev.bars.refine_failure << ")";
    else
      msg << "by " << ev.bars.refined_move << " more at rtol " << ev.bars.refine_rtol;
    msg << ": it does not stop moving under refinement, not located";
    prepend(res.message, msg.str());
    steady.kind = SteadyClass::not_converged;
    return false;
  }
  const Metrics& m = res.metrics;
  if (m.min_film_thickness_m_error > ev.film_resolution * m.min_film_thickness_m) {
    // The film, and so where the journal sits against the wall, is not resolved at this rtol.
    std::ostringstream msg;
    msg << "the orbit's minimum film, " << m.min_film_thickness_m << " m, moves by " << m.min_film_thickness_m_error
        << " m when its periods are integrated 100 times tighter (kappa " << ev.bars.conditioning
        << "): more than " << ev.film_resolution << " of itself, not located";
    prepend(res.message, msg.str());
    steady.kind = SteadyClass::not_converged;
    return false;
  }
  return true;
}

std::string orbit_message(const OrbitEvidence& ev) {
  RunResult r;
  orbit(r, ev);
  return r.message;
}

std::string newton_picard_failure(const steady::ShootingResult& picard, bool period_failed,
                                  const std::string& failure) {
  std::ostringstream msg;
  if (period_failed)
    msg << "Newton-Picard: a period failed: " << failure;
  else if (picard.outcome == steady::ShootingOutcome::converged)
    msg << "Newton-Picard's orbit lies outside the coordinates' chart";
  else
    msg << picard.message << ", residual " << picard.residual << " after " << picard.iterations << " iterations";
  return msg.str();
}

bool shooting(RunResult& res, const ShootingEvidence& ev) {
  using Outcome = ShootingEvidence::Outcome;
  switch (ev.outcome) {
    case Outcome::no_budget:
      res.steady.kind = SteadyClass::not_converged;
      return false;
    case Outcome::error:
      res.steady.kind = SteadyClass::not_converged;
      res.message = "shooting: " + ev.error;
      return false;
    case Outcome::too_short:
      return false;
    case Outcome::no_freedom:
      // Every state follows the drivers: periodic from the first cycle (the periodicity
      // column shows what the integration's drift makes of it).
      res.steady.kind = SteadyClass::periodic;
      return true;
    case Outcome::orbit:
      break;
  }
  return orbit(res, ev.orbit);
}

namespace {

/// A drifting case's law of approach to the wall and when its film crosses the safe film.
void drift_law(std::ostringstream& msg, const RunResult& res, const SlowFlowEvidence& ev) {
  const SteadyCycle& steady = res.steady;
  if (!ev.no_law.empty()) {
    msg << "; no drift law: " << ev.no_law;
    return;
  }
  if (!std::isfinite(steady.drift_exponent)) return;
  msg << "; its film falls as dh/dN = -a h^p, p = " << steady.drift_exponent << " ± " << steady.drift_exponent_error
      << " (fitted over films " << ev.law_film_low << " to " << ev.law_film_high << " m)";
  if (std::isfinite(steady.safe_film_cycle)) {
    msg << ": it crosses the safe film " << res.metrics.safe_film_thickness_m << " m at about "
        << "cycle " << std::lround(steady.safe_film_cycle) << " ± " << std::lround(steady.safe_film_cycle_error);
    if (!res.cycles.empty()) {
      const double period = res.cycles.back().t_end_s - res.cycles.back().t_start_s;
      msg << " (t = " << steady.safe_film_cycle * period << " s)";
    }
  } else if (ev.safe_beyond_reach) {
    msg << ": the safe film " << res.metrics.safe_film_thickness_m << " m lies "
        << std::round(10.0 * ev.law_film_low / res.metrics.safe_film_thickness_m) / 10.0
        << " times below the films it was fitted over, beyond the factor 2 its crossings are checked to";
  } else if (res.metrics.below_safe_film) {
    msg << ", already below the safe film";
  }
}

}  // namespace

void slow_flow(RunResult& res, const SlowFlowEvidence& ev) {
  using Outcome = SlowFlowEvidence::Outcome;
  SteadyCycle& steady = res.steady;
  const long long n = std::lround(ev.cycles);
  if (ev.outcome == Outcome::not_followed || ev.outcome == Outcome::off_manifold) {
    if (ev.outcome == Outcome::off_manifold) {
      // The case as shooting left it, and why the flow says nothing.
      std::ostringstream why;
      why << "; its slow flow not followed: where it got to (about " << n << " cycles on), two cycles differ by "
          << ev.periodicity << " clearances, off any slow manifold";
      res.message += why.str();
    }
    return;
  }
  // Newton where the flow stopped found no orbit (an earlier try): the metrics are no orbit's.
  if (ev.newton_tried) steady.method = SteadyCycleMethod::transient;
  switch (ev.outcome) {
    case Outcome::newton_refused:  // the budget's note says it (close)
      steady.kind = SteadyClass::not_converged;
      res.message.clear();
      return;
    case Outcome::newton: {
      res.message.clear();
      if (orbit(res, ev.orbit)) {
        std::ostringstream msg;
        msg << "found from where its slow flow stops, about " << n << " cycles after the transient (" << ev.periods
            << " periods); from the transient: " << ev.shooting;
        prepend(res.message, msg.str());
      }
      return;
    }
    default:
      break;
  }
  std::ostringstream msg;
  switch (ev.outcome) {
    case Outcome::film_fails:
      steady.kind = SteadyClass::drifting;
      msg << "the film fails: followed along its slow manifold, the journal leaves the clearance about " << n
          << " cycles after the transient (" << ev.failure << ")";
      break;
    case Outcome::refused:
      // The budget's note says it (close), after why shooting found no orbit.
      steady.kind = SteadyClass::not_converged;
      res.message = ev.shooting;
      return;
    case Outcome::still:
      steady.kind = SteadyClass::not_converged;
      msg << "its slow flow stops within the map's noise about " << n
          << " cycles after the transient, but Newton finds no orbit there (" << ev.newton << ")";
      break;
    default:  // its periods spent, still moving
      steady.kind = SteadyClass::drifting;
      msg << "still moving about " << n << " cycles after the transient, followed along its slow manifold";
      break;
  }
  if (ev.measured) {
    steady.method = SteadyCycleMethod::slow_flow;
    msg << ": minimum film " << ev.film_at_end << " m at the transient's end, " << steady.last_cycle_min_film_m
        << " m there";
    if (ev.drift_not_measured.empty())
      msg << ", changing by " << steady.min_film_drift_m_per_cycle << " m a cycle";
    else
      msg << ", its drift not measured (" << ev.drift_not_measured << ")";
    const double drift = steady.min_film_drift_m_per_cycle, error = steady.min_film_drift_error_m_per_cycle;
    if (ev.outcome == Outcome::moving && std::isfinite(drift) && std::isfinite(error)) {
      msg << " (its period map's own error a cycle: " << error << " m at rtol " << ev.flow_rtol << ")";
      // The drift is no larger than the error of the periods that gave it: which way the
      // journal goes is the integrator's, not the film's (docs/theory/steady-cycles.md).
      if (!(std::abs(drift) > error)) {
        steady.kind = SteadyClass::not_converged;
        msg << ", the drift within it: where it goes is not resolved at this rtol";
      }
    }
    if (steady.kind == SteadyClass::drifting && ev.outcome == Outcome::moving) drift_law(msg, res, ev);
  } else if (!ev.not_measured.empty()) {
    // The film and drift on record are the transient's: the message says so.
    msg << "; its cycles there not measured (" << ev.not_measured << "): the film and drift are the transient's, at "
        << "its end";
  }
  msg << " (" << ev.periods << " periods, " << name_of(ev.flow) << "); from the transient: " << ev.shooting;
  res.message = msg.str();
}

bool continuation_step(RunResult& res, const ContinuationStep& ev) {
  switch (ev.outcome) {
    case ContinuationStep::Outcome::other_mechanism:
      res.message = "the neighbour's orbit is of another mechanism";
      return false;
    case ContinuationStep::Outcome::no_freedom:
      res.steady.kind = SteadyClass::periodic;
      return true;
    case ContinuationStep::Outcome::error:
      res.steady.kind = SteadyClass::not_converged;
      res.message = "continuation: " + ev.error;
      return false;
    case ContinuationStep::Outcome::orbit:
      break;
  }
  return orbit(res, ev.orbit);
}

void continued(RunResult& res, int steps) {
  res.steady.method = SteadyCycleMethod::continuation;
  res.steady.continuation_steps = steps;
}

std::string path_stopped(double lambda, int steps, const std::string& why) {
  std::ostringstream msg;
  msg << "continuation stopped at λ = " << lambda << " after " << steps << " steps (" << why << ")";
  return msg.str();
}

void thick_film_continued(RunResult& res) { res.message = "continued from 16 × the viscosity"; }

void thick_film_none(RunResult& own, const RunResult& seeded) {
  own.message = "no orbit at 16 × the viscosity either (" + classification(seeded) + "); " + own.message;
}

void thick_film_path_failed(RunResult& own, const std::string& why) {
  own.message = "from 16 × the viscosity: " + why + "; " + own.message;
}

void budget_spent(RunResult& res, const std::string& why) {
  if (res.message.find("simulation.max_periods") == std::string::npos) res.message = why + "; " + res.message;
}

void path_then_alone(RunResult& res, const std::string& why) { res.message = why + "; " + res.message; }

void path_spent(RunResult& res, const std::string& why) { res.message = why; }

void path_lost(RunResult& res, const std::string& why) {
  res.steady.kind = SteadyClass::not_converged;
  res.message = "the neighbour's orbit was not continued to this scene: " + why;
}

RunResult close(SteadyContext& cx, std::chrono::steady_clock::time_point wall0) {
  RunResult& res = cx.res;
  const SteadyCycle& steady = res.steady;
  if (!cx.budget.note().empty())
    res.message = cx.budget.note() + (res.message.empty() ? "" : "; " + res.message);
  res.metrics.steady = res.status == RunStatus::ok && steady.kind == SteadyClass::periodic;
  res.metrics.cycles_to_steady = res.metrics.steady ? static_cast<int>(steady.periods_integrated) : -1;
  res.metrics.cycles_run = static_cast<int>(res.cycles.size());
  res.stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return std::move(res);
}

}  // namespace detail::verdict

}  // namespace lub
