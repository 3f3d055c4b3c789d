// Right-hand-side cost: one evaluation of the equations of motion of the paper's
// slider-crank (absolute coordinates, 9 coordinates, 7 constraint rows, one film) for
// each force law, and the same with all joints ideal (no film).
//
//   build/tests/bench/bench_rhs
#include <benchmark/benchmark.h>

#include "lub/mechanism/builder.hpp"
#include "lub/mechanism/model.hpp"

namespace {

struct Fixture {
  lub::Scene scene;
  lub::Model model;
  Eigen::VectorXd q, v, a;
  explicit Fixture(const std::string& law) {
    nlohmann::json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
    doc["joints"][3]["force_law"] = law;
    scene = lub::parse_scene(doc);
    model = lub::build_model(scene);
    lub::assemble_initial_state(model, scene, 0.0, q, v);
    // Move the journal off-centre, as in a running bearing (ε ≈ 0.6, moving).
    q(3) += 2.0e-4;
    q(4) += 2.0e-4;
    v(3) += 0.05;
    a.resize(model.nq);
  }
};

void BM_Evaluate(benchmark::State& state, const std::string& law) {
  Fixture f(law);
  lub::Workspace ws(f.model);
  for (auto _ : state) {
    benchmark::DoNotOptimize(lub::evaluate(f.model, ws, lub::stabilisation(f.scene), 1e-3, f.q.data(), f.v.data(), f.a.data()));
    benchmark::ClobberMemory();
  }
}

BENCHMARK_CAPTURE(BM_Evaluate, ideal, std::string("ideal"));
BENCHMARK_CAPTURE(BM_Evaluate, frene_long, std::string("frene_long"));
BENCHMARK_CAPTURE(BM_Evaluate, frene_short, std::string("frene_short"));
BENCHMARK_CAPTURE(BM_Evaluate, pinkus_sternlicht, std::string("pinkus_sternlicht"));

}  // namespace

BENCHMARK_MAIN();
