// One command-line style for the three programs (lubsim, lubbearing, lubsweep; CLI11): every
// program and subcommand answers --help (exit 0, its options on stdout) and --version (exit 0,
// "PROGRAM VERSION (revision REV, TYPE build)"), and a usage error is "PROGRAM: message" then
// "run 'PROGRAM --help' for usage" on stderr, exit 2. Runs the built executables.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "fixtures/run_command.hpp"
#include "lub/io/json_reader.hpp"

namespace {

using Result = lub_test::CommandResult;

// stdout (stderr too with `merge`).
Result run(const std::string& program, const std::string& args, bool merge = false) {
  // lubsweep outside mpirun: a singleton MPI process (as root in containers: Open MPI's consent).
  return lub_test::run_command("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " +
                               std::string(LUB_BINARY_DIR) + program + " " + args + (merge ? " 2>&1" : " 2>/dev/null"));
}

const struct Program {
  std::string name, path;
} kPrograms[] = {{"lubsim", "/core/lubsim"}, {"lubbearing", "/core/lubbearing"}, {"lubsweep", "/sweep/lubsweep"}};

TEST(ProgramsCli, EveryProgramAnswersVersionWithRevisionAndBuildType) {
  for (const Program& p : kPrograms) {
    const Result r = run(p.path, "--version");
    EXPECT_EQ(r.status, 0) << p.name << "\n" << r.out;
    const std::regex line(p.name + R"( \d+\.\d+\.\d+ \(revision ([0-9a-f]{12}|unknown), [A-Za-z]+ build\)\n)");
    EXPECT_TRUE(std::regex_match(r.out, line)) << p.name << ": " << r.out;
  }
}

TEST(ProgramsCli, EveryProgramAndSubcommandAnswersHelpWithItsOptions) {
  const struct {
    std::string path, args;
    std::vector<std::string> mentions;  // options (and files) the help must name
  } cases[] = {
      {"/core/lubsim", "--help",
       {"SCENE.json", "-o,--output", "--set", "--strict", "--check", "--print-scene", "-q,--quiet", "--version",
        "/series", "/metrics", "/solver", "/cycles", "Exit status"}},
      {"/core/lubsim", "-h", {"--output"}},
      {"/core/lubbearing", "--help", {"force", "steady", "--version", "Exit status"}},
      {"/core/lubbearing", "force --help",
       {"--model", "--eps", "--eps-dot", "--omega", "--gamma-dot", "--gamma", "--radius-m", "--clearance-m",
        "--length-m", "--viscosity-Pa-s", "--cavitation", "--n-theta", "--n-z", "--groove", "--strict",
        "gumbel_short", "finite_reynolds"}},
      {"/core/lubbearing", "steady --help",
       {"--model", "--load-N", "--speed-rpm", "--radius-m", "--clearance-m", "--length-m", "--viscosity-Pa-s",
        "--cavitation", "--n-theta", "--n-z", "--groove", "--strict"}},
      {"/core/lubbearing", "steady -h", {"--load-N"}},
      {"/sweep/lubsweep", "--help",
       {"GRID.json", "-o,--output STUDY.h5", "--restart", "--drop-other-cases", "--retry-failed", "--check",
        "--strict", "--summary STUDY.h5", "--no-summary", "-q,--quiet", "--version", "/cases", "/grids",
        "/scene_patches", "/series", "mpirun -np N lubsweep GRID.json -o STUDY.h5", "Exit status"}},
      {"/sweep/lubsweep", "-h", {"--output"}},
  };
  for (const auto& c : cases) {
    const Result r = run(c.path, c.args);
    EXPECT_EQ(r.status, 0) << c.path << " " << c.args << "\n" << r.out;
    for (const std::string& m : c.mentions)
      EXPECT_NE(r.out.find(m), std::string::npos) << c.path << " " << c.args << " does not name " << m << "\n" << r.out;
  }
  // Every option of every program's help says what it does: a description after its name.
  for (const Program& p : kPrograms) {
    const std::string help = run(p.path, "--help").out;
    const std::regex option(R"(^  (-\S+)( [A-Z][A-Za-z0-9.=_]*( \.\.\.)?)? *(.*)$)");
    std::size_t options = 0;
    std::size_t from = help.find("\nOptions:\n");
    ASSERT_NE(from, std::string::npos) << p.name << "\n" << help;
    for (std::size_t at = help.find('\n', from + 1) + 1; at < help.size() && help[at] != '\n';) {
      const std::size_t end = help.find('\n', at);
      const std::string line = help.substr(at, end - at);
      std::smatch m;
      if (std::regex_match(line, m, option)) {
        ++options;
        EXPECT_FALSE(m[4].str().empty()) << p.name << ": " << m[1] << " has no description\n" << help;
      }
      at = end + 1;
    }
    EXPECT_GE(options, 2u) << p.name << "\n" << help;
  }
  // The help describes the files as they are: the study file has no /scenes group.
  EXPECT_EQ(run("/sweep/lubsweep", "--help").out.find("/scenes"), std::string::npos);
  // A subcommand's help is its own: force's does not offer steady's options.
  EXPECT_EQ(run("/core/lubbearing", "force --help").out.find("--load-N"), std::string::npos);
}

TEST(ProgramsCli, UsageErrorsHaveOneFormat) {
  const struct {
    std::string name, path, args, message, hint;
  } cases[] = {
      {"lubsim", "/core/lubsim", "--bogus", "unknown option --bogus", "lubsim"},
      {"lubsim", "/core/lubsim", "-o x.h5", "no scene given", "lubsim"},
      {"lubsim", "/core/lubsim", "a.json", "no output file given (-o RUN.h5)", "lubsim"},
      {"lubsim", "/core/lubsim", "a.json b.json -o x.h5", "more than one scene given (a.json, b.json)", "lubsim"},
      {"lubsim", "/core/lubsim", "a.json --check --print-scene", "--check and --print-scene exclude each other",
       "lubsim"},
      {"lubbearing", "/core/lubbearing", "", "a command is required (force or steady)", "lubbearing"},
      {"lubbearing", "/core/lubbearing", "spin", "unknown command spin (must be force or steady)", "lubbearing"},
      {"lubbearing", "/core/lubbearing", "force --bogus 1", "unknown argument --bogus", "lubbearing force"},
      {"lubbearing", "/core/lubbearing", "steady --load-N", "--load-N", "lubbearing steady"},
      {"lubsweep", "/sweep/lubsweep", "--bogus", "unknown option --bogus", "lubsweep"},
      {"lubsweep", "/sweep/lubsweep", "g.json", "no output file given (-o STUDY.h5)", "lubsweep"},
  };
  for (const auto& c : cases) {
    const Result r = run(c.path, c.args, true);
    EXPECT_EQ(r.status, 2) << c.name << " " << c.args << "\n" << r.out;
    const std::string hint = "\nrun '" + c.hint + " --help' for usage\n";
    EXPECT_EQ(r.out.rfind(c.name + ": ", 0), 0u) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.message), std::string::npos) << c.args << "\n" << r.out;
    ASSERT_GE(r.out.size(), hint.size()) << r.out;
    EXPECT_EQ(r.out.substr(r.out.size() - hint.size()), hint) << c.args << "\n" << r.out;
    EXPECT_EQ(r.out.find("usage:"), std::string::npos) << "the whole usage is not repeated: " << r.out;
  }
}

