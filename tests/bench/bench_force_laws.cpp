// Cost per evaluation of each force law (docs/theory/force-laws.md).
//
//   build/tests/bench/bench_force_laws --benchmark_min_time=0.5
//
// States: the paper's bearing (R_J = 9.5 mm, c = 0.5 mm, L = 40 mm, 400 cP). Closed forms cycle
// through 64 states spread over ε ∈ [0, 0.95] with mixed squeeze and wedge of both signs (so
// branch prediction sees realistic variety). finite_reynolds is measured two ways:
//  - "trajectory": one solver along a slowly varying state, as inside a simulation (the
//    Reynolds active set is warm-started from the previous call);
//  - "jumps": one solver through the 64 unrelated states (a cold-ish start every call).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "lub/bearing/film_force.hpp"
#include "lub/bearing/reynolds.hpp"
#include "../fixtures/bearing_fixture.hpp"

namespace {

using bearing_fixture::kMu;
using bearing_fixture::paper_bearing;

std::vector<lub::BearingState> spread_states() {
  std::vector<lub::BearingState> v;
  for (int k = 0; k < 64; ++k) {
    lub::BearingState s;
    s.eps = 0.95 * ((k * 37) % 64) / 63.0;
    s.eps_dot = 20.0 * std::sin(1.7 * k);
    s.wedge = 500.0 * std::cos(0.9 * k);
    v.push_back(s);
  }
  return v;
}

std::vector<lub::BearingState> trajectory_states() {
  // A journal orbit: ε between 0.3 and 0.9, slowly varying, 2000 samples over one cycle.
  std::vector<lub::BearingState> v;
  const double pi = 3.14159265358979323846;
  for (int k = 0; k < 2000; ++k) {
    const double ph = 2.0 * pi * k / 2000.0;
    lub::BearingState s;
    s.eps = 0.6 + 0.3 * std::sin(ph);
    s.eps_dot = 0.3 * 2.0 * pi * 80.0 * std::cos(ph);  // 80 Hz orbit
    s.wedge = 523.6 - 2.0 * 100.0 * std::sin(2.0 * ph);
    v.push_back(s);
  }
  return v;
}

const lub::ForceLaw kClosed[] = {lub::ForceLaw::pinkus_sternlicht, lub::ForceLaw::frene_long,
                                 lub::ForceLaw::frene_short,       lub::ForceLaw::gumbel_long,
                                 lub::ForceLaw::gumbel_short,      lub::ForceLaw::pinkus_sternlicht_continuous};

void BM_ClosedForm(benchmark::State& state) {
  const lub::ForceLaw law = kClosed[state.range(0)];
  const auto g = paper_bearing();
  const auto states = spread_states();
  size_t k = 0;
  for (auto _ : state) {
    const lub::FilmForce f = lub::film_force(law, g, kMu, states[k]);
    benchmark::DoNotOptimize(f);
    k = (k + 1) & 63;
  }
  state.SetLabel(std::string(lub::name_of(law)));
}
BENCHMARK(BM_ClosedForm)->DenseRange(0, 5);

const lub::Cavitation kCav[] = {lub::Cavitation::sommerfeld, lub::Cavitation::gumbel, lub::Cavitation::reynolds};

void BM_FiniteReynolds(benchmark::State& state) {
  lub::FiniteBearingOptions o;
  o.cavitation = kCav[state.range(0)];
  o.n_theta = static_cast<int>(state.range(1));
  o.n_z = static_cast<int>(state.range(2));
  const bool jumps = state.range(3) != 0;
  lub::FiniteBearingSolver solver(o);
  const auto g = paper_bearing();
  const auto states = jumps ? spread_states() : trajectory_states();
  size_t k = 0;
  long long iterations = 0;
  for (auto _ : state) {
    const lub::FilmForce f = solver.solve(g, kMu, states[k]);
    benchmark::DoNotOptimize(f);
    iterations += solver.stats().active_set_iterations;
    k = (k + 1) % states.size();
  }
  state.counters["active_set_iterations"] =
      benchmark::Counter(double(iterations), benchmark::Counter::kAvgIterations);
  state.SetLabel(std::string(lub::name_of(o.cavitation)) + (jumps ? " jumps" : " trajectory"));
}
BENCHMARK(BM_FiniteReynolds)
    ->ArgsProduct({{0, 1, 2}, {48}, {8}, {0, 1}})
    ->ArgsProduct({{1, 2}, {32, 64, 96}, {4, 8, 12}, {0}})
    ->Unit(benchmark::kMicrosecond);

// The friction, flows and peak pressure of the last solution (lub/bearing/film_outputs.hpp):
// what they add to a solve, on the default grid, Reynolds cavitation.
void BM_FiniteOutputs(benchmark::State& state) {
  lub::FiniteBearingOptions o;
  o.cavitation = lub::Cavitation::reynolds;
  lub::FiniteBearingSolver solver(o);
  const auto g = paper_bearing();
  solver.solve(g, kMu, trajectory_states()[0]);
  for (auto _ : state) benchmark::DoNotOptimize(solver.outputs(100.0));
  state.SetLabel("reynolds 48 x 8, after a solve");
}
BENCHMARK(BM_FiniteOutputs)->Unit(benchmark::kMicrosecond);

// The peak of a closed-form law's pressure field (lub/bearing/film_outputs.hpp), what a run's
// recorder pays per measuring observation: short (Eq. 3), long (Eq. 5), π film.
void BM_PeakPressure(benchmark::State& state) {
  const lub::ForceLaw laws[] = {lub::ForceLaw::frene_short, lub::ForceLaw::frene_long,
                                lub::ForceLaw::pinkus_sternlicht_continuous};
  const lub::ForceLaw law = laws[state.range(0)];
  const auto g = paper_bearing();
  const auto states = trajectory_states();
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(lub::peak_film_pressure(law, g, kMu, states[k]));
    k = (k + 1) % states.size();
  }
  state.SetLabel(std::string(lub::name_of(law)));
}
BENCHMARK(BM_PeakPressure)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
