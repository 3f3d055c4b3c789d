// IDA on the stabilised index-2 (GGL) formulation: the constraints hold at position and
// velocity level without Baumgarte's terms, and the lubricated reference case — with
// the printed law's switching and Filippov sliding, where a sliding film adds a
// constraint row and a multiplier — gives the answer the ODE formulations give.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lub/run.hpp"

namespace {

using lub::RunResult;
using lub::RunStatus;
using nlohmann::json;

RunResult run(const std::string& law, const std::string& method, const std::string& formulation, double rtol,
              int cycles) {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = law;
  doc["solver"]["method"] = method;
  if (!formulation.empty()) doc["solver"]["formulation"] = formulation;
  doc["solver"]["rtol"] = rtol;
  doc["simulation"]["max_cycles"] = cycles;
  doc["simulation"]["metric_cycles"] = 1;
  doc["outputs"]["channels"] = json::array();
  return lub::run_scene(lub::parse_scene(doc));
}

TEST(IdaGgl, KeepsTheConstraintsWhereBaumgarteDrifts) {
  // Same case, same rtol: Baumgarte's drift is what the integration error feeds it;
  // GGL enforces Φ = 0 and Φ̇ = 0 in every step's Newton solve. The observers also look
  // between steps, at the interpolating polynomial, so what remains is the local error
  // the error test allows: rtol × the scale of the state, 0.2 m for positions and the
  // slider's 26 m/s for velocities (factor 10 for the interpolation).
  const double rtol = 1e-8;
  const RunResult b = run("frene_long", "cvode_bdf", "", rtol, 3);
  const RunResult g = run("frene_long", "ida", "", rtol, 3);
  ASSERT_EQ(b.status, RunStatus::ok) << b.message;
  ASSERT_EQ(g.status, RunStatus::ok) << g.message;
  EXPECT_LT(g.stats.max_position_drift, 10 * rtol * 0.2);
  EXPECT_LT(g.stats.max_velocity_drift, 10 * rtol * 26.0);
  EXPECT_LT(g.stats.max_position_drift, 1e-2 * b.stats.max_position_drift);
  EXPECT_LT(g.stats.max_velocity_drift, 1e-1 * b.stats.max_velocity_drift);
}

TEST(IdaGgl, AgreesWithThePartitionedReferenceForEachPaperLaw) {
  // Reference: CVODE BDF on the partitioned ODE at rtol 1e-10. IDA at 1e-8: the metrics
  // over the third cycle agree to the integration error, which the work-precision
  // study puts at ~1e-3 c on the orbit at this tolerance; allow 2e-3 relative.
  for (const std::string law : {"pinkus_sternlicht", "frene_long", "frene_short"}) {
    SCOPED_TRACE(law);
    const RunResult ref = run(law, "cvode_bdf", "partitioned", 1e-10, 3);
    const RunResult g = run(law, "ida", "ggl", 1e-8, 3);
    ASSERT_EQ(ref.status, RunStatus::ok) << ref.message;
    ASSERT_EQ(g.status, RunStatus::ok) << g.message;
    EXPECT_NEAR(g.metrics.min_film_thickness_m / ref.metrics.min_film_thickness_m, 1.0, 2e-3);
    EXPECT_NEAR(g.metrics.max_eps / ref.metrics.max_eps, 1.0, 2e-3);
    EXPECT_NEAR(g.metrics.peak_reaction_N / ref.metrics.peak_reaction_N, 1.0, 2e-3);
    if (law == "pinkus_sternlicht") {
      // The printed law switched (and slid) under IDA too.
      EXPECT_GT(g.stats.mode_switches, 0);
    }
  }
}

}  // namespace