// --sensitivity names a number of the effective scene: otherwise exit 2, naming the option
// and the pointer, before anything runs, and no file.
TEST(ProgramsCli, LubsimRefusesASensitivityToWhatIsNotANumber) {
  const std::string scene = std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json";
  const std::string out = ::testing::TempDir() + "sens_refused.h5";
  std::remove(out.c_str());
  for (const std::string ptr : {"/joints/3/force_law", "/nope", "/joints/3/initial_eccentricity_m/0"}) {
    const Result r = run("/core/lubsim", scene + " -o " + out + " --sensitivity " + ptr, true);
    EXPECT_EQ(r.status, 2) << ptr << "\n" << r.out;
    EXPECT_NE(r.out.find("--sensitivity " + ptr), std::string::npos) << r.out;
    EXPECT_FALSE(std::ifstream(out).good()) << ptr;
  }
}

// A scene or grid file that cannot be read or parsed (issue 46): one line that names the file
// once and says what is wrong (no such file; a directory; where the syntax breaks, without
// the JSON library's echo of the text), exit 2, no output file.
TEST(ProgramsCli, AnUnreadableInputFileIsNamedOnceAndSaidPlainly) {
  const std::string dir = ::testing::TempDir() + "unreadable_input/";
  std::system(("rm -rf '" + dir + "' && mkdir -p '" + dir + "'").c_str());
  std::ofstream(dir + "bad.json") << "{\n  \"description\": \"" << std::string(250, 'x') << "\",\n  \"bodies\": [,]\n}\n";
  const std::string out = dir + "out.h5";
  const struct {
    std::string name, path, input, message;
  } cases[] = {
      {"lubsim", "/core/lubsim", dir + "nope.json", "no such file"},
      {"lubsim", "/core/lubsim", dir, "a directory, not a file"},
      {"lubsim", "/core/lubsim", dir + "bad.json",
       "line 3, column 14: not valid JSON: syntax error while parsing value - unexpected ','; expected '[', '{', or "
       "a literal"},
      {"lubsweep", "/sweep/lubsweep", dir + "nope.json", "no such file"},
      {"lubsweep", "/sweep/lubsweep", dir, "a directory, not a file"},
      {"lubsweep", "/sweep/lubsweep", dir + "bad.json",
       "line 3, column 14: not valid JSON: syntax error while parsing value - unexpected ','; expected '[', '{', or "
       "a literal"},
  };
  for (const auto& c : cases) {
    const Result r = run(c.path, "'" + c.input + "' -o '" + out + "'", true);
    EXPECT_EQ(r.status, 2) << c.name << " " << c.input << "\n" << r.out;
    EXPECT_EQ(r.out, c.name + ": " + c.input + ": " + c.message + "\n");
    EXPECT_FALSE(std::ifstream(out).good()) << c.name << " " << c.input;
  }
}

