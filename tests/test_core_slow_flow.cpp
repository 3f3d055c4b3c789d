// The slow flow of `auto` (docs/theory/steady-cycles.md, slow flow): where shooting from
// the transient finds no orbit, the journal's creep along its slow manifold is followed by
// projective steps; checked against a transient integrated cycle by cycle to the same
// cycle, and the scene key that turns it off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "lub/run/run.hpp"

namespace {

using lub::RunResult;
using lub::RunStatus;
using nlohmann::json;

/// The slider-crank with Frêne's short-bearing law at 0.1 mm, 100 cP, 2500 rpm (a cell of
/// the full factorial): its journal sinks along a slow manifold for thousands of cycles
/// (66 µm of film at cycle 40, ~6 µm at cycle 3000), and Newton from cycle 8 finds no orbit.
json sinking(const std::string& steady, int max_cycles) {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = "frene_short";
  doc["joints"][3]["viscosity_Pa_s"] = 0.1;
  doc["joints"][3]["journal_radius_m"] = 0.0099;
  doc["drivers"][0]["speed_rpm"] = 2500.0;
  doc["simulation"]["steady"] = steady;
  doc["simulation"]["max_cycles"] = max_cycles;
  doc["simulation"]["stop_when_steady"] = true;
  doc["outputs"]["channels"] = json::array();
  return doc;
}

RunResult run(const json& doc) { return lub::run_scene(lub::parse_scene(doc)); }

TEST(SlowFlow, FollowsASinkingJournalHundredsOfCyclesAndAgreesWithItsTransient) {
  const RunResult r = run(sinking("auto", 40));
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(lub::classification(r), "drifting") << r.message;
  EXPECT_EQ(r.steady.method, lub::SteadyCycleMethod::slow_flow);
  EXPECT_NE(r.message.find("still moving"), std::string::npos) << r.message;
  // Hundreds of cycles for the flow's 200 periods (745: each jump held to 5 % of its own
  // length, and the slope after a jump still carries the modes it excites, which decay
  // over tens of cycles), a few hundred periods in all (the transient, Newton from it).
  EXPECT_GT(r.steady.slow_flow_cycles, 500.0);
  EXPECT_LT(r.steady.periods_integrated, 600);
  // How it drifts: thinner than at the transient's end (66.6 µm; 14.2 µm), still thinning.
  EXPECT_LT(r.steady.last_cycle_min_film_m, 0.3 * r.cycles.back().min_film_thickness_m);
  EXPECT_LT(r.steady.min_film_drift_m_per_cycle, 0.0);
  // The metrics are those of the cycles where the flow got to (the last of them its film).
  EXPECT_LE(r.metrics.min_film_thickness_m, r.steady.last_cycle_min_film_m);
  EXPECT_GT(r.metrics.min_film_thickness_m, 0.99 * r.steady.last_cycle_min_film_m);
  EXPECT_LE(r.metrics.periodicity, 1e-2);

  // The independent route: the same scene integrated cycle by cycle, at the slow flow's
  // own rtol (the scene's / 10), to the cycle the flow got to. Agreement within 10 %: the
  // jumps' error control allows 5 % of each jump, one way (the flow's cycle count is good
  // to ~5 %, the film thinning as k^−0.5 there: ~3 %), and the transient at 1e-9 is itself
  // a few % off one at 1e-10 (Frêne short at 40 cP, cycle 1760: 5.05 against 4.78 µm).
  // Measured: 14.16 µm against 14.65 µm at cycle 786.
  const int cycles = 40 + static_cast<int>(std::lround(r.steady.slow_flow_cycles)) + 1;
  json t = sinking("transient", cycles);
  t["simulation"]["stop_when_steady"] = false;
  t["solver"]["rtol"] = 1e-9;
  const RunResult tr = run(t);
  ASSERT_EQ(tr.status, RunStatus::ok) << tr.message;
  const double h_transient = tr.cycles.back().min_film_thickness_m;
  std::printf("slow flow: %.4e m about %d cycles from rest; transient at rtol 1e-9 there: %.4e m\n",
              r.steady.last_cycle_min_film_m, cycles, h_transient);
  EXPECT_NEAR(r.steady.last_cycle_min_film_m, h_transient, 0.10 * h_transient)
      << "slow flow at about cycle " << cycles << ": " << r.steady.last_cycle_min_film_m << " m";
  // The transient at the scene's own rtol (1e-8) creeps by less than its own error a cycle
  // (issue 25): it lags behind (a thicker film), further from the tight transient than the
  // slow flow is.
  json d = sinking("transient", cycles);
  d["simulation"]["stop_when_steady"] = false;
  const RunResult loose = run(d);
  ASSERT_EQ(loose.status, RunStatus::ok) << loose.message;
  const double h_loose = loose.cycles.back().min_film_thickness_m;
  EXPECT_GT(h_loose, h_transient);
  EXPECT_LT(std::abs(r.steady.last_cycle_min_film_m - h_transient), std::abs(h_loose - h_transient));
}

/// Frêne's long-bearing law at 0.5 mm, 100 cP, 500 rpm (a cell of the full factorial): its
/// flow ends some 300 cycles on within 10–30 nm of the wall, where the film barely moves.
json at_the_wall(double rtol) {
  json doc = sinking("auto", 40);
  doc["joints"][3]["force_law"] = "frene_long";
  doc["joints"][3]["journal_radius_m"] = 0.0095;
  doc["drivers"][0]["speed_rpm"] = 500.0;
  doc["solver"]["rtol"] = rtol;
  return doc;
}

TEST(SlowFlow, ItsDriftCarriesItsMapsErrorAndADriftWithinItIsNoDirection) {
  // Where the journal sinks (the cell above), the drift is some 20 times its map's error a
  // cycle (−7.2e-9 m against 3.8e-10 m): a direction, `drifting`, the error in the message.
  const RunResult r = run(sinking("auto", 40));
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  const double drift = r.steady.min_film_drift_m_per_cycle, error = r.steady.min_film_drift_error_m_per_cycle;
  ASSERT_TRUE(std::isfinite(error)) << r.message;
  EXPECT_GT(error, 0.0);
  EXPECT_LT(error, 0.2 * std::abs(drift)) << drift;
  EXPECT_EQ(lub::classification(r), "drifting") << r.message;
  EXPECT_NE(r.message.find("its period map's own error a cycle"), std::string::npos) << r.message;

  // At the wall the film moves by less than its map's error a cycle: the flow's direction
  // is the integrator's, `not_converged`, and the message says so.
  const RunResult wall = run(at_the_wall(1e-8));
  ASSERT_EQ(wall.status, RunStatus::ok) << wall.message;
  const double d8 = wall.steady.min_film_drift_m_per_cycle, e8 = wall.steady.min_film_drift_error_m_per_cycle;
  ASSERT_TRUE(std::isfinite(e8)) << wall.message;
  EXPECT_LE(std::abs(d8), e8);
  EXPECT_EQ(lub::classification(wall), "not_converged") << wall.message;
  EXPECT_NE(wall.message.find("not resolved at this rtol"), std::string::npos) << wall.message;
  // The independent route: the same cell at rtol/10. An integration error shrinks with
  // the tolerance (measured 3.6e-8 m, 3.4e-9 m, 3.9e-10 m at 1e-8, 1e-9, 1e-10: first
  // order, so at most half), and the tighter drift lies within the looser one's error bar
  // (−8.7e-11 against −4.5e-10 ± 3.6e-8 m).
  const RunResult tight = run(at_the_wall(1e-9));
  ASSERT_EQ(tight.status, RunStatus::ok) << tight.message;
  EXPECT_LT(tight.steady.min_film_drift_error_m_per_cycle, 0.5 * e8);
  EXPECT_LE(std::abs(tight.steady.min_film_drift_m_per_cycle - d8), e8);
}

TEST(SlowFlow, TheRunsBudgetOfPeriodsBoundsItAndSaysSo) {
  // The sinking cell spends ~100 periods before its flow (the transient to cycle 8, Newton
  // from there, the transient to cycle 40: it contracts at 0.99, so no second Newton) and
  // 305 in all; budgets of 120 and 180 stop the flow itself some 20 and 80 periods in, 250
  // the Newton–Picard where it seemed to stop: not_converged with the budget's word, never
  // "still moving" on a flow the budget cut short, and no period beyond it.
  for (const long long budget : {120LL, 180LL, 250LL}) {
    json doc = sinking("auto", 40);
    doc["simulation"]["max_periods"] = budget;
    const RunResult r = run(doc);
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_LE(r.steady.periods_integrated, budget);
    EXPECT_GT(r.steady.slow_flow_cycles, 0.0) << r.message;  // the flow did start
    EXPECT_EQ(lub::classification(r), "not_converged") << budget << ": " << r.message;
    EXPECT_NE(r.message.find("simulation.max_periods = " + std::to_string(budget) + " reached"), std::string::npos)
        << r.message;
    EXPECT_EQ(r.message.find("still moving"), std::string::npos) << budget << ": " << r.message;
  }
}

TEST(SlowFlow, ATransientThatContractsSlowlyGoesToItsFlowWithoutASecondNewton) {
  // Newton from cycle 8 finds no orbit (or is not run); the transient to cycle 40
  // contracts at 0.99 a cycle: the orbit, if any, lies along the slow manifold, where the
  // flow goes. A second Newton from cycle 40 (446 periods on this cell, 694e1d5) found no
  // orbit on any of the full factorial's 131 such cells.
  const RunResult r = run(sinking("auto", 40));
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(r.steady.method, lub::SteadyCycleMethod::slow_flow);
  // Cycle 8's Newton either runs and fails or is not run (the map's error at rtol would
  // move its orbit by 0.0145 c, against 10 × steady_tolerance = 0.01 c): that estimate
  // sits near its bound and round-off decides which.
  EXPECT_NE(r.message.find("from cycle 8: "), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("no Newton from cycle 40"), std::string::npos) << r.message;
  // The transient's 40, the first Newton's ~60, the flow's 200 and the measurement where it
  // got to: 305 (877 with the second Newton and KINSOL where the flow seemed to stop).
  EXPECT_LE(r.steady.periods_integrated, 400);
}

TEST(SlowFlow, ADriftingCaseHasTheSqueezeFilmsDriftLaw) {
  // The sinking cell creeps toward the wall: its film's drift law dh/dN = −a h^p has the
  // short bearing's squeeze exponent, 5/2 (measured 2.5 ± 0.1; 2.52 the full factorial's
  // median for Frêne short).
  const RunResult r = run(sinking("auto", 40));
  ASSERT_EQ(lub::classification(r), "drifting") << r.message;
  ASSERT_TRUE(std::isfinite(r.steady.drift_exponent)) << r.message;
  EXPECT_NEAR(r.steady.drift_exponent, 2.5, 0.3) << r.message;
  EXPECT_GT(r.steady.drift_exponent_error, 0.0);
  EXPECT_LT(r.steady.drift_exponent_error, 0.3);
  EXPECT_NE(r.message.find("its film falls as dh/dN = -a h^p"), std::string::npos) << r.message;
}

/// A full-factorial cell given as the grid sets it: `law` at clearance `c_mm`, `mu` Pa s, `rpm`.
json cell(const std::string& law, double c_mm, double mu, double rpm) {
  json doc = sinking("auto", 40);
  doc["joints"][3]["force_law"] = law;
  doc["joints"][3]["viscosity_Pa_s"] = mu;
  doc["joints"][3]["journal_radius_m"] = 0.01 - 1e-3 * c_mm;
  doc["drivers"][0]["speed_rpm"] = rpm;
  return doc;
}

TEST(SlowFlow, ItsDriftIsTheFlowsEvenWhereItsLastLegIsShort) {
  // Frêne long at 0.1 mm, 200 cP, 50 rpm: the flow stops twice for a Newton that finds no
  // orbit, and its last leg is a few cycles long. The drift is still the flow's (against a
  // point of an earlier leg), not the transient's: a descent that slows as the film thins
  // drifts at its end by less than its mean over the flow (the transient's 40-cycle trend,
  // which was reported before, is 12 times that mean).
  const RunResult r = run(cell("frene_long", 0.1, 0.2, 50.0));
  ASSERT_EQ(lub::classification(r), "drifting") << r.message;
  ASSERT_EQ(r.steady.method, lub::SteadyCycleMethod::slow_flow) << r.message;
  const double mean = (r.cycles.back().min_film_thickness_m - r.steady.last_cycle_min_film_m) /
                      r.steady.slow_flow_cycles;
  ASSERT_GT(mean, 0.0);
  EXPECT_LT(r.steady.min_film_drift_m_per_cycle, 0.0) << r.message;
  EXPECT_LT(-r.steady.min_film_drift_m_per_cycle, mean) << r.message;
}

TEST(SlowFlow, WhereItGotToUnmeasuredItsNumbersAreSaidToBeTheTransients) {
  // The printed law at 0.5 mm, 400 cP, 50 rpm: the flow follows 200 periods, but a cycle from
  // where it got to at the scene's rtol crawls into its step budget (the film's ε̇ = 0
  // switches). Its film and drift on record are the transient's, and the message says so.
  const RunResult r = run(cell("pinkus_sternlicht", 0.5, 0.4, 50.0));
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  ASSERT_GT(r.steady.slow_flow_cycles, 100.0) << r.message;
  EXPECT_NE(r.steady.method, lub::SteadyCycleMethod::slow_flow) << r.message;
  EXPECT_NE(r.message.find("its cycles there not measured"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("the film and drift are the transient's"), std::string::npos) << r.message;
  EXPECT_EQ(r.steady.last_cycle_min_film_m, r.cycles.back().min_film_thickness_m) << r.message;
}

/// The first cycle (from the run's start) whose minimum film is below `safe` (-1: none).
int first_below(const RunResult& r, double safe) {
  for (size_t k = 0; k < r.cycles.size(); ++k)
    if (r.cycles[k].min_film_thickness_m < safe) return static_cast<int>(k);
  return -1;
}

TEST(SlowFlow, TheDriftLawsSafeFilmCycleAgreesWithATightTransient) {
  // Two cells of the full factorial whose flow ends within twice the safe film: Frêne
  // short at 0.2 mm, 40 cP, 50 rpm, and Frêne long at 0.1 mm, 200 cP, 2500 rpm. The
  // independent route: the same scene from rest, cycle by cycle at rtol 1e-10 (the flow's
  // own rtol / 10), past the predicted cycle; it crosses within the law's error bar
  // (measured: 306 ± 25 against 308, 745 ± 68 against 763).
  struct Cell {
    const char* law;
    double journal_radius_m, viscosity_Pa_s, speed_rpm;
  };
  for (const Cell& cell : {Cell{"frene_short", 0.0098, 0.04, 50.0}, Cell{"frene_long", 0.0099, 0.2, 2500.0}}) {
    json doc = sinking("auto", 40);
    doc["joints"][3]["force_law"] = cell.law;
    doc["joints"][3]["journal_radius_m"] = cell.journal_radius_m;
    doc["joints"][3]["viscosity_Pa_s"] = cell.viscosity_Pa_s;
    doc["drivers"][0]["speed_rpm"] = cell.speed_rpm;
    const RunResult r = run(doc);
    ASSERT_EQ(lub::classification(r), "drifting") << cell.law << ": " << r.message;
    ASSERT_TRUE(std::isfinite(r.steady.safe_film_cycle)) << cell.law << ": " << r.message;
    const double predicted = r.steady.safe_film_cycle, bar = r.steady.safe_film_cycle_error;
    EXPECT_LT(bar, 0.25 * predicted) << cell.law;  // a bar that says something
    EXPECT_NE(r.message.find("it crosses the safe film"), std::string::npos) << r.message;
    json t = doc;
    t["simulation"]["steady"] = "transient";
    t["simulation"]["stop_when_steady"] = false;
    t["simulation"]["max_cycles"] = static_cast<int>(predicted + bar) + 20;
    t["solver"]["rtol"] = 1e-10;
    t["solver"]["max_steps"] = 1000000000;
    const RunResult tr = run(t);
    ASSERT_EQ(tr.status, RunStatus::ok) << tr.message;
    const int seen = first_below(tr, r.metrics.safe_film_thickness_m);
    ASSERT_GE(seen, 0) << cell.law << ": the transient did not cross by cycle " << tr.cycles.size();
    std::printf("%s: law %.0f ± %.0f, transient %d\n", cell.law, predicted, bar, seen);
    EXPECT_LE(std::abs(seen - predicted), bar) << cell.law;
  }
}

TEST(SlowFlow, IsAutosDefaultAndTheSceneCanTurnItOff) {
  EXPECT_TRUE(lub::parse_scene(sinking("auto", 40)).simulation.slow_flow);
  EXPECT_FALSE(lub::parse_scene(sinking("shooting", 40)).simulation.slow_flow);
  EXPECT_FALSE(lub::parse_scene(sinking("transient", 40)).simulation.slow_flow);
  json off = sinking("auto", 40);
  off["simulation"]["slow_flow"] = false;
  const RunResult r = run(off);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(r.steady.slow_flow_cycles, 0.0);
  EXPECT_NE(r.steady.method, lub::SteadyCycleMethod::slow_flow);
  EXPECT_EQ(r.message.find("slow"), std::string::npos) << r.message;
  // Without the flow, Newton tries again from the transient's end, as before the stage.
  EXPECT_EQ(r.message.find("no Newton from cycle"), std::string::npos) << r.message;
  // Bad input names the key, the value and the rule.
  json bad = sinking("auto", 40);
  bad["simulation"]["slow_flow"] = "yes";
  try {
    lub::parse_scene(bad);
    FAIL() << "a string for a boolean was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("simulation.slow_flow"), std::string::npos) << e.what();
  }
}

}  // namespace
