// Independent route: the engine (absolute coordinates, constraints; partitioned, Baumgarte
// or Baumgarte with projection) against a
// hand-written two-degree-of-freedom Lagrangian model of the same lubricated
// slider-crank (tests/floor_slider_crank.hpp). Both start from the paper's initial
// state; the journal orbits must agree to the integration tolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "floor_slider_crank.hpp"
#include "lub/run/run.hpp"

namespace {

using nlohmann::json;

// formulation: "partitioned", "baumgarte", or "projection" (baumgarte with CVODE's projection).
void compare(const std::string& law, lub::ForceLaw flaw, const std::string& formulation, double tol_over_c) {
  const bool projection = formulation == "projection";
  const double rtol = 1e-10, cycles = 2, dt = 1e-4;
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = law;
  doc["solver"]["rtol"] = rtol;
  doc["solver"]["formulation"] = projection ? "baumgarte" : formulation;
  doc["solver"]["projection"] = projection;
  doc["simulation"]["max_cycles"] = 2;
  doc["outputs"]["sample_interval_s"] = dt;
  doc["outputs"]["channels"] = json::array({json{{"name", "e_x"}, {"joint", "rod_slider"}, {"quantity", "e_x"}},
                                            json{{"name", "e_y"}, {"joint", "rod_slider"}, {"quantity", "e_y"}}});
  const lub::RunResult r = lub::run_scene(lub::parse_scene(doc));
  ASSERT_EQ(r.status, lub::RunStatus::ok) << r.message;

  floor_model::Params p;
  p.law = flaw;
  const floor_model::Result f = floor_model::integrate(p, cycles, rtol, true, dt);
  const auto& t = r.series.data[0];
  const auto& ex = r.series.data[1];
  const auto& ey = r.series.data[2];
  ASSERT_GE(t.size(), f.t.size());
  double worst = 0;
  for (size_t k = 0; k < f.t.size(); ++k) {
    ASSERT_NEAR(t[k + 1], f.t[k], 1e-12);
    worst = std::max(worst, std::hypot(ex[k + 1] - f.e_x[k], ey[k + 1] - f.e_y[k]));
  }
  const double c = 0.5e-3;
  EXPECT_LT(worst / c, tol_over_c) << law << " " << formulation;
  std::printf("%s %s: max |e_engine - e_floor| / c = %.3g over %zu samples\n", law.c_str(),
              formulation.c_str(), worst / c, f.t.size());
}

// rtol 1e-10: both integrations are accurate to ~1e-8 of the orbit; the engine adds its
// constraint drift (Baumgarte α = β = 5 lets ~1e-8 m through at this tolerance). The
// journal's approach to the wall magnifies differences near the minimum film, so allow
// 1e-5 c (5 nm) with every formulation (the partitioned one has no drift, but its
// integrated coordinates are not the floor's, so the local errors differ). Projection:
// 2e-5 c. Each step's projection moves the state by up to its local error (rtol × |x|,
// |x| up to 0.17 m: ~2e-11 m) in a direction the error test does not see, and with the
// per-state tolerances its orbit lies 1.06e-5 c from the floor's (partitioned 3.4e-6,
// baumgarte 2.5e-6).
TEST(MinimalCoordinates, FreneLongOrbitMatchesTheLagrangianModel) {
  compare("frene_long", lub::ForceLaw::frene_long, "partitioned", 1e-5);
  compare("frene_long", lub::ForceLaw::frene_long, "baumgarte", 1e-5);
  compare("frene_long", lub::ForceLaw::frene_long, "projection", 2e-5);
}

TEST(MinimalCoordinates, FreneShortOrbitMatchesTheLagrangianModel) {
  compare("frene_short", lub::ForceLaw::frene_short, "partitioned", 1e-5);
  compare("frene_short", lub::ForceLaw::frene_short, "baumgarte", 1e-5);
}

}  // namespace
