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

#include <Eigen/LU>

#include "lub/mechanism/film_element.hpp"
#include "fixtures/near_wall_state.hpp"

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

// Every force law near the wall, the printed one also sliding, and the contact hand-over:
// the cases of both structured Jacobians' suites.
const Case kCases[] = {Case{"pinkus_sternlicht", "pinkus_sternlicht"},
                       Case{"pinkus_sternlicht_sliding", "pinkus_sternlicht", true},
                       Case{"frene_long", "frene_long"},
                       Case{"frene_short", "frene_short"},
                       Case{"gumbel_long", "gumbel_long"},
                       Case{"gumbel_short", "gumbel_short"},
                       Case{"pinkus_sternlicht_continuous", "pinkus_sternlicht_continuous"},
                       Case{"finite_reynolds", "finite_reynolds"},
                       Case{"frene_long_contact_handover", "frene_long", false, true}};
std::string case_name(const ::testing::TestParamInfo<Case>& i) { return i.param.name; }

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
    ::testing::ValuesIn(kCases), case_name);

// A consistent state (Φ = 0, Φ̇ = 0) of the reference slider-crank with the journal at
// ε = 0.95, moving outwards and round the bearing (NearWall's e and ė), for the partitioned
// formulation: from the paper's initial state, the degrees of freedom are solved for that
// e and ė by Newton on difference quotients of the recovery, so the test need not know
// which coordinates the partition made independent.
struct PartitionedNearWall {
  explicit PartitionedNearWall(const Case& c) : base(c, lub::Formulation::partitioned) {
    const lub::Model& m = base.model;
    nq = m.nq;
    Eigen::VectorXd q, v;
    lub::assemble_initial_state(m, base.scene, 0.0, q, v);
    Eigen::VectorXd qv(2 * nq);
    qv << q, v;
    sys().partition(0.0, qv.data());
    y.resize(sys().size());
    sys().reduce(qv.data(), y.data());
    nz = sys().size() / 2;
    c_m = m.films[0].clearance;
    const double omega = 5000.0 * 2.0 * M_PI / 60.0;
    const Eigen::Vector2d r(std::cos(0.7), std::sin(0.7)), t(-r.y(), r.x());
    const Eigen::Vector2d e_target = 0.95 * c_m * r, ed_target = c_m * omega * (0.2 * r + 0.5 * t);
    // Positions: e(z) = e_target (2 equations in the 2 degrees of freedom).
    for (int it = 0; it < 30; ++it) {
      const Eigen::Vector2d f = film(y).first - e_target;
      if (f.norm() < 1e-14) break;
      Eigen::Matrix2d D;
      for (int j = 0; j < 2; ++j) D.col(j) = (film(bumped(j, 1e-8)).first - film(y).first) / 1e-8;
      const Eigen::Vector2d dz = D.inverse() * f;
      y(0) -= dz(0), y(1) -= dz(1);
    }
    // Velocities: ė is affine in ż.
    Eigen::Matrix2d D;
    for (int j = 0; j < 2; ++j) D.col(j) = film(bumped(nz + j, 1.0)).second - film(y).second;
    const Eigen::Vector2d dzd = D.inverse() * (film(y).second - ed_target);
    y(nz) -= dzd(0), y(nz + 1) -= dzd(1);
    if (c.sliding) {
      base.ws->film_mode[0] = lub::FilmMode::sliding;
      base.ws->slide_radius[0] = 0.95 * c_m;
    }
  }
  lub::MultibodySystem& sys() { return *base.sys; }
  Eigen::VectorXd bumped(int j, double h) const {
    Eigen::VectorXd yy = y;
    yy(j) += h;
    return yy;
  }
  // e and ė of the film at the recovered state of yy [m, m/s].
  std::pair<Eigen::Vector2d, Eigen::Vector2d> film(const Eigen::VectorXd& yy) {
    Eigen::VectorXd full(2 * nq);
    EXPECT_EQ(sys().expand(0.0, yy.data(), full.data()), 0);
    const lub::FilmKinematics fk = lub::film_kinematics(base.model, 0, full.data(), full.data() + nq);
    return {fk.e, fk.e_dot};
  }
  NearWall base;
  Eigen::VectorXd y;
  int nq = 0, nz = 0;
  double c_m = 0.0;
};

class PartitionedJacobian : public ::testing::TestWithParam<Case> {};

