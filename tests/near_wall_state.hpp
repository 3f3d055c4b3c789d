// A state of the reference slider-crank near the wall, shared by the tests of the
// structured Jacobians (the baumgarte ODE's, test_core_jacobian.cpp; the GGL DAE's,
// test_core_ida.cpp).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "lub/formulation/multibody_system.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/mechanism/builder.hpp"
#include "lub/mechanism/model.hpp"
#include "lub/run/run.hpp"

namespace lub_test {

using nlohmann::json;

inline json reference_doc() {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["outputs"]["channels"] = json::array();
  return doc;
}

struct Case {
  std::string name, law;
  bool sliding = false;
  bool contact = false;
};

// A state of the reference slider-crank with the journal at ε = 0.95, moving outwards
// (ε̇ > 0: the printed law on its outward branch) and round the bearing.
struct NearWall {
  explicit NearWall(const Case& c, lub::Formulation form = lub::Formulation::baumgarte) {
    json doc = reference_doc();
    doc["joints"][3]["force_law"] = c.law;
    if (c.law == "finite_reynolds") {
      doc["joints"][3]["cavitation"] = "sommerfeld";  // smooth in the state
    }
    if (c.contact)
      doc["effects"]["contact"] = {{"stiffness_N_per_m_n", 1e10}, {"restitution", 0.9},
                                   {"handover_eps", {0.93, 0.97}}};
    scene = lub::parse_scene(doc);
    model = lub::build_model(scene);
    ws = std::make_unique<lub::Workspace>(model);
    Eigen::VectorXd q, v;
    lub::assemble_initial_state(model, scene, 0.0, q, v);
    const lub::FilmElement& f = model.films.at(0);
    const double c_m = f.clearance, omega = 5000.0 * 2.0 * M_PI / 60.0;
    const Eigen::Vector2d r(std::cos(0.7), std::sin(0.7)), t(-r.y(), r.x());
    const Eigen::Vector2d e = 0.95 * c_m * r, ed = c_m * omega * (0.2 * r + 0.5 * t);
    // Move the bearing body (the slider): e = journal point − bearing point.
    const int b = f.bearing;
    q.segment<2>(3 * b) -= e;
    v.segment<2>(3 * b) -= ed;
    y.resize(2 * model.nq);
    y << q, v;
    sys = std::make_unique<lub::MultibodySystem>(model, *ws, lub::stabilisation(scene), 0.999, false, form);
    if (c.sliding) {
      ws->film_mode[0] = lub::FilmMode::sliding;
      ws->slide_radius[0] = 0.95 * c_m;
    }
  }
  lub::Scene scene;
  lub::Model model;
  std::unique_ptr<lub::Workspace> ws;
  std::unique_ptr<lub::MultibodySystem> sys;
  Eigen::VectorXd y;
};

/// Bounds on how far a structured-Jacobian run may differ from its difference-quotient twin.
struct SameRunBounds {
  double film_c, eps, reaction, acceleration;  ///< film in clearances, ε absolute, peaks relative
};

/// The two runs of one case, with SUNDIALS' difference quotients and with the structured
/// Jacobian: both ok, labelled, the same metrics within `b`, and the structured one
/// cheaper (a count, not a timing: no right-hand side spent on Jacobians).
inline void expect_same_run_fewer_evaluations(const lub::RunResult& dq, const lub::RunResult& st,
                                              const SameRunBounds& b) {
  ASSERT_EQ(dq.status, lub::RunStatus::ok) << dq.message;
  ASSERT_EQ(st.status, lub::RunStatus::ok) << st.message;
  EXPECT_EQ(dq.stats.jacobian, "difference_quotients");
  EXPECT_EQ(st.stats.jacobian, "structured");
  const double c = 0.5e-3;
  EXPECT_NEAR(st.metrics.min_film_thickness_m, dq.metrics.min_film_thickness_m, b.film_c * c);
  EXPECT_NEAR(st.metrics.max_eps, dq.metrics.max_eps, b.eps);
  EXPECT_NEAR(st.metrics.peak_reaction_N, dq.metrics.peak_reaction_N, b.reaction * dq.metrics.peak_reaction_N);
  EXPECT_NEAR(st.metrics.peak_acceleration_m_s2, dq.metrics.peak_acceleration_m_s2,
              b.acceleration * dq.metrics.peak_acceleration_m_s2);
  EXPECT_GT(dq.stats.rhs_evals_jac, 0);
  EXPECT_EQ(st.stats.rhs_evals_jac, 0);
  EXPECT_GT(st.stats.jac_evals, 0);
  EXPECT_GT(st.stats.film_law_evals_jac, 0);
  EXPECT_LT(st.stats.rhs_evals + st.stats.rhs_evals_jac, dq.stats.rhs_evals + dq.stats.rhs_evals_jac);
}

}  // namespace lub_test
