// Tests of the study file (lub/sweep/study_file.hpp) and of running and encoding one case
// (lub/sweep/case_result.hpp): layout and units, dimension scales, canonical order,
// resume by hash (also from a killed writer), a foreign output file, the progress line.
#include "lub/sweep/study_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "lub/io/json_reader.hpp"
#include "lub/run/orbit_seed_fields.hpp"
#include "lub/sweep/case_result.hpp"
#include "lub/sweep/continuation_tree.hpp"
#include "lub/io/output_path.hpp"
#include "fixtures/temp_dir_test.hpp"
#include "lub/sweep/grid.hpp"
#include "lub/sweep/hash.hpp"
#include "lub/sweep/output_lock.hpp"
#include "lub/sweep/progress.hpp"
#include "lub/sweep/sweep.hpp"

namespace fs = std::filesystem;
using namespace lub::sweep;
using nlohmann::json;

namespace {

const std::string kScenes = std::string(LUB_SOURCE_DIR) + "/configs/scenes";

/// 2 x 2 factorial plus one explicit case: 5 cases, two of them store series.
Grid small_grid() {
  return parse_grid(R"({
      "scene": "slider_crank.json",
      "set": {"/solver/rtol": 1e-6, "/simulation/steady": "auto"},
      "study": {"max_cycles": 2, "metric_cycles": 1, "channels": ["h_min"], "last_cycles": 1, "samples_per_cycle": 90},
      "grids": [{"name": "main", "axes": [{"name": "force_law", "values": ["ideal", "frene_short"]},
                                          {"name": "speed_rpm", "values": [5000, 500]}]},
                {"name": "extra", "cases": [{"/solver/rtol": 1e-7, "force_law": "ideal"}]}]})",
                    kScenes, "small.json");
}

/// A made-up result: distinct values per case, series for even ids.
CaseResult fake(const Grid& g, int id, CaseStatus status = CaseStatus::ok) {
  CaseResult r;
  r.case_id = id;
  r.rank = id % 2;
  r.status = status;
  r.classification = case_class(status).value_or(CaseClass::periodic);
  r.message = status == CaseStatus::ok ? "" : "it broke";
  r.revision = lub::build_revision();
  const auto fields = result_fields();
  for (std::size_t i = 0; i < fields.size(); ++i) r.values.push_back(fields[i].integer ? double(id + i) : 0.5 * id + 0.001 * i);
  if (id % 2 == 0) {
    r.series.names = {"t", "h_min"};
    r.series.units = {"s", "m"};
    r.series.data = {{0.0, 0.1, 0.2}, {1e-4 * id, 2e-4, 3e-4}};
  }
  (void)g;
  return r;
}

/// The index of result field `name` in CaseResult::values.
std::size_t at(const std::string& name) {
  const auto fields = result_fields();
  std::size_t i = 0;
  while (fields[i].name != name) ++i;
  return i;
}

/// `lubsweep --summary` of `path`, each line split into its words.
std::vector<std::vector<std::string>> summary_words(const std::string& path) {
  std::FILE* out = std::tmpfile();
  if (!out) throw std::runtime_error("no temporary file");
  print_summary(path, out);
  std::rewind(out);
  std::vector<std::vector<std::string>> rows;
  char line[4096];
  while (std::fgets(line, sizeof line, out)) {
    std::istringstream words(line);
    rows.emplace_back(std::istream_iterator<std::string>(words), std::istream_iterator<std::string>());
  }
  std::fclose(out);
  return rows;
}

/// Writes a new study file at `path` holding `results`, in the order given. `finalize`: the
/// file rewritten canonically, as a sweep that ends leaves it; else the live file (rows in
/// arrival order), as a killed sweep leaves it.
void write_study(const std::string& path, const Grid& g, const std::vector<CaseResult>& results, bool finalize) {
  StudyWriter w(path, g, {}, "");
  for (const CaseResult& r : results) w.append(r);
  if (finalize) w.finalize();
}

class StudyFile : public lub_test::TempDirTest {
 protected:
  StudyFile() : TempDirTest("lub_sweep_") {}
};

}  // namespace

