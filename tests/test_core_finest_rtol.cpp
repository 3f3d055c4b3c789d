// A run at the finest rtol the integrator reaches (SteadyTuning::finest_rtol, 1e-12): its
// tighter integrations (difference Jacobians and monodromy at rtol/100, error bars, the
// slow flow's checks) stay at that rtol instead of going below it, where BDF's error test
// meets round-off and the steps crawl (10 cycles of the near-wall case below took 194 s
// and 1.3e7 failed error tests when they went to 1e-14). What cannot be had there is said.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lub/io/json_reader.hpp"
#include "lub/mechanism/film_element.hpp"
#include "lub/run/orbit.hpp"
#include "lub/run/run.hpp"
#include "run/segment.hpp"

namespace {

using nlohmann::json;

json reference(double rtol) {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["simulation"]["steady"] = "auto";
  doc["solver"]["rtol"] = rtol;
  doc["outputs"]["channels"] = json::array();
  return doc;
}

lub::RunResult run(const json& doc) { return lub::run_scene(lub::parse_scene(doc)); }

// The printed law's orbit is well conditioned (κ ≈ 1): found at 1e-12 with its metrics,
// at about the cost of 1e-11, its error bars NaN and the message saying why.
TEST(FinestRtol, AWellConditionedOrbitIsFoundWithoutErrorBars) {
  const lub::RunResult at11 = run(reference(1e-11)), at12 = run(reference(1e-12));
  ASSERT_EQ(at11.status, lub::RunStatus::ok) << at11.message;
  ASSERT_EQ(at12.status, lub::RunStatus::ok) << at12.message;
  EXPECT_EQ(at12.steady.kind, lub::SteadyClass::periodic) << at12.message;
  EXPECT_EQ(at11.steady.kind, lub::SteadyClass::periodic) << at11.message;
  // At 1e-11 the bars integrate at 1e-12 (10 times tighter, not 100): still measured.
  EXPECT_TRUE(std::isfinite(at11.metrics.min_film_thickness_m_error));
  EXPECT_TRUE(std::isnan(at12.metrics.min_film_thickness_m_error));
  EXPECT_NE(at12.message.find("leaves no room below it"), std::string::npos) << at12.message;
  // The same orbit: the two films within the 1e-11 run's own error bar, ten times over.
  EXPECT_NEAR(at12.metrics.min_film_thickness_m, at11.metrics.min_film_thickness_m,
              10.0 * at11.metrics.min_film_thickness_m_error + 1e-12);
  // Steps: the 1e-12 run integrates nothing finer than 1e-12. Going from 1e-11 to 1e-12
  // costs BDF ~1.6 times the steps a period; integrations at 1e-14 cost ~50 times those
  // at 1e-12. Three times is the bound.
  EXPECT_LT(static_cast<double>(at12.stats.steps), 3.0 * static_cast<double>(at11.stats.steps))
      << at12.stats.steps << " steps at 1e-12 against " << at11.stats.steps << " at 1e-11";
}

// Frêne short near the wall (ε ≈ 0.991): Newton stalls at the film's own drift a period
// (~1.8e-7 c, which the map at 1e-12 resolves), and its best iterate has κ ~ 5e4. Such an
// orbit is located only where it stops moving under refinement, for which 1e-12 leaves no
// room: not converged, saying so, and in seconds.
TEST(FinestRtol, AnIllConditionedOrbitIsNotLocatedWithoutRoomToRefine) {
  json doc = reference(1e-12);
  doc["joints"][3]["force_law"] = "frene_short";
  doc["joints"][3]["initial_eccentricity_m"] = json::array({-4.955e-4, -2.04e-5});
  doc["simulation"]["max_cycles"] = 10;
  const lub::RunResult r = run(doc);
  ASSERT_EQ(r.status, lub::RunStatus::ok) << r.message;
  EXPECT_NE(r.steady.kind, lub::SteadyClass::periodic) << r.message;
  EXPECT_NE(r.steady.kind, lub::SteadyClass::periodic_unstable) << r.message;
  EXPECT_NE(r.message.find("located only where it stops moving under refinement"), std::string::npos) << r.message;
  // 10 cycles and a Newton at 1e-12 take ~6e5 steps; with integrations at 1e-14, 2.7e7.
  EXPECT_LT(r.stats.steps, 3000000) << r.message;
}

// The same rule without error bars: Frêne short at 0.5 mm, 400 cP, 5000 rpm, the journal at
// rest 1 µm from the wall (tests/test_core_near_wall_orbits.cpp). With its error bars (the
// default) the orbit Newton finds there from cycle 8 (κ ~ 2e4) moves under refinement and
// the case drifts; with simulation.error_bars = false nothing shows it stops moving, so it
// is not located either.
TEST(FinestRtol, WithoutErrorBarsAnIllConditionedOrbitIsNotLocated) {
  json doc = reference(1e-8);
  doc["joints"][3]["force_law"] = "frene_short";
  doc["joints"][3]["initial_eccentricity_m"] = {-4.9850e-4, -2.0768e-5};
  doc["simulation"]["max_cycles"] = 40;
  doc["simulation"]["stop_when_steady"] = true;
  doc["simulation"]["steady_tolerance"] = 1e-3;
  doc["simulation"]["metric_cycles"] = 2;
  doc["simulation"]["error_bars"] = false;
  const lub::RunResult off = run(doc);
  ASSERT_EQ(off.status, lub::RunStatus::ok) << off.message;
  EXPECT_FALSE(lub::has_orbit(off.steady.kind)) << off.message;
  EXPECT_NE(off.message.find("simulation.error_bars = false, and an orbit with kappa"), std::string::npos)
      << off.message;
  doc["simulation"]["error_bars"] = true;
  const lub::RunResult on = run(doc);
  EXPECT_EQ(lub::classification(on), "drifting") << on.message;
  // A well-conditioned orbit needs no refinement: the printed law's, found without bars.
  json printed = reference(1e-8);
  printed["simulation"]["error_bars"] = false;
  const lub::RunResult p = run(printed);
  EXPECT_EQ(p.steady.kind, lub::SteadyClass::periodic) << p.message;
}

// Why Newton's stall there is not the map's noise: near the wall at 1e-12 a period started
// afresh from a cycle boundary (as the period map starts each one) ends where the
// continued integration does to ~1e-9 c, while the film's own drift moves the boundary
// by ~1.8e-7 c a period (measured: restart against continuation 5e-10–8.5e-9 c over 7
// periods; the drift 1.8e-7 c at each). The map resolves the drift it stalls on.
TEST(FinestRtol, APeriodMapResolvesTheNearWallDrift) {
  json doc = reference(1e-12);
  doc["joints"][3]["force_law"] = "frene_short";
  doc["joints"][3]["initial_eccentricity_m"] = json::array({-4.976274e-4, -2.093674e-5});  // h ≈ 1.93 µm
  const lub::Scene scene = lub::parse_scene(doc);
  lub::detail::RunModel rm(scene);
  lub::detail::SegmentOptions continued;
  continued.cycles = 8;
  continued.series = false;
  const lub::detail::SegmentResult run = lub::detail::run_segment(rm, continued);
  ASSERT_EQ(run.res.status, lub::RunStatus::ok) << run.res.message;
  ASSERT_EQ(run.boundaries.size(), 9u);
  const double c = 5e-4;  // [m], the scene's clearance
  auto e = [&](const lub::detail::StartState& s) {
    return lub::film_kinematics(rm.model, 0, s.qv.data(), s.qv.data() + rm.model.nq).e;
  };
  for (size_t k = 2; k < 8; k += 2) {  // after the start has settled onto its slow manifold
    lub::detail::StartState from = run.boundaries[k];
    lub::detail::SegmentOptions one;
    one.start = &from;
    one.cycles = 1;
    one.observe = false;
    one.series = false;
    const lub::detail::SegmentResult period = lub::detail::run_segment(rm, one);
    ASSERT_EQ(period.res.status, lub::RunStatus::ok) << period.res.message;
    const double drift = (e(run.boundaries[k + 1]) - e(from)).norm() / c;
    const double apart = (e(period.end) - e(run.boundaries[k + 1])).norm() / c;
    EXPECT_GT(drift, 1e-7) << "cycle " << k;  // the film still thins, inward
    EXPECT_LT(apart, 0.1 * drift) << "cycle " << k << ": restarted and continued periods " << apart << " c apart";
  }
}

}  // namespace
