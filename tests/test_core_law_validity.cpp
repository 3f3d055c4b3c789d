// Validity notes (lub/bearing/law_validity.hpp): a law used outside its assumptions is named,
// with its deviation from the finite bearing measured at the scene's L/D, and a full-film law
// whose load reverses in a run is named after it. Notes inform; they are not plausibility
// warnings (--strict does not refuse them).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "fixtures/bearing_scene.hpp"
#include "lub/bearing/law_validity.hpp"
#include "lub/run/run.hpp"

namespace {

using lub::BearingGeometry;
using lub::ForceLaw;
using nlohmann::json;

json slider_crank(const std::string& law) {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = law;
  return doc;
}

bool has(const std::vector<std::string>& notes, const std::string& part) {
  for (const auto& n : notes)
    if (n.find(part) != std::string::npos) return true;
  return false;
}

// The deviation against the finite bearing, two routes: a law inside its assumption comes
// close to the finite bearing, one outside does not. The short bearing (Ocvirk) at L/D = 1/4
// overestimates by a few % at moderate ε and more towards the wall: at ε = 0.9 its Sommerfeld
// number is 0.053 against Raimondi & Boyd's 0.0736, a load 1.4 times theirs (measured here
// 1.04–1.54, squeeze included); bound 1.6. At the paper's L/D = 40/19 it overestimates 3 to 24
// times (the force-law page's table, 2.75–47 over ε ∈ [0, 0.95], brackets it).
TEST(LawValidity, DeviationFromTheFiniteBearingGrowsOutsideTheAssumption) {
  const BearingGeometry paper{0.0095, 0.010, 0.04}, narrow{0.0095, 0.010, 0.25 * 0.019};
  const lub::LawDeviation in = lub::deviation_from_finite_bearing(ForceLaw::gumbel_short, narrow);
  const lub::LawDeviation out = lub::deviation_from_finite_bearing(ForceLaw::frene_short, paper);
  std::printf("[ measured ] gumbel_short at L/D 1/4: %.4g-%.4g; frene_short at 40/19: %.4g-%.4g\n", in.lo, in.hi,
              out.lo, out.hi);
  EXPECT_GT(in.lo, 0.9);
  EXPECT_LT(in.hi, 1.6);
  EXPECT_GT(out.lo, in.hi);
  EXPECT_GT(out.lo, 2.75);
  EXPECT_LT(out.hi, 47.0);
}

TEST(LawValidity, AShortLawAtThePapersLengthIsNoted) {
  const lub::Scene s = lub::parse_scene(slider_crank("frene_short"));
  ASSERT_EQ(s.validity_notes.size(), 1u);
  EXPECT_TRUE(has(s.validity_notes, "/joints/3/force_law = \"frene_short\" is a short-bearing law")) << s.validity_notes[0];
  EXPECT_TRUE(has(s.validity_notes, "L/D = 2.1")) << s.validity_notes[0];
  EXPECT_TRUE(s.warnings.empty());  // a note, not a plausibility warning
}

TEST(LawValidity, LawsInsideTheirAssumptionsAreNotNoted) {
  for (const std::string law : {"pinkus_sternlicht", "frene_long", "gumbel_long", "finite_reynolds"})
    EXPECT_TRUE(lub::parse_scene(slider_crank(law)).validity_notes.empty()) << law;
  json doc = slider_crank("gumbel_short");
  doc["joints"][3]["length_m"] = 0.009;  // L/D = 0.47
  EXPECT_TRUE(lub::parse_scene(doc).validity_notes.empty());
  doc["joints"][3]["force_law"] = "pinkus_sternlicht";
  const lub::Scene s = lub::parse_scene(doc);
  EXPECT_TRUE(has(s.validity_notes, "is a long-bearing law (it assumes L/D >= 2) at L/D = 0.47"))
      << (s.validity_notes.empty() ? "no note" : s.validity_notes[0]);
}

// The slider–crank's rod force turns from compression to tension every cycle; a shaft under
// its own weight is loaded one way.
TEST(LawValidity, AFullFilmLawsReversingLoadIsNotedAfterTheRun) {
  json doc = slider_crank("frene_long");
  doc["simulation"]["max_cycles"] = 3;
  doc["simulation"]["steady"] = "transient";
  doc["outputs"]["channels"] = json::array();
  const lub::RunResult r = lub::run_scene(lub::parse_scene(doc));
  ASSERT_EQ(r.status, lub::RunStatus::ok) << r.message;
  EXPECT_TRUE(r.metrics.load_reverses);
  EXPECT_TRUE(has(r.notes, "/joints/3: the load on a full-film law (\"frene_long\") reverses"));

  doc["joints"][3]["force_law"] = "gumbel_long";  // cavitated: the reversal needs no note
  const lub::RunResult g = lub::run_scene(lub::parse_scene(doc));
  EXPECT_TRUE(g.metrics.load_reverses);
  EXPECT_TRUE(g.notes.empty());

  json shaft = scene_fixture::grounded_bearing("frene_short");
  shaft["drivers"] = json::array({{{"name", "spin"}, {"type", "constant_speed"}, {"body", "shaft"}, {"speed_rpm", 5.0}}});
  shaft["effects"]["gravity_m_s2"] = {0.0, -9.81};
  shaft["simulation"] = {{"max_cycles", 4}, {"metric_cycles", 2}, {"steady", "transient"}};
  shaft["metrics"] = {{"joint", "bearing"}};
  const lub::RunResult s = lub::run_scene(lub::parse_scene(shaft));
  ASSERT_EQ(s.status, lub::RunStatus::ok) << s.message;
  EXPECT_FALSE(s.metrics.load_reverses);
  EXPECT_FALSE(has(s.notes, "reverses"));
}

}  // namespace
