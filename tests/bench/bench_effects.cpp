// What not simulating an absent effect saves. The model holds only the terms a scene names
// (DESIGN: no zero-multiplied term), so each effect costs only when it is there:
//
//  - BM_Rhs: one right-hand-side evaluation (lub::evaluate, q̈ from q, q̇) of a scene with
//    and without gravity, with gravity named but zero (what an always-present,
//    zero-multiplied term would cost), and with its lubricated joints as films or ideal
//    (force_law "ideal": two constraint rows instead of a force law);
//  - BM_Run: one crank cycle of the four-bar, recording every channel or none (metrics
//    only), so the cost of series nobody asked for;
//  - BM_RhsMixed: one evaluation of the slider-crank (Frêne short) without and with mixed
//    lubrication, its journal 100 µm or 1 µm from the wall (asperity band not reached, reached);
//  - BM_RhsFriction: the same evaluation (film 100 µm) without and with effects.film_friction
//    (the film's shear torques applied to the bodies).
//
//   build/tests/bench/bench_effects
#include <benchmark/benchmark.h>

#include <string>

#include "lub/mechanism/builder.hpp"
#include "lub/mechanism/model.hpp"
#include "lub/run/run.hpp"

namespace {

using nlohmann::json;

json load(const std::string& name) {
  return lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/" + name);
}

enum Gravity { kGravity, kNoGravity, kZeroGravity };

// scene: 0 four_bar (one film), 1 slider_crank_two_lubricated (two films).
json variant(int scene, Gravity g, bool films) {
  json doc = load(scene == 0 ? "four_bar.json" : "slider_crank_two_lubricated.json");
  if (g == kNoGravity) doc.erase("effects");
  if (g == kZeroGravity) doc["effects"]["gravity_m_s2"] = {0.0, 0.0};
  for (auto& j : doc["joints"])
    if (j["type"] == "lubricated_revolute") {
      // A running bearing: off-centre (ε ≈ 0.45), which the assembly keeps.
      j["initial_eccentricity_m"] = {2.0e-4, 1.0e-4};
      if (!films) j["force_law"] = "ideal";
    }
  return doc;
}

// Times lub::evaluate of `m` at the scene's assembled initial state.
void time_rhs(benchmark::State& state, const lub::Scene& s, const lub::Model& m, lub::Workspace& ws) {
  Eigen::VectorXd q, v;
  lub::assemble_initial_state(m, s, 0.0, q, v);
  Eigen::VectorXd a(m.nq);
  for (auto _ : state) {
    benchmark::DoNotOptimize(lub::evaluate(m, ws, lub::stabilisation(s), 1e-3, q.data(), v.data(), a.data()));
    benchmark::ClobberMemory();
  }
}

void BM_Rhs(benchmark::State& state) {
  const int scene = static_cast<int>(state.range(0));
  const auto g = static_cast<Gravity>(state.range(1));
  const bool films = state.range(2) != 0;
  const lub::Scene s = lub::parse_scene(variant(scene, g, films));
  const lub::Model m = lub::build_model(s);
  lub::Workspace ws(m);
  time_rhs(state, s, m, ws);
  const double n = static_cast<double>(ws.counters.rhs);
  state.counters["gravity_per_rhs"] = static_cast<double>(ws.counters.gravity) / n;
  state.counters["laws_per_rhs"] = static_cast<double>(ws.counters.film) / n;
  state.counters["constraint_rows"] = m.nc;
  static const char* kScene[] = {"four_bar", "slider_crank_two_lubricated"};
  static const char* kGravityName[] = {"gravity", "no gravity", "gravity [0,0]"};
  state.SetLabel(std::string(kScene[scene]) + ", " + kGravityName[g] + ", " +
                 (films ? "films" : "ideal joints"));
}
// Arguments: scene, gravity (0 named, 1 absent, 2 named but zero), films (1) or ideal (0).
BENCHMARK(BM_Rhs)
    ->ArgsProduct({{0, 1}, {kGravity, kNoGravity, kZeroGravity}, {1, 0}})
    ->ArgNames({"scene", "gravity", "films"});

void BM_Run(benchmark::State& state) {
  json doc = load("four_bar.json");
  doc["simulation"]["max_cycles"] = 1;
  doc["simulation"]["metric_cycles"] = 1;
  const bool record = state.range(0) != 0;
  if (!record) doc["outputs"]["channels"] = json::array();
  const lub::Scene s = lub::parse_scene(doc);
  lub::RunResult r;
  for (auto _ : state) r = lub::run_scene(s);
  state.counters["model_evals"] = static_cast<double>(r.stats.model_evals);
  state.counters["samples"] = r.series.data.empty() ? 0.0 : static_cast<double>(r.series.data[0].size());
  state.SetLabel(record ? "four_bar, 1 cycle, 14 channels" : "four_bar, 1 cycle, metrics only");
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Run)->Arg(1)->Arg(0)->ArgNames({"channels"})->Unit(benchmark::kMillisecond);

void BM_RhsMixed(benchmark::State& state) {
  const bool mixed = state.range(0) != 0;
  const double film_um = static_cast<double>(state.range(1));
  json doc = load("slider_crank.json");
  doc["joints"][3]["force_law"] = "frene_short";
  const double e = 0.5e-3 - film_um * 1e-6;  // the scene's clearance less the film
  doc["joints"][3]["initial_eccentricity_m"] = {-e, 0.0};
  if (mixed)
    doc["effects"]["mixed_lubrication"] = {{"roughness_m", 5e-7}, {"asperity_density_per_m2", 1.6e8},
                                           {"asperity_radius_m", 5e-4}, {"composite_modulus_Pa", 8e10}};
  const lub::Scene s = lub::parse_scene(doc);
  const lub::Model m = lub::build_model(s);
  lub::Workspace ws(m);
  time_rhs(state, s, m, ws);
  state.SetLabel(std::string("slider_crank frene_short, film ") + std::to_string(state.range(1)) + " um, " +
                 (mixed ? "mixed lubrication" : "no asperities"));
}
// Arguments: mixed lubrication (1) or not (0), the film from the wall [µm].
BENCHMARK(BM_RhsMixed)->ArgsProduct({{0, 1}, {100, 1}})->ArgNames({"mixed", "film_um"});

void BM_RhsFriction(benchmark::State& state) {
  const bool friction = state.range(0) != 0;
  json doc = load("slider_crank.json");
  doc["joints"][3]["force_law"] = "frene_short";
  doc["joints"][3]["initial_eccentricity_m"] = {-4e-4, 0.0};
  if (friction) doc["effects"]["film_friction"] = json::object();
  const lub::Scene s = lub::parse_scene(doc);
  const lub::Model m = lub::build_model(s);
  lub::Workspace ws(m);
  time_rhs(state, s, m, ws);
  state.SetLabel(std::string("slider_crank frene_short, film 100 um, ") + (friction ? "friction applied" : "no friction"));
}
BENCHMARK(BM_RhsFriction)->Arg(0)->Arg(1)->ArgNames({"friction"});

}  // namespace

BENCHMARK_MAIN();
