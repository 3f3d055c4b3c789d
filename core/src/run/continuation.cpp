// The continuation strategy: a neighbour's orbit carried along a path of scenes to this
// one (Newton at each step from the last step's orbit, the step halved where Newton fails
// and doubled where it converges quickly), and the thick-film seed: where a scene alone
// finds no orbit, its orbit at 16 times the viscosity continued back
// (docs/theory/continuation.md).
#include <cmath>

#include <nlohmann/json.hpp>

#include "run/orbit_seed.hpp"
#include "run/steady_strategies.hpp"
#include "run/verdict.hpp"

namespace lub::detail {

namespace {

bool found_orbit(const RunResult& r) { return r.status == RunStatus::ok && verdict::is_orbit(r.steady.kind); }

/// Adds what `part` cost to `total`.
void add_costs(RunResult& total, const RunResult& part) {
  accumulate(total.stats, part.stats);
  total.steady.periods_integrated += part.steady.periods_integrated;
  total.steady.newton_iterations += part.steady.newton_iterations;
}

/// Whether the case has spent its simulation.max_periods, having integrated `spent`; if
/// so, `why` is the budget's note.
bool budget_spent(const Scene& scene, long long spent, std::string& why) {
  if (spent < scene.simulation.max_periods) return false;
  PeriodBudget b(scene.simulation.max_periods, spent);
  b.stopped(0, "no further step");
  why = b.note();
  return true;
}

RunResult finish_wall(RunResult r, std::chrono::steady_clock::time_point wall0) {
  r.stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  r.metrics.cycles_to_steady = r.metrics.steady ? static_cast<int>(r.steady.periods_integrated) : -1;
  return r;
}

/// One step of a path: Newton from a neighbour's orbit placed into this context's scene;
/// `final`: the run's own scene (metrics, error bars); `single`: the path's only step
/// (ContinuationStart::min_step 1), which accepts or retries a Newton stalled at the map's
/// noise where a path would shorten its step (solve_orbit).
verdict::ContinuationStep continue_from(SteadyContext& cx, const OrbitSeed& seed, bool final, bool single) {
  using Outcome = verdict::ContinuationStep::Outcome;
  verdict::ContinuationStep step;
  try {
    const std::optional<StartState> base = place_seed(cx.rm, seed);
    if (!base) {
      step.outcome = Outcome::other_mechanism;
      return step;
    }
    Chart chart(cx.rm, *base, cx.sim.shooting_coordinates);
    if (chart.size() == 0) {
      step.outcome = Outcome::no_freedom;
      return step;
    }
    // Within the neighbour's gap, as from a transient.
    steady::ShootingOptions options = cx.shooting_options(chart, seed.max_eps);
    options.max_iterations = cx.tuning.continuation_iterations;
    // A single step's line search stops at the map's noise: a shorter step cannot change the
    // residual measurably, and each trial costs a period (a step with no orbit near spent
    // most of its periods there).
    if (single) options.step_tolerance = cx.orbit_noise_floor();
    Eigen::MatrixXd J0;
    if (const std::optional<Eigen::MatrixXd> M0 = seed_monodromy(seed, chart)) {
      J0 = *M0 - Eigen::MatrixXd::Identity(chart.size(), chart.size());
      options.initial_jacobian = &J0;
    }
    // The neighbour's steps per period, with room for a thinner film's smaller steps.
    const long long budget = static_cast<long long>(cx.tuning.path_step_factor * seed.steps_per_period) + 1000;
    step.orbit = solve_orbit(cx, chart, *base, seed.winding, budget, options, final, seed, single);
  } catch (const std::exception& e) {
    step.outcome = Outcome::error;
    step.error = e.what();
  }
  return step;
}

/// Follows the path from the seed to the scene (λ = 1); the run's result there, or nullopt
/// with `why` and what the tries cost in `spent`. `before`: what the case integrated
/// before the path (its simulation.max_periods bounds both).
std::optional<RunResult> follow_path(const Scene& scene, const ContinuationStart& from, RunResult& spent,
                                     std::string& why, long long before = 0) {
  const SteadyTuning tuning;
  OrbitSeed seed = from.seed;
  double lambda = 0.0, step = 1.0;
  int steps = 0;
  why = seed.valid() ? "" : "the neighbour has no orbit";
  const double min_step = from.min_step > 0.0 ? from.min_step : tuning.min_path_step;
  while (seed.valid() && step >= min_step) {
    const long long used = before + spent.steady.periods_integrated;
    if (budget_spent(scene, used, why)) break;
    const double next = std::min(1.0, lambda + step);
    const bool final = next >= 1.0;
    const Scene between = final ? Scene{} : from.path(next);
    SteadyContext cx(final ? scene : between, PeriodBudget(scene.simulation.max_periods, used));
    const verdict::ContinuationStep tried = continue_from(cx, seed, final, min_step >= 1.0);
    const bool ok = verdict::continuation_step(cx.res, tried);
    ++steps;
    const long iterations = tried.outcome == verdict::ContinuationStep::Outcome::orbit ? tried.orbit.newton.iterations : 0;
    RunResult part = verdict::close(cx, std::chrono::steady_clock::now());
    if (ok && final) {
      add_costs(part, spent);
      verdict::continued(part, steps);
      return part;
    }
    add_costs(spent, part);
    if (ok) {
      seed = std::move(part.orbit_seed);
      lambda = next;
      if (iterations <= 2) step *= 2.0;  // quick: a longer step next
    } else {
      step *= 0.5;
      why = part.message;
    }
  }
  why = verdict::path_stopped(lambda, steps, why);
  return std::nullopt;
}

}  // namespace

RunResult run_alone(const Scene& scene, long long before) {
  const auto wall0 = std::chrono::steady_clock::now();
  const SteadyTuning tuning;
  const long long limit = scene.simulation.max_periods;
  RunResult own = run_steady(scene, PeriodBudget(limit, before));
  if (own.status != RunStatus::ok || found_orbit(own) || scene.simulation.max_cycles < kMinSteadyCycles) return own;
  std::string why;
  if (budget_spent(scene, before + own.steady.periods_integrated, why)) {
    verdict::budget_spent(own, why);
    return finish_wall(std::move(own), wall0);
  }
  auto thick_version = [&scene](double factor) {
    Scene s = scene;
    for (JointSpec& j : s.joints)
      if (j.type == JointType::lubricated_revolute) j.viscosity_Pa_s *= factor;
    return s;
  };
  const Scene thick = thick_version(tuning.thick_film);
  const RunResult seeded = run_steady(thick, PeriodBudget(limit, before + own.steady.periods_integrated));
  add_costs(own, seeded);
  if (!seeded.orbit_seed.valid()) {
    verdict::thick_film_none(own, seeded);
    return finish_wall(std::move(own), wall0);
  }
  const ContinuationStart from{seeded.orbit_seed, [&](double lambda) {
                                 return thick_version(std::pow(tuning.thick_film, 1.0 - lambda));
                               }};
  std::optional<RunResult> r = follow_path(scene, from, own, why, before);
  if (!r) {
    verdict::thick_film_path_failed(own, why);
    return finish_wall(std::move(own), wall0);
  }
  verdict::thick_film_continued(*r);
  return finish_wall(std::move(*r), wall0);
}

RunResult run_continued(const Scene& scene, const ContinuationStart& from) {
  const auto wall0 = std::chrono::steady_clock::now();
  RunResult spent;
  std::string why;
  if (std::optional<RunResult> r = follow_path(scene, from, spent, why)) return finish_wall(std::move(*r), wall0);
  // The budget is spent: the path's account is the case's.
  std::string none;
  if (budget_spent(scene, spent.steady.periods_integrated, none)) {
    verdict::path_spent(spent, why);
    return finish_wall(std::move(spent), wall0);
  }
  if (!from.alone_if_lost) {  // the seed's orbit is lost on the way: the run ends there
    verdict::path_lost(spent, why);
    return finish_wall(std::move(spent), wall0);
  }
  // The path could not be followed: the scene alone.
  RunResult r = run_alone(scene, spent.steady.periods_integrated);
  add_costs(r, spent);
  verdict::path_then_alone(r, why);
  return finish_wall(std::move(r), wall0);
}

}  // namespace lub::detail

