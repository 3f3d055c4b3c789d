// IDA on the stabilised index-2 (GGL) formulation: the constraints hold at position and
// velocity level without Baumgarte's terms, and the lubricated reference case — with
// the printed law's switching and Filippov sliding, where a sliding film adds a
// constraint row and a multiplier — gives the answer the ODE formulations give; and its
// structured iteration matrix (MultibodySystem::dae_jacobian) is the residual's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "lub/formulation/model_jacobian.hpp"
#include "lub/integrators/integrator.hpp"
#include "lub/run/run.hpp"
#include "fixtures/near_wall_state.hpp"

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
  // slider's 26 m/s for velocities (factor 10 for the interpolation). Baumgarte's position
  // drift accumulates; its velocity drift is damped by α and sits at that same
  // interpolation level (2.9e-7 m/s here against GGL's 6.4e-7 m/s with the per-state
  // tolerances), so only the position drift is compared between the two.
  const double rtol = 1e-8;
  const RunResult b = run("frene_long", "cvode_bdf", "baumgarte", rtol, 3);
  const RunResult g = run("frene_long", "ida", "", rtol, 3);
  ASSERT_EQ(b.status, RunStatus::ok) << b.message;
  ASSERT_EQ(g.status, RunStatus::ok) << g.message;
  EXPECT_LT(g.stats.max_position_drift, 10 * rtol * 0.2);
  EXPECT_LT(g.stats.max_velocity_drift, 10 * rtol * 26.0);
  EXPECT_LT(g.stats.max_position_drift, 1e-2 * b.stats.max_position_drift);
}

TEST(IdaGgl, AgreesWithThePartitionedReferenceForEachPaperLaw) {
  // Reference: CVODE BDF on the partitioned ODE at rtol 1e-10. IDA at 1e-8: the metrics
  // over the third cycle agree to the integration error, which the work-precision
  // study puts at ~1e-3 c on the orbit at this tolerance; allow 2e-3 relative.
  for (const std::string law : {"pinkus_sternlicht", "frene_long", "frene_short"}) {
    SCOPED_TRACE(law);
    const RunResult ref = run(law, "cvode_bdf", "partitioned", 1e-10, 3);
    const RunResult g = run(law, "ida", "ggl", 1e-8, 3);
    EXPECT_EQ(ref.status, RunStatus::ok) << ref.message;
    EXPECT_EQ(g.status, RunStatus::ok) << g.message;
    if (ref.status != RunStatus::ok || g.status != RunStatus::ok) continue;
    EXPECT_EQ(g.stats.jacobian, lub::JacobianKind::structured);  // IDA's default
    EXPECT_NEAR(g.metrics.min_film_thickness_m / ref.metrics.min_film_thickness_m, 1.0, 2e-3);
    EXPECT_NEAR(g.metrics.max_eps / ref.metrics.max_eps, 1.0, 2e-3);
    EXPECT_NEAR(g.metrics.peak_reaction_N / ref.metrics.peak_reaction_N, 1.0, 2e-3);
    if (law == "pinkus_sternlicht") {
      // The printed law switched (and slid) under IDA too.
      EXPECT_GT(g.stats.mode_switches, 0);
    }
  }
}

// The structured iteration matrix J = ∂F/∂Y + cj ∂F/∂Y' against central differences of
// the whole residual, Y and Y' perturbed together (Y ± h e_j, Y' ± cj h e_j), at the
// near-wall state of test_core_jacobian.cpp, with the multipliers of a consistent state
// and μ ≠ 0 (so that ∂(Φ_qᵀμ)/∂q is exercised). cj = 2e4 1/s: a step of ~5e-5 s.
class DaeJacobian : public ::testing::TestWithParam<lub_test::Case> {};

