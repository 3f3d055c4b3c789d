// The scenes of configs/scenes through the whole engine: every scene runs with finite
// output; the four-bar moves the same whichever of its two bodies carries the bearing
// (the film force is frame-invariant in a running mechanism); and the model evaluates
// only the effects a scene names (gravity, force laws, channels, cycles).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "lub/run/run.hpp"

namespace {

using lub::RunResult;
using lub::RunStatus;
using nlohmann::json;

const std::string kScenes = std::string(LUB_SOURCE_DIR) + "/configs/scenes/";

json load(const std::string& name) { return lub::read_json_file(kScenes + name); }

RunResult run(const json& doc) { return lub::run_scene(lub::parse_scene(doc)); }

const std::vector<double>& channel(const RunResult& r, const std::string& name) {
  for (size_t i = 0; i < r.series.names.size(); ++i)
    if (r.series.names[i] == name) return r.series.data[i];
  throw std::runtime_error("no channel " + name);
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b, double sign = 1.0) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0.0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) d = std::max(d, std::fabs(a[i] - sign * b[i]));
  return d;
}

std::vector<std::string> scene_files() {
  std::vector<std::string> out;
  for (const auto& entry : std::filesystem::directory_iterator(kScenes))
    if (entry.path().extension() == ".json") out.push_back(entry.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Scenes, TheIssuesScenesExist) {
  const auto files = scene_files();
  for (const std::string name : {"slider_crank.json", "slider_crank_ideal.json", "four_bar.json",
                                 "four_bar_bearing_on_coupler.json", "slider_crank_two_lubricated.json"})
    EXPECT_NE(std::find(files.begin(), files.end(), name), files.end()) << name;
}

TEST(Scenes, EverySceneRunsTwoCyclesWithFiniteOutput) {
  for (const std::string& name : scene_files()) {
    SCOPED_TRACE(name);
    json doc = load(name);
    if (!doc["simulation"].contains("duration_s")) {
      doc["simulation"]["max_cycles"] = 2;
      doc["simulation"]["metric_cycles"] = 1;
    }
    const RunResult r = run(doc);
    EXPECT_EQ(r.status, RunStatus::ok) << name << ": " << r.message;
    if (r.status != RunStatus::ok) continue;
    EXPECT_GE(r.metrics.cycles_run, 2) << name;
    EXPECT_FALSE(r.series.data.empty()) << name;
    if (r.series.data.empty()) continue;
    EXPECT_GT(r.series.data[0].size(), 100u) << name;
    for (size_t c = 0; c < r.series.data.size(); ++c) {
      const auto& x = r.series.data[c];
      const auto bad = std::find_if(x.begin(), x.end(), [](double v) { return !std::isfinite(v); });
      EXPECT_TRUE(bad == x.end()) << name << " " << r.series.names[c] << "[" << (bad - x.begin()) << "]";
    }
    EXPECT_TRUE(std::isfinite(r.metrics.peak_reaction_N)) << name;
    EXPECT_TRUE(std::isfinite(r.metrics.max_eps)) << name;
    EXPECT_LT(r.metrics.max_eps, 1.0) << name;
    // Constraint drift (Baumgarte at rtol 1e-6: ~1e-5 m) well below the smallest length
    // of any scene, the 0.5 mm clearance.
    EXPECT_LT(r.stats.max_position_drift, 0.1 * 0.5e-3) << name;
  }
}

TEST(Scenes, TwoLubricatedJointsBothCarryAFilm) {
  json doc = load("slider_crank_two_lubricated.json");
  doc["simulation"]["max_cycles"] = 2;
  doc["simulation"]["metric_cycles"] = 1;
  const RunResult r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  // Both journals leave the centre and carry load: neither joint is silently ideal.
  for (const std::string j : {"crank_rod", "rod_slider"}) {
    const auto& eps = channel(r, j + "_eps");
    const auto& force = channel(r, j + "_force");
    EXPECT_EQ(eps.front(), 0.0) << j;
    EXPECT_GT(*std::max_element(eps.begin(), eps.end()), 0.3) << j;
    EXPECT_GT(*std::max_element(force.begin(), force.end()), 100.0) << j;
  }
}

// --- The four-bar, bearing on the rocker or on the coupler --------------------------------

json four_bar(const std::string& file, double rtol) {
  json doc = load(file);
  doc["solver"]["rtol"] = rtol;
  doc["simulation"]["max_cycles"] = 2;
  doc["simulation"]["metric_cycles"] = 1;
  return doc;
}

TEST(FourBar, MovesTheSameWhicheverBodyCarriesTheBearing) {
  // The two scenes differ only in which body carries the bearing. The film force depends
  // on e = journal centre − bearing centre, ė and the wedge speed ω_J + ω_B − 2γ̇: swapping
  // the bodies turns e into −e, leaves ε, ε̇ and the wedge speed unchanged, and puts the
  // same force on each body. So the two runs integrate the same equations and may differ
  // only by the integrator's error (their step sequences differ at round-off and then each
  // has its own global error). (The paper's wedge ω − 2γ̇, with ω the relative angular
  // velocity and γ̇ in the global frame, is not symmetric: with the bearing in the rocker,
  // which swings at up to ±150 rad/s, it would change the film and the motion by O(c).)
  //
  // Tolerance: at rtol 1e-8 (atol = rtol × c) we measure the global error of each variant
  // against a run at rtol 1e-11 and require the difference between the two variants to be
  // within 10× the larger error (two runs, each off by its own error: a difference of 1–3×
  // the error is expected; the error of one run alone can be 20× smaller than the other's
  // when round-off changes the step sequence). We measured, over two cycles: positions
  // 2e-8–4e-8 m, angles 4e-7 rad, e 1e-8 m (2e-5 c), ε 3e-5. An absolute bound backs it up:
  // |e_A + e_B| < 1e-3 c, while the orbit spans the whole clearance (ε up to 0.98).
  const double c = 0.5e-3;
  const RunResult A = run(four_bar("four_bar.json", 1e-8));
  const RunResult B = run(four_bar("four_bar_bearing_on_coupler.json", 1e-8));
  const RunResult ref = run(four_bar("four_bar.json", 1e-11));
  ASSERT_EQ(A.status, RunStatus::ok) << A.message;
  ASSERT_EQ(B.status, RunStatus::ok) << B.message;
  ASSERT_EQ(ref.status, RunStatus::ok) << ref.message;
  ASSERT_EQ(channel(A, "t"), channel(B, "t"));

  // The bearing body really rotates, and the journal really moves in its bearing.
  const auto& omega = channel(A, "rocker_omega");
  EXPECT_GT(*std::max_element(omega.begin(), omega.end()), 50.0);
  EXPECT_GT(A.metrics.max_eps, 0.5);

  struct Check {
    const char* channel;
    double sign;       // B's e is −A's e
    double abs_bound;  // absolute backstop [SI]
  };
  const Check checks[] = {
      {"coupler_x", 1, 1e-6},     {"coupler_y", 1, 1e-6},     {"coupler_angle", 1, 1e-5},
      {"rocker_x", 1, 1e-6},      {"rocker_y", 1, 1e-6},      {"rocker_angle", 1, 1e-5},
      {"e_x", -1, 1e-3 * c},      {"e_y", -1, 1e-3 * c},      {"eps", 1, 1e-3},
  };
  for (const Check& k : checks) {
    const double diff = max_abs_diff(channel(A, k.channel), channel(B, k.channel), k.sign);
    const double err = std::max(max_abs_diff(channel(A, k.channel), channel(ref, k.channel)),
                                max_abs_diff(channel(B, k.channel), channel(ref, k.channel), k.sign));
    EXPECT_LE(diff, 10.0 * std::max(err, 1e-3 * k.abs_bound))
        << k.channel << ": variants differ by " << diff << ", the integration error is " << err;
    EXPECT_LT(diff, k.abs_bound) << k.channel;
  }
  EXPECT_NEAR(A.metrics.min_film_thickness_m, B.metrics.min_film_thickness_m, 1e-3 * c);
  EXPECT_NEAR(A.metrics.peak_reaction_N / B.metrics.peak_reaction_N, 1.0, 1e-3);
}

// --- Only the effects a scene names are evaluated ------------------------------------------

json short_run(const std::string& file) {
  json doc = load(file);
  doc["simulation"]["max_cycles"] = 1;
  doc["simulation"]["metric_cycles"] = 1;
  return doc;
}

TEST(EffectCounts, SceneWithoutGravityNeverEvaluatesGravity) {
  json doc = short_run("four_bar.json");
  doc.erase("effects");
  const RunResult r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_GT(r.stats.model_evals, 1000);
  EXPECT_EQ(r.stats.gravity_evals, 0);
  // The same scene with gravity: every evaluation adds it.
  const RunResult g = run(short_run("four_bar.json"));
  ASSERT_EQ(g.status, RunStatus::ok) << g.message;
  EXPECT_EQ(g.stats.gravity_evals, g.stats.model_evals);
}

TEST(EffectCounts, SceneWithoutLubricatedJointsNeverCallsAForceLaw) {
  // The four-bar with its lubricated joint made ideal, and the ideal slider-crank.
  json doc = short_run("four_bar.json");
  doc["joints"][3]["force_law"] = "ideal";
  RunResult r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_GT(r.stats.model_evals, 100);
  EXPECT_EQ(r.stats.film_law_evals, 0);
  r = run(short_run("slider_crank_ideal.json"));
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(r.stats.film_law_evals, 0);
}

TEST(EffectCounts, EachLubricatedJointCallsItsLawInEveryEvaluation) {
  // Every evaluation calls the law of every film joint once; the switching events of the
  // printed Pinkus–Sternlicht law add a few calls of their own (to pick the branch at an
  // ε̇ = 0 crossing: ~2 % here). Twice the calls per evaluation would be a regression.
  for (const auto& [file, films] : {std::pair<std::string, long long>{"four_bar.json", 1},
                                    std::pair<std::string, long long>{"slider_crank_two_lubricated.json", 2}}) {
    SCOPED_TRACE(file);
    const RunResult r = run(short_run(file));
    EXPECT_EQ(r.status, RunStatus::ok) << file << ": " << r.message;
    EXPECT_GE(r.stats.film_law_evals, films * r.stats.model_evals) << file;
    EXPECT_LT(r.stats.film_law_evals, 1.25 * films * r.stats.model_evals) << file;
    // The same scene with the joints' law switched off: no law call at all.
    json doc = short_run(file);
    for (auto& j : doc["joints"])
      if (j["type"] == "lubricated_revolute") j["force_law"] = "ideal";
    const RunResult ideal = run(doc);
    EXPECT_EQ(ideal.status, RunStatus::ok) << file << ": " << ideal.message;
    EXPECT_EQ(ideal.stats.film_law_evals, 0) << file;
  }
}

TEST(EffectCounts, ChannelsNobodyAskedForAreNotRecorded) {
  // No channels: no series at all (not even time).
  json doc = short_run("four_bar.json");
  doc["outputs"]["channels"] = json::array();
  RunResult r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_TRUE(r.series.names.empty());
  EXPECT_TRUE(r.series.data.empty());
  // Two channels: time and exactly those two, in the scene's order.
  doc["outputs"]["channels"] = json::array({json{{"name", "h"}, {"joint", "coupler_rocker"}, {"quantity", "h_min"}},
                                            json{{"name", "a"}, {"body", "rocker"}, {"quantity", "angle"}}});
  r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(r.series.names, (std::vector<std::string>{"t", "h", "a"}));
  ASSERT_EQ(r.series.data.size(), 3u);
  // No outputs object at all: nothing recorded either.
  doc.erase("outputs");
  r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_TRUE(r.series.names.empty());
}

TEST(EffectCounts, MetricsOnlyRunStopsAtTheSteadyCycle) {
  // A metrics-only run (no channels) with stop_when_steady: the four-bar's orbit repeats to
  // within steady_tolerance after some ten cycles; the run must stop at the end of the
  // cycle where the criterion first holds, long before max_cycles.
  json doc = load("four_bar.json");
  doc["outputs"]["channels"] = json::array();
  doc["simulation"]["max_cycles"] = 40;
  doc["simulation"]["metric_cycles"] = 2;
  doc["simulation"]["stop_when_steady"] = true;
  const RunResult r = run(doc);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  ASSERT_TRUE(r.metrics.steady);
  EXPECT_LT(r.metrics.cycles_run, 40);
  // cycles_to_steady counts every period until the steady cycle was known: the transient's
  // and the period map's confirmation of its stop (2 n + 1 more).
  EXPECT_EQ(r.metrics.cycles_to_steady, r.steady.periods_integrated);
  EXPECT_GT(r.metrics.cycles_to_steady, r.metrics.cycles_run);
  const double T = 60.0 / 3000.0;
  // It stops within the integrator step that crosses the cycle end.
  EXPECT_GE(r.stats.final_time_s, r.metrics.cycles_run * T * (1 - 1e-12));
  EXPECT_LT(r.stats.final_time_s, (r.metrics.cycles_run + 0.05) * T);
  EXPECT_TRUE(r.series.names.empty());
  // The last metric_cycles cycles each repeat the one before.
  ASSERT_GE(r.cycles.size(), 3u);
  for (size_t i = r.cycles.size() - 2; i < r.cycles.size(); ++i) {
    EXPECT_GE(r.cycles[i].periodicity, 0.0);
    EXPECT_LT(r.cycles[i].periodicity, 1e-3);
  }
}

}  // namespace
