// The lubbearing program: JSON output of `force` and `steady`, and bad arguments (exit 2,
// message naming the argument, value and rule). Runs the built executable.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "fixtures/run_command.hpp"
#include "lub/bearing/film_force.hpp"

namespace {

using Result = lub_test::CommandResult;

// lubbearing ARGS, stdout and stderr together.
Result run(const std::string& args) {
  return lub_test::run_command(std::string(LUB_BINARY_DIR) + "/core/lubbearing " + args + " 2>&1");
}

const std::string kGeom = " --radius-m 0.0095 --clearance-m 0.0005 --length-m 0.04 --viscosity-Pa-s 0.4";

TEST(Lubbearing, ForcePrintsTheLawsForceAndItsCartesianComponents) {
  const Result r = run("force --model gumbel_short --eps 0.6 --eps-dot 0.5 --omega 523.6 --gamma-dot 10"
                       " --gamma 0.3" + kGeom);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  lub::BearingGeometry g;
  g.journal_radius_m = 0.0095;
  g.bearing_radius_m = 0.0095 + 0.0005;
  g.length_m = 0.04;
  lub::BearingState s;
  s.eps = 0.6;
  s.eps_dot = 0.5;
  s.wedge = 523.6 - 2.0 * 10.0;
  const lub::FilmForce f = lub::film_force(lub::ForceLaw::gumbel_short, g, 0.4, s);
  EXPECT_EQ(j["radial_N"].get<double>(), f.radial_N);  // same computation, printed exactly
  EXPECT_EQ(j["tangential_N"].get<double>(), f.tangential_N);
  EXPECT_DOUBLE_EQ(j["wedge_rad_s"].get<double>(), 503.6);
  EXPECT_NEAR(j["x_N"].get<double>(), f.radial_N * std::cos(0.3) - f.tangential_N * std::sin(0.3), 1e-12 * 1000);
  EXPECT_NEAR(j["y_N"].get<double>(), f.radial_N * std::sin(0.3) + f.tangential_N * std::cos(0.3), 1e-12 * 1000);
}

TEST(Lubbearing, SteadyPrintsTheEquilibrium) {
  // Ocvirk π film: tan φ = π(1−ε²)^(1/2)/(4ε) at the printed ε (the library's own check is in
  // test_core_steady_bearing; here: the program reports what the solver found, consistently).
  const Result r = run("steady --model gumbel_short --load-N 500 --speed-rpm 3000 --radius-m 0.025"
                       " --clearance-m 5e-5 --length-m 0.01 --viscosity-Pa-s 0.05");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  const double e = j["eps"].get<double>();
  EXPECT_GT(e, 0.0);
  EXPECT_LT(e, 1.0);
  const double kPi = 3.14159265358979323846;
  EXPECT_NEAR(std::tan(j["attitude_angle_deg"].get<double>() * kPi / 180.0), kPi * std::sqrt(1 - e * e) / (4 * e),
              1e-9);
  EXPECT_NEAR(j["min_film_thickness_m"].get<double>(), 5e-5 * (1 - e), 1e-15);
  // S = (R/c)² μ N/P, P = W/(L D)
  EXPECT_NEAR(j["sommerfeld_number"].get<double>(), 500.0 * 500.0 * 0.05 * 50.0 / (500.0 / (0.01 * 0.05)), 1e-9);
}

TEST(Lubbearing, FiniteReynoldsOptionsAndNoSteadyState) {
  Result r = run("steady --model finite_reynolds --cavitation gumbel --n-theta 32 --n-z 4 --load-N 2000"
                 " --speed-rpm 3000 --radius-m 0.025 --clearance-m 5e-5 --length-m 0.05 --viscosity-Pa-s 0.05");
  ASSERT_EQ(r.status, 0) << r.out;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["cavitation"], "gumbel");
  EXPECT_EQ(j["n_theta"], 32);
  r = run("steady --model gumbel_short --load-N 1e30 --speed-rpm 3000 --radius-m 0.025 --clearance-m 5e-5"
          " --length-m 0.05 --viscosity-Pa-s 0.05");
  EXPECT_EQ(r.status, 3) << r.out;
  j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["converged"].get<bool>());
  EXPECT_NE(j["message"].get<std::string>().find("cannot carry"), std::string::npos);
}

TEST(Lubbearing, BadArgumentsExitTwoNamingArgumentValueAndRule) {
  const struct {
    std::string args, expect;
  } cases[] = {
      {"", "a command is required"},
      {"spin", "unknown command spin"},
      {"force --model gumbel_long --eps 1.2 --eps-dot 0 --omega 1 --gamma-dot 0" + kGeom, "--eps = 1.2: must be in [0, 1)"},
      {"force --model gumbel_long --eps x --eps-dot 0 --omega 1 --gamma-dot 0" + kGeom, "--eps = x: must be a number"},
      {"force --model gumbel --eps 0.2 --eps-dot 0 --omega 1 --gamma-dot 0" + kGeom, "--model = gumbel: must be one of"},
      {"force --model gumbel_long --eps 0.2 --eps-dot 0 --omega 1" + kGeom, "--gamma-dot is required"},
      {"force --model gumbel_long --eps 0.2 --eps-dot 0 --omega 1 --gamma-dot 0 --cavitation reynolds" + kGeom,
       "--cavitation = reynolds: applies only to --model finite_reynolds"},
      {"force --model finite_reynolds --cavitation elrod --eps 0.2 --eps-dot 0 --omega 1 --gamma-dot 0" + kGeom,
       "--cavitation = elrod: must be one of gumbel, reynolds, sommerfeld"},
      {"force --model finite_reynolds --n-theta 4 --eps 0.2 --eps-dot 0 --omega 1 --gamma-dot 0" + kGeom,
       "--n-theta = 4: must be in [8, 4096]"},
      {"steady --model gumbel_short --load-N -5 --speed-rpm 3000" + kGeom, "--load-N = -5: must be > 0 N"},
      {"steady --model gumbel_short --load-N 5 --speed-rpm 3000 --radius-m 0.01 --clearance-m 0 --length-m 0.04"
       " --viscosity-Pa-s 0.4", "--clearance-m = 0: must be > 0 m"},
      {"steady --model gumbel_short --load-N 5 --speed-rpm 3000 --bogus 1" + kGeom, "unknown argument --bogus"},
      {"steady --model gumbel_short --load-N 5 --load-N 6 --speed-rpm 3000" + kGeom, "--load-N given twice"},
      {"steady --model gumbel_short --load-N 5 6 --speed-rpm 3000" + kGeom, "unknown argument 6"},
  };
  for (const auto& c : cases) {
    const Result r = run(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.args << "\n" << r.out;
    // One format (tests/test_core_programs_cli.cpp): "lubbearing: message", then the hint.
    EXPECT_EQ(r.out.rfind("lubbearing: ", 0), 0u) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find("\nrun 'lubbearing"), std::string::npos) << c.args << "\n" << r.out;
  }
}

}  // namespace
