// The structured Jacobian of the baumgarte formulation (core/src/formulation/multibody_jacobian.cpp)
// against a central-difference Jacobian of the full right-hand side near the wall, for
// every force law, in sliding mode and with the contact hand-over; no allocation inside
// it (nor inside the GGL DAE's, test_core_ida.cpp); and whole runs with it against runs with SUNDIALS' difference quotients.
#include <gtest/gtest.h>

#include <atomic>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "near_wall_state.hpp"

// Counts the heap allocations of this process while g_count is set (glibc: the real
// allocator is __libc_malloc; lubcore is linked statically, so its calls land here).
extern "C" void* __libc_malloc(size_t);
namespace {
std::atomic<bool> g_count{false};
std::atomic<long> g_allocs{0};
}  // namespace
extern "C" void* malloc(size_t n) {
  if (g_count.load(std::memory_order_relaxed)) g_allocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}

namespace {

using nlohmann::json;

using lub_test::Case;
using lub_test::NearWall;
using lub_test::reference_doc;

// Central differences of the whole right-hand side (18 columns × 2 full evaluations).
Eigen::MatrixXd full_difference_jacobian(NearWall& s) {
  const int n = static_cast<int>(s.y.size()), nq = n / 2;
  const double c_m = s.model.films[0].clearance;
  Eigen::MatrixXd J(n, n);
  Eigen::VectorXd yp = s.y, fp(n), fm(n);
  for (int j = 0; j < n; ++j) {
    const bool vel = j >= nq, ang = j % 3 == 2;
    // Steps: u^(1/3) of the distance to the wall (0.05 c) for positions, of 1 m/s for
    // velocities; angles over a 0.1 m arm.
    double h = vel ? 6e-6 * 1.0 : 6e-6 * 0.05 * c_m;
    if (ang) h /= 0.1;
    yp(j) = s.y(j) + h;
    EXPECT_EQ(s.sys->rhs(0.0, yp.data(), fp.data()), 0);
    yp(j) = s.y(j) - h;
    EXPECT_EQ(s.sys->rhs(0.0, yp.data(), fm.data()), 0);
    yp(j) = s.y(j);
    J.col(j) = (fp - fm) / (2.0 * h);
  }
  return J;
}

class StructuredJacobian : public ::testing::TestWithParam<Case> {};

// The velocity block J_v = ∂a/∂v is exact in the structured Jacobian (the film's
// derivatives by central differences of the element, ∂γ/∂v analytic): it agrees with
// the full central-difference Jacobian to the difference quotients' own accuracy
// (measured ~5e-10 of the block's largest entry: both are central differences with
// errors ~(h/d)² + u d/h; the bound 1e-5 leaves room for the full RHS's constraint
// solve). The position block neglects the derivatives of P and of the ideal joints'
// curvature: terms of order ω² (~3e5 1/s², ω = 524 rad/s) and |g|/(m L), which at
// ε = 0.95 are small against the film's stiffness (~1e10..1e12 1/s²): measured ~7e-6
// of the block's largest entry, bound 1e-4. The sliding row's curvature is not
// neglected (radius |e| ~ c): without it the sliding case is 5e-2 off.
TEST_P(StructuredJacobian, AgreesWithFullDifferencesNearTheWall) {
  NearWall s(GetParam());
  const int n = static_cast<int>(s.y.size()), nq = n / 2;
  Eigen::VectorXd f(n);
  ASSERT_EQ(s.sys->rhs(0.0, s.y.data(), f.data()), 0);
  const Eigen::MatrixXd Jfd = full_difference_jacobian(s);
  Eigen::MatrixXd J(n, n);
  ASSERT_EQ(s.sys->jacobian(0.0, s.y.data(), f.data(), J.data()), 0);
  // The kinematic rows are exact.
  EXPECT_LT((J.topRows(nq) - Jfd.topRows(nq)).cwiseAbs().maxCoeff(), 1e-8);
  const auto dq = (J.bottomLeftCorner(nq, nq) - Jfd.bottomLeftCorner(nq, nq)).cwiseAbs().maxCoeff();
  const auto dv = (J.bottomRightCorner(nq, nq) - Jfd.bottomRightCorner(nq, nq)).cwiseAbs().maxCoeff();
  const double sq = Jfd.bottomLeftCorner(nq, nq).cwiseAbs().maxCoeff();
  const double sv = Jfd.bottomRightCorner(nq, nq).cwiseAbs().maxCoeff();
  std::printf("%s: J_q max %.3g, diff %.3g (%.2g); J_v max %.3g, diff %.3g (%.2g)\n", GetParam().name.c_str(), sq,
              dq, dq / sq, sv, dv, dv / sv);
  EXPECT_LT(dv, 1e-5 * sv);
  EXPECT_LT(dq, 1e-4 * sq);
}

// No heap allocation inside the Jacobian (it runs inside the integrator's step). While a
// film slides it calls evaluate() once (the multiplier at this state), and evaluate()
// itself allocates today (Eigen temporaries for Φ_q(M⁻¹g) and g − Φ_qᵀλ: 2 per call, the
// speed work's business): the Jacobian may allocate exactly what one evaluation does.
TEST_P(StructuredJacobian, DoesNotAllocate) {
  NearWall s(GetParam());
  const int n = static_cast<int>(s.y.size());
  Eigen::VectorXd f(n);
  Eigen::MatrixXd J(n, n);
  ASSERT_EQ(s.sys->rhs(0.0, s.y.data(), f.data()), 0);
  ASSERT_EQ(s.sys->jacobian(0.0, s.y.data(), f.data(), J.data()), 0);  // warm
  long allowed = 0;
  if (GetParam().sliding) {
    g_allocs = 0;
    g_count = true;
    s.sys->rhs(0.0, s.y.data(), f.data());
    g_count = false;
    allowed = g_allocs.load();
  }
  g_allocs = 0;
  g_count = true;
  const int rc = s.sys->jacobian(0.0, s.y.data(), f.data(), J.data());
  g_count = false;
  EXPECT_EQ(rc, 0);
  EXPECT_EQ(g_allocs.load(), allowed);
}

// The GGL DAE's iteration matrix (IDA, dae_jacobian) allocates nothing at all: it needs
// no evaluate(), the sliding film included (its multiplier is part of Y).
TEST_P(StructuredJacobian, DaeJacobianDoesNotAllocate) {
  NearWall s(GetParam(), lub::Formulation::ggl);
  const int n = s.sys->size() + s.sys->num_algebraic();
  Eigen::VectorXd Y(n), Yp(n);
  ASSERT_EQ(s.sys->consistent_state(0.0, s.y.data(), Y.data(), Yp.data()), 0);
  Eigen::MatrixXd J(n, n);
  ASSERT_EQ(s.sys->dae_jacobian(0.0, 1e4, Y.data(), Yp.data(), J.data()), 0);  // warm
  g_allocs = 0;
  g_count = true;
  const int rc = s.sys->dae_jacobian(0.0, 1e4, Y.data(), Yp.data(), J.data());
  g_count = false;
  EXPECT_EQ(rc, 0);
  EXPECT_EQ(g_allocs.load(), 0);
}

INSTANTIATE_TEST_SUITE_P(
    ForceLaws, StructuredJacobian,
    ::testing::Values(Case{"pinkus_sternlicht", "pinkus_sternlicht"},
                      Case{"pinkus_sternlicht_sliding", "pinkus_sternlicht", true},
                      Case{"frene_long", "frene_long"}, Case{"frene_short", "frene_short"},
                      Case{"gumbel_long", "gumbel_long"}, Case{"gumbel_short", "gumbel_short"},
                      Case{"pinkus_sternlicht_continuous", "pinkus_sternlicht_continuous"},
                      Case{"finite_reynolds", "finite_reynolds"},
                      Case{"frene_long_contact_handover", "frene_long", false, true}),
    [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });

// The partitioned formulation keeps difference quotients.
TEST(StructuredJacobianPlumbing, PartitionedProvidesNone) {
  const lub::Scene scene = lub::parse_scene(reference_doc());
  const lub::Model m = lub::build_model(scene);
  lub::Workspace ws(m);
  lub::MultibodySystem sys(m, ws, 0.999, false, lub::Formulation::partitioned);
  std::vector<double> y(static_cast<size_t>(sys.size()), 0.0), J(y.size() * y.size());
  EXPECT_EQ(sys.jacobian(0.0, y.data(), y.data(), J.data()), -1);
}

lub::RunResult run(const std::string& method, const std::string& jacobian, const std::string& law, double rtol,
                   int cycles) {
  json doc = reference_doc();
  doc["solver"]["method"] = method;
  doc["solver"]["rtol"] = rtol;
  doc["solver"]["jacobian"] = jacobian;
  doc["solver"]["formulation"] = "baumgarte";  // the structured Jacobian is baumgarte's
  doc["joints"][3]["force_law"] = law;
  doc["simulation"]["max_cycles"] = cycles;
  return lub::run_scene(lub::parse_scene(doc));
}

// Same answer as with SUNDIALS' difference quotients, to within the integration
// tolerance (the Newton matrix only changes how the corrector converges, not what it
// converges to): at rtol 1e-8 the film metrics of the two runs differ by ~1e-6 c, within
// the bound 2e-5 c, the size of their own integration error at this tolerance (README:
// "metrics within ~5e-6 of converged"). The peaks (reaction, acceleration) are sampled
// at step ends and 120 crank angles and carry a sampling error of a few 1e-4 (cvode_bdf
// and arkode_dirk, both with difference quotients, differ by 4e-4 on frene_long): 1e-3.
// The printed law's peak acceleration peaks at the ε̇ = 0 switches, located only to the
// root tolerance: sampled at the third cycle it scatters by ~2e-3 between methods that
// agree on the orbit (cvode_bdf at 1e-11: 68283 m/s²; arkode_erk at 1e-10: 68178;
// arkode_dirk at 1e-8, DQ 68282, structured 68141): 3e-3 there.
// And cheaper: no right-hand sides spent on Jacobians.
TEST(StructuredJacobianRun, SameMetricsFewerEvaluations) {
  for (const std::string method : {"cvode_bdf", "arkode_dirk"}) {
    for (const std::string law : {"pinkus_sternlicht", "frene_long"}) {
      SCOPED_TRACE(method + " " + law);
      const lub::RunResult dq = run(method, "difference_quotients", law, 1e-8, 3);
      const lub::RunResult st = run(method, "structured", law, 1e-8, 3);
      lub_test::expect_same_run_fewer_evaluations(dq, st,
                                                  {2e-5, 2e-5, 1e-3, law == "pinkus_sternlicht" ? 3e-3 : 1e-3});
    }
  }
}

}  // namespace
