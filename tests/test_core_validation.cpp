// Bad input is refused clearly: a table of malformed scenes, each a small edit of a valid
// scene. Each must be refused before any work with a message naming the JSON path, the
// value and the rule, both by the library (InputError) and by lubsim (exit status 2, the
// message on stderr, no output file created and an existing one left untouched).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "lub/bearing/force_laws.hpp"
#include "lub/run/run.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kScenes = std::string(LUB_SOURCE_DIR) + "/configs/scenes/";
const std::string kLubsim = std::string(LUB_BINARY_DIR) + "/core/lubsim";

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// Replaces the one occurrence of `from` in `text` (the test fails if it is not there once).
std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "edit target not found: " << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "edit target not unique: " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

struct Case {
  const char* what;
  const char* base;                                  // scene file in configs/scenes
  std::function<void(json&)> edit;                   // a JSON edit, or
  std::function<std::string(const std::string&)> text_edit;  // an edit of the file's text
  std::vector<std::string> expect;                   // substrings of the message
  std::vector<std::string> sets = {};                // --set POINTER=VALUE
  bool at_assembly = false;                          // refused by the kinematic analysis
};

json& chan(json& d, size_t i) { return d["outputs"]["channels"][i]; }

const std::vector<Case>& cases() {
  static const std::vector<Case> table = {
      // Syntax and document shape.
      {"not JSON", "four_bar.json", nullptr,
       [](const std::string&) { return std::string("{ bodies: [] }"); },
       {"scene.json: line 1, column 3: not valid JSON: syntax error while parsing object key - invalid literal; "
        "expected string literal"}},
      {"a number too large for a double", "four_bar.json", nullptr,
       [](const std::string& t) { return replace_once(t, "\"mass_kg\": 0.30", "\"mass_kg\": 1e999"); },
       {"not valid JSON", "number overflow", "1e999"}},
      {"NaN is not JSON", "four_bar.json", nullptr,
       [](const std::string& t) { return replace_once(t, "\"mass_kg\": 0.30", "\"mass_kg\": NaN"); },
       {"not valid JSON"}},
      {"a key twice in one object", "four_bar.json", nullptr,
       [](const std::string& t) {
         return replace_once(t, "\"mass_kg\": 0.40,", "\"mass_kg\": 0.40, \"mass_kg\": -1,");
       },
       {"bodies[1].mass_kg: duplicate key"}},
      {"the document is not an object", "four_bar.json", nullptr,
       [](const std::string&) { return std::string("[1, 2]"); },
       {"(document) = [1,2]: must be a JSON object"}},
      {"$schema is not a string", "four_bar.json", [](json& d) { d["$schema"] = json::array({1}); }, nullptr,
       {"$schema = [1]: must be a string"}},
      // Unknown keys (typos) at every level.
      {"unknown top-level key", "four_bar.json", [](json& d) { d["gravity_m_s2"] = {0, -9.81}; }, nullptr,
       {"gravity_m_s2 = [0,-9.81]: unknown key"}},
      {"typo in a body key", "four_bar.json", [](json& d) { d["bodies"][1]["mass_kgs"] = 0.4; }, nullptr,
       {"bodies[1].mass_kgs = 0.4: unknown key; did you mean `mass_kg`?"}},
      {"typo in a lubricated joint key", "four_bar.json",
       [](json& d) { d["joints"][3]["viscosty_Pa_s"] = 0.4; }, nullptr,
       {"joints[3].viscosty_Pa_s = 0.4: unknown key; did you mean `viscosity_Pa_s`?"}},
      // A misspelt required key is named, not the key it stands for as missing (issue 46)...
      {"a required key misspelt", "four_bar.json",
       [](json& d) {
         d["joints"][3]["viscosty_Pa_s"] = d["joints"][3]["viscosity_Pa_s"];
         d["joints"][3].erase("viscosity_Pa_s");
       },
       nullptr, {"joints[3].viscosty_Pa_s = 0.4: unknown key; did you mean `viscosity_Pa_s`?"}},
      {"a top-level key misspelt", "four_bar.json",
       [](json& d) { d["bodys"] = d["bodies"]; d.erase("bodies"); }, nullptr,
       {"bodys = [", ": unknown key; did you mean `bodies`?"}},
      {"a required key misspelt beside its sibling", "four_bar.json",
       [](json& d) { d["joints"][0]["body_k"] = d["joints"][0]["body_i"]; d["joints"][0].erase("body_i"); }, nullptr,
       {"joints[0].body_k = \"ground\": unknown key; did you mean `body_i`?"}},
      // ... but a key of its own that is close to the missing one is no misspelling.
      {"a required key missing beside its sibling", "four_bar.json", [](json& d) { d["joints"][0].erase("body_i"); },
       nullptr, {"joints[0].body_i is missing: required"}},
      {"typo in an effect", "four_bar.json", [](json& d) { d["effects"]["gravity"] = {0, -9.81}; }, nullptr,
       {"effects.gravity = [0,-9.81]: unknown key; did you mean `gravity_m_s2`?"}},
      {"typo in a channel", "four_bar.json", [](json& d) { chan(d, 0)["quantitiy"] = "x"; }, nullptr,
       {"outputs.channels[0].quantitiy = \"x\": unknown key; did you mean `quantity`?"}},
      // Missing required keys.
      {"no bodies", "four_bar.json", [](json& d) { d.erase("bodies"); }, nullptr,
       {"bodies is missing: required"}},
      {"empty bodies", "four_bar.json", [](json& d) { d["bodies"] = json::array(); }, nullptr,
       {"bodies = []: must list at least one body"}},
      {"no mass", "four_bar.json", [](json& d) { d["bodies"][0].erase("mass_kg"); }, nullptr,
       {"bodies[0].mass_kg is missing: required"}},
      {"no force law", "four_bar.json", [](json& d) { d["joints"][3].erase("force_law"); }, nullptr,
       {"joints[3].force_law is missing: required"}},
      {"reversing driver without its period", "four_bar.json",
       [](json& d) { d["drivers"][0]["type"] = "reversing"; }, nullptr,
       {"drivers[0].reversal_period_s is missing: required"}},
      {"translational joint without an axis", "slider_crank.json",
       [](json& d) { d["joints"][2].erase("axis_i"); }, nullptr, {"joints[2].axis_i is missing: required"}},
      // Wrong types.
      {"mass as a string", "four_bar.json", [](json& d) { d["bodies"][0]["mass_kg"] = "0.3"; }, nullptr,
       {"bodies[0].mass_kg = \"0.3\": must be a number, not string"}},
      {"position with one number", "four_bar.json", [](json& d) { d["bodies"][0]["position_m"] = {1.0}; },
       nullptr, {"bodies[0].position_m = [1.0]: must be an array of two numbers [x, y]"}},
      {"a flag as a string", "four_bar.json", [](json& d) { d["simulation"]["stop_when_steady"] = "yes"; },
       nullptr, {"simulation.stop_when_steady = \"yes\": must be true or false"}},
      {"a fractional cycle count", "four_bar.json", [](json& d) { d["simulation"]["max_cycles"] = 2.5; },
       nullptr, {"simulation.max_cycles = 2.5: must be an integer in [1, 1000000]"}},
      {"a cycle count beyond 64 bits", "four_bar.json", nullptr,
       [](const std::string& t) {
         return replace_once(t, "\"max_cycles\": 6", "\"max_cycles\": 18446744073709551615");
       },
       {"simulation.max_cycles = 18446744073709551615: must be an integer in [1, 1000000]"}},
      {"joints not an array", "four_bar.json", [](json& d) { d["joints"] = json::object(); }, nullptr,
       {"joints = {}: must be an array"}},
      {"a body that is not an object", "four_bar.json", [](json& d) { d["bodies"][2] = 7; }, nullptr,
       {"bodies[2] = 7: must be a JSON object"}},
      // Non-physical values.
      {"zero mass", "four_bar.json", [](json& d) { d["bodies"][0]["mass_kg"] = 0; }, nullptr,
       {"bodies[0].mass_kg = 0: must be > 0 kg"}},
      {"negative inertia", "four_bar.json", [](json& d) { d["bodies"][2]["inertia_kg_m2"] = -1e-4; }, nullptr,
       {"bodies[2].inertia_kg_m2 = -0.0001: must be > 0 kg m^2"}},
      {"negative bearing length", "four_bar.json", [](json& d) { d["joints"][3]["length_m"] = -0.04; },
       nullptr, {"joints[3].length_m = -0.04: must be > 0 m"}},
      {"zero viscosity", "four_bar.json", [](json& d) { d["joints"][3]["viscosity_Pa_s"] = 0.0; }, nullptr,
       {"joints[3].viscosity_Pa_s = 0.0: must be > 0 Pa s"}},
      {"journal as large as the bearing", "four_bar.json",
       [](json& d) { d["joints"][3]["journal_radius_m"] = 0.0100; }, nullptr,
       {"joints[3].journal_radius_m = 0.01: must be < bearing_radius_m = 0.01"}},
      {"journal larger than the bearing", "slider_crank_two_lubricated.json",
       [](json& d) { d["joints"][1]["journal_radius_m"] = 0.02; }, nullptr,
       {"joints[1].journal_radius_m = 0.02: must be < bearing_radius_m"}},
      {"negative bearing radius", "four_bar.json", [](json& d) { d["joints"][3]["bearing_radius_m"] = -0.01; },
       nullptr, {"joints[3].bearing_radius_m = -0.01: must be > 0 m"}},
      {"translational axis of zero length", "slider_crank.json",
       [](json& d) { d["joints"][2]["axis_i"] = {0.0, 0.0}; }, nullptr,
       {"joints[2].axis_i = [0.0,0.0]: must be a non-zero direction"}},
      {"initial eccentricity outside the film", "four_bar.json",
       [](json& d) { d["joints"][3]["initial_eccentricity_m"] = {0.0005, 0.0}; }, nullptr,
       {"joints[3].initial_eccentricity_m = [0.0005,0.0]: |initial_eccentricity_m| must be <"}},
      {"reversal period so short that 2π/period overflows", "four_bar.json",
       [](json& d) {
         d["drivers"][0]["type"] = "reversing";
         d["drivers"][0]["reversal_period_s"] = 5e-324;
       },
       nullptr, {"drivers[0].reversal_period_s = 5e-324: must be > 0 s and 2π/period finite"}},
      {"crank speed so small that the cycle never ends", "four_bar.json",
       [](json& d) { d["drivers"][0]["speed_rpm"] = 1e-320; }, nullptr,
       {"drivers[0].speed_rpm = 1e-320: gives a cycle period 2π/|ω| that is not finite"}},
      {"relative tolerance of 2", "four_bar.json", [](json& d) { d["solver"]["rtol"] = 2; }, nullptr,
       {"solver.rtol = 2: must be in [1e-14, 1)"}},
      {"IDA on the Baumgarte ODE", "four_bar.json",
       [](json& d) {
         d["solver"]["method"] = "ida";
         d["solver"]["formulation"] = "partitioned";
       },
       nullptr,
       {"solver.formulation = \"partitioned\": solver.method = ida integrates the GGL index-2 DAE: the "
        "formulation must be ggl (or absent)"}},
      {"the GGL DAE with an ODE method", "four_bar.json", [](json& d) { d["solver"]["formulation"] = "ggl"; },
       nullptr, {"solver.formulation = \"ggl\": ggl is a DAE: it requires solver.method = ida"}},
      {"projection with IDA", "four_bar.json",
       [](json& d) {
         d["solver"]["method"] = "ida";
         d["solver"]["projection"] = true;
       },
       nullptr, {"solver.projection = true: requires solver.method = cvode_bdf"}},
      {"BDF order 6 with IDA", "four_bar.json",
       [](json& d) {
         d["solver"]["method"] = "ida";
         d["solver"]["max_order"] = 6;
       },
       nullptr, {"solver.max_order = 6: must be <= 5 for ida (BDF orders 1 to 5)"}},
      {"a Jacobian for a method without Newton", "four_bar.json",
       [](json& d) {
         d["solver"]["method"] = "cvode_adams";
         d["solver"]["jacobian"] = "structured";
       },
       nullptr,
       {"solver.jacobian = \"structured\": applies only to the methods with a Newton iteration (cvode_bdf, "
        "arkode_dirk, ida)"}},
      {"unknown Jacobian", "four_bar.json", [](json& d) { d["solver"]["jacobian"] = "exact"; }, nullptr,
       {"solver.jacobian = \"exact\": must be one of"}},
      {"eps limit of 1", "four_bar.json", [](json& d) { d["simulation"]["eps_limit"] = 1; }, nullptr,
       {"simulation.eps_limit = 1: must be in (0, 1)"}},
      {"negative sample interval", "four_bar.json", [](json& d) { d["outputs"]["sample_interval_s"] = -1e-5; },
       nullptr, {"outputs.sample_interval_s = -1e-05: must be > 0 s"}},
      // Names: unknown, reserved, empty, duplicated, or naming the wrong kind of thing.
      {"joint names a body that does not exist", "four_bar.json",
       [](json& d) { d["joints"][1]["body_j"] = "coupler2"; }, nullptr,
       {"joints[1].body_j = \"coupler2\": names no body (bodies: ground, crank, coupler, rocker)"}},
      {"bearing body that does not exist", "four_bar.json",
       [](json& d) { d["joints"][3]["bearing_body"] = "rocket"; }, nullptr,
       {"joints[3].bearing_body = \"rocket\": names no body"}},
      {"joint between a body and itself", "four_bar.json",
       [](json& d) { d["joints"][3]["journal_body"] = "rocker"; }, nullptr,
       {"joints[3].journal_body = \"rocker\": must differ from bearing_body"}},
      {"ground joint on the ground", "four_bar.json",
       [](json& d) { d["joints"].push_back({{"name", "fix"}, {"type", "ground"}, {"body", "ground"}}); },
       nullptr, {"joints[4].body = \"ground\": must be a moving body, not the ground"}},
      {"driver names a body that does not exist", "four_bar.json",
       [](json& d) { d["drivers"][0]["body"] = "crank2"; }, nullptr,
       {"drivers[0].body = \"crank2\": names no body"}},
      {"driver on the ground", "four_bar.json", [](json& d) { d["drivers"][0]["body"] = "ground"; }, nullptr,
       {"drivers[0].body = \"ground\": must be a moving body, not the ground"}},
      {"two drivers on one body", "four_bar.json",
       [](json& d) {
         d["drivers"].push_back({{"name", "again"}, {"type", "constant_speed"}, {"body", "crank"}, {"speed_rpm", 10}});
       },
       nullptr, {"drivers[1].body = \"crank\": names a body another driver (\"crank_speed\") already drives"}},
      {"driver on a body fixed to the ground", "four_bar.json",
       [](json& d) { d["joints"].push_back({{"name", "fix"}, {"type", "ground"}, {"body", "crank"}}); },
       nullptr, {"drivers[0].body = \"crank\": names a body that joint \"fix\" (type ground) fixes"}},
      {"body named ground", "four_bar.json", [](json& d) { d["bodies"][0]["name"] = "ground"; }, nullptr,
       {"bodies[0].name = \"ground\": \"ground\" is reserved"}},
      {"empty joint name", "four_bar.json", [](json& d) { d["joints"][0]["name"] = ""; }, nullptr,
       {"joints[0].name = \"\": must not be empty"}},
      {"duplicate body name", "four_bar.json", [](json& d) { d["bodies"][2]["name"] = "crank"; }, nullptr,
       {"bodies[2].name = \"crank\": must be unique"}},
      {"duplicate joint name", "four_bar.json", [](json& d) { d["joints"][3]["name"] = "crank_pivot"; },
       nullptr, {"joints[3].name = \"crank_pivot\": must be unique"}},
      {"duplicate driver name", "four_bar.json",
       [](json& d) {
         d["drivers"].push_back(
             {{"name", "crank_speed"}, {"type", "constant_speed"}, {"body", "rocker"}, {"speed_rpm", 10}});
       },
       nullptr, {"drivers[1].name = \"crank_speed\": must be unique"}},
      {"duplicate channel name", "four_bar.json", [](json& d) { chan(d, 1)["name"] = "crank_angle"; }, nullptr,
       {"outputs.channels[1].name = \"crank_angle\": must be unique"}},
      {"channel names a joint that does not exist", "four_bar.json",
       [](json& d) { chan(d, 9)["joint"] = "coupler_rocket"; }, nullptr,
       {"outputs.channels[9].joint = \"coupler_rocket\": names no joint (joints: crank_pivot, crank_coupler, "
        "rocker_pivot, coupler_rocker)"}},
      {"channel on the ground", "four_bar.json", [](json& d) { chan(d, 0)["body"] = "ground"; }, nullptr,
       {"outputs.channels[0].body = \"ground\": must be a moving body"}},
      {"film quantity of an ideal joint", "four_bar.json",
       [](json& d) { chan(d, 9)["joint"] = "crank_coupler"; }, nullptr,
       {"outputs.channels[9].quantity = \"e_x\": is a film quantity, but joint \"crank_coupler\" is revolute"}},
      {"unknown channel quantity", "four_bar.json", [](json& d) { chan(d, 0)["quantity"] = "speed"; }, nullptr,
       {"outputs.channels[0].quantity = \"speed\": must be one of x, y, angle"}},
      {"channel with a body and a joint", "four_bar.json", [](json& d) { chan(d, 0)["joint"] = "crank_pivot"; },
       nullptr, {"outputs.channels[0] = {", "must name exactly one of \"body\" or \"joint\""}},
      {"metric joint that does not exist", "four_bar.json", [](json& d) { d["metrics"]["joint"] = "bearing"; },
       nullptr, {"metrics.joint = \"bearing\": names no joint"}},
      {"unknown force law", "four_bar.json", [](json& d) { d["joints"][3]["force_law"] = "reynolds"; }, nullptr,
       {"joints[3].force_law = \"reynolds\": must be one of ideal, pinkus_sternlicht"}},
      {"unknown joint type", "four_bar.json", [](json& d) { d["joints"][0]["type"] = "hinge"; }, nullptr,
       {"joints[0].type = \"hinge\": must be one of revolute, translational, ground, lubricated_revolute"}},
      // Whole-scene rules.
      {"duration and cycles together", "four_bar.json", [](json& d) { d["simulation"]["duration_s"] = 0.1; },
       nullptr, {"simulation.max_cycles = 6: must not be given together with simulation.duration_s"}},
      {"more metric cycles than cycles", "four_bar.json", [](json& d) { d["simulation"]["metric_cycles"] = 7; },
       nullptr, {"simulation.metric_cycles = 7: must be <= simulation.max_cycles = 6"}},
      {"steady stop that can never happen", "four_bar.json",
       [](json& d) {
         d["simulation"]["stop_when_steady"] = true;
         d["simulation"]["max_cycles"] = 2;
       },
       nullptr, {"simulation.stop_when_steady = true: can never stop", "simulation.metric_cycles + 1 = 3"}},
      {"no cycle and no duration", "four_bar.json", [](json& d) { d.erase("drivers"); }, nullptr,
       {"simulation = {", "needs duration_s, or cycle_period_s, or a driver"}},
      {"series too long to hold", "four_bar.json", [](json& d) { d["outputs"]["sample_interval_s"] = 1e-12; },
       nullptr, {"outputs.sample_interval_s = 1e-12: would record", "must be <= 1e+08"}},
      {"over-constrained mechanism", "four_bar.json",
       [](json& d) { d["joints"].push_back({{"name", "fix"}, {"type", "ground"}, {"body", "coupler"}}); },
       nullptr, {"joints + drivers = 12 constraint equations (5 joints, 1 drivers): must be <= 9", "over-constrained"}},
      {"assembly the kinematic analysis cannot close", "four_bar.json",
       [](json& d) { d["joints"][2]["point_i_m"] = {0.6, 0.0}; }, nullptr,
       {"assembly:", "cannot close the mechanism"}, {}, true},
      {"redundant joint the kinematic analysis refuses", "four_bar.json", nullptr,
       [](const std::string&) {  // a pendulum pinned twice at the same point (and a free body)
         return std::string(R"({"bodies": [{"name": "arm", "mass_kg": 1, "inertia_kg_m2": 0.01},
                                          {"name": "free", "mass_kg": 1, "inertia_kg_m2": 0.01}],
           "joints": [{"name": "pin", "type": "revolute", "body_i": "ground", "body_j": "arm", "point_j_m": [-0.1, 0]},
                      {"name": "pin2", "type": "revolute", "body_i": "ground", "body_j": "arm", "point_j_m": [-0.1, 0]}],
           "effects": {"gravity_m_s2": [0, -9.81]}, "simulation": {"duration_s": 0.1}})");
       },
       {"assembly:", "the 4 constraint equations have rank 2", "redundant"}, {}, true},
      // Overrides on the command line are validated like the file.
      {"--set a negative viscosity", "four_bar.json", nullptr, nullptr,
       {"joints[3].viscosity_Pa_s = -0.4: must be > 0 Pa s"}, {"/joints/3/viscosity_Pa_s=-0.4"}},
      {"--set a pointer that names nothing", "four_bar.json", nullptr, nullptr,
       {"--set /joints/9/x=1", "names no value of the scene"}, {"/joints/9/x=1"}},
      {"--set a number too large for a double", "four_bar.json", nullptr, nullptr,
       {"--set /solver/rtol=1e999", "not a usable JSON value"}, {"/solver/rtol=1e999"}},
      // An element of joints, bodies, ... by its name (issue 46): one it has not, the names it has.
      {"--set a joint by a name no joint has", "four_bar.json", nullptr, nullptr,
       {"--set /joints/coupler_rockr/viscosity_Pa_s=0.1: /joints has no element named \"coupler_rockr\": did you mean "
        "`coupler_rocker`? (its names: crank_pivot, crank_coupler, rocker_pivot, coupler_rocker; or an index 0-3)"},
       {"/joints/coupler_rockr/viscosity_Pa_s=0.1"}},
      {"--set by name validated like the file", "four_bar.json", nullptr, nullptr,
       {"joints[3].viscosity_Pa_s = -0.4: must be > 0 Pa s"}, {"/joints/coupler_rocker/viscosity_Pa_s=-0.4"}},
  };
  return table;
}