TEST_F(StudyFile, LayoutUnitsAndAttributes) {
  const Grid g = small_grid();
  ASSERT_EQ(g.cases.size(), 5u);
  const std::string path = file("s.h5");
  {
    StudyWriter w(path, g, {}, "");
    for (int id : {0, 1, 2, 3, 4}) w.append(fake(g, id));
    EXPECT_TRUE(w.complete());
    w.finalize();
  }
  EXPECT_FALSE(fs::exists(path + ".partial"));
  const auto f = lub::h5::File::open(path);
  EXPECT_EQ(f.attribute_string("program"), "lubsweep");
  EXPECT_EQ(f.attribute_string("format"), kStudyFormat);
  EXPECT_EQ(f.attribute_string("grid"), g.text);
  EXPECT_EQ(f.attribute_string("grid_file"), "small.json");
  EXPECT_EQ(f.attribute_string("base_scene"), g.base_scene_text);
  EXPECT_EQ(f.attribute_string("version"), lub::program_version());
  EXPECT_EQ(f.attribute_string("revision"), lub::build_revision());
  EXPECT_EQ(f.attribute_int64("cases_total"), 5);
  EXPECT_EQ(f.attribute_int64("complete"), 1);

  const auto t = f.open_table("cases");
  EXPECT_EQ(t.rows(), 5u);
  std::vector<std::string> names;
  for (const auto& c : t.columns()) names.push_back(c.name);
  const std::vector<std::string> head = {"case", "name", "hash", "force_law", "speed_rpm", "solver.rtol", "status", "message"};
  EXPECT_EQ(std::vector<std::string>(names.begin(), names.begin() + 8), head);
  EXPECT_EQ(names.back(), "revision");
  EXPECT_EQ(t.columns()[t.column_index("speed_rpm")].units, "min-1");
  EXPECT_EQ(t.columns()[t.column_index("min_film_thickness_m")].units, "m");
  EXPECT_EQ(t.columns()[t.column_index("peak_acceleration_m_s2")].units, "m s-2");
  EXPECT_EQ(t.columns()[t.column_index("steps")].units, "1");
  EXPECT_FALSE(t.columns()[t.column_index("max_eps")].long_name.empty());
  // netCDF-4 style: `case` (the case ids) is the dimension scale of every column.
  EXPECT_TRUE(t.column("case").is_scale());
  EXPECT_EQ(t.read_int64s("case"), (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(t.column("max_eps").has_attribute("DIMENSION_LIST"));
  EXPECT_TRUE(t.column("status").has_attribute("DIMENSION_LIST"));
  EXPECT_EQ(t.columns()[t.column_index("steps")].type, lub::h5::ColumnType::Int64);
  EXPECT_EQ(t.attribute_strings("axes"), (std::vector<std::string>{"force_law", "speed_rpm", "solver.rtol"}));
  EXPECT_EQ(t.read_strings("force_law"), (std::vector<std::string>{"ideal", "ideal", "frene_short", "frene_short", "ideal"}));
  EXPECT_EQ(t.read_doubles("speed_rpm"), (std::vector<double>{5000, 500, 5000, 500, 5000}));
  EXPECT_EQ(t.read_doubles("solver.rtol")[4], 1e-7);
  EXPECT_EQ(t.read_strings("hash")[3], g.cases[3].hash);

  // Every case's scene, by case id: a JSON Patch of case 0's scene that gives the case's
  // canonical scene, byte for byte (and so its hash).
  const auto patches = f.open_dataset("scene_patches").read_strings();
  ASSERT_EQ(patches.size(), 5u);
  const json reference = json::parse(f.attribute_string("reference_scene"));
  EXPECT_EQ(f.attribute_string("reference_scene"), g.cases[0].scene);
  EXPECT_EQ(patches[0], "[]");
  for (std::size_t i = 0; i < 5; ++i) {
    const json scene = reference.patch(json::parse(patches[i]));
    EXPECT_EQ(canonical_json(scene), g.cases[i].scene) << "case " << i;
    EXPECT_EQ(scene_hash(scene), g.cases[i].hash) << "case " << i;
    EXPECT_LT(patches[i].size(), 300u) << "a case differs from the reference in a few values: " << patches[i];
  }

  // The factorial's case ids over its axes, with dimension scales.
  const auto idx = f.open_dataset("grids/main/case_id");
  EXPECT_EQ(idx.shape(), (std::vector<std::size_t>{2, 2}));
  EXPECT_EQ(idx.read_int64s(), (std::vector<std::int64_t>{0, 1, 2, 3}));
  EXPECT_TRUE(f.open_dataset("grids/main/speed_rpm").is_scale());
  EXPECT_EQ(f.open_dataset("grids/main/speed_rpm").read_doubles(), (std::vector<double>{5000, 500}));
  EXPECT_EQ(f.open_dataset("grids/main/speed_rpm").units(), "min-1");
  EXPECT_EQ(f.open_dataset("grids/main/force_law").read_strings(), (std::vector<std::string>{"ideal", "frene_short"}));
  EXPECT_EQ(f.open_dataset("grids/extra/case_id").read_int64s(), std::vector<std::int64_t>{4});
  EXPECT_TRUE(f.open_dataset("grids/extra/case").is_scale());

  // Every result field as a variable over the sub-grid's axes, with units and long_name.
  const auto h = f.open_dataset("grids/main/min_film_thickness_m");
  EXPECT_EQ(h.shape(), (std::vector<std::size_t>{2, 2}));
  EXPECT_EQ(h.units(), "m");
  EXPECT_TRUE(h.has_attribute("long_name"));
  EXPECT_TRUE(h.has_attribute("DIMENSION_LIST"));
  const std::size_t k = t.column_index("min_film_thickness_m");
  const auto col = t.read_doubles("min_film_thickness_m");
  EXPECT_EQ(h.read_doubles(), (std::vector<double>{col[0], col[1], col[2], col[3]}));
  EXPECT_GT(k, 0u);
  EXPECT_EQ(f.open_dataset("grids/main/status").read_strings(), (std::vector<std::string>(4, "ok")));
  EXPECT_EQ(f.open_dataset("grids/extra/steps").read_doubles(), (std::vector<double>{t.read_doubles("steps")[4]}));

  // Series of the cases that have them.
  EXPECT_TRUE(f.exists("series/case_0002/h_min"));
  EXPECT_FALSE(f.exists("series/case_0001"));
  EXPECT_EQ(f.open_dataset("series/case_0002/h_min").units(), "m");
  EXPECT_EQ(f.open_group("series/case_0002").attribute_strings("channels"), (std::vector<std::string>{"t", "h_min"}));
  EXPECT_TRUE(f.open_dataset("series/case_0002/t").is_scale());
  EXPECT_TRUE(f.open_dataset("series/case_0002/h_min").has_attribute("DIMENSION_LIST"));
}

// The file says what a reader in another language would otherwise restate (lubjoint.study
// reads these): which classifications carry an orbit, how a row of orbit_seed is packed,
// and the grid's lattice neighbours. Written with the header: the live file has them too.
TEST_F(StudyFile, TheFileDescribesItsOwnLayout) {
  const Grid g = small_grid();
  for (const bool finalize : {false, true}) {
    SCOPED_TRACE(finalize ? "finalized" : "live");
    const std::string path = file(finalize ? "final.h5" : "live.h5");
    write_study(path, g, {fake(g, 0), fake(g, 1)}, finalize);
    const auto f = lub::h5::File::open(path);
    const auto t = f.open_table("cases");
    std::vector<std::string> orbit, no_orbit;
    for (const auto& [c, name] : lub::NameTable<CaseClass>::entries) {
      if (has_orbit(c)) orbit.emplace_back(name);
      if (!has_orbit(c) && ran(c)) no_orbit.emplace_back(name);
    }
    EXPECT_EQ(t.attribute_strings("orbit_classifications"), (std::vector<std::string>{"periodic", "periodic_unstable"}));
    EXPECT_EQ(t.attribute_strings("orbit_classifications"), orbit);
    EXPECT_EQ(t.attribute_strings("no_orbit_classifications"),
              (std::vector<std::string>{"drifting", "not_converged", "film_collapse", "solver_failure", "budget_exceeded"}));
    EXPECT_EQ(t.attribute_strings("no_orbit_classifications"), no_orbit);

    const auto seed = t.column("orbit_seed");
    EXPECT_EQ(seed.attribute_int64("layout"), lub::orbit_seed_layout());
    std::vector<std::string> names, shapes, types, units;
    for (const auto& fld : lub::orbit_seed_fields()) {
      names.emplace_back(fld.name);
      shapes.emplace_back(lub::name_of(fld.shape));
      types.emplace_back(fld.integer ? "int64" : "float64");
      units.emplace_back(fld.unit);
    }
    EXPECT_EQ(seed.attribute_strings("fields"), names);
    EXPECT_EQ(seed.attribute_strings("field_shapes"), shapes);
    EXPECT_EQ(seed.attribute_strings("field_types"), types);
    EXPECT_EQ(seed.attribute_strings("field_units"), units);
    EXPECT_EQ(seed.attribute_strings("field_long_names").size(), names.size());
    EXPECT_TRUE(seed.has_attribute("packing"));

    const auto edges = lattice_edges(g);
    ASSERT_FALSE(edges.empty());
    const auto lower = f.open_dataset("lattice/case_a").read_int64s();
    const auto upper = f.open_dataset("lattice/case_b").read_int64s();
    const auto axis = f.open_dataset("lattice/axis").read_strings();
    ASSERT_EQ(lower.size(), edges.size());
    ASSERT_EQ(upper.size(), edges.size());
    ASSERT_EQ(axis.size(), edges.size());
    for (std::size_t i = 0; i < edges.size(); ++i) {
      EXPECT_EQ(lower[i], edges[i].lower);
      EXPECT_EQ(upper[i], edges[i].upper);
      EXPECT_EQ(axis[i], g.axes[static_cast<std::size_t>(edges[i].axis)].name);
    }
    EXPECT_TRUE(f.open_dataset("lattice/edge").is_scale());
  }
}

// A file of format 5 written before the self-description (no orbit_classifications, no
// orbit_seed packing) resumes as before: resume reads none of it, and the file it writes
// has it.
TEST_F(StudyFile, AFileWithoutItsSelfDescriptionResumes) {
  const Grid g = small_grid();
  const std::string path = file("older.h5");
  write_study(path, g, {fake(g, 0), fake(g, 3, CaseStatus::film_collapse)}, true);
  {
    auto f = lub::h5::File::open(path, lub::h5::File::Mode::ReadWrite);
    auto t = f.open_table("cases");
    t.remove_attribute("orbit_classifications");
    t.remove_attribute("no_orbit_classifications");
    auto seed = t.column("orbit_seed");
    for (const char* a : {"layout", "fields", "field_shapes", "field_types", "field_units", "field_long_names", "packing"})
      seed.remove_attribute(a);
  }
  const ResumeState st = read_existing(path, g, false, lub::build_revision());
  ASSERT_EQ(st.done.size(), 2u);
  EXPECT_EQ(st.done.at(3).classification, CaseClass::film_collapse);
  {
    StudyWriter w(path, g, st.done, path);
    w.finalize();
  }
  const auto t = lub::h5::File::open(path).open_table("cases");
  EXPECT_EQ(t.rows(), 2u);
  EXPECT_TRUE(t.has_attribute("orbit_classifications"));
  EXPECT_TRUE(t.column("orbit_seed").has_attribute("fields"));
}

TEST_F(StudyFile, GridVariablesHoldNaNMetricsForCasesNotOkAndSayWhy) {
  const Grid g = small_grid();
  const std::string path = file("s.h5");
  // Cases 3 and 4 never run: an incomplete study.
  write_study(path, g, {fake(g, 0), fake(g, 1, CaseStatus::film_collapse), fake(g, 2)}, true);
  const auto f = lub::h5::File::open(path);
  const auto h = f.open_dataset("grids/main/min_film_thickness_m").read_doubles();
  EXPECT_FALSE(std::isnan(h[0]));
  EXPECT_TRUE(std::isnan(h[1]));  // not ok
  EXPECT_TRUE(std::isnan(h[3]));  // not run
  EXPECT_EQ(f.open_dataset("grids/main/status").read_strings(),
            (std::vector<std::string>{"ok", "film_collapse", "ok", "not_run"}));
  EXPECT_EQ(f.open_dataset("grids/main/message").read_strings()[1], "it broke");
  // Solver statistics of a failed case are kept: they say what the failure cost.
  EXPECT_FALSE(std::isnan(f.open_dataset("grids/main/steps").read_doubles()[1]));
}

TEST_F(StudyFile, OneMissingValueConventionNaNForFloatsADeclaredSentinelForIntegers) {
  // An unknown periodicity (a float) is NaN in /cases as in /grids (it was -1 in /cases);
  // an unknown count (cycles_to_steady, an integer) is -1 in /cases, declared by the
  // column's missing_value, NaN in /grids; every float column declares _FillValue = NaN.
  const Grid g = small_grid();
  const std::string path = file("m.h5");
  CaseResult r = fake(g, 0);
  r.values[at("periodicity")] = std::nan("");
  r.values[at("cycles_to_steady")] = std::nan("");
  write_study(path, g, {r, fake(g, 1)}, true);
  {
    const auto f = lub::h5::File::open(path);
    const auto t = f.open_table("cases");
    EXPECT_TRUE(std::isnan(t.read_doubles("periodicity")[0]));
    EXPECT_EQ(t.read_int64s("cycles_to_steady")[0], -1);
    EXPECT_EQ(t.read_int64s("cycles_to_steady")[1], static_cast<std::int64_t>(fake(g, 1).values[at("cycles_to_steady")]));
    EXPECT_TRUE(std::isnan(f.open_dataset("grids/main/periodicity").read_doubles()[0]));
    EXPECT_TRUE(std::isnan(f.open_dataset("grids/main/cycles_to_steady").read_doubles()[0]));
    for (const auto& fld : result_fields()) {
      SCOPED_TRACE(fld.name);
      const auto col = t.column(fld.name);
      if (fld.integer) {
        EXPECT_EQ(col.attribute_int64("missing_value"), lub::kMissingInteger);
      } else {
        EXPECT_TRUE(std::isnan(col.attribute_double("_FillValue")));
      }
      EXPECT_TRUE(std::isnan(f.open_dataset("grids/main/" + fld.name).attribute_double("_FillValue")));
    }
    EXPECT_TRUE(std::isnan(t.column("speed_rpm").attribute_double("_FillValue")));
  }
  // Resumed, the sentinel reads back as NaN: the rewritten /grids is the same as a fresh one's.
  const ResumeState st = read_existing(path, g, false, lub::build_revision());
  EXPECT_TRUE(std::isnan(st.done.at(0).values[at("cycles_to_steady")]));
  EXPECT_EQ(st.done.at(1).values[at("cycles_to_steady")], fake(g, 1).values[at("cycles_to_steady")]);
}

TEST_F(StudyFile, SummaryOfAMissingOrForeignFileIsOneShortLine) {
  // lubsweep --summary prints "lubsweep: --summary PATH: " and this: no HDF5 error stack.
  auto message = [](const std::string& path) {
    try {
      print_summary(path, stdout);
    } catch (const lub::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(file("missing.h5")), "no such file");
  std::ofstream(file("text.h5")) << "not a study";
  EXPECT_EQ(message(file("text.h5")), "not an HDF5 file, so not a lubsweep study file");
  lub::h5::File::create(file("plain.h5")).set_attribute("program", "lubsim");
  EXPECT_EQ(message(file("plain.h5")), "not a lubsweep study file");
}

TEST_F(StudyFile, SummarySaysWhereACaseWithoutAnOrbitGotTo) {
  // A case without a steady cycle shows its last film, its drift a cycle, the drift's error
  // bar and the cycles its slow flow followed; a case with an orbit shows "-" there (its metrics say it).
  const Grid g = small_grid();
  const std::string path = file("where.h5");
  CaseResult orbit = fake(g, 0), drifting = fake(g, 1);
  orbit.classification = CaseClass::periodic;
  drifting.classification = CaseClass::drifting;
  write_study(path, g, {orbit, drifting, fake(g, 2), fake(g, 3), fake(g, 4)}, true);
  const std::vector<std::vector<std::string>> rows = summary_words(path);
  ASSERT_GE(rows.size(), 5u);
  const std::vector<std::string>& head = rows[2];  // after the counts and the classification line
  ASSERT_EQ(head.front(), "case");
  const auto t = lub::h5::File::open(path).open_table("cases");
  for (const auto& [column, name, scale] : {std::tuple{"last_h[um]", "last_cycle_min_film_m", 1e6},
                                            std::tuple{"dh/cycle[nm]", "min_film_drift_m_per_cycle", 1e9},
                                            std::tuple{"dh_error[nm]", "min_film_drift_m_per_cycle_error", 1e9},
                                            std::tuple{"flow[cycles]", "slow_flow_cycles", 1.0}}) {
    SCOPED_TRACE(column);
    const auto at = std::find(head.begin(), head.end(), std::string(column));
    ASSERT_NE(at, head.end());
    const std::size_t k = static_cast<std::size_t>(at - head.begin());
    EXPECT_EQ(rows[3].at(k), "-");  // case_0000, periodic
    const double v = t.read_doubles(name)[1] * scale;
    char want[64];
    std::snprintf(want, sizeof want, std::string(column) == "flow[cycles]" ? "%.0f" : "%.3g", v);
    EXPECT_EQ(rows[4].at(k), want);  // case_0001, drifting
  }
}

TEST_F(StudyFile, SummaryShowsANegativeNumberThatRoundsToZeroAsZero) {
  // A metric of -3e-7 rounds to "-0.0000" in {:.4f}: shown as 0.0000 (issue 46), in every
  // column and format ({:.4f}, {:.2e}, {:.3g} of -0.0); a negative number that does
  // not round to zero keeps its sign.
  const Grid g = small_grid();
  const std::string path = file("negative_zero.h5");
  CaseResult r = fake(g, 0);
  r.values[at("max_eps")] = -3e-7;
  r.values[at("periodicity")] = -0.0;
  r.values[at("orbit_conditioning")] = -0.0;
  r.values[at("wall_time_s")] = -0.25;
  write_study(path, g, {r}, true);
  const std::vector<std::vector<std::string>> rows = summary_words(path);
  ASSERT_GE(rows.size(), 4u);
  const std::vector<std::string>& head = rows[2];
  ASSERT_EQ(head.front(), "case");
  auto cell = [&](const std::string& column) {
    const auto k = std::find(head.begin(), head.end(), column);
    return k == head.end() ? std::string("(no column)") : rows[3].at(static_cast<std::size_t>(k - head.begin()));
  };
  EXPECT_EQ(cell("max_eps"), "0.0000");
  EXPECT_EQ(cell("periodicity"), "0.00e+00");
  EXPECT_EQ(cell("kappa"), "0");
  EXPECT_EQ(cell("wall[s]"), "-0.25");
}

TEST_F(StudyFile, OlderFormatIsRefusedWithAClearMessage) {
  const Grid g = small_grid();
  const std::string path = file("old.h5");
  {
    auto f = lub::h5::File::create(path);
    f.set_attribute("program", "lubsweep");
    f.set_attribute("format", "lubsweep-study-1");
    f.write_dataset("cases", std::vector<double>{1.0}, "1");  // stands for the compound table
  }
  try {
    read_existing(path, g, false, lub::build_revision());
    FAIL() << "an old-format study file was read";
  } catch (const lub::InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("format lubsweep-study-1"), std::string::npos) << msg;
    EXPECT_NE(msg.find(kStudyFormat), std::string::npos) << msg;
    EXPECT_NE(msg.find("--restart"), std::string::npos) << msg;
  }
}

TEST_F(StudyFile, FinalFileIsInCaseIdOrderWhateverTheArrivalOrder) {
  const Grid g = small_grid();
  const std::string a = file("a.h5"), b = file("b.h5");
  write_study(a, g, {fake(g, 0), fake(g, 1), fake(g, 2), fake(g, 3), fake(g, 4)}, true);
  write_study(b, g, {fake(g, 3), fake(g, 0), fake(g, 4), fake(g, 2), fake(g, 1)}, true);
  const auto ta = lub::h5::File::open(a).open_table("cases"), tb = lub::h5::File::open(b).open_table("cases");
  EXPECT_EQ(tb.read_int64s("case"), (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
  for (const auto& f : result_fields()) EXPECT_EQ(ta.read_doubles(f.name), tb.read_doubles(f.name)) << f.name;
}

TEST_F(StudyFile, ResumeFindsTheCasesByHash) {
  const Grid g = small_grid();
  const std::string path = file("r.h5");
  write_study(path, g, {fake(g, 2), fake(g, 3, CaseStatus::film_collapse)}, false);  // the live file
  ResumeState st = read_existing(path, g, false, lub::build_revision());
  ASSERT_EQ(st.done.size(), 2u);
  EXPECT_EQ(st.done.at(3).status, CaseStatus::film_collapse);
  EXPECT_EQ(st.done.at(3).classification, CaseClass::film_collapse);
  EXPECT_EQ(st.done.at(2).classification, CaseClass::periodic);
  EXPECT_EQ(st.done.at(3).message, "it broke");
  EXPECT_EQ(st.done.at(2).values, fake(g, 2).values);
  EXPECT_EQ(st.other_rows, 0u);
  EXPECT_EQ(read_existing(path, g, true, lub::build_revision()).done.size(), 1u);  // --retry-failed
  EXPECT_EQ(read_existing(path, g, true, lub::build_revision()).retried, 1u);
  // Rows of another build are run again: a file never mixes two builds' results.
  const ResumeState newer = read_existing(path, g, false, "another-revision");
  EXPECT_TRUE(newer.done.empty());
  EXPECT_EQ(newer.other_revision, 2u);

  // Resume: the reused rows and their series are carried over, the rest appended.
  {
    StudyWriter w(path, g, st.done, path);
    EXPECT_EQ(w.rows(), 2u);
    for (int id : {0, 1, 4}) w.append(fake(g, id));
    w.finalize();
  }
  const auto f = lub::h5::File::open(path);
  EXPECT_EQ(f.attribute_int64("complete"), 1);
  EXPECT_EQ(f.open_table("cases").read_int64s("case"), (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(f.open_dataset("series/case_0002/h_min").read_doubles(), fake(g, 2).series.data[1]);

  // Another grid over the same file: rows of other scenes are not reused, and only
  // dropped with consent (--drop-other-cases).
  const Grid other = parse_grid(R"({"scene": "slider_crank.json", "study": {"max_cycles": 3},
                                    "axes": [{"name": "force_law", "values": ["ideal"]}]})", kScenes);
  const ResumeState o = read_existing(path, other, false, lub::build_revision(), true);
  EXPECT_TRUE(o.done.empty());
  EXPECT_EQ(o.other_rows, 5u);
}

TEST_F(StudyFile, AFileOfAnotherGridIsRefusedNamingTheCasesAndAxes) {
  // Re-running a smaller grid on the same -o once dropped the rows it did not list. Now the
  // file is refused, naming what would be lost, unless --drop-other-cases says to drop them.
  const Grid g = small_grid();
  const std::string path = file("s.h5");
  write_study(path, g, {fake(g, 0), fake(g, 1), fake(g, 2), fake(g, 3)}, true);
  const auto before = fs::last_write_time(path);
  const Grid smaller = parse_grid(R"({
      "scene": "slider_crank.json",
      "set": {"/solver/rtol": 1e-6, "/simulation/steady": "auto"},
      "study": {"max_cycles": 2, "metric_cycles": 1, "channels": ["h_min"], "last_cycles": 1, "samples_per_cycle": 90},
      "grids": [{"name": "main", "axes": [{"name": "force_law", "values": ["ideal", "frene_short"]},
                                          {"name": "speed_rpm", "values": [5000]}]},
                {"name": "extra", "cases": [{"/solver/rtol": 1e-7, "force_law": "ideal"}]}]})",
                                  kScenes, "smaller.json");
  // The message read_existing refuses `grid` with ("" if it does not).
  auto refusal = [&path](const Grid& grid) {
    try {
      read_existing(path, grid, false, lub::build_revision());
    } catch (const lub::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  {
    const std::string msg = refusal(smaller);
    EXPECT_NE(msg.find("the file holds 2 computed cases that are not cases of the grid smaller.json: "
                       "case_0001 (force_law=ideal speed_rpm=500 solver.rtol=1e-06), "
                       "case_0003 (force_law=frene_short speed_rpm=500 solver.rtol=1e-06)"),
              std::string::npos) << msg;
    EXPECT_NE(msg.find("same axes (force_law, speed_rpm, solver.rtol)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("--drop-other-cases"), std::string::npos) << msg;
    EXPECT_NE(msg.find("--restart"), std::string::npos) << msg;
  }
  const Grid other_axes = parse_grid(R"({"scene": "slider_crank.json", "study": {"max_cycles": 3},
                                         "axes": [{"name": "viscosity_Pa_s", "values": [0.4]}]})", kScenes, "v.json");
  {
    const std::string msg = refusal(other_axes);
    EXPECT_NE(msg.find("4 computed cases"), std::string::npos) << msg;
    EXPECT_NE(msg.find("axes only in the file: force_law, speed_rpm, solver.rtol; only in this grid: viscosity_Pa_s"),
              std::string::npos) << msg;
  }
  // A file whose /cases lacks this build's result columns: its rows cannot be reused,
  // and are not dropped without consent either.
  const std::string bare = file("bare.h5");
  {
    auto f = lub::h5::File::create(bare);
    f.set_attribute("program", "lubsweep");
    f.set_attribute("format", kStudyFormat);
    auto t = f.create_table("cases", {{"case", lub::h5::ColumnType::Int64, "1", "case id"},
                                      {"hash", lub::h5::ColumnType::String, "", "hash"}});
    t.append(lub::h5::Row{std::int64_t{0}, g.cases[0].hash});
  }
  try {
    read_existing(bare, g, false, lub::build_revision());
    ADD_FAILURE() << "rows without result columns were dropped silently";
  } catch (const lub::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("its 1 rows lack result columns of this build"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_existing(bare, g, false, lub::build_revision(), true).incompatible_rows, 1u);
  EXPECT_EQ(fs::last_write_time(path), before) << "the refused file was changed";
  const ResumeState consent = read_existing(path, smaller, false, lub::build_revision(), true);
  EXPECT_EQ(consent.other_rows, 2u);
  EXPECT_EQ(consent.done.size(), 2u);
  // A subset of the file's cases is no refusal: a grid that holds every case of the file.
  EXPECT_EQ(read_existing(path, g, false, lub::build_revision()).done.size(), 4u);
}

TEST_F(StudyFile, ResumeIntoAnExtendedGridKeepsEachCaseItsOwnSeries) {
  // A grid extended by an axis value renumbers its cases: the reused case's series must
  // follow its hash to its new name (it once kept the old name's, another case's, series).
  const Grid g = small_grid();
  const std::string path = file("x.h5");
  write_study(path, g, {fake(g, 2)}, false);
  const Grid wider = parse_grid(R"({
      "scene": "slider_crank.json",
      "set": {"/solver/rtol": 1e-6, "/simulation/steady": "auto"},
      "study": {"max_cycles": 2, "metric_cycles": 1, "channels": ["h_min"], "last_cycles": 1, "samples_per_cycle": 90},
      "grids": [{"name": "main", "axes": [{"name": "force_law", "values": ["frene_long", "ideal", "frene_short"]},
                                          {"name": "speed_rpm", "values": [5000, 500]}]},
                {"name": "extra", "cases": [{"/solver/rtol": 1e-7, "force_law": "ideal"}]}]})",
                                kScenes, "wider.json");
  int moved = -1;
  for (const Case& c : wider.cases)
    if (c.hash == g.cases[2].hash) moved = c.id;
  ASSERT_GE(moved, 0);
  ASSERT_NE(moved, 2);
  const ResumeState st = read_existing(path, wider, false, lub::build_revision());
  ASSERT_EQ(st.done.size(), 1u);
  ASSERT_EQ(st.done.count(moved), 1u);
  {
    StudyWriter w(path, wider, st.done, path);
    w.finalize();
  }
  const auto f = lub::h5::File::open(path);
  const std::string name = wider.cases[static_cast<std::size_t>(moved)].name;
  EXPECT_EQ(f.open_dataset("series/" + name + "/h_min").read_doubles(), fake(g, 2).series.data[1]);
  EXPECT_EQ(f.open_group("series/" + name).attribute_int64("case_id"), moved);
  EXPECT_EQ(f.open_group("series/" + name).attribute_string("hash"), g.cases[2].hash);
  EXPECT_FALSE(f.exists("series/" + g.cases[2].name));  // no series under the old name
}

TEST_F(StudyFile, KilledWriterLeavesAFileThatResumes) {
  const Grid g = small_grid();
  const std::string path = file("k.h5");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // Rows are written in batches: those flushed survive the kill, the one still held does
    // not (a killed sweep loses at most its last flush interval).
    StudyWriter w(path, g, {}, "", 3600.0);
    w.append(fake(g, 0));
    w.append(fake(g, 4));
    if (w.pending() != 2) ::_exit(3);
    w.flush();
    w.append(fake(g, 2));
    ::kill(::getpid(), SIGKILL);  // no close, no finalize
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  const ResumeState st = read_existing(path, g, false, lub::build_revision());
  EXPECT_EQ(st.done.size(), 2u);
  EXPECT_TRUE(st.done.count(0) && st.done.count(4));
  StudyWriter w(path, g, st.done, path);
  for (int id : {1, 2, 3}) w.append(fake(g, id));
  w.finalize();
  EXPECT_EQ(lub::h5::File::open(path).open_table("cases").rows(), 5u);
  EXPECT_TRUE(lub::h5::File::open(path).exists("series/case_0000/t"));
}

TEST_F(StudyFile, IncompleteStudyIsMarkedIncomplete) {
  const Grid g = small_grid();
  const std::string path = file("i.h5");
  StudyWriter w(path, g, {}, "");
  w.append(fake(g, 1));
  EXPECT_FALSE(w.complete());
  w.finalize();
  EXPECT_EQ(lub::h5::File::open(path).attribute_int64("complete"), 0);
}

TEST_F(StudyFile, ForeignOutputFileIsRefused) {
  const Grid g = small_grid();
  const std::string text = file("notes.h5"), other = file("other.h5");
  std::ofstream(text) << "not hdf5";
  try {
    read_existing(text, g, false, "r");
    FAIL() << "no error";
  } catch (const lub::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "-o " + text + ": the file exists and is not an HDF5 file (use --restart to overwrite it, or another -o)");
  }
  lub::h5::File::create(other).set_attribute("program", "lubsim");
  try {
    read_existing(other, g, false, "r");
    FAIL() << "no error";
  } catch (const lub::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "-o " + other + ": the file exists and is not a lubsweep study file (use --restart to overwrite it, or another -o)");
  }
}

TEST(SweepCase, RunsAScene) {
  const Grid g = small_grid();
  const CaseResult r = run_case(2, g.cases[2].scene, 7);  // frene_short, 5000 rpm, 2 cycles
  EXPECT_EQ(r.status, CaseStatus::ok) << r.message;
  EXPECT_EQ(r.case_id, 2);
  EXPECT_EQ(r.rank, 7);
  ASSERT_EQ(r.values.size(), result_fields().size());
  // A study reports steady metrics only for a steady cycle (two cycles of Frêne short are
  // none); counts, the periodicity measure and the solver's statistics always.
  const bool steady = has_orbit(r.classification);
  EXPECT_TRUE(steady || r.classification == CaseClass::drifting || r.classification == CaseClass::not_converged)
      << r.classification;
  const std::set<std::string> always = {"periodicity", "steady", "cycles_run",
                                        "safe_film_thickness_m", "newton_iterations",
                                        "transient_cycles", "periods_integrated"};
  const auto fields = result_fields();
  for (std::size_t i = 0; i < fields.size(); ++i) {
    SCOPED_TRACE(fields[i].name);
    if (fields[i].steady_metric && !steady) {
      EXPECT_TRUE(std::isnan(r.values[i]));
    }
    if (always.count(fields[i].name) || i >= lub::metric_fields().size() || (fields[i].steady_metric && steady)) {
      EXPECT_TRUE(std::isfinite(r.values[i]));
    }
  }
  // below_safe_film is an orbit's, and unknown where there is neither an orbit nor a film
  // that collapsed or drifts below (run_io.cpp).
  std::size_t below = 0;
  while (fields[below].name != "below_safe_film") ++below;
  if (steady) {
    EXPECT_TRUE(std::isfinite(r.values[below]));
  }
  if (r.classification == CaseClass::not_converged) {
    EXPECT_TRUE(std::isnan(r.values[below]));
  }
  // Unknown is NaN for every field, integers included (a writer of integers stores -1).
  std::size_t to_steady = 0;
  while (fields[to_steady].name != "cycles_to_steady") ++to_steady;
  EXPECT_EQ(std::isnan(r.values[to_steady]), r.classification != CaseClass::periodic) << r.values[to_steady];
  EXPECT_EQ(r.series.names, (std::vector<std::string>{"t", "h_min"}));
  // Only the last cycle is kept, sampled 90 times (both ends included).
  EXPECT_EQ(r.series.data[0].size(), 91u);
  // The same scene gives the same numbers (what makes -np 1 and -np 2 agree): parsed
  // afresh from the case's JSON, as every rank runs it.
  const CaseResult again = run_case(2, lub::parse_scene(json::parse(g.cases[2].scene)), 0);
  for (std::size_t i = 0; i < r.values.size(); ++i) {
    if (std::string(result_fields()[i].name) == "wall_time_s") continue;
    if (std::isnan(r.values[i]) && std::isnan(again.values[i])) continue;
    EXPECT_EQ(r.values[i], again.values[i]) << result_fields()[i].name;
  }
}

TEST(SweepCase, APeriodicCaseStoresItsPeriodicOrbitNotTheTransient) {
  // Frêne long at the reference case: shooting finds the orbit (|μ|max 0.998) while the
  // 40-cycle transient still turns about it, 0.4 c from cycle to cycle. The channels a
  // study stores are the orbit's: two metric cycles that repeat (e at crank angle 0 and
  // one period later within 1e-4 c: the orbit's residual and error bar are ~1e-5 c).
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = "frene_long";
  doc["simulation"]["steady"] = "auto";
  doc["simulation"]["max_cycles"] = 40;
  doc["simulation"]["metric_cycles"] = 2;
  doc["outputs"]["channels"] = json::array({json{{"name", "e_x"}, {"joint", "rod_slider"}, {"quantity", "e_x"}},
                                            json{{"name", "e_y"}, {"joint", "rod_slider"}, {"quantity", "e_y"}}});
  doc["outputs"]["last_cycles"] = 2;
  doc["outputs"]["sample_interval_s"] = 0.012 / 120;  // 120 samples a cycle: one at every 3° of crank
  const CaseResult r = run_case(0, lub::parse_scene(doc), 0);
  ASSERT_EQ(r.status, CaseStatus::ok) << r.message;
  ASSERT_EQ(r.classification, CaseClass::periodic) << r.message;
  ASSERT_EQ(r.series.names, (std::vector<std::string>{"t", "e_x", "e_y"}));
  const std::vector<double>& t = r.series.data[0];
  const std::vector<double>& ex = r.series.data[1];
  const std::vector<double>& ey = r.series.data[2];
  ASSERT_GE(t.size(), 3u);
  const double period = 0.012, c = 5e-4;  // 5000 rpm; 0.5 mm
  EXPECT_NEAR(t.back() - t.front(), 2 * period, 1e-9) << "two metric cycles";
  std::size_t k = 0;  // the sample one period after the first
  while (k < t.size() && t[k] < t.front() + period - 1e-9) ++k;
  ASSERT_LT(k, t.size());
  EXPECT_NEAR(t[k] - t.front(), period, 1e-9);
  EXPECT_LT(std::hypot(ex[k] - ex[0], ey[k] - ey[0]), 1e-4 * c) << "the orbit closes after a period";
}

TEST(SweepCase, FailuresAreValues) {
  const CaseResult bad = run_case(1, "{not json", 0);
  EXPECT_EQ(bad.status, CaseStatus::error);
  EXPECT_EQ(bad.classification, CaseClass::error);
  EXPECT_FALSE(bad.message.empty());
  EXPECT_TRUE(std::isnan(bad.values[0]));
  const CaseResult invalid = run_case(1, R"({"bodies": []})", 0);
  EXPECT_EQ(invalid.status, CaseStatus::invalid_scene);
  EXPECT_EQ(invalid.classification, CaseClass::invalid_scene);
  EXPECT_EQ(invalid.message.substr(0, 7), "bodies ");
}

// A case's status and classification are the core's names (RunStatus, SteadyClass) and
// the sweep's own two, from one table each: what the study file holds and resume reads back.
TEST(SweepCase, OutcomeNamesAreTheCoresAndTheSweepsTwo) {
  std::vector<std::string> status = lub::names_of<lub::RunStatus>();
  status.insert(status.end(), {"invalid_scene", "error"});
  EXPECT_EQ(lub::names_of<CaseStatus>(), status);
  std::vector<std::string> cls = lub::names_of<lub::SteadyClass>();
  cls.insert(cls.end(), status.begin() + 1, status.end());  // ok has no classification of its own
  EXPECT_EQ(lub::names_of<CaseClass>(), cls);
  for (const auto& [k, name] : lub::NameTable<lub::SteadyClass>::entries) {
    EXPECT_EQ(lub::name_of(case_class(k)), name);
    EXPECT_EQ(has_orbit(case_class(k)), lub::has_orbit(k)) << name;
  }
  for (const auto& [s, name] : lub::NameTable<lub::RunStatus>::entries) EXPECT_EQ(lub::name_of(case_status(s)), name);
  for (const auto& [s, name] : lub::NameTable<CaseStatus>::entries) {
    if (s != CaseStatus::ok) {
      EXPECT_EQ(lub::name_of(*case_class(s)), name);
    }
  }
  EXPECT_FALSE(case_class(CaseStatus::ok));
  EXPECT_TRUE(ran(CaseClass::budget_exceeded) && ran(CaseClass::drifting));
  EXPECT_FALSE(ran(CaseClass::invalid_scene) || ran(CaseClass::error));
  // A message naming no status is refused, not misread.
  const Grid g = small_grid();
  json m = json::from_msgpack(encode(fake(g, 1)));
  m["status"] = "fine";
  const std::vector<std::uint8_t> bytes = json::to_msgpack(m);
  try {
    decode(std::string(bytes.begin(), bytes.end()));
    FAIL() << "an unknown status was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("\"status\" = \"fine\": not one of ok, film_collapse"), std::string::npos)
        << e.what();
  }
}

TEST(SweepCase, EncodeDecodeRoundTrip) {
  const Grid g = small_grid();
  CaseResult r = fake(g, 4, CaseStatus::solver_failure);
  r.values[1] = std::nan("");
  const CaseResult d = decode(encode(r));
  EXPECT_EQ(d.case_id, 4);
  EXPECT_EQ(d.rank, r.rank);
  EXPECT_EQ(d.status, r.status);
  EXPECT_EQ(d.classification, CaseClass::solver_failure);
  EXPECT_EQ(d.message, r.message);
  EXPECT_EQ(d.revision, r.revision);
  ASSERT_EQ(d.values.size(), r.values.size());
  EXPECT_TRUE(std::isnan(d.values[1]));
  EXPECT_EQ(d.values[2], r.values[2]);
  EXPECT_EQ(d.series.names, r.series.names);
  EXPECT_EQ(d.series.units, r.series.units);
  EXPECT_EQ(d.series.data, r.series.data);
  std::string cut = encode(r);
  cut.resize(cut.size() - 3);
  EXPECT_THROW(decode(cut), std::runtime_error);
  EXPECT_THROW(decode("short"), std::runtime_error);
}

TEST(SweepProgress, LineAndEta) {
  const Grid g = small_grid();
  Progress p(5, 1, 0);  // one case already in the file
  CaseResult r = fake(g, 2);
  std::string line = p.record(g.cases[2], r, 2.0);
  EXPECT_EQ(line.substr(0, 17), "[2/5] case_0002 o");
  EXPECT_NE(line.find("frene_short"), std::string::npos);
  EXPECT_NE(line.find("0 failed"), std::string::npos);
  EXPECT_NEAR(p.eta_s(2.0), 6.0, 1e-12);  // 3 left at 2 s per case
  r.status = CaseStatus::film_collapse;
  line = p.record(g.cases[3], r, 4.0);
  EXPECT_NE(line.find("1 failed"), std::string::npos);
  EXPECT_EQ(format_duration(0.5), "0.50 s");
  EXPECT_EQ(format_duration(185), "3 min 05 s");
  EXPECT_EQ(format_duration(7300), "2 h 01 min");
}

TEST(SweepOptions, CommandLine) {
  Options o;
  bool help = false;
  std::string text;
  EXPECT_FALSE(parse_options({"g.json", "-o", "s.h5", "--retry-failed", "-q"}, o, help, text));
  EXPECT_EQ(o.grid, "g.json");
  EXPECT_EQ(o.output, "s.h5");
  EXPECT_TRUE(o.retry_failed && o.quiet);
  EXPECT_FALSE(o.drop_other_cases);
  Options d;
  EXPECT_FALSE(parse_options({"g.json", "-o", "s.h5", "--drop-other-cases"}, d, help, text));
  EXPECT_TRUE(d.drop_other_cases);
  Options e;
  EXPECT_EQ(*parse_options({"g.json"}, e, help, text), "no output file given (-o STUDY.h5)");
  Options c;
  EXPECT_FALSE(parse_options({"g.json", "--check"}, c, help, text));
  Options u;
  EXPECT_EQ(*parse_options({"g.json", "-o", "x", "--fast"}, u, help, text), "unknown option --fast");
  Options h;
  EXPECT_FALSE(parse_options({"--help"}, h, help, text));
  EXPECT_TRUE(help);
  // CLI11's generated help: every option with its value's name and its description, and
  // the exit statuses.
  for (const char* line : {"-h,--help                   print this text and exit",
                           "-o,--output STUDY.h5        the study file (required)",
                           "--restart                   ignore an existing output file",
                           "--drop-other-cases          resume, dropping the file's rows",
                           "--retry-failed              run again the cases the file records as not ok",
                           "--check                     validate the grid and list its cases",
                           "--strict                    a plausibility warning",
                           "--summary STUDY.h5          print the study's table and exit",
                           "--no-summary                no table at the end",
                           "-q,--quiet                  no progress lines on stderr",
                           "--version                   print the version", "grid GRID.json",
                           "Exit status: 0 the study is complete", "130/143 interrupted"})
    EXPECT_NE(text.find(line), std::string::npos) << "the help lacks \"" << line << "\":\n" << text;
  Options short_help;
  EXPECT_FALSE(parse_options({"g.json", "-h"}, short_help, help, text));
  EXPECT_TRUE(help) << "-h anywhere asks for the help";
  Options r;
  EXPECT_EQ(*parse_options({"g.json", "-o", "x", "--restart", "--retry-failed"}, r, help, text),
            "--restart and --retry-failed exclude each other");
  EXPECT_FALSE(help) << "help is reset by every parse";
  Options two;
  EXPECT_EQ(*parse_options({"a.json", "-o", "x", "b.json"}, two, help, text), "more than one grid given (a.json, b.json)");
  Options missing;
  EXPECT_NE(parse_options({"g.json", "-o"}, missing, help, text)->find("--output"), std::string::npos);
  Options forms;
  EXPECT_FALSE(parse_options({"--output=s.h5", "g.json", "--no-summary", "--quiet"}, forms, help, text));
  EXPECT_EQ(forms.output, "s.h5");
  EXPECT_FALSE(forms.summary);
  EXPECT_TRUE(forms.quiet);
  Options v;
  EXPECT_FALSE(parse_options({"--version"}, v, help, text));
  EXPECT_TRUE(help);
  EXPECT_EQ(text.substr(0, 9), "lubsweep ");
}

TEST(SweepOptions, TheReportSubcommandTakesAStudyAnOutputAndABaseline) {
  using lub::sweep::Options;
  using lub::sweep::parse_options;
  bool help = false;
  std::string text;
  Options o;
  EXPECT_FALSE(parse_options({"report", "s.h5", "-o", "r.html", "--baseline", "b.csv"}, o, help, text));
  EXPECT_TRUE(o.report);
  EXPECT_EQ(o.report_study, "s.h5");
  EXPECT_EQ(o.report_output, "r.html");
  EXPECT_EQ(o.report_baseline, "b.csv");
  EXPECT_TRUE(o.grid.empty() && o.output.empty());
  Options plain;
  EXPECT_FALSE(parse_options({"g.json", "-o", "s.h5"}, plain, help, text));
  EXPECT_FALSE(plain.report);
  Options no_out;
  EXPECT_NE(parse_options({"report", "s.h5"}, no_out, help, text)->find("--output"), std::string::npos);
  Options extra;  // an option of the main command given to the subcommand: named, no crash
  EXPECT_EQ(*parse_options({"report", "s.h5", "-o", "r.html", "--summary", "x"}, extra, help, text),
            "report: unknown option --summary");
  Options two;
  EXPECT_EQ(*parse_options({"report", "a.h5", "b.h5", "-o", "r.html"}, two, help, text),
            "report: more than one study given (a.h5, b.h5)");
  Options h;
  EXPECT_FALSE(parse_options({"report", "--help"}, h, help, text));
  EXPECT_TRUE(help);
  EXPECT_NE(text.find("--baseline CSV"), std::string::npos) << text;  // the subcommand's own help
  Options top;
  EXPECT_FALSE(parse_options({"--help"}, top, help, text));
  EXPECT_NE(text.find("lubsweep report STUDY.h5 -o report.html"), std::string::npos) << text;
}

TEST_F(StudyFile, OutputLockRefusesASecondHolderNamingTheFirst) {
  const std::string path = file("s.h5");
  {
    lub::sweep::OutputLock first(path);
    EXPECT_TRUE(first.held());
    try {
      lub::sweep::OutputLock second(path);
      FAIL() << "a second lock was granted";
    } catch (const lub::InputError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("the file is in use by another sweep (pid " + std::to_string(::getpid())), std::string::npos)
          << msg;
    }
    EXPECT_TRUE(fs::exists(path + ".lock"));
  }
  EXPECT_FALSE(fs::exists(path + ".lock"));  // removed when released
  { std::ofstream stale(path + ".lock"); stale << "pid 1 on host gone\n"; }  // a killed sweep's
  lub::sweep::OutputLock again(path);  // not locked by anyone: taken over
  EXPECT_TRUE(again.held());
}

TEST(OutputPath, RefusedWithTheRule) {
  EXPECT_EQ(lub::output_path_problem("x/"), std::optional<std::string>("-o x/: must name a file, not a directory (the path ends in '/')"));
  EXPECT_NE(lub::output_path_problem("/")->find("must name a file"), std::string::npos);
  EXPECT_NE(lub::output_path_problem(".")->find("existing directory"), std::string::npos);
  EXPECT_NE(lub::output_path_problem("/no/such/dir/s.h5")->find("its directory /no/such/dir does not exist"), std::string::npos);
  EXPECT_NE(lub::output_path_problem("")->find("empty"), std::string::npos);
  EXPECT_FALSE(lub::output_path_problem(::testing::TempDir() + "/fine.h5").has_value());
}