namespace lub {

namespace {

using nlohmann::json;

/// The scene's JSON at λ on the path from `from` (λ = 0) to `to` (λ = 1): every number that
/// differs interpolated, in its logarithm where both ends are positive (viscosities,
/// speeds, radii), linearly otherwise; anything else as `to` has it.
json between(const json& from, const json& to, double lambda) {
  if (from.is_object() && to.is_object()) {
    json out = to;
    for (auto it = out.begin(); it != out.end(); ++it)
      if (from.contains(it.key())) *it = between(from.at(it.key()), *it, lambda);
    return out;
  }
  if (from.is_array() && to.is_array() && from.size() == to.size()) {
    json out = to;
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = between(from[i], to[i], lambda);
    return out;
  }
  if (from.is_number() && to.is_number() && !to.is_number_integer() && from != to) {
    const double a = from.get<double>(), b = to.get<double>();
    return a > 0.0 && b > 0.0 ? std::exp((1.0 - lambda) * std::log(a) + lambda * std::log(b))
                              : (1.0 - lambda) * a + lambda * b;
  }
  return to;
}

}  // namespace

std::function<Scene(double lambda)> scene_path(const json& from, const json& to) {
  return [from, to](double lambda) { return parse_scene(between(from, to, lambda)); };
}

}  // namespace lub
