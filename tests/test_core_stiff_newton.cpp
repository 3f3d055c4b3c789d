// CVODE BDF, partitioned formulation, on the stiff squeeze film: accepted steps must carry a converged Newton
// corrector. With CVODE's default Jacobian reuse (up to 51 steps old, setup every 20) the
// film's coupling terms, which change sign within a fraction of a cycle, left the corrector
// unconverged in the stiff mode; when a rod's angular velocity crossed zero (90° and 270°
// of crank) its error weight became 1/atol and the error test failed repeatedly at that
// quarter-cycle time (solver_failure). The case below failed that way before the
// partitioned formulation refreshed the Jacobian at every step.
#include <gtest/gtest.h>

#include <string>

#include "lub/run/run.hpp"
#include "lub/scene/scene.hpp"

namespace {

using lub::RunResult;
using lub::RunStatus;
using nlohmann::json;

json reference_scene() {
  return lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
}

RunResult run(const json& doc) { return lub::run_scene(lub::parse_scene(doc)); }

// Partitioned formulation, 50 rpm, 0.2 mm clearance, 200 cP, Frêne long: failed at
// t = 29.1 s (24.25 periods) with the error test on the rod's angular velocity.
TEST(StiffNewton, PartitionedSlowCrankPassesQuarterCycles) {
  json doc = reference_scene();
  doc["joints"][3]["journal_radius_m"] = 0.0098;
  doc["joints"][3]["viscosity_Pa_s"] = 0.2;
  doc["joints"][3]["force_law"] = "frene_long";
  doc["drivers"][0]["speed_rpm"] = 50.0;
  doc["solver"]["formulation"] = "partitioned";
  // The run as reported (40 cycles: the end time enters CVODE as its stop time, and any
  // change to the step sequence moves where a marginal case breaks).
  doc["simulation"]["max_cycles"] = 40;
  doc["outputs"]["channels"] = json::array();
  const RunResult r = run(doc);
  EXPECT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_NEAR(r.stats.final_time_s, 48.0, 1e-9);
  EXPECT_EQ(r.metrics.cycles_run, 40);
}

// Projection (baumgarte + CVODE's projection), 50 rpm, 0.05 mm clearance, 200 cP, Frêne
// long: case 166 of configs/grids/full_factorial.json run on projection. It failed at
// t = 2.4 s, a cycle boundary and dead centre, where the step lands on the zero of the
// slider's velocity (weight 1/atol) and its local error stayed ~3e-10 m/s (~100 atol)
// while CVODE cut h from 1.5e-4 to 3e-8 s. Refreshing the Jacobian every step alone moved
// the failure to t = 22.27 s; leaving the error estimate unprojected alone passed this case
// but failed two others (cases 154 and 167); both together: 0 of 192 fail.
TEST(StiffNewton, ProjectionSlowCrankPassesCycleBoundaries) {
  json doc = reference_scene();
  doc["joints"][3]["journal_radius_m"] = 0.00995;
  doc["joints"][3]["viscosity_Pa_s"] = 0.2;
  doc["joints"][3]["force_law"] = "frene_long";
  doc["drivers"][0]["speed_rpm"] = 50.0;
  doc["solver"]["formulation"] = "baumgarte";
  doc["solver"]["projection"] = true;
  doc["simulation"]["max_cycles"] = 40;
  doc["simulation"]["stop_when_steady"] = true;
  doc["outputs"]["channels"] = json::array();
  const RunResult r = run(doc);
  EXPECT_EQ(r.status, RunStatus::ok) << r.message;
  // As in the full factorial: steady before the 40-cycle cap is not reached (Frêne long at
  // 50 rpm keeps sinking), so the run covers all 40 cycles, 80 dead centres.
  EXPECT_NEAR(r.stats.final_time_s, 48.0, 1e-9);
  // Projected at every step end; the observers also see the dense output between step
  // ends, which is not projected: measured 1.3e-10 m (2.7e-6 c). Bound 1e-4 c, far inside
  // the drift limit (0.1 c) that ends a Baumgarte run.
  EXPECT_LT(r.stats.max_position_drift, 1e-4 * 5e-5);
}

}  // namespace