// The partitioned formulation's Jacobian (MultibodySystem::partitioned_jacobian: the
// reduced form N⁻¹Tᵀ(g − M q̈_p), film terms along the degrees of freedom) against central
// differences of its whole right-hand side, which recovers the dependent coordinates by
// Newton at every call. The reference's steps: positions move e by 1e-3 of the distance
// to the wall (truncation ~1e-6; the recovery's Newton stops at |Φ| <= 1e-13 m, which
// the smaller steps of the baumgarte test would turn into ~1e-3 of noise), velocities by
// 6e-6 m/s (the velocity recovery is a direct solve: no such noise). The velocity
// columns are exact up to the two difference quotients' errors: measured ≤ 1e-9 of the
// block's largest entry, bound 1e-6. The position columns neglect the constraint
// geometry's curvature terms (ω² ≈ 3e5 1/s², |F|/(m L) ≈ 4e5 1/s²) against film
// stiffnesses of 2e10–2e12 1/s² at ε = 0.95: measured 2.5e-6–6.8e-6, bound 1e-4. While a
// film slides (its radial force a multiplier) the Jacobian is forward differences of
// rhs() with increments √u of each state's size, as SUNDIALS' own: their truncation and
// the recovery's Newton tolerance on increments of ~1e-8 c show as 1e-4 of the position
// block (9e-8 of the velocity block): bounds 1e-3 and 1e-5.
TEST_P(PartitionedJacobian, AgreesWithDifferencesOfTheRecoveredRightHandSide) {
  PartitionedNearWall s(GetParam());
  const int n = static_cast<int>(s.y.size()), nz = s.nz;
  ASSERT_EQ(nz, 2);
  std::vector<double> scales(static_cast<size_t>(n));
  Eigen::VectorXd f(n), fp(n), fm(n);
  ASSERT_EQ(s.sys().rhs(0.0, s.y.data(), f.data()), 0);
  const double eps = s.film(s.y).first.norm() / s.c_m;
  ASSERT_NEAR(eps, 0.95, 1e-9);
  Eigen::MatrixXd Jfd(n, n);
  for (int j = 0; j < n; ++j) {
    const bool vel = j >= nz;
    // The size of a unit of this state in e or ė, from the recovery itself.
    const double unit = vel ? (s.film(s.bumped(j, 1.0)).second - s.film(s.y).second).norm()
                            : (s.film(s.bumped(j, 1e-8)).first - s.film(s.y).first).norm() / 1e-8;
    const double h = vel ? 6e-6 / unit : 1e-3 * (1.0 - eps) * s.c_m / unit;
    scales[static_cast<size_t>(j)] = vel ? s.c_m * 524.0 / unit : s.c_m / unit;  // rtol × scale: atol
    ASSERT_EQ(s.sys().rhs(0.0, s.bumped(j, h).data(), fp.data()), 0);
    ASSERT_EQ(s.sys().rhs(0.0, s.bumped(j, -h).data(), fm.data()), 0);
    Jfd.col(j) = (fp - fm) / (2.0 * h);
  }
  s.sys().set_difference_scales(scales);
  ASSERT_EQ(s.sys().rhs(0.0, s.y.data(), f.data()), 0);
  Eigen::MatrixXd J(n, n);
  ASSERT_EQ(s.sys().jacobian(0.0, s.y.data(), f.data(), J.data()), 0);
  EXPECT_LT((J.topRows(nz) - Jfd.topRows(nz)).cwiseAbs().maxCoeff(), 1e-8);  // ż: exact
  const double dq = (J.bottomLeftCorner(nz, nz) - Jfd.bottomLeftCorner(nz, nz)).cwiseAbs().maxCoeff();
  const double dv = (J.bottomRightCorner(nz, nz) - Jfd.bottomRightCorner(nz, nz)).cwiseAbs().maxCoeff();
  const double sq = Jfd.bottomLeftCorner(nz, nz).cwiseAbs().maxCoeff();
  const double sv = Jfd.bottomRightCorner(nz, nz).cwiseAbs().maxCoeff();
  std::printf("%s: ∂a/∂z max %.3g, diff %.3g (%.2g); ∂a/∂ż max %.3g, diff %.3g (%.2g)\n", GetParam().name.c_str(),
              sq, dq, dq / sq, sv, dv, dv / sv);
  const bool sliding = GetParam().sliding;
  EXPECT_LT(dv, (sliding ? 1e-5 : 1e-6) * sv);
  EXPECT_LT(dq, (sliding ? 1e-3 : 1e-4) * sq);
}

// No heap allocation inside it (it runs at every step), the forward differences of a
// sliding film included.
TEST_P(PartitionedJacobian, DoesNotAllocate) {
  PartitionedNearWall s(GetParam());
  const int n = static_cast<int>(s.y.size());
  Eigen::VectorXd f(n);
  Eigen::MatrixXd J(n, n);
  ASSERT_EQ(s.sys().rhs(0.0, s.y.data(), f.data()), 0);
  ASSERT_EQ(s.sys().jacobian(0.0, s.y.data(), f.data(), J.data()), 0);  // warm
  long allowed = 0;
  if (GetParam().sliding) {  // n evaluations of rhs(), each allowed what one allocates
    g_allocs = 0;
    g_count = true;
    s.sys().rhs(0.0, s.y.data(), f.data());
    g_count = false;
    allowed = n * g_allocs.load();
  }
  g_allocs = 0;
  g_count = true;
  const int rc = s.sys().jacobian(0.0, s.y.data(), f.data(), J.data());
  g_count = false;
  EXPECT_EQ(rc, 0);
  EXPECT_LE(g_allocs.load(), allowed);
}

INSTANTIATE_TEST_SUITE_P(
    ForceLaws, PartitionedJacobian,
    ::testing::ValuesIn(kCases), case_name);

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
// the bound 2e-5 c, the size of their own integration error at this tolerance (docs/validation/work-precision.md:
// metrics within ~5e-6 of converged). The peaks (reaction, acceleration) are sampled
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
