// The joint-coordinate formulation's tree and forward kinematics (lub/formulation/
// joint_tree.hpp) against the absolute-coordinate model, for every scene in configs/scenes
// (and configs/scenes/hard): the tree exists wherever the lubricated joints cut every loop
// (all scenes but slider_crank_ideal.json, whose ideal joints close the slider-crank's loop;
// a body held by lubricated joints alone, the coupler of slider_crank_two_lubricated.json,
// hangs on the ground by a free joint: its x, y, φ),
// it has the mechanism's degrees of freedom (nq − nc), and at random states (seeded)
//  - positions satisfy every ideal joint's and driver's constraint Φ = 0,
//  - velocities Φ̇ = Φ_q q̇ + Φ_t = 0,
//  - accelerations q̈ = J θ̈ + c satisfy Φ_q q̈ = γ (the absolute model's γ),
// each to 1e-12 relative to the size of the terms that cancel in the row (round-off of a
// few operations on numbers of that size); independently of the constraint equations, J
// against central differences of the positions (1e-7 relative: the h² truncation at
// h = 1e-5 and the round-off ~1e-16/h) and q̈ against central differences of the
// velocities along θ(τ) = θ + τθ̇ + τ²θ̈/2 (same bound); and the joint coordinates of the
// forward kinematics' state give back θ, θ̇.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "lub/formulation/joint_tree.hpp"
#include "lub/formulation/multibody_system.hpp"
#include "lub/mechanism/film_element.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/mechanism/builder.hpp"
#include "lub/run/run.hpp"
#include "mechanism/constraints.hpp"
#include "run/period_map.hpp"
#include "run/segment.hpp"

