// The run's bearing outputs (core/src/run/cycle_recorder.cpp): the metric joint's film power
// loss and peak film pressure, against the steadily loaded bearing (lub/bearing/steady_bearing.hpp)
// that a spinning shaft under its own weight settles into: a second route, through the
// integrator, the mechanism and the recorder, to the same equilibrium.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "fixtures/bearing_scene.hpp"
#include "lub/bearing/steady_bearing.hpp"
#include "lub/common/constants.hpp"
#include "lub/run/run.hpp"

namespace {

using nlohmann::json;

// The shaft (0.5 kg) spins at 5 rpm in the fixed housing under gravity: a constant 4.905 N
// load on a π-film short bearing, ε = 0.844 (stable: the rigid rotor on an Ocvirk film is
// stable above ε ≈ 0.76), reached within the first of 8 cycles.
json spinning_shaft(bool peak_pressure) {
  json doc = scene_fixture::grounded_bearing("gumbel_short");
  doc["drivers"] = json::array({{{"name", "spin"}, {"type", "constant_speed"}, {"body", "shaft"}, {"speed_rpm", 5.0}}});
  doc["effects"]["gravity_m_s2"] = {0.0, -9.81};
  doc["simulation"] = {{"max_cycles", 8}, {"metric_cycles", 2}, {"steady", "transient"}};
  doc["metrics"] = {{"joint", "bearing"}, {"peak_pressure", peak_pressure}};
  doc["outputs"]["channels"] = json::array();
  return doc;
}

TEST(BearingOutputs, ASpinningShaftsPowerLossAndPeakPressureAreTheSteadyBearings) {
  const lub::RunResult r = lub::run_scene(lub::parse_scene(spinning_shaft(true)));
  ASSERT_EQ(r.status, lub::RunStatus::ok) << r.message;
  lub::SteadyBearingInput in;
  in.law = lub::ForceLaw::gumbel_short;
  in.geometry = {0.0095, 0.010, 0.04};
  in.viscosity_Pa_s = 0.4;
  in.load_N = 0.5 * 9.81;
  in.speed_rad_s = 5.0 * lub::kTwoPi / 60.0;
  const lub::SteadyBearingResult s = lub::solve_steady_bearing(in);
  ASSERT_TRUE(s.converged) << s.message;
  // The run settles to the steady ε to its rtol (1e-8 of the scene's default, ε known to
  // ~1e-7); power loss T_J ω and peak pressure follow with their sensitivity to ε (a few
  // times larger near ε = 0.84): 1e-5.
  EXPECT_NEAR(r.metrics.max_eps, s.eps, 1e-6);
  const double power = s.outputs.journal_friction_torque_Nm * in.speed_rad_s;
  EXPECT_NEAR(r.metrics.film_power_loss_W, power, 1e-5 * power);
  EXPECT_NEAR(r.metrics.peak_film_pressure_Pa, s.outputs.peak_pressure_Pa, 1e-5 * s.outputs.peak_pressure_Pa);
  // Where it sits: θ from the line of maximum film, as the steady bearing's (its sensitivity
  // to ε is O(1) rad per unit ε: 1e-5 rad).
  EXPECT_NEAR(r.metrics.peak_pressure_angle_rad, s.outputs.peak_pressure_angle_rad, 1e-5);
  EXPECT_TRUE(std::isfinite(r.metrics.crank_angle_at_peak_pressure_rad));
  std::printf("[ measured ] run: power %.8g W, peak %.8g Pa; steady bearing: %.8g W, %.8g Pa\n",
              r.metrics.film_power_loss_W, r.metrics.peak_film_pressure_Pa, power, s.outputs.peak_pressure_Pa);
}

TEST(BearingOutputs, PeakPressureIsMeasuredOnlyWhereTheSceneAsks) {
  const lub::RunResult off = lub::run_scene(lub::parse_scene(spinning_shaft(false)));
  const lub::RunResult on = lub::run_scene(lub::parse_scene(spinning_shaft(true)));
  ASSERT_EQ(off.status, lub::RunStatus::ok) << off.message;
  EXPECT_TRUE(std::isnan(off.metrics.peak_film_pressure_Pa));
  EXPECT_TRUE(std::isnan(off.metrics.peak_pressure_angle_rad));
  EXPECT_TRUE(std::isnan(off.metrics.crank_angle_at_peak_pressure_rad));
  EXPECT_GT(on.metrics.peak_film_pressure_Pa, 0.0);
  // Nothing else moves: the measurement reads the state, it does not change the run.
  EXPECT_EQ(off.metrics.min_film_thickness_m, on.metrics.min_film_thickness_m);
  EXPECT_EQ(off.metrics.film_power_loss_W, on.metrics.film_power_loss_W);
  EXPECT_EQ(off.stats.steps, on.stats.steps);
}

// Mixed lubrication with boundary friction (effects.mixed_lubrication.boundary_friction):
// the asperities' friction μ_b W_a R_J, against the sliding, adds μ_b W_a R_J ω to the power
// loss, W_a the asperity load at the run's ε. Surfaces rough enough (σ 20 µm) that the
// shaft's film (78 µm) is within 8σ; with the film-friction effect the driver supplies it.
TEST(BearingOutputs, AsperityFrictionAddsItsPowerToTheLoss) {
  json doc = spinning_shaft(false);
  doc["effects"]["mixed_lubrication"] = {{"roughness_m", 2e-5},
                                         {"asperity_density_per_m2", 1.6e8},
                                         {"asperity_radius_m", 5e-4},
                                         {"composite_modulus_Pa", 8e10}};
  doc["outputs"]["energy_balance"] = true;
  doc["effects"]["film_friction"] = json::object();
  const lub::RunResult dry = lub::run_scene(lub::parse_scene(doc));
  doc["effects"]["mixed_lubrication"]["boundary_friction"] = 0.1;
  const lub::RunResult r = lub::run_scene(lub::parse_scene(doc));
  ASSERT_EQ(dry.status, lub::RunStatus::ok) << dry.message;
  ASSERT_EQ(r.status, lub::RunStatus::ok) << r.message;
  const double W = r.metrics.peak_asperity_load_N;
  ASSERT_GT(W, 1e-3 * 4.905) << "the test needs asperity contact";
  // Friction torques act on the spinning shaft only as a drag its driver overcomes: the
  // journal's position, hence W_a, does not move (the bearing is fixed).
  EXPECT_NEAR(W, dry.metrics.peak_asperity_load_N, 1e-9 * W);
  const double omega = 5.0 * lub::kTwoPi / 60.0;
  // Coulomb's sign regularised as ω/(ω² + ω₀²)^½, ω₀ = 1e-3 rad/s: 1 − 1.8e-6 here.
  const double expected = 0.1 * W * 0.0095 * omega * omega / std::hypot(omega, 1e-3);
  EXPECT_NEAR(r.metrics.film_power_loss_W - dry.metrics.film_power_loss_W, expected, 1e-6 * expected);
  const double scale = std::fabs(r.metrics.driver_work_J) + std::fabs(r.metrics.film_dissipation_J);
  EXPECT_LT(std::fabs(r.metrics.energy_residual_J), 1e-5 * scale);
}

TEST(BearingOutputs, FilmFrictionNamedForNoJointIsRejected) {
  json doc = spinning_shaft(false);
  doc["effects"]["film_friction"] = {{"joints", json::array({"nope"})}};
  try {
    lub::parse_scene(doc);
    FAIL() << "expected a scene error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("effects.film_friction.joints[0]"), std::string::npos) << e.what();
  }
}

}  // namespace
