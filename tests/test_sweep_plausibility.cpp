// Plausibility warnings of a grid (issue 29): each distinct warning of its cases once, with how
// many cases give it (Grid::warnings); none for the shipped grids; stored in the
// study file's root attribute `warnings`; lubsweep prints them once and refuses them under
// --strict (exit 2, nothing written). The ranges and scenes: test_core_plausibility.cpp.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "fixtures/temp_dir_test.hpp"
#include "lub/io/h5.hpp"
#include "lub/sweep/grid.hpp"
#include "lub/sweep/study_file.hpp"

namespace {

namespace fs = std::filesystem;
using lub::sweep::Grid;

const std::string kSource = LUB_SOURCE_DIR;
const std::string kScenes = kSource + "/configs/scenes";

// A 2 x 3 factorial: 400 Pa s (400 cP typed as Pa s) in 3 cases, 5e6 rpm in 2.
const std::string kSlipGrid = R"({
    "scene": "slider_crank.json",
    "study": {"max_cycles": 1, "metric_cycles": 1},
    "axes": [{"name": "viscosity_Pa_s", "values": [0.4, 400]},
             {"name": "speed_rpm", "values": [5000, 500, 5e6]}]})";

const std::string kViscosity400 =
    "/joints/3/viscosity_Pa_s = 400 Pa s is outside the plausible 1e-4 – 5 Pa s (400 cP is 0.4 Pa s)";

TEST(GridPlausibility, EachDistinctWarningOnceWithItsCaseCount) {
  const Grid g = lub::sweep::parse_grid(kSlipGrid, kScenes, "slip.json");
  ASSERT_EQ(g.cases.size(), 6u);
  ASSERT_EQ(g.warnings.size(), 2u);
  // Cases in factorial order (viscosity slowest): the first 5e6 rpm is case 2, the first 400 Pa s case 3.
  EXPECT_EQ(g.warnings[0].rfind("/drivers/0/speed_rpm = 5e+06 rpm is above the plausible 50000 rpm", 0), 0u);
  EXPECT_NE(g.warnings[0].find("; in 2 of 6 cases (the first case_0002)"), std::string::npos) << g.warnings[0];
  EXPECT_EQ(g.warnings[1], kViscosity400 + "; in 3 of 6 cases (the first case_0003)");
}

TEST(GridPlausibility, EveryShippedGridHasNoWarning) {
  int grids = 0;
  for (const auto& e : fs::directory_iterator(kSource + "/configs/grids")) {
    if (e.path().extension() != ".json") continue;
    ++grids;
    const Grid g = lub::sweep::load_grid(e.path().string());
    EXPECT_FALSE(g.cases.empty()) << e.path();
    EXPECT_TRUE(g.warnings.empty()) << e.path() << ": " << (g.warnings.empty() ? "" : g.warnings.front());
  }
  EXPECT_GE(grids, 10);  // the paper's grids among them
}

class SweepPlausibility : public lub_test::TempDirTest {
 protected:
  SweepPlausibility() : TempDirTest("lub_sweep_plausibility_") {}
};

TEST_F(SweepPlausibility, TheStudyFileStoresTheGridsWarnings) {
  const Grid g = lub::sweep::parse_grid(kSlipGrid, kScenes, "slip.json");
  const std::string path = file("s.h5");
  {
    lub::sweep::StudyWriter w(path, g, {}, "");
    w.finalize();
  }
  EXPECT_EQ(lub::h5::File::open(path).attribute_strings("warnings"), g.warnings);
  const Grid clean = lub::sweep::parse_grid(R"({"scene": "slider_crank.json", "axes": [{"name": "speed_rpm", "values": [500]}]})",
                                            kScenes, "clean.json");
  const std::string clean_path = file("clean.h5");
  {
    lub::sweep::StudyWriter w(clean_path, clean, {}, "");
    w.finalize();
  }
  EXPECT_TRUE(lub::h5::File::open(clean_path).attribute_strings("warnings").empty());
}

struct Result {
  int status = -1;
  std::string err;
};

// lubsweep (one process: rank 0 alone) with `args`; stderr captured, stdout discarded.
Result lubsweep(const std::string& args, const std::string& err_file) {
  const std::string cmd = std::string(LUB_BINARY_DIR) + "/sweep/lubsweep " + args + " >/dev/null 2>" + err_file;
  Result r;
  const int st = std::system(cmd.c_str());
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  if (FILE* e = std::fopen(err_file.c_str(), "r")) {
    std::array<char, 4096> buf{};
    while (std::fgets(buf.data(), buf.size(), e)) r.err += buf.data();
    std::fclose(e);
  }
  return r;
}

TEST_F(SweepPlausibility, LubsweepPrintsEachWarningOnceAndRefusesThemUnderStrict) {
  const std::string grid = file("slip.json");
  {
    std::FILE* f = std::fopen(grid.c_str(), "w");
    ASSERT_NE(f, nullptr);
    const std::string text = std::string(kSlipGrid).replace(kSlipGrid.find("slider_crank.json"), 17,
                                                            kScenes + "/slider_crank.json");
    std::fputs(text.c_str(), f);
    std::fclose(f);
  }
  const Grid g = lub::sweep::load_grid(grid);
  ASSERT_EQ(g.warnings.size(), 2u);
  // --check: the warnings once each (not once per case), the grid still listed.
  const Result check = lubsweep(grid + " --check", file("err"));
  EXPECT_EQ(check.status, 0) << check.err;
  EXPECT_EQ(check.err, "lubsweep: warning: " + g.warnings[0] + "\nlubsweep: warning: " + g.warnings[1] + "\n");
  // --strict: exit 2, each warning as an error, no output file.
  const std::string out = file("s.h5");
  const Result strict = lubsweep(grid + " -o " + out + " --strict", file("err"));
  EXPECT_EQ(strict.status, 2);
  EXPECT_EQ(strict.err, "lubsweep: " + grid + ": " + g.warnings[0] + "; refused under --strict\nlubsweep: " + grid +
                            ": " + g.warnings[1] + "; refused under --strict\n");
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out + ".partial"));
  // A plausible grid under --strict: no warning, the check passes.
  const Result clean = lubsweep(kSource + "/configs/grids/paper_speed.json --check --strict", file("err"));
  EXPECT_EQ(clean.status, 0) << clean.err;
  EXPECT_EQ(clean.err, "");
}

}  // namespace
