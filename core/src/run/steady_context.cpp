// The steady stage's shared context: measuring, the period maps, shooting's options.
#include "run/steady_context.hpp"

#include <algorithm>

namespace lub::detail {

double SteadyContext::orbit_noise_floor() const {
  // The phase points come from the dense output, accurate to about rtol × c in the
  // clearance's unit; the cycle-to-cycle distance of a converged printed-law transient
  // plateaus near there (the interpolant and the restarts at every ε̇ = 0 switch).
  return std::max(tuning.noise_per_rtol * scene.solver.rtol, tuning.noise_per_tolerance * sim.steady_tolerance);
}

double SteadyContext::finer(double factor) const {
  if (factor >= 1.0) return factor;
  return std::min(1.0, std::max(factor, tuning.finest_rtol / scene.solver.rtol));
}

SegmentResult SteadyContext::measure(const StartState& s, double factor, bool series, int cycles) {
  SegmentOptions o;
  o.start = &s;
  o.cycles = cycles > 0 ? cycles : sim.metric_cycles;
  if (!budget.allows(o.cycles, spent(), factor == 1.0 ? "the orbit not measured" : "no error bars")) {
    SegmentResult refused;
    refused.res.status = RunStatus::budget_exceeded;
    refused.res.message = "simulation.max_periods reached";
    return refused;
  }
  o.rtol_factor = finer(factor);
  o.series = series;
  // Bounded like a period map once a transient has set the pace: a measurement that crawls
  // near the wall (the printed law's kink where ε̇ and the wedge speed vanish: 2e7 steps in
  // one measurement, twice, on the full factorial) ends with the segment's budget instead.
  if (!res.cycles.empty())
    o.max_steps = transient_step_budget() * o.cycles * (factor < 1.0 ? tuning.tight_step_factor : 1);
  SegmentResult seg = run_segment(rm, o);
  accumulate(res.stats, seg.res.stats);
  res.steady.periods_integrated += o.cycles;
  return seg;
}

void SteadyContext::period_maps(std::optional<PeriodMap>& period, std::optional<PeriodMap>& tight, Chart& chart,
                                const StartState& base, const std::vector<double>& winding, double factor,
                                long long steps) {
  period.emplace(rm, chart, base, winding, finer(factor), res.stats, res.steady.periods_integrated);
  period->set_step_budget(steps);
  period->set_period_budget(budget.run_limit());
  tight.emplace(rm, chart, base, winding, finer(factor * tuning.tight_factor), res.stats,
                res.steady.periods_integrated);
  tight->set_step_budget(tuning.tight_step_factor * steps);
  tight->set_period_budget(budget.run_limit());
}

std::vector<double> SteadyContext::transient_winding() const {
  return winding_per_period(rm.model, boundaries[boundaries.size() - 2], boundaries.back());
}

long long SteadyContext::transient_step_budget() const {
  // Its first cycles, from rest, included.
  return tuning.crawl_factor * res.stats.steps / std::max<long long>(1, static_cast<long long>(res.cycles.size())) +
         1000;
}

steady::ShootingOptions SteadyContext::shooting_options(const Chart& chart, double max_eps) const {
  steady::ShootingOptions options;
  options.scales = chart.units();
  options.residual_scales = chart.residual_units();
  options.tolerance = sim.shooting_tolerance;
  if (sim.shooting_fallback == ShootingFallback::anderson) options.difference_retries = 2;
  options.map_derivative = sim.monodromy == MonodromyMethod::sensitivities;
  // The wall chart keeps every iterate and difference step inside the clearance, and
  // its steps are relative changes of the gap.
  if (chart.wall()) {
    options.step = tuning.difference_step;
    return options;
  }
  // Near the wall a step of 1 % of the clearance would put the perturbed journal through
  // it: at most a tenth of the thinnest gap, 1 − ε_max (in clearances), of the cycle
  // shooting starts from.
  const double gap = !(max_eps > 0.0) ? 1.0 : 1.0 - max_eps;
  options.step = std::min(tuning.difference_step, 0.1 * gap);
  // Newton's steps no longer than the gap either (they are measured in the same units).
  options.max_newton_step = std::min(options.max_newton_step, gap);
  return options;
}

}  // namespace lub::detail
