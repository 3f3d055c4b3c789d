// Steady cycles of the slider-crank (docs/theory/steady-cycles.md): shooting against the
// transient, the Floquet multipliers against the transient's own cycle map, and the cases
// without a steady cycle never called periodic.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "lub/run/run.hpp"

namespace {

using lub::RunResult;
using lub::RunStatus;
using nlohmann::json;

json reference(const std::string& law, const std::string& steady, int max_cycles) {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = law;
  doc["simulation"]["steady"] = steady;
  doc["simulation"]["max_cycles"] = max_cycles;
  doc["outputs"]["channels"] = json::array();
  return doc;
}

RunResult run(const json& doc) { return lub::run_scene(lub::parse_scene(doc)); }

TEST(SteadyCycle, PrintedLawConvergesInAFewNewtonStepsAndMatchesItsTransient) {
  const RunResult s = run(reference("pinkus_sternlicht", "shooting", 40));
  ASSERT_EQ(s.status, RunStatus::ok) << s.message;
  EXPECT_EQ(lub::classification(s), "periodic") << s.message;
  // The orbit attracts fast (|μ|max ≈ 0.05): chord steps on the monodromy at the 8th
  // cycle need few iterations, through the law's ε̇ = 0 switches and Filippov sliding.
  EXPECT_LE(s.steady.newton_iterations, 5);
  ASSERT_FALSE(s.steady.multipliers.empty());
  const double mu = std::abs(s.steady.multipliers.front());
  EXPECT_LT(mu, 0.2);
  // Located as the chords accept an orbit: to its residual over 1 − |μ|max, within a
  // tenth of steady_tolerance (the switches make the map noisy at 1e-7–1e-6 c), and the
  // orbit re-solved at rtol/100 lies within steady_tolerance of it.
  const double tol = lub::parse_scene(reference("pinkus_sternlicht", "shooting", 40)).simulation.steady_tolerance;
  EXPECT_LE(s.steady.orbit_residual / (1.0 - mu), 0.1 * tol);
  EXPECT_LE(s.steady.orbit_error, tol);

  json t = reference("pinkus_sternlicht", "transient", 40);
  t["simulation"]["stop_when_steady"] = true;
  t["simulation"]["error_bars"] = true;
  const RunResult tr = run(t);
  ASSERT_EQ(tr.status, RunStatus::ok) << tr.message;
  EXPECT_EQ(lub::classification(tr), "periodic");
  // The transient's verdict is the period map's too: its multipliers at the transient's
  // end are shooting's at the orbit (both central differences at rtol/100, 1 % steps).
  ASSERT_FALSE(tr.steady.multipliers.empty());
  EXPECT_NEAR(std::abs(tr.steady.multipliers.front()), std::abs(s.steady.multipliers.front()), 1e-2);
  EXPECT_LE(tr.steady.remaining_distance, 1e-3);
  // Two routes to one cycle: they agree within their error bars (each the change at a
  // 100x tighter rtol, the transient's with its remaining change on top).
  const auto& a = s.metrics;
  const auto& b = tr.metrics;
  EXPECT_NEAR(a.min_film_thickness_m, b.min_film_thickness_m,
              2 * (a.min_film_thickness_m_error + b.min_film_thickness_m_error));
  EXPECT_NEAR(a.peak_reaction_N, b.peak_reaction_N, 2 * (a.peak_reaction_N_error + b.peak_reaction_N_error));
  EXPECT_NEAR(a.max_eps, b.max_eps, 2 * (a.max_eps_error + b.max_eps_error));
  // Error bars are there and small against the values they qualify.
  EXPECT_GT(a.min_film_thickness_m_error, 0.0);
  EXPECT_LT(a.min_film_thickness_m_error, 1e-3 * a.min_film_thickness_m);
}

// The transient's cycle map, linearised: successive Poincaré points y_k (the journal's
// e/c, ė/c at crank angle 0) differ by d_k = y_{k+1} − y_k ≈ M d_{k−1} once the fast modes
// have died; the slow pair spans the differences. Its eigenvalues from least squares on
// the two leading directions of the differences.
std::vector<std::complex<double>> transient_multipliers(const RunResult& r, int first, int last) {
  std::vector<Eigen::Vector4d> y;
  for (int k = first; k <= last; ++k) {
    const auto& c = r.cycles[static_cast<size_t>(k)];
    y.emplace_back(c.end_eccentricity_x, c.end_eccentricity_y, c.end_eccentricity_rate_x, c.end_eccentricity_rate_y);
  }
  const int n = static_cast<int>(y.size()) - 1;
  Eigen::MatrixXd D(4, n);
  for (int k = 0; k < n; ++k) D.col(k) = y[static_cast<size_t>(k) + 1] - y[static_cast<size_t>(k)];
  // Scale the rates to the positions' size before the SVD (ė/c ~ Ω e/c).
  Eigen::Vector4d w(1, 1, 0, 0);
  w(2) = w(3) = 1.0 / std::max(1e-30, D.bottomRows(2).cwiseAbs().maxCoeff() / D.topRows(2).cwiseAbs().maxCoeff());
  D = w.asDiagonal() * D;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(D.leftCols(n - 1), Eigen::ComputeThinU);
  const Eigen::MatrixXd U = svd.matrixU().leftCols(2);
  const Eigen::MatrixXd X0 = U.transpose() * D.leftCols(n - 1), X1 = U.transpose() * D.rightCols(n - 1);
  const Eigen::Matrix2d A = X1 * X0.transpose() * (X0 * X0.transpose()).inverse();
  Eigen::EigenSolver<Eigen::Matrix2d> es(A);
  return {es.eigenvalues()(0), es.eigenvalues()(1)};
}

TEST(SteadyCycle, FreneLongConvergesAndItsMultipliersMatchTheTransientsOwnCycleMap) {
  const RunResult s = run(reference("frene_long", "shooting", 40));
  ASSERT_EQ(s.status, RunStatus::ok) << s.message;
  EXPECT_EQ(lub::classification(s), "periodic") << s.message;
  // Converged to shooting_tolerance (1e-9), or stalled at the map's noise just above it
  // (1.02e-9 measured in joint coordinates: accepted at the noise floor). Over 1 − |μ| ≈
  // 2e-3 a residual of 1e-8 moves the orbit by 5e-6 c, below its error bar (orbit_error
  // 3.7e-5 c).
  EXPECT_LT(s.steady.orbit_residual, 1e-8);
  ASSERT_GE(s.steady.multipliers.size(), 2u);
  const std::complex<double> mu = s.steady.multipliers.front();
  // A weakly damped rotation: the "not periodic" look of the paper's 40 cycles.
  EXPECT_GT(std::abs(mu), 0.99);
  EXPECT_LT(std::abs(mu), 1.0);

  // The same multipliers, independently, from a transient far enough in to be linear.
  // Its estimate over cycles k..k+99 (from rest, rtol 1e-8): k = 300: 0.9833 ∠0.919,
  // 600: 0.9966 ∠0.931, 1000: 0.9975 ∠0.934, 1500: 0.99798 ∠0.9350, 2000: 0.99803 ∠0.9351:
  // the decay rate depends on the amplitude (cycle-to-cycle change 0.2 c at 300, 0.01 c at
  // 1500) until it is small.
  const RunResult t = run(reference("frene_long", "transient", 1600));
  ASSERT_EQ(t.status, RunStatus::ok) << t.message;
  const auto est = transient_multipliers(t, 1500, 1599);
  const std::complex<double> m0 = std::abs(std::arg(est[0])) > 0 ? est[0] : est[1];
  // 5e-4 in modulus, 5e-3 rad in angle: the transient's estimate still moves by 5e-5 from
  // 1500 to 2000 and the shooting monodromy carries its 1 % difference step (O(h²)).
  EXPECT_NEAR(std::abs(m0), std::abs(mu), 5e-4);
  EXPECT_NEAR(std::abs(std::arg(m0)), std::abs(std::arg(mu)), 5e-3);
}

TEST(SteadyCycle, SinkingAndDriftingCasesAreNeverPeriodic) {
  // The printed law at 50 rpm: the journal sinks a little every cycle (docs/validation/hard-cases.md).
  json slow = reference("pinkus_sternlicht", "auto", 100);
  slow["drivers"][0]["speed_rpm"] = 50;
  const RunResult a = run(slow);
  EXPECT_NE(lub::classification(a), "periodic") << a.message;
  EXPECT_NE(lub::classification(a), "periodic_unstable") << a.message;
  if (a.status == RunStatus::ok) {
    EXPECT_LT(a.steady.min_film_drift_m_per_cycle, 0.0);
  }
  // Frêne short: still thinning after 1300 cycles.
  const RunResult b = run(reference("frene_short", "auto", 100));
  EXPECT_NE(lub::classification(b), "periodic") << b.message;
  EXPECT_NE(lub::classification(b), "periodic_unstable") << b.message;

  // The old fixed threshold stopped the 50 rpm transient at cycle 17 and called it steady;
  // the contraction estimate does not.
  json tr = slow;
  tr["simulation"]["steady"] = "transient";
  tr["simulation"]["max_cycles"] = 40;
  tr["simulation"]["stop_when_steady"] = true;
  const RunResult c = run(tr);
  EXPECT_NE(lub::classification(c), "periodic") << "stopped after " << c.cycles.size() << " cycles";
}

TEST(SteadyCycle, ATransientsStopOnASlowManifoldIsNotConfirmedByThePeriodMap) {
  // Frêne long, 0.2 mm, 500 rpm (issue 25): the contraction estimate sees the fast pair
  // (ρ ≈ 0.95) and says steady at cycle 1142 with h_min 1.1 µm; the period map there has
  // |μ|max 0.9989 and puts the orbit 6.5e-3 c away. Without the confirmation the run
  // stopped there, "periodic"; it goes on and its film keeps sinking.
  json d = reference("frene_long", "transient", 2000);
  d["joints"][3]["journal_radius_m"] = 0.0098;
  d["drivers"][0]["speed_rpm"] = 500;
  d["solver"]["formulation"] = "partitioned";
  d["simulation"]["stop_when_steady"] = true;
  const RunResult r = run(d);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_NE(lub::classification(r), "periodic") << r.message;
  EXPECT_EQ(r.cycles.size(), 2000u) << "stopped early: " << r.message;
  // The film a stop anywhere past cycle 1000 would have reported is not the steady one:
  // it thins by more than a third over the last thousand cycles.
  EXPECT_LT(r.cycles.back().min_film_thickness_m, 0.67 * r.cycles[1000].min_film_thickness_m);
}

json cell(const std::string& law, double clearance_m, double viscosity_Pa_s, double rpm) {
  json d = reference(law, "auto", 40);
  d["joints"][3]["journal_radius_m"] = 0.0100 - clearance_m;
  d["joints"][3]["viscosity_Pa_s"] = viscosity_Pa_s;
  d["drivers"][0]["speed_rpm"] = rpm;
  d["solver"]["formulation"] = "partitioned";
  d["simulation"]["stop_when_steady"] = true;
  return d;
}

TEST(SteadyCycle, ChordsStalledAtTheMapsNoiseLocateAStronglyAttractingOrbit) {
  // The printed law, 0.1 mm, 100 cP, 5000 rpm (full factorial): the map's noise at rtol
  // 1e-8 is ~2.5e-6 c (its switches), where KINSOL's line search stalled and the
  // transient's own estimate never settles (rate 1.17). The monodromy at the transient's
  // end contracts strongly (|μ|max ≈ 0.016): chord steps on it stall at that noise, which
  // locates the orbit to residual / (1 − |μ|) within a tenth of steady_tolerance; the
  // orbit re-solved at rtol/100 lies ~1e-5 c from it.
  const json doc = cell("pinkus_sternlicht", 1e-4, 0.1, 5000);
  const RunResult r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(lub::classification(r), "periodic") << r.message;
  ASSERT_FALSE(r.steady.multipliers.empty());
  const double mu = std::abs(r.steady.multipliers.front());
  EXPECT_LT(mu, 0.1);
  EXPECT_LE(r.steady.newton_iterations, 8);  // at most kChordIterations chord steps
  const double tol = lub::parse_scene(doc).simulation.steady_tolerance;
  EXPECT_LE(r.steady.orbit_residual / (1.0 - mu), 0.1 * tol);
  EXPECT_LT(r.steady.orbit_error, 1e-4);
  EXPECT_LT(r.metrics.min_film_thickness_m_error, 1e-3 * r.metrics.min_film_thickness_m);
}

TEST(SteadyCycle, NewtonStalledAtTheMapsNoiseTriesAgainTenTimesTighter) {
  // Frêne long, 0.2 mm, 200 cP, 2500 rpm (full factorial): |μ|max ≈ 1 at the transient's
  // end, so KINSOL, whose line search stalls at a residual of ~1e-6 (the map's noise at
  // rtol 1e-8); the map's error there moves the orbit by ~1e-4 c, well within what can
  // be located. At rtol/10 Newton converges to the orbit, which rtol/100 moves by ~1e-4 c.
  const json doc = cell("frene_long", 2e-4, 0.2, 2500);
  const RunResult r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_TRUE(lub::classification(r) == "periodic" || lub::classification(r) == "periodic_unstable") << r.message;
  ASSERT_FALSE(r.steady.multipliers.empty());
  EXPECT_NEAR(std::abs(r.steady.multipliers.front()), 1.0, 1e-2);
  EXPECT_LE(r.steady.orbit_residual, 1e-6);  // noise_factor x shooting_tolerance
  EXPECT_LT(r.steady.orbit_error, lub::parse_scene(doc).simulation.steady_tolerance);
}

TEST(SteadyCycle, NoNewtonWhereTheMapsErrorWouldMoveTheOrbitBeyondLocating) {
  // Frêne short, 0.2 mm, 400 cP, 500 rpm (full factorial): at the transient's end the
  // map's error at rtol, over 1 − |μ|max, would move its orbit by ~0.17 c, beyond 10 ×
  // steady_tolerance: no Newton, at rtol or rtol/10. The independent route: the same
  // case with steady_tolerance 0.1 lets Newton run from the same 8 cycles, and it finds no
  // orbit (it walked into the wall after 20 iterations and ~470 periods; it is now stopped
  // where its residual stops halving, SteadyTuning::stagnation_maps).
  // With the slow flow, which says where the journal goes instead (the default).
  json doc = cell("frene_short", 2e-4, 0.4, 500);
  doc["simulation"]["steady"] = "shooting";
  doc["simulation"]["transient_cycles"] = 8;
  doc["simulation"]["slow_flow"] = true;
  const RunResult r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(lub::classification(r).rfind("periodic", 0), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("no shooting (the map's error at rtol would move its orbit by"), std::string::npos)
      << r.message;
  EXPECT_EQ(r.steady.newton_iterations, 0);

  doc["simulation"]["steady_tolerance"] = 0.1;
  doc["simulation"]["slow_flow"] = false;  // Newton's own verdict
  const RunResult newton = run(doc);
  ASSERT_EQ(newton.status, RunStatus::ok) << newton.message;
  EXPECT_EQ(lub::classification(newton).rfind("periodic", 0), std::string::npos) << newton.message;
  EXPECT_NE(newton.message.find("shooting did not converge"), std::string::npos) << newton.message;
  EXPECT_GE(newton.steady.newton_iterations, 1);
}

TEST(SteadyCycle, WithoutTheSlowFlowNewtonRunsWhereItCouldNotLocateAnOrbit) {
  // The same cell with slow_flow off (shooting's default): nothing else would say where
  // the journal goes, and Newton's own verdict is the evidence (walking into the wall:
  // drifting; here its line search stalls after a period failed: not_converged).
  json doc = cell("frene_short", 2e-4, 0.4, 500);
  doc["simulation"]["slow_flow"] = false;
  const RunResult r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(lub::classification(r).rfind("periodic", 0), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("shooting did not converge"), std::string::npos) << r.message;
  EXPECT_EQ(r.message.find("no shooting"), std::string::npos) << r.message;
  EXPECT_GT(r.steady.newton_iterations, 0);
}

TEST(SteadyCycle, ANewtonThatCreepsAlongASlowManifoldIsStopped) {
  // Frêne short, 0.2 mm, 200 cP, 5000 rpm (full factorial): from the transient's end Newton
  // creeps, its residual falling by ~10 % an iteration of ~10 periods (a fresh Jacobian
  // each), and at rtol/10 on to a fixed point of the map's error (|μ|max 0.9998) that moves
  // by 1.3e-2 c when re-solved 100 times tighter: 50 iterations and 668 periods for an
  // orbit the error bars then refuse. Inside Newton's region of convergence every iteration
  // halves the residual; this Newton is stopped after five trial periods without, and
  // the case says so: the same verdict for a sixth of the periods. (The error bars' refusal
  // itself: NearWallOrbits.*.) The slow flow off: this pins shooting's own verdict.
  json doc = cell("frene_short", 2e-4, 0.2, 5000);
  doc["simulation"]["slow_flow"] = false;
  const RunResult r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(lub::classification(r), "not_converged") << r.message;
  EXPECT_NE(r.message.find("its residual did not halve in 5 trial periods"), std::string::npos) << r.message;
  EXPECT_LT(r.steady.periods_integrated, 668 / 3) << r.message;
}

TEST(SteadyCycle, AutoDoesNotDependOnMaxCyclesBeyondWhatItUses) {
  const RunResult a = run(reference("frene_long", "auto", 60));
  const RunResult b = run(reference("frene_long", "auto", 90));
  ASSERT_EQ(a.status, RunStatus::ok);
  ASSERT_EQ(b.status, RunStatus::ok);
  EXPECT_EQ(lub::classification(a), lub::classification(b));
  EXPECT_EQ(a.metrics.min_film_thickness_m, b.metrics.min_film_thickness_m);
  EXPECT_EQ(a.metrics.peak_reaction_N, b.metrics.peak_reaction_N);
  EXPECT_EQ(a.steady.periods_integrated, b.steady.periods_integrated);
}

TEST(SteadyCycle, ErrorBarsThatCouldNotBeMeasuredAreNaNAndTheCaseSaysWhy) {
  // solver.max_steps bounds each integration: Frêne long's loose periods take ~500 steps,
  // its orbit's two metric cycles at rtol/100 more than 850. Shooting finds the orbit; its
  // error bars are not measured, and the case says why (before: NaN and no word). A
  // budget the user set keeps the orbit (docs/theory/steady-cycles.md, budgets); any other
  // failure there makes it not_converged.
  json doc = reference("frene_long", "shooting", 40);
  doc["simulation"]["transient_cycles"] = 2;
  const RunResult full = run(doc);
  ASSERT_EQ(full.status, RunStatus::ok) << full.message;
  ASSERT_EQ(lub::classification(full), "periodic") << full.message;
  ASSERT_TRUE(std::isfinite(full.metrics.min_film_thickness_m_error));

  doc["solver"]["max_steps"] = 850;
  const RunResult r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(lub::classification(r), "periodic") << r.message;
  EXPECT_EQ(r.metrics.min_film_thickness_m, full.metrics.min_film_thickness_m);
  EXPECT_TRUE(std::isnan(r.metrics.min_film_thickness_m_error));
  EXPECT_NE(r.message.find("error bars not measured"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("solver.max_steps = 850"), std::string::npos) << r.message;
}

TEST(SteadyCycle, SettingsAreValidatedWithTheirRule) {
  auto refused = [](const json& doc, const std::string& needle) {
    try {
      lub::parse_scene(doc);
    } catch (const lub::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted: " << doc["simulation"].dump();
  };
  refused(reference("frene_long", "newton", 5), "simulation.steady");
  json d = reference("frene_long", "shooting", 5);
  d["simulation"].erase("max_cycles");
  d["simulation"]["duration_s"] = 0.1;
  refused(d, "simulation.steady");
  json t = reference("frene_long", "shooting", 5);
  t["simulation"]["transient_cycles"] = 6;
  refused(t, "simulation.transient_cycles");
  json tol = reference("frene_long", "shooting", 5);
  tol["simulation"]["shooting_tolerance"] = 0.0;
  refused(tol, "simulation.shooting_tolerance");
}

}  // namespace