TEST_P(DaeJacobian, AgreesWithDifferencesOfTheResidualNearTheWall) {
  lub_test::NearWall s(GetParam(), lub::Formulation::ggl);
  const int nq = s.model.nq, na = s.model.nc + s.model.n_switching, n = 2 * nq + 2 * na;
  ASSERT_EQ(s.sys->size() + s.sys->num_algebraic(), n);
  Eigen::VectorXd Y(n), Yp(n);
  ASSERT_EQ(s.sys->consistent_state(0.0, s.y.data(), Y.data(), Yp.data()), 0);
  for (int i = 0; i < na; ++i) Y(2 * nq + na + i) = 1e-6 * (i + 1);  // μ
  if (GetParam().sliding) {
    ASSERT_GT(s.model.n_switching, 0);
    EXPECT_NE(Y(2 * nq + s.model.nc), 0.0);  // the sliding slot's λ: the radial film force
  }
  const double cj = 2e4, c_m = s.model.films[0].clearance;
  Eigen::MatrixXd J(n, n), Jfd(n, n);
  ASSERT_EQ(s.sys->dae_jacobian(0.0, cj, Y.data(), Yp.data(), J.data()), 0);
  Eigen::VectorXd Yh = Y, Yph = Yp, fp(n), fm(n);
  for (int j = 0; j < n; ++j) {
    // Steps: u^(1/3) of the distance to the wall (0.05 c) for positions, of 1 m/s for
    // velocities, angles over a 0.1 m arm; the residual is linear in the multipliers.
    double h = j < nq ? 6e-6 * 0.05 * c_m : j < 2 * nq ? 6e-6 : 1.0;
    if (j < 2 * nq && j % 3 == 2) h /= 0.1;
    // The steps actually taken (a 1.5e-10 m step on a 0.2 m coordinate is rounded by ~1e-7
    // of itself).
    Yh(j) = Y(j) + h;
    const double hp = Yh(j) - Y(j);
    Yph(j) = Yp(j) + cj * hp;
    ASSERT_EQ(s.sys->residual(0.0, Yh.data(), Yph.data(), fp.data()), 0);
    Yh(j) = Y(j) - h;
    const double hm = Y(j) - Yh(j);
    Yph(j) = Yp(j) - cj * hm;
    ASSERT_EQ(s.sys->residual(0.0, Yh.data(), Yph.data(), fm.data()), 0);
    Yh(j) = Y(j);
    Yph(j) = Yp(j);
    Jfd.col(j) = (fp - fm) / (hp + hm);
  }
  // Block by block (rows, columns: q, v, λ, μ), relative to the block's largest entry.
  // Nothing is neglected, so both sides are central differences of the same functions
  // (errors ~(h/d)² + u d/h): measured ≤ 4e-10, finite_reynolds 4e-8 (its iterative
  // solver's tolerance). The bound 1e-7 still sees any constraint term: in ∂F_v/∂q the
  // film's ∂g/∂q (2e8..2e10 N/m at ε = 0.95) sits next to ∂(Φ_qᵀλ)/∂q (~λ/L ~ 1e5 N/m;
  // the sliding row's λ_s/|e| ~ 1e7 N/m, which counting the sliding radial force in g
  // as well — SlidingRadial::held_multiplier — would double): ≥ 5e-6 of the block.
  const int start[4] = {0, nq, 2 * nq, 2 * nq + na}, size[4] = {nq, nq, na, na};
  const char* names[4] = {"q", "v", "lambda", "mu"};
  for (int bi = 0; bi < 4; ++bi)
    for (int bj = 0; bj < 4; ++bj) {
      const Eigen::MatrixXd ref = Jfd.block(start[bi], start[bj], size[bi], size[bj]);
      const Eigen::MatrixXd got = J.block(start[bi], start[bj], size[bi], size[bj]);
      const double scale = std::max(ref.cwiseAbs().maxCoeff(), got.cwiseAbs().maxCoeff());
      Eigen::Index ri = 0, ci = 0;
      const double diff = (got - ref).cwiseAbs().maxCoeff(&ri, &ci);
      if (scale > 0)
        std::printf("%s: dF_%s/d%s max %.3g, diff %.3g (%.2g) at (%d, %d) %.6g\n", GetParam().name.c_str(),
                    names[bi], names[bj], scale, diff, diff / scale, int(ri), int(ci), ref(ri, ci));
      EXPECT_LE(diff, 1e-7 * scale) << "block F_" << names[bi] << " / " << names[bj];
    }
}

INSTANTIATE_TEST_SUITE_P(
    ForceLaws, DaeJacobian,
    ::testing::Values(lub_test::Case{"pinkus_sternlicht", "pinkus_sternlicht"},
                      lub_test::Case{"pinkus_sternlicht_sliding", "pinkus_sternlicht", true},
                      lub_test::Case{"frene_long", "frene_long"}, lub_test::Case{"frene_short", "frene_short"},
                      lub_test::Case{"gumbel_short", "gumbel_short"},
                      lub_test::Case{"finite_reynolds", "finite_reynolds"},
                      lub_test::Case{"frene_long_contact_handover", "frene_long", false, true},
                      lub_test::Case{"pinkus_sternlicht_sliding_contact", "pinkus_sternlicht", true, true}),
    [](const ::testing::TestParamInfo<lub_test::Case>& i) { return i.param.name; });