// lubsim --check: the scene (after --set) valid or not, "ok" or the error, nothing run or
// written; --print-scene: the effective scene as JSON. Both take an element by its name in
// --set, as every --set does (issue 46).
TEST(ProgramsCli, LubsimChecksOrPrintsTheSceneWithoutRunningIt) {
  const std::string scene = std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json";
  const std::string out = ::testing::TempDir() + "check_only.h5";
  std::remove(out.c_str());
  const std::string by_name = " --set /joints/rod_slider/viscosity_Pa_s=0.125";
  Result r = run("/core/lubsim", scene + " --check" + by_name, true);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "ok\n");
  r = run("/core/lubsim", scene + " --check -o " + out + " --set /joints/rod_slider/viscosity_Pa_s=-1", true);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_EQ(r.out, "lubsim: " + scene + ": joints[3].viscosity_Pa_s = -1: must be > 0 Pa s\n");
  // A plausibility warning: said, not refused; refused under --strict.
  r = run("/core/lubsim", scene + " --check --set /joints/3/viscosity_Pa_s=400", true);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.rfind("lubsim: warning: /joints/3/viscosity_Pa_s = 400 Pa s is outside", 0), 0u) << r.out;
  EXPECT_EQ(r.out.substr(r.out.size() - 3), "ok\n") << r.out;
  EXPECT_EQ(run("/core/lubsim", scene + " --check --strict --set /joints/3/viscosity_Pa_s=400").status, 2);
  // A mechanism that cannot assemble is bad input too, as a run would find it.
  const std::string four_bar = std::string(LUB_SOURCE_DIR) + "/configs/scenes/four_bar.json";
  r = run("/core/lubsim", four_bar + " --check --set /joints/rocker_pivot/point_i_m=[0.6,0.0]", true);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_EQ(r.out.rfind("lubsim: " + four_bar + ": assembly: ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("cannot close the mechanism"), std::string::npos) << r.out;

  r = run("/core/lubsim", scene + " --print-scene" + by_name);
  EXPECT_EQ(r.status, 0) << r.out;
  const nlohmann::json printed = nlohmann::json::parse(r.out);
  nlohmann::json want = lub::read_json_file(scene);
  want["joints"][3]["viscosity_Pa_s"] = 0.125;
  EXPECT_EQ(printed, want);
  EXPECT_EQ(run("/core/lubsim", scene + " --print-scene --set /joints/rod/viscosity_Pa_s=1").status, 2);
  EXPECT_FALSE(std::ifstream(out).good());
}

// The files a help or a message points to (the scene schema, example grids, docs pages) are
// named where the user finds them: a program of the build tree names the repository's paths,
// an installed one its prefix's share/lubjoint (the test install_consumer), and
// LUBJOINT_DATADIR overrides both.
TEST(ProgramsCli, HelpAndMessagesNameTheRepositoryOrTheInstalledFiles) {
  const std::string scene = ::testing::TempDir() + "schema_not_a_string.json";
  std::ofstream(scene) << R"({"$schema": 1})";
  for (const std::string& dir : {std::string(), std::string("/opt/lj/share/lubjoint")}) {
    const std::string env = dir.empty() ? "env -u LUBJOINT_DATADIR" : "env LUBJOINT_DATADIR=" + dir;
    const auto with_env = [&](const std::string& program, const std::string& args) {
      return lub_test::run_command(env + " OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " +
                                   std::string(LUB_BINARY_DIR) + program + " " + args + " 2>&1");
    };
    const std::string root = dir.empty() ? "" : dir + "/";
    const std::string lubsim = with_env("/core/lubsim", "--help").out;
    EXPECT_NE(lubsim.find("(format: " + root + "configs/scene.schema.json)"), std::string::npos) << lubsim;
    EXPECT_NE(lubsim.find("Example scenes: " + root + "configs/scenes/\n"), std::string::npos) << lubsim;
    const std::string lubsweep = with_env("/sweep/lubsweep", "--help").out;
    EXPECT_NE(lubsweep.find("(" + root + "docs/guide/grids.md; examples in " + root + "configs/grids/)"),
              std::string::npos)
        << lubsweep;
    const Result r = with_env("/core/lubsim", scene + " --check");
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("the URI or path of " + root + "configs/scene.schema.json, for editors"), std::string::npos)
        << r.out;
  }
}

}  // namespace