namespace {

namespace fs = std::filesystem;

std::vector<std::string> scene_paths() {
  std::vector<std::string> out;
  for (const std::string dir : {"/configs/scenes", "/configs/scenes/hard"})
    for (const auto& e : fs::directory_iterator(std::string(LUB_SOURCE_DIR) + dir))
      if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

struct Rows {
  Eigen::MatrixXd Phi_q;
  Eigen::VectorXd Phi, Phi_dot, gamma;
};

Rows constraint_rows(const lub::Model& m, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  Rows r{Eigen::MatrixXd::Zero(m.nc, m.nq), Eigen::VectorXd::Zero(m.nc), Eigen::VectorXd::Zero(m.nc),
         Eigen::VectorXd::Zero(m.nc)};
  std::vector<double> c(static_cast<size_t>(m.nb)), s(static_cast<size_t>(m.nb));
  lub::body_trig(m.nb, q.data(), c.data(), s.data());
  lub::detail::fill_constraints(m.constraints, t, q.data(), v.data(), c.data(), s.data(), r.Phi_q, r.Phi,
                                r.Phi_dot, &r.gamma);
  return r;
}

// The size of the terms a constraint row sums: the bodies' positions and joint points
// (positions), and those times the rates (velocities) and their squares (accelerations).
double length_scale(const lub::Model& m, const Eigen::VectorXd& q) {
  double L = q.cwiseAbs().maxCoeff();
  for (const lub::Constraint& c : m.constraints) L = std::max({L, c.s_i.norm(), c.s_j.norm(), c.offset.norm()});
  return std::max(L, 1.0);
}

class JointTreeScenes : public ::testing::TestWithParam<std::string> {};

TEST_P(JointTreeScenes, ForwardKinematicsAgreeWithTheAbsoluteModel) {
  const std::string path = GetParam();
  const lub::Scene scene = lub::parse_scene(lub::read_json_file(path));
  const lub::Model m = lub::build_model(scene);
  std::string why;
  const auto tree = lub::build_joint_tree(m, &why);
  if (fs::path(path).filename() == "slider_crank_ideal.json") {
    EXPECT_FALSE(tree) << "the ideal slider-crank's joints close a loop";
    EXPECT_NE(why.find("closes a loop"), std::string::npos) << why;
    return;
  }
  ASSERT_TRUE(tree) << path << ": " << why;
  EXPECT_EQ(tree->ndof, m.nq - m.nc) << "the tree's coordinates are the mechanism's degrees of freedom";
  Eigen::VectorXd q0, v0;
  lub::assemble_initial_state(m, scene, 0.0, q0, v0);
  const int nd = tree->ndof;
  std::vector<double> th0(static_cast<size_t>(nd)), thd0(static_cast<size_t>(nd));
  std::vector<double> qv0(q0.data(), q0.data() + m.nq);
  qv0.insert(qv0.end(), v0.data(), v0.data() + m.nq);
  lub::joint_coordinates(m, *tree, qv0.data(), th0.data(), thd0.data());

  std::mt19937 rng(26);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  lub::JointKinematics k(m, *tree), kp(m, *tree), km(m, *tree);
  for (int trial = 0; trial < 8; ++trial) {
    const double t = 0.05 * (1.0 + U(rng));
    std::vector<double> th(th0), thd(thd0), thdd(static_cast<size_t>(nd));
    for (int j = 0; j < nd; ++j) {
      th[j] += 0.3 * U(rng);    // rad, or m of a slide (the scenes' links are ~0.1-1 m)
      thd[j] = 50.0 * U(rng);   // rad/s or m/s
      thdd[j] = 5e3 * U(rng);   // rad/s² or m/s²
    }
    lub::forward_kinematics(m, *tree, t, th.data(), thd.data(), k, true);
    const Eigen::VectorXd a = k.J * Eigen::Map<const Eigen::VectorXd>(thdd.data(), nd) + k.c;
    const Rows r = constraint_rows(m, t, k.q, k.v);
    const double L = length_scale(m, k.q), W = std::max(1.0, k.v.cwiseAbs().maxCoeff());
    for (int row = 0; row < m.nc; ++row) {
      EXPECT_LE(std::abs(r.Phi(row)), 1e-12 * L) << path << " row " << row << " (positions)";
      EXPECT_LE(std::abs(r.Phi_dot(row)), 1e-12 * L * W) << path << " row " << row << " (velocities)";
      double size = std::abs(r.gamma(row));
      for (int i = 0; i < m.nq; ++i) size += std::abs(r.Phi_q(row, i) * a(i));
      EXPECT_LE(std::abs(r.Phi_q.row(row).dot(a) - r.gamma(row)), 1e-12 * std::max(size, 1e-300))
          << path << " row " << row << " (accelerations)";
    }
    // J against central differences of the positions.
    const double h = 1e-5;
    for (int j = 0; j < nd; ++j) {
      std::vector<double> tp(th), tm(th);
      tp[j] += h, tm[j] -= h;
      lub::forward_kinematics(m, *tree, t, tp.data(), thd.data(), kp, false);
      lub::forward_kinematics(m, *tree, t, tm.data(), thd.data(), km, false);
      const Eigen::VectorXd fd = (kp.q - km.q) / (2 * h);
      EXPECT_LE((fd - k.J.col(j)).cwiseAbs().maxCoeff(), 1e-7 * L) << path << " column " << j;
    }
    // q̈ against central differences of q̇ along θ(τ) = θ + τθ̇ + τ²θ̈/2 (and t + τ), with a
    // smaller step: the drivers turn at up to ~1e3 rad/s (speed_10000rpm.json), where the
    // truncation h² q⃛/6 reached 1.8e-2 m/s² at 1e-6 s (measured: it falls as h²), against
    // a bound of 1e-7 |q̈| ~ 2e-3; at 1e-7 s it is ~2e-4, and the round-off ~1e-16 |q̇|/h ~ 1e-7.
    const double ht = 1e-7;
    std::vector<double> tp(th), tm(th), vp(thd), vm(thd);
    for (int j = 0; j < nd; ++j) {
      tp[j] += ht * thd[j] + 0.5 * ht * ht * thdd[j], tm[j] += -ht * thd[j] + 0.5 * ht * ht * thdd[j];
      vp[j] += ht * thdd[j], vm[j] -= ht * thdd[j];
    }
    lub::forward_kinematics(m, *tree, t + ht, tp.data(), vp.data(), kp, false);
    lub::forward_kinematics(m, *tree, t - ht, tm.data(), vm.data(), km, false);
    const Eigen::VectorXd fd = (kp.v - km.v) / (2 * ht);
    const double A = std::max(1.0, a.cwiseAbs().maxCoeff());
    EXPECT_LE((fd - a).cwiseAbs().maxCoeff(), 1e-7 * A) << path << " accelerations";
    // The joint coordinates of the state give back θ, θ̇.
    std::vector<double> qv(k.q.data(), k.q.data() + m.nq), th2(th), thd2(thd);
    qv.insert(qv.end(), k.v.data(), k.v.data() + m.nq);
    lub::joint_coordinates(m, *tree, qv.data(), th2.data(), thd2.data());
    for (int j = 0; j < nd; ++j) {
      EXPECT_NEAR(th2[j], th[j], 1e-12 * L) << path;
      EXPECT_NEAR(thd2[j], thd[j], 1e-12 * L * W) << path;
    }
  }
}

// The observers' evaluation in joint coordinates (MultibodySystem::joint_observation, what
// the run loop measures on the joint formulation) against the absolute model's evaluate()
// at the same state (what it measured before): accelerations, the films' forces and
// eccentricities, at states near the scene's start (θ within 1e-4 rad or m: the films stay
// inside their clearances), each switching film also held sliding. Both solve the same
// equations by different eliminations: agreement to 1e-10 of the largest term (round-off
// of a 7-row Schur complement against a 2 × 2 Cholesky, amplified by the mass ratios).
TEST_P(JointTreeScenes, ObserversSeeTheAbsoluteModelsAccelerations) {
  const std::string path = GetParam();
  const lub::Scene scene = lub::parse_scene(lub::read_json_file(path));
  const lub::Model m = lub::build_model(scene);
  if (!lub::build_joint_tree(m)) GTEST_SKIP() << "no tree: " << path;
  const lub::Stabilisation stab = lub::stabilisation(scene);
  lub::Workspace ws(m), obs(m), abs_ws(m);
  lub::MultibodySystem sys(m, ws, stab, scene.simulation.eps_limit, false, lub::Formulation::joint);
  const int nd = sys.size() / 2;
  Eigen::VectorXd q0, v0;
  lub::assemble_initial_state(m, scene, 0.0, q0, v0);
  std::vector<double> qv0(q0.data(), q0.data() + m.nq);
  qv0.insert(qv0.end(), v0.data(), v0.data() + m.nq);
  sys.partition(0.0, qv0.data());
  std::vector<double> y0(static_cast<size_t>(2 * nd)), qv(2 * static_cast<size_t>(m.nq));
  sys.reduce(qv0.data(), y0.data());
  std::vector<double> a_joint(static_cast<size_t>(m.nq)), a_abs(static_cast<size_t>(m.nq));
  std::mt19937 rng(2626);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int compared = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const double t = 1e-7 * (1.0 + U(rng));  // s: the driven crank moves by < 1e-4 rad
    std::vector<double> y(y0);
    for (int j = 0; j < nd; ++j) y[j] += 1e-4 * U(rng), y[nd + j] += U(rng);
    ASSERT_EQ(sys.expand(t, y.data(), qv.data()), 0);
    for (const bool sliding : {false, true}) {
      for (size_t k = 0; k < m.films.size(); ++k) {
        const bool slide = sliding && m.films[k].switching;
        const double e = lub::film_kinematics(m, static_cast<int>(k), qv.data(), qv.data() + m.nq).e.norm();
        for (lub::Workspace* w : {&obs, &abs_ws}) {
          w->film_mode[k] = slide ? lub::FilmMode::sliding : m.films[k].switching ? lub::FilmMode::outward : lub::FilmMode::natural;
          w->slide_radius[k] = e;
        }
      }
      const lub::EvalStatus sj = sys.joint_observation(t, y.data(), obs, a_joint.data());
      const lub::EvalStatus sa = lub::evaluate(m, abs_ws, stab, t, qv.data(), qv.data() + m.nq, a_abs.data());
      ASSERT_EQ(sj, sa) << path;
      if (sa != lub::EvalStatus::ok) continue;
      ++compared;
      double A = 1.0;
      for (int i = 0; i < m.nq; ++i) A = std::max(A, std::abs(a_abs[i]));
      for (int i = 0; i < m.nq; ++i) EXPECT_NEAR(a_joint[i], a_abs[i], 1e-10 * A) << path << " q̈ " << i;
      for (size_t k = 0; k < m.films.size(); ++k) {
        const lub::FilmKinematics &fj = obs.films[k], &fa = abs_ws.films[k];
        const double F = std::max(1.0, fa.F.norm());
        EXPECT_NEAR((fj.F - fa.F).norm(), 0.0, 1e-10 * F) << path << " film " << k << (sliding ? " sliding" : "");
        EXPECT_EQ(fj.state.eps, fa.state.eps) << path << " film " << k;
        EXPECT_EQ(fj.state.eps_dot, fa.state.eps_dot) << path << " film " << k;
      }
      for (int j = 0; j < static_cast<int>(scene.joints.size()); ++j) {
        if (m.joint_film[j] < 0) continue;  // an ideal joint's reaction: the absolute path
        const Eigen::Vector2d R = lub::joint_force(m, abs_ws, j);
        EXPECT_LE((lub::joint_force(m, obs, j) - R).norm(), 1e-10 * std::max(1.0, R.norm()))
            << path << " reaction of joint " << j;
      }
    }
  }
  EXPECT_GT(compared, 0) << path << ": no state inside the films' clearances";
}

INSTANTIATE_TEST_SUITE_P(EveryScene, JointTreeScenes, ::testing::ValuesIn(scene_paths()),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                           std::string n = fs::path(p.param).parent_path().filename().string() + "_" +
                                           fs::path(p.param).stem().string();
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

}  // namespace

namespace {

lub::RunResult run_with(const std::string& scene, const std::string& formulation,
                        void (*edit)(nlohmann::json&) = nullptr) {
  nlohmann::json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/" + scene);
  doc["solver"]["formulation"] = formulation;
  doc["outputs"]["channels"] = nlohmann::json::array();
  if (edit) edit(doc);
  return lub::run_scene(lub::parse_scene(doc));
}

// The reference case on joint coordinates against the partitioned formulation: both stop
// when two cycles repeat to simulation.steady_tolerance (1e-3, relative), so their metrics
// agree to that (measured: min film 2.2e-4, peak reaction 5.6e-5, peak acceleration 1.1e-4).
// forward_kinematics keeps the state it was last asked for (JointKinematics::at_t, at_y):
// asked again it must give exactly what a fresh computation gives, and a call without J
// and c must not let a later call with them find stale ones.
TEST(JointKinematicsKept, TheSameStateGivesAFreshComputationsEntries) {
  const lub::Scene scene =
      lub::parse_scene(lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json"));
  const lub::Model m = lub::build_model(scene);
  const auto tree = lub::build_joint_tree(m);
  ASSERT_TRUE(tree);
  const std::vector<double> th{0.3, 0.12}, thd{-20.0, 1.5}, th2{0.31, 0.12};
  const double t = 0.004;
  lub::JointKinematics fresh(m, *tree), kept(m, *tree);
  lub::forward_kinematics(m, *tree, t, th.data(), thd.data(), fresh, true);
  // Kept: positions only at (t, th), then another state, then (t, th) with J and c.
  lub::forward_kinematics(m, *tree, t, th.data(), thd.data(), kept, false);
  EXPECT_EQ(kept.q, fresh.q);
  EXPECT_EQ(kept.v, fresh.v);
  EXPECT_FALSE(kept.at_derivatives);
  lub::forward_kinematics(m, *tree, t, th.data(), thd.data(), kept, true);
  EXPECT_EQ(kept.J, fresh.J) << "J computed, not left from the call without derivatives";
  EXPECT_EQ(kept.c, fresh.c);
  lub::forward_kinematics(m, *tree, t, th2.data(), thd.data(), kept, true);
  EXPECT_NE(kept.q, fresh.q) << "another state is computed";
  lub::forward_kinematics(m, *tree, t + 1e-6, th.data(), thd.data(), kept, true);
  EXPECT_NE(kept.q, fresh.q) << "another time moves the driven crank";
  lub::forward_kinematics(m, *tree, t, th.data(), thd.data(), kept, true);
  lub::forward_kinematics(m, *tree, t, th.data(), thd.data(), kept, false);  // kept, J and c too
  EXPECT_EQ(kept.q, fresh.q);
  EXPECT_EQ(kept.J, fresh.J);
  EXPECT_EQ(kept.c, fresh.c);
  EXPECT_TRUE(kept.at_derivatives);
}

TEST(JointFormulation, ReferenceCaseAgreesWithThePartitionedFormulation) {
  const lub::RunResult p = run_with("slider_crank.json", "partitioned");
  const lub::RunResult j = run_with("slider_crank.json", "joint");
  ASSERT_EQ(p.status, lub::RunStatus::ok) << p.message;
  ASSERT_EQ(j.status, lub::RunStatus::ok) << j.message;
  EXPECT_EQ(j.stats.formulation, lub::Formulation::joint);
  EXPECT_LT(j.stats.max_position_drift, 1e-15) << "forward kinematics: no drift but round-off";
  auto rel = [](double a, double b) { return std::abs(a - b) / std::abs(b); };
  EXPECT_LT(rel(j.metrics.min_film_thickness_m, p.metrics.min_film_thickness_m), 1e-3);
  EXPECT_LT(rel(j.metrics.max_eps, p.metrics.max_eps), 1e-3);
  EXPECT_LT(rel(j.metrics.peak_reaction_N, p.metrics.peak_reaction_N), 1e-3);
  EXPECT_LT(rel(j.metrics.peak_acceleration_m_s2, p.metrics.peak_acceleration_m_s2), 1e-3);
}

// A Jacobian serves three steps (kJointJacobianSteps), the iteration matrix is formed anew
// every step: the squeeze film's stiff mode turns by ~1.3° of crank a step, and a Jacobian
// that old still holds Newton. Frêne long, 4 cycles from rest: no convergence failure, and
// a fresh Jacobian on every third step (1707 of 5120 steps over 20 cycles). CVODE's own
// reuse (up to 51 steps) took twice the steps with 104 convergence failures.
TEST(JointFormulation, AJacobianServesThreeStepsAndNewtonHolds) {
  const lub::RunResult r = run_with("slider_crank.json", "joint", [](nlohmann::json& d) {
    d["joints"][3]["force_law"] = "frene_long";
    d["simulation"]["steady"] = "transient";
    d["simulation"]["max_cycles"] = 4;
    d["simulation"]["stop_when_steady"] = false;
  });
  ASSERT_EQ(r.status, lub::RunStatus::ok) << r.message;
  EXPECT_EQ(r.stats.nonlinear_conv_fails, 0);
  const double per_jacobian = static_cast<double>(r.stats.steps) / static_cast<double>(r.stats.jacobian_evals);
  EXPECT_NEAR(per_jacobian, 3.0, 0.05) << r.stats.steps << " steps, " << r.stats.jacobian_evals << " Jacobians";
  EXPECT_GE(r.stats.linear_setups, r.stats.steps) << "the iteration matrix is formed every step";
  // Each Jacobian's forward differences are 2 nd = 4 right-hand sides, counted as the
  // Jacobian's (SUNDIALS sees a user Jacobian and counts none): what the work-precision
  // study's cost adds.
  EXPECT_EQ(r.stats.rhs_evals_jacobian, 4 * r.stats.jacobian_evals);
}

// A loop of ideal joints has no tree: the run falls back (partitioned, then baumgarte for
// the ideal slider-crank, which has no degree of freedom) and says which formulation ran.
TEST(JointFormulation, ClosedLoopFallsBackAndSaysSo) {
  const lub::RunResult r = run_with("slider_crank_ideal.json", "joint");
  ASSERT_EQ(r.status, lub::RunStatus::ok) << r.message;
  EXPECT_EQ(r.stats.formulation, lub::Formulation::baumgarte);
}

// Near the wall (the full factorial's 0.5 mm, 100 cP, 50 rpm printed-law case, ε 0.9999):
// the forward-difference Jacobian's increments relative to |θ| (a 0.4 m slide) moved the
// journal by a tenth of the film and the corrector failed at h ~ 1e-8 s after 31 cycles.
TEST(JointFormulation, NearTheWallTheJacobianHoldsNewton) {
  const lub::RunResult r = run_with("slider_crank.json", "joint", [](nlohmann::json& d) {
    d["joints"][3]["viscosity_Pa_s"] = 0.1;
    d["drivers"][0]["speed_rpm"] = 50;
    d["simulation"]["max_cycles"] = 40;
  });
  EXPECT_EQ(r.status, lub::RunStatus::ok) << r.message;
  EXPECT_GT(r.metrics.max_eps, 0.999);
}

// Shooting in joint coordinates (simulation.shooting_coordinates = independent on the
// joint formulation): the chart's coordinates are the tree's (the rod's angle, the
// slider's travel, their rates), every z is a consistent state by forward kinematics (no
// Newton, nothing to fail), and z -> state -> z is the identity to round-off.
TEST(JointChart, ItsCoordinatesAreTheTreesAndEveryPointIsAConsistentState) {
  nlohmann::json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["outputs"]["channels"] = nlohmann::json::array();
  const lub::Scene scene = lub::parse_scene(doc);
  ASSERT_EQ(scene.solver.formulation, lub::Formulation::joint);
  lub::detail::RunModel rm(scene);
  lub::detail::SegmentOptions o;
  o.cycles = 1;
  o.series = false;
  const lub::detail::StartState x = lub::detail::run_segment(rm, o).end;
  lub::detail::Chart chart(rm, x, lub::ShootingCoordinates::independent);
  ASSERT_EQ(chart.size(), 4);
  EXPECT_FALSE(chart.wall());
  EXPECT_EQ(chart.independent(), (std::vector<int>{lub::detail::Chart::kJointChart, lub::detail::Chart::kJointChart - 1}));
  const lub::Model& m = rm.model;
  const Eigen::VectorXd z0 = chart.reduce(x.qv);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 6; ++trial) {
    // Within a clearance of the start (units: lengths in clearances, rates × Ω).
    Eigen::VectorXd z = z0;
    for (int i = 0; i < 4; ++i) z(i) += (trial == 0 ? 0.0 : 0.3) * U(rng) * chart.units()[static_cast<size_t>(i)];
    std::vector<double> qv(x.qv.size());
    ASSERT_TRUE(chart.expand(x.t, z.data(), qv));
    if (trial == 0) {
      for (size_t i = 0; i < qv.size(); ++i) EXPECT_NEAR(qv[i], x.qv[i], 1e-12 * std::max(1.0, std::abs(x.qv[i]))) << i;
    }
    const Eigen::Map<const Eigen::VectorXd> q(qv.data(), m.nq), v(qv.data() + m.nq, m.nq);
    const Rows r = constraint_rows(m, x.t, q, v);
    EXPECT_LE(r.Phi.cwiseAbs().maxCoeff(), 1e-15) << "positions";
    EXPECT_LE(r.Phi_dot.cwiseAbs().maxCoeff(), 1e-12) << "velocities";
    const Eigen::VectorXd back = chart.reduce(qv);
    for (int i = 0; i < 4; ++i)
      EXPECT_NEAR(back(i), z(i), 1e-15 * std::max(1.0, std::abs(z(i)))) << "coordinate " << i;
  }
}

// Shooting in joint coordinates finds the orbit shooting found in the partitioned
// formulation's coordinates before joint coordinates became the default: Newton's unknowns
// and the integration change, the orbit and its multipliers (invariant under a change of
// coordinates) must not, beyond their error bars.
TEST(JointChart, FindsThePartitionedFormulationsOrbit) {
  for (const char* law : {"pinkus_sternlicht", "frene_long"}) {
    auto shoot = [&](const char* formulation) {
      nlohmann::json d = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
      d["solver"]["formulation"] = formulation;
      d["outputs"]["channels"] = nlohmann::json::array();
      d["joints"][3]["force_law"] = law;
      d["simulation"]["steady"] = "auto";
      d["simulation"]["max_cycles"] = 40;
      return lub::run_scene(lub::parse_scene(d));
    };
    const lub::RunResult j = shoot("joint"), p = shoot("partitioned");
    ASSERT_EQ(lub::classification(j), "periodic") << law << ": " << j.message;
    ASSERT_EQ(lub::classification(p), "periodic") << law << ": " << p.message;
    EXPECT_NEAR(j.metrics.min_film_thickness_m, p.metrics.min_film_thickness_m,
                j.metrics.min_film_thickness_m_error + p.metrics.min_film_thickness_m_error)
        << law;
    EXPECT_NEAR(j.metrics.max_eps, p.metrics.max_eps, j.metrics.max_eps_error + p.metrics.max_eps_error) << law;
    EXPECT_NEAR(std::abs(j.steady.multipliers.front()), std::abs(p.steady.multipliers.front()), 1e-3) << law;
  }
}

}  // namespace