// The same run with the structured iteration matrix and with SUNDIALS' difference
// quotients: the same metrics to within IDA's integration error (the matrix changes how
// Newton converges, not what to) and fewer residual evaluations (none spent on
// Jacobians). IDA's error at rtol 1e-8 is larger than CVODE's: frene_long, three cycles,
// min film thickness against CVODE BDF partitioned at 1e-11: DQ 2.7e-5 c, structured
// 5e-6 c (they differ from each other by 3.3e-5 c). Bound: 1e-4 c on the film, 1e-4 on
// ε, against each other; 1e-3 on the peak reaction (as in test_core_jacobian.cpp).
TEST(IdaGgl, StructuredJacobianSameMetricsFewerResiduals) {
  for (const std::string law : {"pinkus_sternlicht", "frene_long"}) {
    SCOPED_TRACE(law);
    auto with = [&](const std::string& jacobian) {
      json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
      doc["joints"][3]["force_law"] = law;
      doc["solver"]["method"] = "ida";
      doc["solver"]["rtol"] = 1e-8;
      doc["solver"]["jacobian"] = jacobian;
      doc["simulation"]["max_cycles"] = 3;
      // The third cycle: the second still carries the start-up transient, whose brush
      // with the wall (ε ≈ 0.99) is too sensitive to compare two step sequences on.
      doc["simulation"]["metric_cycles"] = 1;
      doc["outputs"]["channels"] = json::array();
      return lub::run_scene(lub::parse_scene(doc));
    };
    const RunResult dq = with("difference_quotients");
    const RunResult st = with("structured");
    // The sampled peak acceleration (a film impact, ~3.5× the ideal peak) is the slowest
    // metric: printed law, third cycle, each run lies within 9e-4 of CVODE BDF at rtol
    // 1e-11 (68272 m/s²), on opposite sides — so 2e-3 against each other.
    lub_test::expect_same_run_fewer_evaluations(dq, st, {1e-4, 1e-4, 1e-3, 2e-3});
  }
}

// Issue 12, item 7: IDA on the printed law stalled at rtol 1e-10 (after the start-up
// transient near the wall the step fell to ~1e-8 s and recovered by ~1 % a step, one
// error-test failure per step; the 120 s budget ended it). With the absolute tolerances per
// state (velocities from c times the crank speed instead of c) and the sliding exit left
// at the next step end it runs 3 cycles in ~9000 steps with ~200 error-test failures;
// with the uniform tolerance of before (solver.atol = rtol c) it still completes but with
// 10352 failures in 20055 steps. Bounds: ~2× the measured steps, 5 % failures.
TEST(IdaGgl, PrintedLawAtTightToleranceDoesNotStall) {
  for (const double rtol : {1e-10, 1e-12}) {
    SCOPED_TRACE(rtol);
    const RunResult r = run("pinkus_sternlicht", "ida", "ggl", rtol, 3);
    EXPECT_EQ(r.status, RunStatus::ok) << r.message;
    if (r.status != RunStatus::ok) continue;
    EXPECT_NEAR(r.stats.final_time_s, 0.036, 1e-12);
    EXPECT_LT(r.stats.steps, rtol < 1e-11 ? 40000 : 20000);
    EXPECT_LT(r.stats.error_test_fails, r.stats.steps / 20);
    // The same film as CVODE's reference (1.20181e-5 m at rtol 1e-12, 4 cycles;
    // docs/validation/work-precision.md): within 1e-4 relative.
    EXPECT_NEAR(r.metrics.min_film_thickness_m, 1.2018e-5, 1.2e-9);
  }
}

// An adapter whose constructor throws half-way (here IDA, which finds no consistent initial
// state after it has created its context and vectors) reports the failure as an exception
// and frees what it created (the handles are owned by unique_ptr members; run this test
// under valgrind --leak-check=full to see no SUNDIALS allocation left behind).
TEST(IntegratorAdapters, ConstructorThatThrowsReportsTheFailure) {
  struct NoConsistentState final : lub::OdeSystem {
    int size() const override { return 2; }
    int rhs(double, const double*, double* ydot) override {
      ydot[0] = ydot[1] = 0.0;
      return 0;
    }
    int num_algebraic() const override { return 1; }
    int consistent_state(double, const double*, double*, double*) override { return 1; }
  } sys;
  lub::IntegratorSettings is;
  is.method = lub::Method::ida;
  is.atol = {1e-8, 1e-8};
  is.t_stop = 1.0;
  try {
    (void)lub::make_integrator(is, sys, 0.0, {0.0, 0.0});
    ADD_FAILURE() << "expected a failure";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no consistent initial state"), std::string::npos) << e.what();
  }
}

}  // namespace