// The scene text of a case, and the message the library gives for it ("" if accepted).
std::string case_text(const Case& c) {
  std::string text = read_text(kScenes + c.base);
  if (c.text_edit) text = c.text_edit(text);
  if (c.edit) {
    json doc = json::parse(text);
    c.edit(doc);
    text = doc.dump(2);
  }
  return text;
}

std::string library_message(const Case& c, const std::string& text) {
  try {
    json doc = lub::parse_json_text(text, "scene.json");
    for (const auto& s : c.sets) lub::apply_override(doc, s);
    const lub::Scene scene = lub::parse_scene(doc);
    if (c.at_assembly) lub::run_scene(scene);
  } catch (const lub::InputError& e) {
    return e.what();
  }
  return "";
}

// One test per malformed scene (the index of cases()), named after its description.
class MalformedScene : public testing::TestWithParam<size_t> {};

TEST_P(MalformedScene, IsRefusedWithPathValueAndRule) {
  const Case& c = cases()[GetParam()];
  const std::string msg = library_message(c, case_text(c));
  ASSERT_FALSE(msg.empty()) << c.what << ": accepted";
  if (std::getenv("LUB_PRINT_MESSAGES")) std::printf("%-48s %s\n", c.what, msg.c_str());
  for (const auto& part : c.expect) EXPECT_NE(msg.find(part), std::string::npos) << c.what << "\n  " << msg;
}

