// What a sensitivity costs (docs/theory/sensitivities.md): d(metrics)/d(viscosity) of the paper's
// reference orbit (printed law, 0.5 mm, 400 cP, 5000 rpm, steady auto) by the implicit-function
// route (steady_sensitivities: 8 periods at rtol/100), against central differences of two
// orbits located separately at ± 1 % (two whole steady stages), side by side in one run.
//
//   build/tests/bench/bench_sensitivity
#include <benchmark/benchmark.h>

#include <string>

#include "lub/run/run.hpp"

namespace {

using nlohmann::json;

json reference() {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["simulation"]["steady"] = "auto";
  doc["outputs"]["channels"] = json::array();
  return doc;
}

lub::Scene at(const json& doc, double viscosity) {
  json d = doc;
  d["joints"][3]["viscosity_Pa_s"] = viscosity;
  return lub::parse_scene(d);
}

void BM_ImplicitFunction(benchmark::State& state) {
  const json doc = reference();
  const lub::Scene scene = lub::parse_scene(doc);
  const lub::RunResult r = lub::run_scene(scene);
  lub::SensitivityParameter p{"/joints/3/viscosity_Pa_s", "Pa s", 0.4, [&doc](double v) { return at(doc, v); }};
  long long periods = 0;
  for (auto _ : state) {
    const auto s = lub::steady_sensitivities(r, {p});
    periods = s.front().periods;
    benchmark::DoNotOptimize(s.front().d_metric.data());
  }
  state.counters["periods"] = static_cast<double>(periods);
  state.SetLabel("dz*/dlambda = (I - M)^-1 dP/dlambda, metrics measured on the predicted orbits");
}
BENCHMARK(BM_ImplicitFunction)->Unit(benchmark::kMillisecond);

void BM_CentralDifferences(benchmark::State& state) {
  const json doc = reference();
  long long periods = 0;
  for (auto _ : state) {
    const lub::RunResult plus = lub::run_scene(at(doc, 0.404)), minus = lub::run_scene(at(doc, 0.396));
    periods = plus.steady.periods_integrated + minus.steady.periods_integrated;
    benchmark::DoNotOptimize(plus.metrics.min_film_thickness_m - minus.metrics.min_film_thickness_m);
  }
  state.counters["periods"] = static_cast<double>(periods);
  state.SetLabel("two orbits located separately at +-1 %");
}
BENCHMARK(BM_CentralDifferences)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
