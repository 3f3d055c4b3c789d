// Fuzz target: the scene reader must refuse any input with an InputError, never crash,
// hang, leak an exception of another type or accept a scene that breaks its invariants.
//
// Each input is used twice:
//  1. as a scene file: parse_json_text → parse_scene; an accepted scene is checked against
//     the invariants the model relies on, then built (build_model) and assembled
//     (assemble_initial_state) when it is small;
//  2. as a `--set POINTER=VALUE` assignment (first line only) applied to a small valid
//     scene, which is then validated: this reaches the deep rules that random JSON rarely
//     gets to.
// Built with libFuzzer + ASan + UBSan by tools/check/fuzz.sh (clang), and as a plain replay
// program (replay_main.cpp) that ctest runs over the seed corpus in every build.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "fuzz_check.hpp"

#include "lub/mechanism/builder.hpp"
#include "lub/mechanism/model.hpp"
#include "lub/scene/scene.hpp"

namespace {

using nlohmann::json;

#define FUZZ_CHECK(cond) LUB_FUZZ_CHECK("fuzz_scene", cond)

bool body_ok(const lub::Scene& s, int b, bool ground_ok) {
  return (ground_ok && b == lub::kGround) || (b >= 0 && b < static_cast<int>(s.bodies.size()));
}

void check_invariants(const lub::Scene& s) {
  FUZZ_CHECK(!s.bodies.empty());
  for (const auto& b : s.bodies) {
    FUZZ_CHECK(b.mass_kg > 0 && std::isfinite(b.mass_kg));
    FUZZ_CHECK(b.inertia_kg_m2 > 0 && std::isfinite(b.inertia_kg_m2));
    FUZZ_CHECK(b.position_m.allFinite() && std::isfinite(b.angle_rad));
  }
  for (const auto& j : s.joints) {
    FUZZ_CHECK(body_ok(s, j.body_i, true) && body_ok(s, j.body_j, true));
    FUZZ_CHECK(j.body_i != j.body_j);
    FUZZ_CHECK(j.point_i_m.allFinite() && j.point_j_m.allFinite() && j.axis_i.allFinite());
    if (j.type == lub::JointType::lubricated_revolute) {
      FUZZ_CHECK(j.bearing.clearance_m() > 0 && j.bearing.length_m > 0 && j.viscosity_Pa_s > 0);
      FUZZ_CHECK(j.initial_eccentricity_m.norm() < j.bearing.clearance_m());
    }
  }
  for (const auto& d : s.drivers) {
    FUZZ_CHECK(body_ok(s, d.body, false));
    FUZZ_CHECK(std::isfinite(d.speed_rad_s) && std::isfinite(d.reversal_frequency_rad_s));
  }
  const std::optional<double> period = s.cycle_period_s();
  FUZZ_CHECK(!period || (std::isfinite(*period) && *period > 0));
  FUZZ_CHECK(s.simulation.duration_s || (period && std::isfinite(s.simulation.max_cycles * *period)));
  for (const auto& c : s.output.channels) {
    if (c.source == lub::ChannelSource::body) FUZZ_CHECK(body_ok(s, c.index, false));
    if (c.source == lub::ChannelSource::joint)
      FUZZ_CHECK(c.index >= 0 && c.index < static_cast<int>(s.joints.size()));
  }
  FUZZ_CHECK(s.metrics.joint < static_cast<int>(s.joints.size()));
  FUZZ_CHECK(s.metrics.body < static_cast<int>(s.bodies.size()));
}

void use_scene(const json& doc) {
  const lub::Scene scene = lub::parse_scene(doc);
  check_invariants(scene);
  if (scene.bodies.size() > 8) return;  // keep each input fast
  const lub::Model model = lub::build_model(scene);
  Eigen::VectorXd q, v;
  lub::assemble_initial_state(model, scene, 0.0, q, v);  // InputError if it cannot close
  FUZZ_CHECK(q.allFinite() && v.allFinite());
}

// A small valid scene: a pendulum with a lubricated pin, every section present.
const char* kBase = R"({
  "bodies": [{"name": "arm", "mass_kg": 1.0, "inertia_kg_m2": 0.01, "position_m": [0.1, 0.0]}],
  "joints": [{"name": "pin", "type": "lubricated_revolute", "bearing_body": "ground", "journal_body": "arm",
              "journal_point_m": [-0.1, 0.0], "bearing_radius_m": 0.01, "journal_radius_m": 0.0095,
              "length_m": 0.04, "viscosity_Pa_s": 0.4, "force_law": "frene_long"}],
  "drivers": [{"name": "spin", "type": "constant_speed", "body": "arm", "speed_rpm": 100}],
  "effects": {"gravity_m_s2": [0, -9.81]},
  "solver": {"rtol": 1e-6},
  "simulation": {"max_cycles": 2},
  "metrics": {"joint": "pin", "body": "arm"},
  "outputs": {"channels": [{"name": "eps", "joint": "pin", "quantity": "eps"}]}
})";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    use_scene(lub::parse_json_text(text, "fuzz"));
  } catch (const lub::InputError&) {
  }
  const std::string line = text.substr(0, text.find('\n'));
  if (line.size() <= 512) {
    static const json base = json::parse(kBase);
    try {
      json doc = base;
      lub::apply_override(doc, line);
      use_scene(doc);
    } catch (const lub::InputError&) {
    }
  }
  return 0;
}
