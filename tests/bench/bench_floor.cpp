// Engine against the floor: the cost per crank cycle of the general engine (absolute
// coordinates, constraints, observers and metrics) and of the hand-written two-degree-
// of-freedom model of the same lubricated slider-crank (tests/fixtures/floor_slider_crank.hpp),
// with the same integrator (CVODE BDF, dense Newton) and tolerance. Both integrate 4
// cycles from the paper's initial state; time per cycle = time / 4. After the runs a
// table gives, per force law and tolerance, the engine's CPU time over the floor's for
// each formulation, and each law's cost over the Frêne long law's. The printed
// Pinkus–Sternlicht law runs with events on both sides. Formulations: baumgarte,
// partitioned and joint (joint coordinates of the tree the lubricated joint leaves) (the floor's Filippov switching,
// tests/fixtures/floor_slider_crank.hpp).
//
//   build/tests/bench/bench_floor --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "../fixtures/floor_slider_crank.hpp"
#include "lub/run/run.hpp"

namespace {

constexpr int kCycles = 4;

// The continuous laws, then the printed one (events).
const char* kLaws[] = {"frene_long", "frene_short", "gumbel_long", "gumbel_short",
                       "pinkus_sternlicht_continuous", "pinkus_sternlicht"};
const lub::ForceLaw kLawIds[] = {lub::ForceLaw::frene_long, lub::ForceLaw::frene_short,
                                 lub::ForceLaw::gumbel_long, lub::ForceLaw::gumbel_short,
                                 lub::ForceLaw::pinkus_sternlicht_continuous, lub::ForceLaw::pinkus_sternlicht};
constexpr int kLawCount = 6;
const double kRtol[] = {1e-6, 1e-8};
const char* kForms[] = {"baumgarte", "partitioned", "joint"};

nlohmann::json scene(const std::string& law, double rtol, const std::string& formulation) {
  nlohmann::json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = law;
  doc["solver"]["rtol"] = rtol;
  doc["solver"]["formulation"] = formulation;
  doc["simulation"]["max_cycles"] = kCycles;
  doc["outputs"]["channels"] = nlohmann::json::array();
  return doc;
}

std::string key(int law, int rtol) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s rtol %.0e", kLaws[law], kRtol[rtol]);
  return buf;
}

void BM_Engine(benchmark::State& state) {
  const int law = static_cast<int>(state.range(0)), rt = static_cast<int>(state.range(1));
  const char* form = kForms[state.range(2)];
  const lub::Scene s = lub::parse_scene(scene(kLaws[law], kRtol[rt], form));
  lub::RunResult r;
  for (auto _ : state) r = lub::run_scene(s);
  if (r.status != lub::RunStatus::ok) state.SkipWithError(r.message.c_str());
  state.counters["steps_per_cycle"] = double(r.stats.steps) / kCycles;
  state.counters["rhs_per_cycle"] = double(r.stats.rhs_evals + r.stats.rhs_evals_jacobian) / kCycles;
  state.counters["observer_per_cycle"] = double(r.stats.observer_evals) / kCycles;
  state.SetLabel("engine " + key(law, rt) + " " + form);
}

void BM_Floor(benchmark::State& state) {
  const int law = static_cast<int>(state.range(0)), rt = static_cast<int>(state.range(1));
  floor_model::Params p;
  p.law = kLawIds[law];
  const double T = 2 * M_PI / p.omega;
  floor_model::Result r;
  for (auto _ : state) r = floor_model::integrate(p, kCycles, kRtol[rt], true, T);
  if (!r.ok) state.SkipWithError("the floor's integration failed");
  state.counters["steps_per_cycle"] = double(r.steps) / kCycles;
  state.counters["rhs_per_cycle"] = double(r.rhs_evals) / kCycles;
  state.SetLabel("floor " + key(law, rt));
}

BENCHMARK(BM_Engine)->ArgsProduct({{0, 1, 2, 3, 4, 5}, {0, 1}, {0, 1, 2}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Floor)->ArgsProduct({{0, 1, 2, 3, 4, 5}, {0, 1}})->Unit(benchmark::kMillisecond);

// Prints as the console does, and keeps each run's CPU time by label for the table.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs)
      if (!r.error_occurred && r.run_type == Run::RT_Iteration) cpu_[r.report_label] = r.GetAdjustedCPUTime();
  }
  double cpu(const std::string& label) const {
    const auto it = cpu_.find(label);
    return it == cpu_.end() ? -1.0 : it->second;
  }

 private:
  std::map<std::string, double> cpu_;
};

void print_ratios(const RatioReporter& rep) {
  std::printf("\nEngine CPU time over the hand-written floor's, per crank cycle (same CVODE BDF, same rtol):\n");
  std::printf("%-44s %12s %12s %12s %12s %12s\n", "law, rtol", "floor [ms]", "baumgarte", "partitioned", "joint",
              "over frene_long");
  for (int rt = 0; rt < 2; ++rt)
    for (int law = 0; law < kLawCount; ++law) {
      const std::string k = key(law, rt);
      const double fl = rep.cpu("floor " + k);
      const double b = rep.cpu("engine " + k + " baumgarte"), p = rep.cpu("engine " + k + " partitioned");
      const double jt = rep.cpu("engine " + k + " joint");
      const double ref = rep.cpu("engine " + key(0, rt) + " baumgarte");
      auto ratio = [](double a, double d) {
        char buf[32];
        if (a > 0 && d > 0) std::snprintf(buf, sizeof buf, "%.2fx", a / d);
        else std::snprintf(buf, sizeof buf, "-");
        return std::string(buf);
      };
      char fbuf[32];
      if (fl > 0) std::snprintf(fbuf, sizeof fbuf, "%.3f", fl / kCycles);
      else std::snprintf(fbuf, sizeof fbuf, "-");
      std::printf("%-44s %12s %12s %12s %12s %12s\n", k.c_str(), fbuf, ratio(b, fl).c_str(), ratio(p, fl).c_str(),
                  ratio(jt, fl).c_str(), ratio(b, ref).c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter rep;
  benchmark::RunSpecifiedBenchmarks(&rep);
  print_ratios(rep);
  benchmark::Shutdown();
  return 0;
}