/// A case's description as a test name: letters and digits, other runs as one '_'.
std::string test_name(const testing::TestParamInfo<size_t>& info) {
  std::string name;
  for (const char ch : std::string(cases()[info.param].what)) {
    const bool alnum = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9');
    if (alnum) {
      name += ch;
    } else if (!name.empty() && name.back() != '_') {
      name += '_';
    }
  }
  while (!name.empty() && name.back() == '_') name.pop_back();
  return name;
}

INSTANTIATE_TEST_SUITE_P(Validation, MalformedScene, testing::Range<size_t>(0, cases().size()), test_name);

// A syntax error is placed by line and column, with the library's reason and none of the
// text around it (nlohmann-json's "last read: '...'" echoes up to a whole line).
TEST(Validation, ASyntaxErrorSaysLineAndColumnAndEchoesNoText) {
  const std::string long_value(300, 'x');
  const std::string text = "{\n  \"description\": \"" + long_value + "\",\n  \"bodies\": [ {\"name\": crank} ]\n}\n";
  // An unterminated string (the column: where its quote is missing): the library's message would
  // echo all 300 characters of it.
  try {
    lub::parse_json_text("{\"description\": \"" + long_value, "scene.json");
    ADD_FAILURE() << "accepted";
  } catch (const lub::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "scene.json: line 1, column 318: not valid JSON: syntax error while parsing "
                                     "value - invalid string: missing closing quote");
  }
  try {
    lub::parse_json_text(text, "scene.json");
    FAIL() << "accepted";
  } catch (const lub::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "scene.json: line 3, column 24: not valid JSON: syntax error while parsing value - invalid literal");
  }
  // The column counts from the line's start, on the first line and after a last newline.
  for (const auto& [bad, where] : {std::pair{std::string("{\"a\": }"), std::string("line 1, column 7")},
                                   std::pair{std::string("{\n\n"), std::string("line 3, column 1")},
                                   std::pair{std::string(""), std::string("line 1, column 1")}}) {
    try {
      lub::parse_json(bad);
      ADD_FAILURE() << bad << ": accepted";
    } catch (const lub::InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(where + ": not valid JSON: ", 0), 0u) << e.what();
    }
  }
}

