// What the period map's derivative costs (docs/theory/steady-cycles.md, the map's
// derivative): the monodromy of Frêne long's period at its state 20 cycles from rest (the
// paper's reference case, 0.5 mm, 400 cP, 5000 rpm), at rtol 1e-10 as the steady stage's
// tight maps, by central differences of whole periods (2 n = 8 periods, shooting's default)
// against one period with its forward sensitivities (simulation.monodromy = sensitivities),
// side by side in one run.
//
//   build/tests/bench/bench_monodromy
#include <benchmark/benchmark.h>

#include <optional>
#include <string>

#include "lub/io/json_reader.hpp"
#include "lub/run/run.hpp"
#include "run/period_map.hpp"
#include "run/segment.hpp"

namespace {

struct Frene {
  Frene() : scene(make_scene()), rm(scene) {
    lub::detail::SegmentOptions o;
    o.cycles = 20;
    o.series = false;
    const lub::detail::SegmentResult seg = lub::detail::run_segment(rm, o);
    x = seg.end;
    winding = lub::detail::winding_per_period(rm.model, seg.boundaries[seg.boundaries.size() - 2], seg.boundaries.back());
    chart.emplace(rm, x);
    P.emplace(rm, *chart, x, winding, 0.01, stats, periods);
    z = chart->reduce(x.qv);
  }
  static lub::Scene make_scene() {
    nlohmann::json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
    doc["joints"][3]["force_law"] = "frene_long";
    doc["outputs"]["channels"] = nlohmann::json::array();
    return lub::parse_scene(doc);
  }
  lub::Scene scene;
  lub::detail::RunModel rm;
  lub::detail::StartState x;
  std::vector<double> winding;
  std::optional<lub::detail::Chart> chart;
  lub::SolverStats stats;
  long long periods = 0;
  std::optional<lub::detail::PeriodMap> P;
  Eigen::VectorXd z;
};

/// M at the state by the map's own derivative (`derivative`) or by central differences.
void BM_Monodromy(benchmark::State& state, bool derivative, const char* label) {
  Frene f;
  const lub::steady::MonodromyOptions o{f.chart->units(), 1e-4, true, 0, derivative};
  long long maps = 0;
  for (auto _ : state) maps = lub::steady::monodromy(*f.P, f.z, f.z, o).maps;
  state.counters["periods"] = static_cast<double>(maps);
  state.SetLabel(label);
}
BENCHMARK_CAPTURE(BM_Monodromy, ByDifferences, false, "central differences of whole periods, step 1e-4 of each unit")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Monodromy, BySensitivities, true, "one period with its forward sensitivities")
    ->Unit(benchmark::kMillisecond);

}  // namespace
BENCHMARK_MAIN();
