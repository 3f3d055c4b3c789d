// Tests of grid reading and expansion (lub/sweep/grid.hpp): factorial order, the union of
// sub-grids with shared cases run once, the named axes, explicit cases, study settings,
// case identity, and a table of malformed grids, each with its message.
#include "lub/sweep/grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "lub/io/json_reader.hpp"
#include "lub/scene/scene.hpp"
#include "lub/sweep/hash.hpp"

using lub::sweep::Grid;
using lub::sweep::parse_grid;
using nlohmann::json;

namespace {

const std::string kScenes = std::string(LUB_SOURCE_DIR) + "/configs/scenes";

/// A grid with the paper's scene as base and `rest` as further top-level members.
std::string grid_text(const std::string& rest) {
  return R"({"scene": "slider_crank.json")" + (rest.empty() ? std::string() : ", " + rest) + "}";
}

Grid parse(const std::string& rest) { return parse_grid(grid_text(rest), kScenes, "test.json"); }

json scene_of(const Grid& g, int id) { return json::parse(g.cases.at(static_cast<std::size_t>(id)).scene); }

/// The InputError message of parsing `rest` ("" if it parses).
std::string error_of(const std::string& rest) {
  try {
    parse(rest);
  } catch (const lub::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SweepGrid, FactorialIsRowMajorFirstAxisSlowest) {
  const Grid g = parse(R"("axes": [{"name": "speed_rpm", "values": [5000, 50]},
                                  {"name": "force_law", "values": ["ideal", "frene_long", "frene_short"]}])");
  ASSERT_EQ(g.cases.size(), 6u);
  ASSERT_EQ(g.blocks.size(), 1u);
  EXPECT_EQ(g.blocks[0].name, "grid");
  EXPECT_EQ(g.blocks[0].shape, (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(g.blocks[0].case_ids, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(scene_of(g, 4)["drivers"][0]["speed_rpm"], 50);
  EXPECT_EQ(scene_of(g, 4)["joints"][3]["force_law"], "frene_long");
  EXPECT_EQ(g.cases[4].label, "speed_rpm=50 force_law=frene_long");
  EXPECT_EQ(g.cases[4].name, "case_0004");
  ASSERT_EQ(g.axes.size(), 2u);
  EXPECT_EQ(g.axes[0].name, "speed_rpm");
  EXPECT_EQ(g.axes[0].pointer, "/drivers/0/speed_rpm");
  EXPECT_EQ(g.axes[0].units, "min-1");
  EXPECT_TRUE(g.axes[0].numeric);
  EXPECT_FALSE(g.axes[1].numeric);
  EXPECT_EQ(g.cases[4].axis_values[0], 50);
  EXPECT_EQ(g.cases[4].axis_values[1], "frene_long");
  // Each case's canonical JSON is the scene that runs.
  const lub::Scene s4 = lub::parse_scene(nlohmann::json::parse(g.cases[4].scene));
  EXPECT_EQ(s4.joints[3].law, lub::ForceLaw::frene_long);
  EXPECT_NEAR(s4.drivers[0].speed_rad_s, 50 * 2 * M_PI / 60, 1e-12);
}

TEST(SweepGrid, ClearanceKeepsTheBearingRadiusAndSetsTheJournalRadius) {
  const Grid g = parse(R"("axes": [{"name": "clearance_m", "values": [5e-4, 5e-5]}])");
  const json s = scene_of(g, 1);
  EXPECT_EQ(s["joints"][3]["bearing_radius_m"].get<double>(), 0.0100);
  // R − c rounded to 15 digits: the decimal a person writes, bit for bit.
  EXPECT_EQ(s["joints"][3]["journal_radius_m"].get<double>(), 0.00995);
  EXPECT_EQ(scene_of(g, 0)["joints"][3]["journal_radius_m"].get<double>(), 0.0095);
  EXPECT_EQ(g.cases[1].axis_values[0].get<double>(), 5e-5);
  EXPECT_EQ(g.axes[0].pointer, "/joints/3/journal_radius_m");
  EXPECT_EQ(g.axes[0].units, "m");
}

TEST(SweepGrid, UnionRunsSharedCasesOnce) {
  // The reference case (0.5 mm, 400 cP, 5000 rpm) belongs to all three one-axis studies.
  const Grid g = parse(R"("grids": [
      {"name": "clearance", "axes": [{"name": "clearance_m", "values": [5e-4, 1e-4]}]},
      {"name": "viscosity", "axes": [{"name": "viscosity_Pa_s", "values": [0.1, 0.4]}]},
      {"name": "speed", "axes": [{"name": "speed_rpm", "values": [5000.0, 500]}]}])");
  ASSERT_EQ(g.blocks.size(), 3u);
  EXPECT_EQ(g.cases.size(), 4u);  // reference, 0.1 mm, 100 cP, 500 rpm
  EXPECT_EQ(g.blocks[0].case_ids, (std::vector<int>{0, 1}));
  EXPECT_EQ(g.blocks[1].case_ids, (std::vector<int>{2, 0}));
  EXPECT_EQ(g.blocks[2].case_ids, (std::vector<int>{0, 3}));
  EXPECT_EQ(g.cases[0].label, "clearance_m=0.0005");
  // Every case has a value on every axis, read back from its scene.
  ASSERT_EQ(g.axes.size(), 3u);
  EXPECT_EQ(g.cases[3].axis_values[0].get<double>(), 5e-4);
  EXPECT_EQ(g.cases[3].axis_values[1].get<double>(), 0.4);
  EXPECT_EQ(g.cases[3].axis_values[2].get<double>(), 500.0);
}

TEST(SweepGrid, NumberSpellingDoesNotChangeTheCase) {
  // The base scene says 5000.0 rpm; a grid that writes 5000 means the same case.
  const Grid a = parse(R"("axes": [{"name": "speed_rpm", "values": [5000]}])");
  const Grid b = parse(R"("axes": [{"name": "speed_rpm", "values": [5000.0]}])");
  const Grid base = parse(R"("axes": [])");
  EXPECT_EQ(a.cases[0].hash, b.cases[0].hash);
  EXPECT_EQ(a.cases[0].hash, base.cases[0].hash);
  EXPECT_EQ(a.cases[0].hash, lub::sweep::sha256_hex(a.cases[0].scene));
  EXPECT_EQ(base.cases[0].label, "base scene");
  EXPECT_EQ(base.blocks[0].case_ids, std::vector<int>{0});
}

TEST(SweepGrid, PointerAxesAndExplicitCases) {
  const Grid g = parse(R"("axes": [{"pointer": "/solver/rtol", "values": [1e-6, 1e-8]},
                                  {"pointer": "/joints/3/length_m", "name": "length", "values": [0.04]}],
                         "cases": [{"force_law": "ideal", "/solver/rtol": 1e-7, "length": 0.02}])");
  ASSERT_EQ(g.axes.size(), 3u);
  EXPECT_EQ(g.axes[0].name, "solver.rtol");
  EXPECT_EQ(g.axes[0].units, "1");
  EXPECT_EQ(g.axes[1].name, "length");
  EXPECT_EQ(g.axes[1].units, "m");
  EXPECT_EQ(g.axes[2].name, "force_law");
  ASSERT_EQ(g.cases.size(), 3u);
  ASSERT_EQ(g.blocks.size(), 2u);
  EXPECT_EQ(g.blocks[1].name, "cases");
  EXPECT_FALSE(g.blocks[1].factorial);
  EXPECT_EQ(g.blocks[1].case_ids, std::vector<int>{2});
  const json s = scene_of(g, 2);
  EXPECT_EQ(s["solver"]["rtol"].get<double>(), 1e-7);
  EXPECT_EQ(s["joints"][3]["length_m"].get<double>(), 0.02);
  EXPECT_EQ(s["joints"][3]["force_law"], "ideal");
  // An axis a case does not set shows the base scene's value.
  EXPECT_EQ(g.cases[0].axis_values[2], "pinkus_sternlicht");
}

// An element of joints (bodies, drivers, ...) by its name in "set", an axis's pointer and an
// explicit case's key, as lubsim --set takes it (lub::resolve_pointer): the same value as by
// its index, so /joints/3/length_m and /joints/rod_slider/length_m are one axis.
TEST(SweepGrid, PointersNameArrayElementsByTheirName) {
  const Grid g = parse(R"("set": {"/joints/rod_slider/viscosity_Pa_s": 0.05, "/bodies/slider/mass_kg": 0.6},
                         "axes": [{"pointer": "/joints/rod_slider/length_m", "values": [0.02, 0.03]}],
                         "cases": [{"/joints/3/length_m": 0.04}, {"/joints/rod_slider/length_m": 0.05}])");
  ASSERT_EQ(g.axes.size(), 1u);
  EXPECT_EQ(g.axes[0].pointer, "/joints/3/length_m");
  EXPECT_EQ(g.axes[0].name, "joints.rod_slider.length_m");  // as written
  EXPECT_EQ(g.axes[0].units, "m");
  ASSERT_EQ(g.cases.size(), 4u);
  for (int id = 0; id < 4; ++id) {
    const json s = scene_of(g, id);
    EXPECT_EQ(s["joints"][3]["viscosity_Pa_s"].get<double>(), 0.05);
    EXPECT_EQ(s["bodies"][2]["mass_kg"].get<double>(), 0.6);
    EXPECT_DOUBLE_EQ(s["joints"][3]["length_m"].get<double>(), 0.02 + 0.01 * id);
    EXPECT_FALSE(s["joints"][3].contains("rod_slider"));
  }
  EXPECT_EQ(error_of(R"("axes": [{"pointer": "/joints/rod_slidr/length_m", "values": [0.02]}])"),
            "grid.axes[0].pointer = \"/joints/rod_slidr/length_m\": /joints has no element named \"rod_slidr\": did "
            "you mean `rod_slider`? (its names: crank_pivot, crank_rod, slider_guide, rod_slider; or an index 0-3)");
  EXPECT_EQ(error_of(R"("set": {"/bodies/piston/mass_kg": 1}, "axes": [])"),
            "grid.set[\"/bodies/piston/mass_kg\"] = \"/bodies/piston/mass_kg\": /bodies has no element named "
            "\"piston\" (its names: crank, rod, slider; or an index 0-2)");
}

TEST(SweepGrid, PointerToAnUnsetValueShowsNull) {
  const Grid g = parse(R"("cases": [{"/solver/max_step_s": 1e-4}, {"/solver/rtol": 1e-7}])");
  ASSERT_EQ(g.axes.size(), 2u);
  EXPECT_TRUE(g.cases[0].axis_values[1].is_number());  // the base scene sets rtol
  EXPECT_TRUE(g.cases[1].axis_values[0].is_null());    // nobody sets max_step_s
  EXPECT_TRUE(g.axes[0].numeric);
}

TEST(SweepGrid, StudySettingsBecomeSceneValues) {
  const Grid g = parse(R"("study": {"max_cycles": 7, "max_periods": 300, "stop_when_steady": true, "steady_tolerance": 0.002,
                                    "metric_cycles": 3, "channels": ["h_min", "crank_angle"], "last_cycles": 2,
                                    "samples_per_cycle": 360, "on_failure": "abort"},
                         "axes": [{"name": "speed_rpm", "values": [6000]}])");
  const json s = scene_of(g, 0);
  EXPECT_EQ(s["simulation"]["max_cycles"], 7);
  EXPECT_EQ(s["simulation"]["max_periods"], 300);
  EXPECT_EQ(s["simulation"]["stop_when_steady"], true);
  EXPECT_EQ(s["simulation"]["steady_tolerance"], 0.002);
  EXPECT_EQ(s["simulation"]["metric_cycles"], 3);
  EXPECT_EQ(s["outputs"]["last_cycles"], 2);
  ASSERT_EQ(s["outputs"]["channels"].size(), 2u);  // in the grid's order
  EXPECT_EQ(s["outputs"]["channels"][0]["name"], "h_min");
  EXPECT_EQ(s["outputs"]["channels"][1]["name"], "crank_angle");
  // 6000 rpm: a 0.01 s cycle in 360 samples.
  EXPECT_NEAR(s["outputs"]["sample_interval_s"].get<double>(), 0.01 / 360, 1e-18);
  EXPECT_EQ(g.on_failure, lub::sweep::FailurePolicy::abort_on_failure);
}

TEST(SweepGrid, NoChannelsUnlessAsked) {
  const Grid g = parse(R"("axes": [])");
  EXPECT_TRUE(scene_of(g, 0)["outputs"]["channels"].empty());
  EXPECT_EQ(g.on_failure, lub::sweep::FailurePolicy::continue_on_failure);
  const Grid all = parse(R"("study": {"channels": "all"}, "axes": [])");
  EXPECT_EQ(scene_of(all, 0)["outputs"]["channels"].size(), 10u);
}

TEST(SweepGrid, InlineSceneAndStudySetOverrides) {
  json scene = lub::read_json_file(kScenes + "/slider_crank.json");
  json grid = {{"scene", scene},
               {"set", {{"/solver/rtol", 1e-7}, {"/joints/3/length_m", 0.03}}},
               {"cases", json::array({json::object({{"viscosity_Pa_s", 0.2}})})}};
  const Grid g = parse_grid(grid.dump(), "/nonexistent");
  EXPECT_EQ(g.base_scene_file, "");
  EXPECT_EQ(json::parse(g.base_scene_text), scene);
  const json s = scene_of(g, 0);
  EXPECT_EQ(s["solver"]["rtol"], 1e-7);
  EXPECT_EQ(s["joints"][3]["length_m"], 0.03);
  EXPECT_EQ(s["joints"][3]["viscosity_Pa_s"], 0.2);
}

TEST(SweepGrid, LoadsTheShippedGrids) {
  const std::string dir = std::string(LUB_SOURCE_DIR) + "/configs/grids/";
  const Grid paper = lub::sweep::load_grid(dir + "paper.json");
  EXPECT_EQ(paper.cases.size(), 16u);  // 4 + 3 + 3 + 2 lubricated, 4 ideal
  ASSERT_EQ(paper.blocks.size(), 5u);
  for (const auto& b : paper.blocks) EXPECT_TRUE(b.name == "clearance" || b.name == "viscosity" || b.name == "speed" ||
                                                 b.name == "force_law" || b.name == "ideal");
  const json s = json::parse(paper.cases[0].scene);
  EXPECT_EQ(s["outputs"]["channels"].size(), 9u);
  EXPECT_EQ(s["outputs"]["last_cycles"], 2);
  EXPECT_EQ(lub::sweep::load_grid(dir + "full_factorial.json").cases.size(), 192u);
  // The same grid with mixed lubrication named: every case's scene carries the effect.
  const Grid mixed = lub::sweep::load_grid(dir + "full_factorial_mixed.json");
  ASSERT_EQ(mixed.cases.size(), 192u);
  for (const auto& c : mixed.cases)
    EXPECT_EQ(json::parse(c.scene)["effects"]["mixed_lubrication"]["roughness_m"], 5e-7) << c.label;
  for (const char* f : {"paper_clearance.json", "paper_viscosity.json", "paper_speed.json", "paper_force_law.json"})
    EXPECT_NO_THROW(lub::sweep::load_grid(dir + f)) << f;
}

// simulation.steady has one default, the scene parser's: a grid that does not say it runs
// each case as lubsim runs its scene (transient); a grid that wants steady cycles says auto,
// and every shipped grid says which it wants, so what they compute does not hang on it.
TEST(SweepGrid, SteadyMethodIsTheScenesUnlessTheGridSaysIt) {
  const lub::SteadyMethod lubsim =
      lub::parse_scene(lub::read_json_file(kScenes + "/slider_crank.json")).simulation.steady;
  EXPECT_EQ(lubsim, lub::SimulationSpec().steady);
  const Grid plain = parse(R"("axes": [{"name": "speed_rpm", "values": [5000, 500]}])");
  for (const auto& c : plain.cases) {
    EXPECT_FALSE(scene_of(plain, c.id)["simulation"].contains("steady")) << c.label;
    EXPECT_EQ(c.steady, lubsim) << c.label;
  }
  const Grid asked = parse(R"("set": {"/simulation/steady": "auto"}, "axes": [{"name": "speed_rpm", "values": [500]}])");
  EXPECT_EQ(scene_of(asked, 0)["simulation"]["steady"], "auto");
  EXPECT_EQ(asked.cases[0].steady, lub::SteadyMethod::automatic);
  const std::string dir = std::string(LUB_SOURCE_DIR) + "/configs/grids/";
  for (const char* f : {"paper.json", "paper_clearance.json", "paper_viscosity.json", "paper_speed.json",
                        "paper_force_law.json", "full_factorial.json", "full_factorial_long_transients.json",
                        "full_factorial_mixed.json",
                        "cheap_4096.json", "accuracy_reference.json", "accuracy_hard_40cP.json",
                        "accuracy_force_laws.json"}) {
    const Grid g = lub::sweep::load_grid(dir + f);
    for (const auto& c : g.cases)
      ASSERT_TRUE(scene_of(g, c.id)["simulation"].contains("steady")) << f << ": " << c.label;
  }
}

// The accuracy grids compare formulations by sub-grid name: each case must run the
// formulation its sub-grid is named after, whatever the scenes' default is (partitioned
// from issue 12, joint since issue 26; before, a sub-grid without a formulation axis silently ran it).
TEST(SweepGrid, AccuracyGridsRunTheFormulationTheirSubGridsName) {
  const std::string dir = std::string(LUB_SOURCE_DIR) + "/configs/grids/";
  for (const char* f : {"accuracy_reference.json", "accuracy_hard_40cP.json", "accuracy_force_laws.json"}) {
    const Grid g = lub::sweep::load_grid(dir + f);
    int checked = 0;
    for (const auto& b : g.blocks) {
      for (int id : b.case_ids) {
        const json solver = scene_of(g, id)["solver"];
        const std::string form = solver.value("formulation", std::string("(default)"));
        const bool projection = solver.value("projection", false);
        const std::string method = solver.value("method", std::string("cvode_bdf"));
        SCOPED_TRACE(std::string(f) + ", sub-grid " + b.name + ", case " + std::to_string(id));
        // Four cycles from the centred start, not a steady stage (auto, which the other
        // shipped grids ask for, would integrate a hundred periods and more a case).
        EXPECT_EQ(scene_of(g, id)["simulation"].value("steady", std::string("(default)")), "transient");
        if (b.name == "baumgarte") {
          EXPECT_EQ(form, "baumgarte");
          EXPECT_FALSE(projection);
        } else if (b.name == "projection") {
          EXPECT_EQ(form, "baumgarte");
          EXPECT_TRUE(projection);
          EXPECT_EQ(method, "cvode_bdf");
        } else if (b.name == "partitioned" || b.name == "reference") {
          EXPECT_EQ(form, "partitioned");
          EXPECT_FALSE(projection);
        } else if (b.name == "joint") {
          EXPECT_EQ(form, "joint");
          EXPECT_FALSE(projection);
        } else if (b.name == "ggl") {
          EXPECT_EQ(form, "ggl");
          EXPECT_EQ(method, "ida");
        } else {
          ADD_FAILURE() << "unexpected sub-grid " << b.name;
        }
        ++checked;
      }
    }
    EXPECT_GT(checked, 40) << f;
  }
}

TEST(SweepGrid, CaseNames) {
  EXPECT_EQ(lub::sweep::case_name(7, 16), "case_0007");
  EXPECT_EQ(lub::sweep::case_name(7, 10000), "case_0007");
  EXPECT_EQ(lub::sweep::case_name(7, 10001), "case_00007");
}

// ---------------------------------------------------------------------------------------
// Malformed grids: each is refused before any work, with a message naming the field, the
// value and the rule.

struct BadGrid {
  std::string rest;     // top-level members after "scene"
  std::string message;  // the whole message, or its start when it ends with "..."
};

/// `rest` of a grid with one axis, the members `spec`: `"axes": [{spec}]`.
std::string one_axis(const std::string& spec) { return R"("axes": [{)" + spec + "}]"; }

class SweepBadGrid : public ::testing::TestWithParam<BadGrid> {};

TEST_P(SweepBadGrid, IsRefusedWithItsMessage) {
  const BadGrid& b = GetParam();
  const std::string msg = error_of(b.rest);
  std::string want = b.message;
  if (want.size() > 3 && want.compare(want.size() - 3, 3, "...") == 0) {
    want.resize(want.size() - 3);
    EXPECT_EQ(msg.substr(0, want.size()), want) << "grid: " << b.rest << "\nmessage: " << msg;
  } else {
    EXPECT_EQ(msg, want) << "grid: " << b.rest;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Table, SweepBadGrid,
    ::testing::Values(
        BadGrid{"", "grid: needs axes, cases or grids (docs/guide/grids.md)"},
        BadGrid{R"("axes": [], "colour": 1)", "grid.colour = 1: unknown key (check the spelling; the keys: docs/reference/)"},
        BadGrid{R"("axes": {})", "grid.axes = {}: must be an array"},
        BadGrid{one_axis(R"("name": "clearance_m", "values": [5e-4, -1e-4])"),
                "grid.axes[0].values[1] = -0.0001: gives an invalid scene (joint rod_slider: journal_radius_m = "
                "bearing_radius_m - clearance = 0.01 m - -0.0001 m): joints[3].journal_radius_m = 0.0101: must be < "
                "bearing_radius_m = 0.01 m (the radial clearance must be > 0)"},
        BadGrid{one_axis(R"("name": "clearance_m", "values": [0.02])"),
                "grid.axes[0].values[0] = 0.02: gives an invalid scene (joint rod_slider: journal_radius_m = "
                "bearing_radius_m - clearance = 0.01 m - 0.02 m): joints[3].journal_radius_m = -0.01: must be > 0 m"},
        BadGrid{one_axis(R"("name": "clearance_m", "values": ["big"])"), "grid.axes[0].values[0] = \"big\": must be a number, not string"},
        BadGrid{one_axis(R"("name": "viscosity_Pa_s", "values": [0])"), "grid.axes[0].values[0] = 0: gives an invalid scene: joints[3].viscosity_Pa_s = 0: must be > 0 Pa s"},
        BadGrid{one_axis(R"("name": "speed_rpm", "values": [0.0])"), "grid.axes[0].values[0] = 0.0: must not be 0 rpm"},
        BadGrid{one_axis(R"("name": "force_law", "values": [3])"), "grid.axes[0].values[0] = 3: must be a string (a force law name)"},
        BadGrid{one_axis(R"("name": "force_law", "values": ["reynolds2d"])"), "grid.axes[0].values[0] = \"reynolds2d\": gives an invalid scene: joints[3].force_law = \"reynolds2d\": must be one of ..."},
        BadGrid{one_axis(R"("name": "viscosity_Pa_s", "values": [0.4, 0.2, 0.4])"), "grid.axes[0].values[2] = 0.4: repeats grid.axes[0].values[0]"},
        BadGrid{one_axis(R"("name": "viscosity_Pa_s", "values": [])"), "grid.axes[0].values = []: must list at least one value"},
        BadGrid{one_axis(R"("name": "viscosity", "values": [0.4])"), "grid.axes[0].name = \"viscosity\": must be one of clearance_m, viscosity_Pa_s, speed_rpm, force_law, or the axis needs a pointer"},
        BadGrid{one_axis(R"("values": [0.4])"), "grid.axes[0]: needs a pointer (\"pointer\": \"/solver/rtol\") or a named axis (clearance_m, viscosity_Pa_s, speed_rpm, force_law)"},
        BadGrid{one_axis(R"("name": "speed_rpm", "values": [50], "unit": "rpm")"), "grid.axes[0].unit = \"rpm\": unknown key; did you mean `units`?"},
        BadGrid{one_axis(R"("pointer": "solver/rtol", "values": [1e-6])"), "grid.axes[0].pointer = \"solver/rtol\": must be a JSON Pointer (RFC 6901) starting with '/', e.g. /solver/rtol"},
        BadGrid{one_axis(R"("pointer": "/solver/rtoll", "values": [1e-7])"), "grid.axes[0].values[0] = 1e-07: gives an invalid scene: solver.rtoll = 1e-07: unknown key; did you mean `rtol`?"},
        BadGrid{one_axis(R"("pointer": "/joints/9/length_m", "values": [0.1])"), "grid.axes[0].values[0] = 0.1: /joints/9/length_m names no value of the scene, and its parent is not an object"},
        BadGrid{one_axis(R"("pointer": "/solver/rtol", "name": "speed_rpm", "values": [1e-7])"), "grid.axes[0].name = \"speed_rpm\": is a named axis: it takes no pointer (rename the pointer axis)"},
        BadGrid{one_axis(R"("pointer": "/solver/rtol", "name": "status", "values": [1e-7])"), "grid.axes[0].name = \"status\": is a column lubsweep writes itself: choose another name"},
        BadGrid{one_axis(R"("pointer": "/solver/rtol", "name": "a/b", "values": [1e-7])"), "grid.axes[0].name = \"a/b\": must be 1-64 letters, digits, '_', '-' or '.' (it names a column and a dataset)"},
        BadGrid{R"("axes": [{"name": "speed_rpm", "values": [50]}, {"name": "speed_rpm", "values": [60]}])",
                "grid.axes[1] = {\"name\":\"speed_rpm\",\"values\":[60]}: varies axis \"speed_rpm\" twice in one grid"},
        BadGrid{R"("axes": [{"pointer": "/solver/rtol", "name": "x", "values": [1e-7]},
                            {"pointer": "/solver/atol", "name": "x", "values": [1e-9]}])",
                "grid.axes[1].name = \"x\": already names another axis (/solver/rtol)"},
        BadGrid{R"("axes": [{"pointer": "/simulation/max_cycles", "name": "n", "values": [3]},
                            {"pointer": "/simulation/metric_cycles", "name": "m", "values": [4]}])",
                "grid.axes: the case {\"m\":4,\"n\":3}: gives an invalid scene: simulation.metric_cycles = 4: must be <= simulation.max_cycles = 3"},
        BadGrid{R"("cases": [{"clearance": 1e-4}])",
                "grid.cases[0][\"clearance\"] = \"clearance\": unknown key: must be a named axis (clearance_m, viscosity_Pa_s, speed_rpm, force_law), an axis declared in the grid, or a JSON Pointer"},
        BadGrid{R"("cases": [{"viscosity_Pa_s": -2}])",
                "grid.cases[0][\"viscosity_Pa_s\"] = -2: gives an invalid scene: joints[3].viscosity_Pa_s = -2: must be > 0 Pa s"},
        BadGrid{R"("cases": [])", "grid.cases = []: must list at least one case"},
        BadGrid{R"("cases": [3])", "grid.cases[0] = 3: must be a JSON object {axis: value, ...}"},
        BadGrid{R"("cases": [{"/simulation/max_cycles": 0}])",
                "grid.cases[0][\"/simulation/max_cycles\"] = 0: gives an invalid scene: simulation.max_cycles = 0: ..."},
        BadGrid{R"("cases": [{"/simulation/max_cycles": 3, "/simulation/metric_cycles": 4}])",
                "grid.cases[0] = {\"/simulation/max_cycles\":3,\"/simulation/metric_cycles\":4}: gives an invalid scene: "
                "simulation.metric_cycles = 4: must be <= simulation.max_cycles = 3"},
        BadGrid{R"("grids": [{"name": "a", "axes": []}, {"name": "a", "cases": [{}]}])",
                "grid.grids[1].name = \"a\": is the name of another sub-grid"},
        BadGrid{R"("grids": [{"name": "a"}])",
                "grid.grids[0]: needs either axes (a full factorial) or cases (an explicit list), not neither"},
        BadGrid{R"("grids": [{"name": "a", "axes": [], "cases": [{}]}])",
                "grid.grids[0]: needs either axes (a full factorial) or cases (an explicit list), not both"},
        BadGrid{R"("grids": [{"axes": []}])", "grid.grids[0].name is missing: required"},
        BadGrid{R"("grids": [])", "grid.grids = []: must list at least one sub-grid"},
        BadGrid{R"("joint": "crank_rod", "axes": [])",
                "grid.joint = \"crank_rod\": must name a lubricated_revolute joint of the base scene"},
        BadGrid{R"("driver": "motor", "axes": [])", "grid.driver = \"motor\": must name a driver of the base scene"},
        BadGrid{R"("set": {"/solver/rtol": -1}, "axes": [])",
                "grid.set = {\"/solver/rtol\":-1}: gives an invalid scene: solver.rtol = -1: ..."},
        BadGrid{R"("set": {"/nowhere/x": 1}, "axes": [])",
                "grid.set[\"/nowhere/x\"] = 1: /nowhere/x names no value of the scene, and its parent is not an object"},
        BadGrid{R"("study": {"max_cycles": 0}, "axes": [])",
                "grid.study.max_cycles = 0: must be an integer in [1, 1000000]"},
        BadGrid{R"("study": {"max_cycles": 2.5}, "axes": [])", "grid.study.max_cycles = 2.5: must be an integer..."},
        BadGrid{R"("study": {"steady_tolerance": -1}, "axes": [])", "grid.study.steady_tolerance = -1: must be > 0"},
        BadGrid{R"("study": {"stop_when_steady": "yes"}, "axes": [])",
                "grid.study.stop_when_steady = \"yes\": must be true or false"},
        BadGrid{R"("study": {"channels": ["h_min", "pressure"]}, "axes": [])",
                "grid.study.channels[1] = \"pressure\": is not a channel of the base scene (crank_angle, slider_x, slider_v, slider_a, reaction_force, e_x, e_y, eps, eps_dot, h_min)"},
        BadGrid{R"("study": {"channels": ["h_min", "h_min"]}, "axes": [])",
                "grid.study.channels[1] = \"h_min\": repeats grid.study.channels[0]"},
        BadGrid{R"("study": {"channels": "some"}, "axes": [])",
                "grid.study.channels = \"some\": must be \"all\" or an array of channel names of the base scene"},
        BadGrid{R"("study": {"on_failure": "stop"}, "axes": [])", "grid.study.on_failure = \"stop\": must be one of continue, abort"},
        BadGrid{R"("study": {"samples_per_cycle": 1}, "axes": [])",
                "grid.study.samples_per_cycle = 1: must be an integer in [2, 100000000]"},
        BadGrid{R"("study": {"metric_cycles": 9, "max_cycles": 4}, "axes": [])",
                "grid.study = {\"max_cycles\":4,\"metric_cycles\":9}: gives an invalid scene: simulation.metric_cycles = 9: must be <= simulation.max_cycles = 4"},
        BadGrid{R"("study": {"cycles": 4}, "axes": [])",
                "grid.study.cycles = 4: unknown key; did you mean `max_cycles`?"}));

