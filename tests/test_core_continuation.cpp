// Periodic orbits continued from a neighbouring scene's orbit (docs/theory/continuation.md):
// a seed carries over between scenes, Newton from it converges in a few chord iterations
// to the orbit shooting finds from the scene's own transient, and a path that cannot be
// followed ends with the scene's own method and says so.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lub/run/run.hpp"

namespace {

using lub::RunResult;
using lub::RunStatus;
using nlohmann::json;

json scene(const std::string& law, double rpm, const std::string& steady) {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = law;
  doc["drivers"][0]["speed_rpm"] = rpm;
  doc["simulation"]["steady"] = steady;
  doc["simulation"]["max_cycles"] = 40;
  doc["simulation"]["stop_when_steady"] = true;
  doc["solver"]["formulation"] = "partitioned";
  doc["outputs"]["channels"] = json::array();
  return doc;
}

lub::ContinuationStart from(const RunResult& r, const json& a, const json& b) {
  // Speed in its logarithm, as lubsweep's path does.
  const double wa = a["drivers"][0]["speed_rpm"], wb = b["drivers"][0]["speed_rpm"];
  return {r.orbit_seed, [a, wa, wb](double l) {
            json s = a;
            s["drivers"][0]["speed_rpm"] = std::exp((1 - l) * std::log(wa) + l * std::log(wb));
            return lub::parse_scene(s);
          }};
}

TEST(Continuation, ASceneContinuedFromItsOwnOrbitIsAtItsFixedPointAtOnce) {
  const json a = scene("pinkus_sternlicht", 5000, "shooting");
  const RunResult ra = lub::run_scene(lub::parse_scene(a));
  ASSERT_EQ(lub::classification(ra), "periodic") << ra.message;
  ASSERT_TRUE(ra.orbit_seed.valid());
  // The seed round-trips through the study file's packed row unchanged.
  const lub::OrbitSeed back = lub::unpack_seed(lub::pack_seed(ra.orbit_seed));
  EXPECT_EQ(back.deviation, ra.orbit_seed.deviation);
  EXPECT_EQ(back.monodromy, ra.orbit_seed.monodromy);
  EXPECT_EQ(back.chart, ra.orbit_seed.chart);

  const RunResult rb = lub::run_scene(lub::parse_scene(a), from(ra, a, a));
  ASSERT_EQ(lub::classification(rb), "periodic") << rb.message;
  EXPECT_EQ(rb.steady.method, lub::SteadyCycleMethod::continuation) << rb.message;
  EXPECT_EQ(rb.steady.continuation_steps, 1);
  // The seed is the orbit, placed at t = 0 instead of the transient's t = k T: the same
  // map up to its noise (the printed law's switches make it non-smooth at 1e-7–1e-6 c,
  // against a residual tolerance of 1e-9), so a few chord iterations, against 3–5 from
  // the transient's end with a fresh Jacobian each.
  EXPECT_LE(rb.steady.newton_iterations, 4);
  // The same orbit: metrics within their error bars.
  EXPECT_NEAR(rb.metrics.min_film_thickness_m, ra.metrics.min_film_thickness_m,
              2 * (ra.metrics.min_film_thickness_m_error + rb.metrics.min_film_thickness_m_error) + 1e-12);
  EXPECT_NEAR(rb.metrics.peak_reaction_N, ra.metrics.peak_reaction_N,
              2 * (ra.metrics.peak_reaction_N_error + rb.metrics.peak_reaction_N_error) + 1e-9);
}

TEST(Continuation, ANeighboursOrbitReachesTheOrbitShootingFindsFromTheTransient) {
  const json a = scene("pinkus_sternlicht", 5000, "shooting");
  const json b = scene("pinkus_sternlicht", 2500, "shooting");
  const RunResult ra = lub::run_scene(lub::parse_scene(a));
  ASSERT_TRUE(ra.orbit_seed.valid()) << ra.message;
  const RunResult direct = lub::run_scene(lub::parse_scene(b));
  ASSERT_EQ(lub::classification(direct), "periodic") << direct.message;
  const RunResult cont = lub::run_scene(lub::parse_scene(b), from(ra, a, b));
  ASSERT_EQ(lub::classification(cont), "periodic") << cont.message;
  EXPECT_EQ(cont.steady.method, lub::SteadyCycleMethod::continuation) << cont.message;
  // Two routes to one orbit, each with its error bar.
  const auto& m = cont.metrics;
  const auto& d = direct.metrics;
  EXPECT_NEAR(m.min_film_thickness_m, d.min_film_thickness_m,
              2 * (m.min_film_thickness_m_error + d.min_film_thickness_m_error) + 1e-12);
  EXPECT_NEAR(m.max_eps, d.max_eps, 2 * (m.max_eps_error + d.max_eps_error) + 1e-12);
  // And cheaper: no transient.
  EXPECT_LT(cont.steady.periods_integrated, direct.steady.periods_integrated);
}

TEST(Continuation, APathThatCannotBeFollowedFallsBackAndSaysWhere) {
  const json b = scene("pinkus_sternlicht", 2500, "shooting");
  lub::OrbitSeed wrong;
  wrong.deviation = {1.0, 2.0};  // of another mechanism
  const RunResult r =
      lub::run_scene(lub::parse_scene(b), lub::ContinuationStart{wrong, [b](double) { return lub::parse_scene(b); }});
  EXPECT_EQ(r.status, RunStatus::ok);
  EXPECT_NE(r.message.find("continuation stopped"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("another mechanism"), std::string::npos) << r.message;
  EXPECT_EQ(lub::classification(r), "periodic") << r.message;
}

}  // namespace
