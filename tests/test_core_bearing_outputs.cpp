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
  std::printf("[ measured ] run: power %.8g W, peak %.8g Pa; steady bearing: %.8g W, %.8g Pa\n",
              r.metrics.film_power_loss_W, r.metrics.peak_film_pressure_Pa, power, s.outputs.peak_pressure_Pa);
}

TEST(BearingOutputs, PeakPressureIsMeasuredOnlyWhereTheSceneAsks) {
  const lub::RunResult off = lub::run_scene(lub::parse_scene(spinning_shaft(false)));
  const lub::RunResult on = lub::run_scene(lub::parse_scene(spinning_shaft(true)));
  ASSERT_EQ(off.status, lub::RunStatus::ok) << off.message;
  EXPECT_TRUE(std::isnan(off.metrics.peak_film_pressure_Pa));
  EXPECT_GT(on.metrics.peak_film_pressure_Pa, 0.0);
  // Nothing else moves: the measurement reads the state, it does not change the run.
  EXPECT_EQ(off.metrics.min_film_thickness_m, on.metrics.min_film_thickness_m);
  EXPECT_EQ(off.metrics.film_power_loss_W, on.metrics.film_power_loss_W);
  EXPECT_EQ(off.stats.steps, on.stats.steps);
}

}  // namespace
