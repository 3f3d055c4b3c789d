// Periodic orbits continued from a neighbouring scene's orbit (docs/theory/continuation.md):
// a seed carries over between scenes, Newton from it converges in a few chord iterations
// to the orbit shooting finds from the scene's own transient, and a path that cannot be
// followed ends with the scene's own method and says so.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "lub/run/orbit_seed_fields.hpp"
#include "lub/run/run.hpp"

namespace {

using lub::RunResult;
using lub::RunStatus;
using nlohmann::json;

json scene(const std::string& law, double rpm, const std::string& steady) {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = law;
  doc["drivers"][0]["speed_rpm"] = rpm;
  doc["simulation"]["steady"] = steady;
  doc["simulation"]["max_cycles"] = 40;
  doc["simulation"]["stop_when_steady"] = true;
  doc["solver"]["formulation"] = "partitioned";
  doc["outputs"]["channels"] = json::array();
  return doc;
}

lub::ContinuationStart from(const RunResult& r, const json& a, const json& b) {
  // Speed in its logarithm, as lubsweep's path does.
  const double wa = a["drivers"][0]["speed_rpm"], wb = b["drivers"][0]["speed_rpm"];
  return {r.orbit_seed, [a, wa, wb](double l) {
            json s = a;
            s["drivers"][0]["speed_rpm"] = std::exp((1 - l) * std::log(wa) + l * std::log(wb));
            return lub::parse_scene(s);
          }};
}

// The packed seed (the study file's /cases/orbit_seed) is what orbit_seed_fields() says it
// is, field by field: a reader that decodes by that list (lubjoint.study.orbit_seed, from
// the attributes the study file writes from it) gets every member back. Layout 1 pinned.
TEST(Continuation, APackedSeedIsWhatItsFieldListSays) {
  lub::OrbitSeed s;
  s.deviation = {0.1, -0.2, 0.3, 0.4};
  s.modes = {2};
  s.chart = {1, 3};
  for (int i = 0; i < 16; ++i) s.monodromy.push_back(0.01 * i);
  s.winding = {0.0, 6.25, 0.0, 0.0};
  s.max_eps = 0.75;
  s.steps_per_period = 123.0;
  const std::vector<double> row = lub::pack_seed(s);
  const std::map<std::string, std::vector<double>> members = {
      {"deviation", s.deviation}, {"modes", {2.0}}, {"chart", {1.0, 3.0}}, {"monodromy", s.monodromy},
      {"winding", s.winding}, {"max_eps", {s.max_eps}}, {"steps_per_period", {s.steps_per_period}}};
  // Decoded by the list alone: the layout number, each non-scalar's count, their values, the scalars.
  ASSERT_EQ(row.at(0), lub::orbit_seed_layout());
  std::size_t counts = 1, at = 1;
  for (const auto& f : lub::orbit_seed_fields()) at += f.shape != lub::SeedShape::scalar;
  std::map<std::string, std::vector<double>> decoded;
  for (const auto& f : lub::orbit_seed_fields()) {
    if (f.shape == lub::SeedShape::scalar) continue;
    const auto n = static_cast<std::size_t>(row.at(counts++));
    decoded[std::string(f.name)].assign(row.begin() + static_cast<long>(at), row.begin() + static_cast<long>(at + n));
    at += n;
  }
  for (const auto& f : lub::orbit_seed_fields())
    if (f.shape == lub::SeedShape::scalar) decoded[std::string(f.name)] = {row.at(at++)};
  EXPECT_EQ(at, row.size());
  EXPECT_EQ(decoded, members);
  for (const auto& f : lub::orbit_seed_fields()) {
    EXPECT_EQ(f.integer, f.name == "modes" || f.name == "chart") << f.name;
    EXPECT_EQ(f.shape == lub::SeedShape::square_matrix, f.name == "monodromy") << f.name;
    EXPECT_FALSE(f.unit.empty() || f.long_name.empty()) << f.name;
  }
  // Layout 1, as study files hold it.
  EXPECT_EQ(std::vector<double>(row.begin(), row.begin() + 6), (std::vector<double>{1, 4, 1, 2, 16, 4}));
  EXPECT_EQ(row.size(), 6u + 4 + 1 + 2 + 16 + 4 + 2);
  const lub::OrbitSeed back = lub::unpack_seed(row);
  EXPECT_EQ(lub::pack_seed(back), row);
  EXPECT_FALSE(lub::unpack_seed({std::nan("")}).valid());
  std::vector<double> other = row;
  other[0] = 2.0;
  EXPECT_THROW(lub::unpack_seed(other), std::invalid_argument);
  EXPECT_THROW(lub::unpack_seed(std::vector<double>(row.begin(), row.end() - 1)), std::invalid_argument);
}

TEST(Continuation, ASceneContinuedFromItsOwnOrbitIsAtItsFixedPointAtOnce) {
  const json a = scene("pinkus_sternlicht", 5000, "shooting");
  const RunResult ra = lub::run_scene(lub::parse_scene(a));
  ASSERT_EQ(lub::classification(ra), "periodic") << ra.message;
  ASSERT_TRUE(ra.orbit_seed.valid());
  // The seed round-trips through the study file's packed row unchanged.
  const lub::OrbitSeed back = lub::unpack_seed(lub::pack_seed(ra.orbit_seed));
  EXPECT_EQ(back.deviation, ra.orbit_seed.deviation);
  EXPECT_EQ(back.monodromy, ra.orbit_seed.monodromy);
  EXPECT_EQ(back.chart, ra.orbit_seed.chart);

  const RunResult rb = lub::run_scene(lub::parse_scene(a), from(ra, a, a));
  ASSERT_EQ(lub::classification(rb), "periodic") << rb.message;
  EXPECT_EQ(rb.steady.method, lub::SteadyCycleMethod::continuation) << rb.message;
  EXPECT_EQ(rb.steady.continuation_steps, 1);
  // The seed is the orbit, placed at t = 0 instead of the transient's t = k T: the same
  // map up to its noise (the printed law's switches make it non-smooth at 1e-7–1e-6 c,
  // against a residual tolerance of 1e-9), so a few chord iterations, against 3–5 from
  // the transient's end with a fresh Jacobian each.
  EXPECT_LE(rb.steady.newton_iterations, 4);
  // The same orbit: metrics within their error bars.
  EXPECT_NEAR(rb.metrics.min_film_thickness_m, ra.metrics.min_film_thickness_m,
              2 * (ra.metrics.min_film_thickness_m_error + rb.metrics.min_film_thickness_m_error) + 1e-12);
  EXPECT_NEAR(rb.metrics.peak_reaction_N, ra.metrics.peak_reaction_N,
              2 * (ra.metrics.peak_reaction_N_error + rb.metrics.peak_reaction_N_error) + 1e-9);
}

TEST(Continuation, ANeighboursOrbitReachesTheOrbitShootingFindsFromTheTransient) {
  const json a = scene("pinkus_sternlicht", 5000, "shooting");
  const json b = scene("pinkus_sternlicht", 2500, "shooting");
  const RunResult ra = lub::run_scene(lub::parse_scene(a));
  ASSERT_TRUE(ra.orbit_seed.valid()) << ra.message;
  const RunResult direct = lub::run_scene(lub::parse_scene(b));
  ASSERT_EQ(lub::classification(direct), "periodic") << direct.message;
  const RunResult cont = lub::run_scene(lub::parse_scene(b), from(ra, a, b));
  ASSERT_EQ(lub::classification(cont), "periodic") << cont.message;
  EXPECT_EQ(cont.steady.method, lub::SteadyCycleMethod::continuation) << cont.message;
  // Two routes to one orbit, each with its error bar.
  const auto& m = cont.metrics;
  const auto& d = direct.metrics;
  EXPECT_NEAR(m.min_film_thickness_m, d.min_film_thickness_m,
              2 * (m.min_film_thickness_m_error + d.min_film_thickness_m_error) + 1e-12);
  EXPECT_NEAR(m.max_eps, d.max_eps, 2 * (m.max_eps_error + d.max_eps_error) + 1e-12);
  // And cheaper: no transient.
  EXPECT_LT(cont.steady.periods_integrated, direct.steady.periods_integrated);
}

TEST(Continuation, APathThatCannotBeFollowedFallsBackAndSaysWhere) {
  const json b = scene("pinkus_sternlicht", 2500, "shooting");
  lub::OrbitSeed wrong;
  wrong.deviation = {1.0, 2.0};  // of another mechanism
  const RunResult r =
      lub::run_scene(lub::parse_scene(b), lub::ContinuationStart{wrong, [b](double) { return lub::parse_scene(b); }});
  EXPECT_EQ(r.status, RunStatus::ok);
  EXPECT_NE(r.message.find("continuation stopped"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("another mechanism"), std::string::npos) << r.message;
  EXPECT_EQ(lub::classification(r), "periodic") << r.message;
}

// Without the run alone (ContinuationStart::alone_if_lost false, a boundary's existence test)
// the same lost path ends there: not_converged, saying the neighbour's orbit was not
// continued and where, with no orbit and only the path's periods spent.
TEST(Continuation, APathThatCannotBeFollowedEndsThereWhenAskedTo) {
  const json b = scene("pinkus_sternlicht", 2500, "shooting");
  lub::OrbitSeed wrong;
  wrong.deviation = {1.0, 2.0};
  lub::ContinuationStart start{wrong, [b](double) { return lub::parse_scene(b); }};
  start.alone_if_lost = false;
  const RunResult r = lub::run_scene(lub::parse_scene(b), start);
  EXPECT_EQ(r.status, RunStatus::ok);
  EXPECT_EQ(lub::classification(r), "not_converged") << r.message;
  EXPECT_NE(r.message.find("was not continued"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("another mechanism"), std::string::npos) << r.message;
  EXPECT_FALSE(r.orbit_seed.valid());
  EXPECT_EQ(r.steady.periods_integrated, 0);
}

// The path lubsweep and lubjoint continue along (lub::scene_path): a number that differs is
// interpolated in its logarithm where both ends are positive, linearly otherwise; the ends
// are the two scenes.
TEST(Continuation, TheScenePathInterpolatesWhatDiffers) {
  json a = scene("pinkus_sternlicht", 5000, "shooting"), b = scene("pinkus_sternlicht", 500, "shooting");
  a["effects"]["gravity_m_s2"] = {0.0, -9.81};
  b["effects"]["gravity_m_s2"] = {0.0, 9.81};
  const auto path = lub::scene_path(a, b);
  const double rpm = 2.0 * M_PI / 60.0;  // rad/s per rpm
  EXPECT_NEAR(path(0.0).drivers[0].speed_rad_s, 5000.0 * rpm, 1e-9);
  EXPECT_NEAR(path(1.0).drivers[0].speed_rad_s, 500.0 * rpm, 1e-9);
  EXPECT_NEAR(path(0.5).drivers[0].speed_rad_s, std::sqrt(5000.0 * 500.0) * rpm, 1e-9);
  EXPECT_NEAR((*path(0.25).gravity_m_s2)[1], -9.81 + 0.25 * 2 * 9.81, 1e-12);
}

}  // namespace
