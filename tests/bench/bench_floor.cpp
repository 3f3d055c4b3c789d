// Engine against the floor: the cost per crank cycle of the general engine (absolute
// coordinates, constraints, observers and metrics) and of the hand-written two-degree-
// of-freedom model of the same lubricated slider-crank (tests/floor_slider_crank.hpp),
// with the same integrator (CVODE BDF, dense Newton) and tolerance. Both integrate 4
// cycles from the paper's initial state; time per cycle = time / 4.
//
//   build/tests/bench/bench_floor --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include "../floor_slider_crank.hpp"
#include "lub/run.hpp"

namespace {

constexpr int kCycles = 4;

nlohmann::json scene(const std::string& law, double rtol) {
  nlohmann::json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = law;
  doc["solver"]["rtol"] = rtol;
  doc["simulation"]["max_cycles"] = kCycles;
  doc["outputs"]["channels"] = nlohmann::json::array();
  return doc;
}

const char* kLaws[] = {"frene_long", "frene_short", "pinkus_sternlicht"};
const lub::ForceLaw kLawIds[] = {lub::ForceLaw::frene_long, lub::ForceLaw::frene_short,
                                 lub::ForceLaw::pinkus_sternlicht};
const double kRtol[] = {1e-6, 1e-8};

void BM_Engine(benchmark::State& state) {
  const lub::Scene s = lub::parse_scene(scene(kLaws[state.range(0)], kRtol[state.range(1)]));
  lub::RunResult r;
  for (auto _ : state) r = lub::run_scene(s);
  state.counters["steps_per_cycle"] = double(r.stats.steps) / kCycles;
  state.counters["rhs_per_cycle"] = double(r.stats.rhs_evals + r.stats.rhs_evals_jac) / kCycles;
  state.counters["observer_per_cycle"] = double(r.stats.observer_evals) / kCycles;
  state.SetLabel(std::string(kLaws[state.range(0)]) + " rtol " + std::to_string(kRtol[state.range(1)]));
}

void BM_Floor(benchmark::State& state) {
  floor_model::Params p;
  p.law = kLawIds[state.range(0)];
  const double T = 2 * M_PI / p.omega;
  floor_model::Result r;
  for (auto _ : state) r = floor_model::integrate(p, kCycles, kRtol[state.range(1)], true, T);
  state.counters["steps_per_cycle"] = double(r.steps) / kCycles;
  state.counters["rhs_per_cycle"] = double(r.rhs_evals) / kCycles;
  state.SetLabel(std::string(kLaws[state.range(0)]) + " rtol " + std::to_string(kRtol[state.range(1)]));
}

// The printed Pinkus–Sternlicht law (index 2) needs event handling that the floor does
// not have: without it the floor chatters, so only the continuous laws are compared.
BENCHMARK(BM_Engine)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Floor)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