// Files: one message a problem, without the path (the caller names it once), or with it
// from read_json_file.
TEST(Validation, AFileThatCannotBeReadIsSaidPlainly) {
  const fs::path dir = fs::temp_directory_path() / ("lub_read_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  auto message = [](const std::function<void()>& read) {
    try {
      read();
    } catch (const lub::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string missing = (dir / "nope.json").string();
  EXPECT_EQ(message([&] { lub::read_text_file(missing); }), "no such file");
  EXPECT_EQ(message([&] { lub::read_json_file(missing); }), missing + ": no such file");
  EXPECT_EQ(message([&] { lub::read_text_file(dir.string()); }), "a directory, not a file");
  EXPECT_EQ(message([&] { lub::read_json_file(dir.string()); }), dir.string() + ": a directory, not a file");
  fs::remove_all(dir);
}

// resolve_pointer: an element of an array of objects by its "name" as well as by its index.
TEST(Overrides, ArrayElementsAreAddressedByNameOrIndex) {
  json doc = lub::read_json_file(kScenes + "four_bar.json");
  auto resolved = [&](const std::string& p) { return lub::resolve_pointer(doc, p).to_string(); };
  EXPECT_EQ(resolved("/joints/coupler_rocker/viscosity_Pa_s"), "/joints/3/viscosity_Pa_s");
  EXPECT_EQ(resolved("/bodies/rocker/mass_kg"), "/bodies/2/mass_kg");
  EXPECT_EQ(resolved("/joints/3/viscosity_Pa_s"), "/joints/3/viscosity_Pa_s");
  EXPECT_EQ(resolved("/joints/coupler_rocker/new_key"), "/joints/3/new_key");  // the rules of --set decide
  EXPECT_EQ(resolved("/joints/coupler_rocker/journal_point_m/1"), "/joints/3/journal_point_m/1");
  EXPECT_EQ(resolved("/joints/-"), "/joints/-");
  EXPECT_EQ(resolved("/nowhere/x/y"), "/nowhere/x/y");
  EXPECT_EQ(resolved("/joints/3/journal_point_m/x"), "/joints/3/journal_point_m/x");  // no names: the pointer's own rules
  lub::apply_override(doc, "/joints/coupler_rocker/viscosity_Pa_s=0.1");
  lub::apply_override(doc, "/drivers/crank_speed/speed_rpm=120");
  EXPECT_EQ(doc["joints"][3]["viscosity_Pa_s"], 0.1);
  EXPECT_EQ(doc["drivers"][0]["speed_rpm"], 120);
  EXPECT_NO_THROW(lub::parse_scene(doc));
  try {
    lub::apply_override(doc, "/bodies/rod/mass_kg=1");
    FAIL() << "accepted";
  } catch (const lub::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--set /bodies/rod/mass_kg=1: /bodies has no element named \"rod\" (its names: "
                                     "crank, coupler, rocker; or an index 0-2)");
  }
}

// Edit distance and the closest name, for "did you mean".
TEST(Validation, TheClosestNameIsOneThatIsClose) {
  EXPECT_EQ(lub::edit_distance("viscosty_Pa_s", "viscosity_Pa_s"), 1u);
  EXPECT_EQ(lub::edit_distance("viscoisty_Pa_s", "viscosity_Pa_s"), 1u);  // two neighbours swapped
  EXPECT_EQ(lub::edit_distance("", "abc"), 3u);
  EXPECT_EQ(lub::edit_distance("kitten", "sitting"), 3u);
  const std::vector<std::string> keys = {"viscosity_Pa_s", "length_m", "max_cycles", "rtol", "atol"};
  EXPECT_EQ(lub::closest_name("viscosty_Pa_s", keys), "viscosity_Pa_s");
  EXPECT_EQ(lub::closest_name("cycles", keys), "max_cycles");  // a part of it
  EXPECT_EQ(lub::closest_name("rtoll", keys), "rtol");
  EXPECT_EQ(lub::closest_name("colour", keys), std::nullopt);
  EXPECT_EQ(lub::closest_name("rtol", {"rtol"}), std::nullopt);  // never the word itself
  EXPECT_EQ(lub::closest_name("rtol", keys), "atol");
}

TEST(Validation, TheUnmodifiedBasesAreAccepted) {
  for (const std::string base : {"four_bar.json", "slider_crank.json", "slider_crank_two_lubricated.json"})
    EXPECT_NO_THROW(lub::parse_scene(lub::read_json_file(kScenes + base))) << base;
}

// Runs lubsim; returns its exit status and stderr.
int run_lubsim(const fs::path& scene, const fs::path& out, const std::vector<std::string>& sets,
               const fs::path& err, std::string& stderr_text) {
  std::string cmd = "'" + kLubsim + "' '" + scene.string() + "' -o '" + out.string() + "' --quiet";
  for (const auto& s : sets) cmd += " --set '" + s + "'";
  cmd += " > /dev/null 2> '" + err.string() + "'";
  const int rc = std::system(cmd.c_str());
  stderr_text = read_text(err);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(Validation, LubsimExitsTwoAndWritesNothing) {
  ASSERT_TRUE(fs::exists(kLubsim)) << kLubsim << " is not built";
  const fs::path dir = fs::temp_directory_path() / ("lub_validation_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path scene = dir / "scene.json", err = dir / "stderr.txt";
  const fs::path fresh = dir / "fresh.h5", existing = dir / "existing.h5";
  const std::string sentinel = "an earlier run file: must survive bad input\n";
  // Every case with a new output path (it must not be created) or, alternately, with an
  // existing file (it must not be overwritten); the assembly cases, refused later on a
  // different path, with both. One lubsim process each keeps the test at a few seconds.
  for (size_t k = 0; k < cases().size(); ++k) {
    const Case& c = cases()[k];
    write_text(scene, case_text(c));
    write_text(existing, sentinel);
    std::string text;
    if (k % 2 == 0 || c.at_assembly) {
      EXPECT_EQ(run_lubsim(scene, fresh, c.sets, err, text), 2) << c.what << "\n" << text;
      EXPECT_FALSE(fs::exists(fresh)) << c.what;
      for (const auto& part : c.expect) EXPECT_NE(text.find(part), std::string::npos) << c.what << "\n  " << text;
    }
    if (k % 2 == 1 || c.at_assembly) {
      EXPECT_EQ(run_lubsim(scene, existing, c.sets, err, text), 2) << c.what << "\n" << text;
      EXPECT_EQ(read_text(existing), sentinel) << c.what;
      for (const auto& part : c.expect) EXPECT_NE(text.find(part), std::string::npos) << c.what << "\n  " << text;
    }
    // Nothing else left behind (e.g. a write probe).
    size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
    EXPECT_EQ(files, 3u) << c.what;  // scene.json, stderr.txt, existing.h5
  }
  fs::remove_all(dir);
}

TEST(Validation, ErrorMessagesStayShortForHugeValues) {
  // The value in a message is cut to ~80 characters, however large or deeply nested it is.
  json doc = lub::read_json_file(kScenes + "four_bar.json");
  json deep = json::array();
  for (int i = 0; i < 100000; ++i) {  // moved, never copied: a copy would recurse 1e5 deep
    json outer = json::array();
    outer.push_back(std::move(deep));
    deep = std::move(outer);
  }
  doc["bodies"][0]["position_m"] = std::move(deep);
  try {
    lub::parse_scene(doc);
    FAIL() << "accepted";
  } catch (const lub::InputError& e) {
    EXPECT_LT(std::string(e.what()).size(), 200u) << e.what();
    EXPECT_NE(std::string(e.what()).find("bodies[0].position_m = [[[["), std::string::npos);
  }
  doc = lub::read_json_file(kScenes + "four_bar.json");
  doc["bodies"][0]["name"] = std::string(100000, 'x');
  doc["bodies"][1]["name"] = std::string(100000, 'x');
  try {
    lub::parse_scene(doc);
    FAIL() << "accepted";
  } catch (const lub::InputError& e) {
    EXPECT_LT(std::string(e.what()).size(), 200u) << e.what();
  }
}

// --- configs/scene.schema.json agrees with the parser -----------------------------------

json schema() { return lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scene.schema.json"); }

std::vector<std::string> strings(const json& enumeration) { return enumeration.get<std::vector<std::string>>(); }

TEST(SceneSchema, EnumerationsMatchTheParser) {
  const json defs = schema()["$defs"];
  std::vector<std::string> laws = lub::names_of<lub::ForceLaw>();
  laws.insert(laws.begin(), "ideal");
  EXPECT_EQ(strings(defs["lubricated_revolute"]["properties"]["force_law"]["enum"]), laws);
  EXPECT_EQ(strings(defs["lubricated_revolute"]["properties"]["cavitation"]["enum"]),
            lub::names_of<lub::Cavitation>());
  EXPECT_EQ(strings(defs["solver"]["properties"]["method"]["enum"]), lub::names_of<lub::Method>());
  EXPECT_EQ(strings(defs["channel"]["oneOf"][0]["properties"]["quantity"]["enum"]), lub::names_of<lub::BodyQuantity>());
  EXPECT_EQ(strings(defs["channel"]["oneOf"][1]["properties"]["quantity"]["enum"]), lub::names_of<lub::JointQuantity>());
  EXPECT_EQ(strings(defs["solver"]["properties"]["formulation"]["enum"]), lub::names_of<lub::Formulation>());
  EXPECT_EQ(strings(defs["solver"]["properties"]["jacobian"]["enum"]), lub::names_of<lub::JacobianKind>());
  EXPECT_EQ(strings(defs["solver"]["properties"]["switching"]["enum"]), lub::names_of<lub::Switching>());
  EXPECT_EQ(strings(defs["driver"]["properties"]["type"]["enum"]), lub::names_of<lub::DriverType>());
  EXPECT_EQ(strings(defs["contact"]["properties"]["model"]["enum"]), lub::names_of<lub::ContactModel>());
  // Joint types: one schema branch per type, each with its constant.
  std::vector<std::string> joint_types;
  for (const char* branch : {"revolute", "translational", "ground", "lubricated_revolute"})
    joint_types.push_back(defs[branch]["properties"]["type"]["const"].get<std::string>());
  EXPECT_EQ(joint_types, lub::names_of<lub::JointType>());
}

// Every key the schema lists is one the parser reads: each is set in turn to a value of
// the wrong type ({"__probe": 1}); the parser must then complain about that value (or
// inside it), never call the key unknown.
TEST(SceneSchema, EveryKeyItListsIsKnownToTheParser) {
  const json defs = schema()["$defs"];
  json top = lub::read_json_file(kScenes + "four_bar.json");
  top["drivers"][0]["type"] = "reversing";  // reversal_period_s is read for reversing drivers
  top["drivers"][0]["reversal_period_s"] = 0.1;
  top["joints"].push_back({{"name", "fix"}, {"type", "ground"}, {"body", "rocker"}});
  top["effects"]["contact"] = {{"stiffness_N_per_m_n", 1e9}, {"restitution", 0.9}, {"handover_eps", {0.97, 0.995}}};
  json slider = lub::read_json_file(kScenes + "slider_crank.json");
  struct Section {
    json properties;  // the schema's keys
    json* doc;
    const char* pointer;  // where they go
    const char* path;     // how the parser names it
  };
  json channel_keys = defs["channel"]["properties"];
  for (const auto& branch : defs["channel"]["oneOf"]) channel_keys.update(branch["properties"]);
  json top_keys = schema()["properties"];
  const Section sections[] = {
      {top_keys, &top, "", ""},
      {defs["body"]["properties"], &top, "/bodies/0", "bodies[0]"},
      {defs["revolute"]["properties"], &top, "/joints/0", "joints[0]"},
      {defs["lubricated_revolute"]["properties"], &top, "/joints/3", "joints[3]"},
      {defs["ground"]["properties"], &top, "/joints/4", "joints[4]"},
      {defs["translational"]["properties"], &slider, "/joints/2", "joints[2]"},
      {defs["driver"]["properties"], &top, "/drivers/0", "drivers[0]"},
      {defs["effects"]["properties"], &top, "/effects", "effects"},
      {defs["contact"]["properties"], &top, "/effects/contact", "effects.contact"},
      {defs["solver"]["properties"], &top, "/solver", "solver"},
      {defs["simulation"]["properties"], &top, "/simulation", "simulation"},
      {defs["metrics"]["properties"], &top, "/metrics", "metrics"},
      {defs["outputs"]["properties"], &top, "/outputs", "outputs"},
      {channel_keys, &top, "/outputs/channels/9", "outputs.channels[9]"},
  };
  int probed = 0;
  for (const Section& sec : sections) {
    for (const auto& [key, _] : sec.properties.items()) {
      json doc = *sec.doc;
      doc[json::json_pointer(std::string(sec.pointer) + "/" + key)] = json{{"__probe", 1}};
      const std::string where = std::string(sec.path) + (*sec.path ? "." : "") + key;
      try {
        lub::parse_scene(doc);
        ADD_FAILURE() << where << ": a wrong-typed value was accepted";
      } catch (const lub::InputError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.find(where + " = {\"__probe\":1}: unknown key"), std::string::npos) << msg;
        EXPECT_NE(msg.find(key), std::string::npos) << where << ": " << msg;  // about this key
      }
      ++probed;
    }
  }
  EXPECT_GT(probed, 80);
}

}  // namespace