TEST(SweepGrid, SceneErrors) {
  auto err = [](const std::string& text, const std::string& dir) {
    try {
      parse_grid(text, dir, "g.json");
    } catch (const lub::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(err(R"({"scene": "missing.json", "axes": []})", "/nonexistent"),
            "grid.scene = \"missing.json\": /nonexistent/missing.json: no such file");
  EXPECT_EQ(err(R"({"scene": "/", "axes": []})", "."), "grid.scene = \"/\": /: a directory, not a file");
  EXPECT_EQ(err(R"({"scene": 5, "axes": []})", "."),
            "grid.scene = 5: must name a scene file (relative to the grid) or be a scene object");
  EXPECT_EQ(err(R"({"axes": []})", "."), "grid.scene is missing: required");
  // The grid's own syntax: where, and why, without its text (the caller names the file).
  EXPECT_EQ(err(R"({"scene": "slider_crank.json", "axes": [})", kScenes),
            "line 1, column 41: not valid JSON: syntax error while parsing value - unexpected '}'; expected '[', "
            "'{', or a literal");
  const std::string prefix = "grid.scene = {\"bodies\":[]}: gives an invalid scene: bodies";
  EXPECT_EQ(err(R"({"scene": {"bodies": []}, "axes": []})", ".").substr(0, prefix.size()), prefix);
  // A named axis needs the lubricated joint: this scene's metric joint is ideal.
  json scene = lub::read_json_file(kScenes + "/slider_crank.json");
  scene["joints"][3] = {{"name", "rod_slider"}, {"type", "revolute"}, {"body_i", "slider"}, {"body_j", "rod"},
                        {"point_i_m", {0.0, 0.0}}, {"point_j_m", {0.06, 0.0}}};
  scene["outputs"]["channels"] = json::array();
  const json grid = {{"scene", scene}, {"axes", json::array({{{"name", "clearance_m"}, {"values", {1e-4}}}})}};
  EXPECT_EQ(err(grid.dump(), "."),
            "grid.axes[0].name = \"clearance_m\": the base scene has no lubricated_revolute joint named \"rod_slider\" (set grid.joint)");
}
