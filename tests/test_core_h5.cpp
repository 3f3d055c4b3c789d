// Tests of the HDF5 wrapper lub::h5: files, groups, attributes, datasets, tables
// (append, reopen, resume, survival of a killed writer) and dimension scales.
#include "lub/io/h5.hpp"
#include "lub/run/run_io.hpp"
#include "fixtures/temp_dir_test.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace lub::h5;

namespace {

/// A fresh directory per test, removed afterwards.
class H5Test : public lub_test::TempDirTest {
 protected:
  H5Test() : TempDirTest("lub_h5_") {}
};

/// Message of the runtime_error thrown by f ("" if none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

std::vector<Column> case_columns() {
  return {{"case_id", ColumnType::Int64, ""},
          {"hash", ColumnType::String, ""},
          {"clearance_m", ColumnType::Float64, "m"},
          {"min_film_thickness_m", ColumnType::Float64, "m"}};
}

}  // namespace

// ---------------------------------------------------------------------------------
// Files and errors

TEST_F(H5Test, CreateOpenAndReopen) {
  const std::string path = file("a.h5");
  {
    File f = File::create(path);
    EXPECT_TRUE(f.valid());
    EXPECT_EQ(f.filename(), path);
    EXPECT_EQ(f.path(), "/");
    f.set_attribute("program", "lubsim");
    f.flush();
  }
  {
    File f = File::open(path);
    EXPECT_EQ(f.attribute_string("program"), "lubsim");
  }
  {
    File f = File::open(path, File::Mode::ReadWrite);
    f.set_attribute("program", "lubsim2");
    f.close();
    EXPECT_FALSE(f.valid());
    f.close();  // closing twice is harmless
  }
  EXPECT_EQ(File::open(path).attribute_string("program"), "lubsim2");
  // create truncates
  { File f = File::create(path); }
  EXPECT_FALSE(File::open(path).has_attribute("program"));
}

TEST_F(H5Test, ErrorsCarryPathAndHdf5MessageAndPrintNothing) {
  const std::string missing = file("missing.h5");
  ::testing::internal::CaptureStderr();
  const std::string msg = error_of([&] { File::open(missing); });
  const std::string msg_rw = error_of([&] { File::open(missing, File::Mode::ReadWrite); });
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(msg.find(missing), std::string::npos) << msg;
  EXPECT_NE(msg.find("read-only"), std::string::npos) << msg;
  EXPECT_NE(msg.find("HDF5:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("H5Fopen"), std::string::npos) << msg;
  EXPECT_NE(msg_rw.find("read-write"), std::string::npos) << msg_rw;
  EXPECT_EQ(printed, "");

  // Not an HDF5 file.
  const std::string junk = file("junk.h5");
  std::ofstream(junk) << "not hdf5\n";
  EXPECT_NE(error_of([&] { File::open(junk); }).find(junk), std::string::npos);

  // Object errors name file and object path.
  File f = File::create(file("b.h5"));
  Group g = f.require_group("/series");
  const std::string m2 = error_of([&] { g.open_dataset("nope"); });
  EXPECT_NE(m2.find("b.h5:/series/nope"), std::string::npos) << m2;
  const std::string m3 = error_of([&] { g.attribute_double("nope"); });
  EXPECT_NE(m3.find("b.h5:/series"), std::string::npos) << m3;
  EXPECT_NE(m3.find("no attribute 'nope'"), std::string::npos) << m3;
}

TEST_F(H5Test, ReadOnlyFileRefusesWrites) {
  const std::string path = file("ro.h5");
  { File::create(path).require_group("g"); }
  File f = File::open(path);
  EXPECT_THROW(f.set_attribute("x", 1.0), std::runtime_error);
  EXPECT_THROW(f.require_group("h"), std::runtime_error);
  EXPECT_THROW(f.write_dataset("d", std::vector<double>{1.0}, "m"), std::runtime_error);
  EXPECT_NO_THROW(f.open_group("g"));
}

TEST_F(H5Test, MoveOnlyHandles) {
  File f = File::create(file("m.h5"));
  Group g = f.require_group("g");
  const Id id = g.id();
  Group h = std::move(g);
  EXPECT_FALSE(g.valid());  // NOLINT(bugprone-use-after-move): moved-from is empty
  EXPECT_EQ(h.id(), id);
  Group k = f.require_group("k");
  k = std::move(h);  // closes k's old handle
  EXPECT_EQ(k.path(), "/g");
  File f2 = std::move(f);
  EXPECT_FALSE(f.valid());  // NOLINT(bugprone-use-after-move)
  EXPECT_TRUE(f2.exists("/k"));
  static_assert(!std::is_copy_constructible_v<File>);
  static_assert(!std::is_copy_assignable_v<Dataset>);
  static_assert(std::is_nothrow_move_constructible_v<Table>);
}

// ---------------------------------------------------------------------------------
// Groups

TEST_F(H5Test, GroupsCreateOrOpenWithIntermediates) {
  File f = File::create(file("g.h5"));
  EXPECT_FALSE(f.exists("/series"));
  Group c = f.require_group("/series/case_0007");
  EXPECT_EQ(c.path(), "/series/case_0007");
  EXPECT_TRUE(f.exists("/series"));
  EXPECT_TRUE(f.exists("series/case_0007"));
  EXPECT_FALSE(f.exists("/series/case_0008"));
  EXPECT_FALSE(f.exists("/nothing/deeper/still"));

  Group again = f.require_group("/series/case_0007");  // opens
  again.set_attribute("k", std::int64_t{7});
  EXPECT_EQ(c.attribute_int64("k"), 7);

  Group series = f.open_group("series");
  Group c8 = series.require_group("case_0008");  // relative to a group
  EXPECT_EQ(c8.path(), "/series/case_0008");
  EXPECT_EQ(series.list(), (std::vector<std::string>{"case_0007", "case_0008"}));
  EXPECT_THROW(f.open_group("/absent"), std::runtime_error);

  f.write_dataset("/series/t", std::vector<double>{0.0}, "s");
  EXPECT_THROW(f.require_group("/series/t"), std::runtime_error);  // a dataset
  EXPECT_FALSE(f.exists("/series/t/x"));
}

// ---------------------------------------------------------------------------------
// Attributes

TEST_F(H5Test, AttributesRoundTripOnRootGroupAndDataset) {
  const std::string path = file("attr.h5");
  {
    File f = File::create(path);
    Group g = f.require_group("meta");
    Dataset d = f.write_dataset("x", std::vector<double>{1, 2, 3}, "m");
    for (Object* o : std::initializer_list<Object*>{&f, &g, &d}) {
      o->set_attribute("s", std::string("clearance μm ✓"));
      o->set_attribute("c", "literal");
      o->set_attribute("empty", "");
      o->set_attribute("d", 0.1);
      o->set_attribute("i", std::int64_t{-1234567890123});
      o->set_attribute("n", 42);           // int → int64
      o->set_attribute("u", std::size_t{5});  // unsigned → int64
      o->set_attribute("vd", std::vector<double>{1.5, -2.0, 3e-9});
      o->set_attribute("vs", std::vector<std::string>{"a", "", "γ"});
      o->set_attribute("vd0", std::vector<double>{});
      o->set_attribute("vs0", std::vector<std::string>{});
    }
  }
  File f = File::open(path);
  Group g = f.open_group("meta");
  Dataset d = f.open_dataset("x");
  for (const Object* o : std::initializer_list<const Object*>{&f, &g, &d}) {
    EXPECT_TRUE(o->has_attribute("s"));
    EXPECT_FALSE(o->has_attribute("absent"));
    EXPECT_EQ(o->attribute_string("s"), "clearance μm ✓");
    EXPECT_EQ(o->attribute_string("c"), "literal");
    EXPECT_EQ(o->attribute_string("empty"), "");
    EXPECT_EQ(o->attribute_double("d"), 0.1);
    EXPECT_EQ(o->attribute_int64("i"), -1234567890123);
    EXPECT_EQ(o->attribute_int64("n"), 42);
    EXPECT_EQ(o->attribute_double("n"), 42.0);  // integer reads as double
    EXPECT_EQ(o->attribute_int64("u"), 5);
    EXPECT_EQ(o->attribute_doubles("vd"), (std::vector<double>{1.5, -2.0, 3e-9}));
    EXPECT_EQ(o->attribute_doubles("d"), (std::vector<double>{0.1}));
    EXPECT_EQ(o->attribute_strings("vs"), (std::vector<std::string>{"a", "", "γ"}));
    EXPECT_EQ(o->attribute_strings("s"), (std::vector<std::string>{"clearance μm ✓"}));
    EXPECT_TRUE(o->attribute_doubles("vd0").empty());
    EXPECT_TRUE(o->attribute_strings("vs0").empty());
    // wrong class / shape
    EXPECT_THROW(o->attribute_int64("d"), std::runtime_error);
    EXPECT_THROW(o->attribute_double("s"), std::runtime_error);
    EXPECT_THROW(o->attribute_string("d"), std::runtime_error);
    EXPECT_THROW(o->attribute_double("vd"), std::runtime_error);
    EXPECT_THROW(o->attribute_string("vs"), std::runtime_error);
    EXPECT_THROW(o->attribute_string("absent"), std::runtime_error);
  }
  const std::vector<std::string> names = g.attribute_names();
  EXPECT_EQ(names.size(), 11u);
  EXPECT_EQ(names.front(), "c");
}

TEST_F(H5Test, AttributesOverwriteEvenWithAnotherType) {
  File f = File::create(file("ow.h5"));
  f.set_attribute("a", 1.0);
  f.set_attribute("a", 2.0);
  EXPECT_EQ(f.attribute_double("a"), 2.0);
  f.set_attribute("a", "now a string");
  EXPECT_EQ(f.attribute_string("a"), "now a string");
  f.set_attribute("a", std::vector<std::string>{"x", "y"});
  EXPECT_EQ(f.attribute_strings("a").size(), 2u);
  f.remove_attribute("a");
  EXPECT_FALSE(f.has_attribute("a"));
  EXPECT_THROW(f.remove_attribute("a"), std::runtime_error);
}

// ---------------------------------------------------------------------------------
// Datasets

TEST_F(H5Test, SeriesRoundTripWithUnitsAndCompression) {
  const std::string path = file("series.h5");
  std::vector<double> shortv{0.0, 1e-3, -2.5};
  std::vector<double> longv(200000);
  for (std::size_t i = 0; i < longv.size(); ++i) longv[i] = static_cast<double>(i % 100) * 0.5;
  {
    File f = File::create(path);
    Dataset s = f.write_dataset("/series/case_0001/t", shortv, "s");
    EXPECT_EQ(s.path(), "/series/case_0001/t");
    EXPECT_EQ(s.units(), "s");
    f.write_dataset("/series/case_0001/x", longv, "m");
    f.write_dataset("/series/case_0001/raw", longv.data(), longv.size(), "m",
                    WriteOptions{0, 0, 0});
    f.write_dataset("/empty", std::vector<double>{}, "1");
    EXPECT_THROW(f.write_dataset("/series/case_0001/t", shortv, "s"), std::runtime_error);
  }
  File f = File::open(path);
  EXPECT_EQ(f.open_dataset("/series/case_0001/t").read_doubles(), shortv);
  Dataset x = f.open_dataset("series/case_0001/x");
  EXPECT_EQ(x.units(), "m");
  EXPECT_EQ(x.attribute_string("units"), "m");
  EXPECT_EQ(x.shape(), (std::vector<std::size_t>{longv.size()}));
  EXPECT_EQ(x.read_doubles(), longv);
  EXPECT_EQ(f.open_dataset("/series/case_0001/raw").read_doubles(), longv);
  EXPECT_TRUE(f.open_dataset("/empty").read_doubles().empty());
  EXPECT_EQ(f.open_dataset("/empty").size(), 0u);
  EXPECT_THROW(x.read_int64s(), std::runtime_error);  // not integers
  // compressed: the two raw copies of 1.6 MB dominate; the compressed one is tiny
  EXPECT_LT(fs::file_size(path), 2 * longv.size() * sizeof(double) - 100000);
}

TEST_F(H5Test, MultiDimensionalAndIntegerDatasets) {
  File f = File::create(file("nd.h5"));
  std::vector<double> grid(6 * 5000);
  for (std::size_t i = 0; i < grid.size(); ++i) grid[i] = static_cast<double>(i);
  Dataset g = f.write_dataset("grid", grid, {6, 5000}, "Pa");  // compressed, chunked 2-D
  EXPECT_EQ(g.shape(), (std::vector<std::size_t>{6, 5000}));
  EXPECT_EQ(g.read_doubles(), grid);
  EXPECT_THROW(f.write_dataset("bad", grid, {7, 5000}, "Pa"), std::runtime_error);
  Dataset small = f.write_dataset("small", std::vector<double>{1, 2, 3, 4, 5, 6}, {2, 3}, "1");
  EXPECT_EQ(small.read_doubles(), (std::vector<double>{1, 2, 3, 4, 5, 6}));

  std::vector<std::int64_t> iv{1, -2, 1LL << 40};
  Dataset i = f.write_dataset("ids", iv, "");
  EXPECT_EQ(i.read_int64s(), iv);
  EXPECT_EQ(i.read_doubles(), (std::vector<double>{1.0, -2.0, 1099511627776.0}));
}

// ---------------------------------------------------------------------------------
// Tables

TEST_F(H5Test, TableAppendAndReadColumns) {
  const std::string path = file("study.h5");
  File f = File::create(path);
  Table t = f.create_table("/cases", case_columns());
  EXPECT_EQ(t.rows(), 0u);
  EXPECT_TRUE(t.read_strings("hash").empty());
  EXPECT_TRUE(t.read_doubles("clearance_m").empty());
  EXPECT_EQ(t.column_index("hash"), 1u);
  EXPECT_TRUE(t.has_column("clearance_m"));
  EXPECT_FALSE(t.has_column("nope"));
  EXPECT_THROW(t.column_index("nope"), std::runtime_error);

  t.append(Row{std::int64_t{0}, std::string("h0"), 1e-4, 2e-6});
  t.append({Row{std::int64_t{1}, std::string("h1"), 2e-4, std::int64_t{0}},  // int → double
            Row{std::int64_t{2}, std::string("ħ2"), 3e-4, 4e-6}});
  t.append(std::vector<Row>{});  // no-op
  EXPECT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.read_int64s("case_id"), (std::vector<std::int64_t>{0, 1, 2}));
  EXPECT_EQ(t.read_strings("hash"), (std::vector<std::string>{"h0", "h1", "ħ2"}));
  EXPECT_EQ(t.read_doubles("clearance_m"), (std::vector<double>{1e-4, 2e-4, 3e-4}));
  EXPECT_EQ(t.read_doubles("min_film_thickness_m"), (std::vector<double>{2e-6, 0.0, 4e-6}));
  EXPECT_EQ(t.read_doubles("case_id"), (std::vector<double>{0, 1, 2}));  // int64 → double
  EXPECT_THROW(t.read_doubles("hash"), std::runtime_error);
  EXPECT_THROW(t.read_strings("case_id"), std::runtime_error);
  EXPECT_THROW(t.read_int64s("clearance_m"), std::runtime_error);

  // Attributes describing the columns.
  EXPECT_EQ(t.attribute_strings("columns"),
            (std::vector<std::string>{"case_id", "hash", "clearance_m", "min_film_thickness_m"}));
  EXPECT_EQ(t.attribute_strings("units"), (std::vector<std::string>{"", "", "m", "m"}));
  t.set_attribute("description", "one row per finished case");

  // netCDF-4 style: one dataset per column, the first the dimension scale of the others.
  EXPECT_TRUE(t.column("case_id").is_scale());
  EXPECT_EQ(t.column("case_id").attribute_string("NAME"), "case_id");
  EXPECT_TRUE(t.column("hash").has_attribute("DIMENSION_LIST"));
  EXPECT_EQ(t.column("clearance_m").units(), "m");
  EXPECT_FALSE(t.column("hash").has_attribute("units"));  // strings have no unit

  // Bad rows append nothing.
  EXPECT_THROW(t.append(Row{std::int64_t{3}, std::string("h3"), 1.0}), std::runtime_error);
  EXPECT_THROW(t.append(Row{3.0, std::string("h3"), 1.0, 1.0}), std::runtime_error);
  const std::string msg = error_of([&] {
    t.append({Row{std::int64_t{3}, std::string("h3"), 1.0, 1.0},
              Row{std::int64_t{4}, 5.0, 1.0, 1.0}});
  });
  EXPECT_NE(msg.find("row 1, column 'hash'"), std::string::npos) << msg;
  EXPECT_EQ(t.rows(), 3u);

  // Many rows across chunks.
  std::vector<Row> batch;
  for (std::int64_t i = 3; i < 500; ++i) {
    batch.push_back({i, "h" + std::to_string(i), 1e-4, 1e-6 * static_cast<double>(i)});
  }
  t.append(batch);
  EXPECT_EQ(t.rows(), 500u);
  EXPECT_EQ(t.read_strings("hash")[499], "h499");
}

TEST_F(H5Test, TableRejectsBadColumns) {
  File f = File::create(file("bad.h5"));
  EXPECT_THROW(f.create_table("t0", {}), std::runtime_error);
  EXPECT_THROW(f.create_table("t1", {{"a", ColumnType::Int64, ""}, {"a", ColumnType::Int64, ""}}),
               std::runtime_error);
  EXPECT_THROW(f.create_table("t2", {{"", ColumnType::Int64, ""}}), std::runtime_error);
  f.create_table("t", {{"a", ColumnType::Int64, ""}});
  EXPECT_THROW(f.create_table("t", {{"a", ColumnType::Int64, ""}}), std::runtime_error);
  f.write_dataset("d", std::vector<double>{1.0}, "m");
  EXPECT_THROW(f.open_table("d"), std::runtime_error);  // not compound
  EXPECT_THROW(f.open_table("absent"), std::runtime_error);
}

TEST_F(H5Test, TableReopenAndResume) {
  const std::string path = file("resume.h5");
  {
    File f = File::create(path);
    Table t = f.create_table("cases", case_columns(), 4);
    t.append({Row{std::int64_t{0}, std::string("aa"), 1.0, 2.0},
              Row{std::int64_t{1}, std::string("bb"), 3.0, 4.0}});
  }
  {
    File f = File::open(path);
    Table t = f.open_table("/cases");
    ASSERT_EQ(t.columns().size(), 4u);
    EXPECT_EQ(t.columns()[1].name, "hash");
    EXPECT_EQ(t.columns()[1].type, ColumnType::String);
    EXPECT_EQ(t.columns()[0].type, ColumnType::Int64);
    EXPECT_EQ(t.columns()[3].type, ColumnType::Float64);
    EXPECT_EQ(t.columns()[3].units, "m");
    EXPECT_EQ(t.rows(), 2u);
    EXPECT_THROW(t.append(Row{std::int64_t{2}, std::string("cc"), 5.0, 6.0}),
                 std::runtime_error);  // read-only
  }
  {
    File f = File::open(path, File::Mode::ReadWrite);
    Table t = f.open_table("cases");
    const std::vector<std::string> done = t.read_strings("hash");
    EXPECT_EQ(done, (std::vector<std::string>{"aa", "bb"}));
    t.append(Row{std::int64_t{2}, std::string("cc"), 5.0, 6.0});
  }
  File f = File::open(path);
  Table t = f.open_table("cases");
  EXPECT_EQ(t.read_strings("hash"), (std::vector<std::string>{"aa", "bb", "cc"}));
  EXPECT_EQ(t.read_doubles("min_film_thickness_m"), (std::vector<double>{2.0, 4.0, 6.0}));
}

TEST_F(H5Test, TableSurvivesKilledWriter) {
  const std::string path = file("killed.h5");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // Child: write, append twice, then die without closing anything.
    try {
      File f = File::create(path);
      f.set_attribute("program", "lubsweep");
      f.write_dataset("/axes/clearance_m", std::vector<double>{1e-4, 2e-4}, "m");
      Table t = f.create_table("/cases", case_columns());
      t.append(Row{std::int64_t{0}, std::string("h0"), 1e-4, 1e-6});
      t.append({Row{std::int64_t{1}, std::string("h1"), 2e-4, 2e-6},
                Row{std::int64_t{2}, std::string("h2"), 3e-4, 3e-6}});
      std::raise(SIGKILL);
    } catch (...) {
    }
    ::_exit(3);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "child exited with " << WEXITSTATUS(status);
  ASSERT_EQ(WTERMSIG(status), SIGKILL);

  {
    File f = File::open(path);
    EXPECT_EQ(f.attribute_string("program"), "lubsweep");
    EXPECT_EQ(f.open_dataset("/axes/clearance_m").read_doubles(),
              (std::vector<double>{1e-4, 2e-4}));
    Table t = f.open_table("/cases");
    EXPECT_EQ(t.rows(), 3u);
    EXPECT_EQ(t.read_strings("hash"), (std::vector<std::string>{"h0", "h1", "h2"}));
  }
  // ... and it can be resumed.
  File f = File::open(path, File::Mode::ReadWrite);
  Table t = f.open_table("/cases");
  t.append(Row{std::int64_t{3}, std::string("h3"), 4e-4, 4e-6});
  EXPECT_EQ(t.read_int64s("case_id"), (std::vector<std::int64_t>{0, 1, 2, 3}));
}

// ---------------------------------------------------------------------------------
// Dimension scales

TEST_F(H5Test, DimensionScales) {
  File f = File::create(file("dims.h5"));
  Dataset c = f.write_dataset("/axes/clearance_m", std::vector<double>{1e-4, 2e-4}, "m");
  Dataset mu = f.write_dataset("/axes/viscosity_Pa_s", std::vector<double>{0.01, 0.02, 0.03},
                               "Pa s");
  Dataset h = f.write_dataset("/grid/min_film_thickness_m",
                              std::vector<double>{1, 2, 3, 4, 5, 6}, {2, 3}, "m");
  EXPECT_FALSE(c.is_scale());
  c.make_scale("clearance_m");
  EXPECT_TRUE(c.is_scale());
  h.attach_scale(c, 0, "clearance_m");
  h.attach_scale(mu, 1);  // made a scale on the fly
  EXPECT_TRUE(mu.is_scale());
  EXPECT_TRUE(h.has_attribute("DIMENSION_LIST"));
  EXPECT_TRUE(h.has_attribute("DIMENSION_LABELS"));
  EXPECT_EQ(c.attribute_string("CLASS"), "DIMENSION_SCALE");  // fixed-length string
  EXPECT_EQ(c.attribute_string("NAME"), "clearance_m");
  EXPECT_THROW(h.attach_scale(c, 2), std::runtime_error);  // no such dimension
  EXPECT_THROW(c.attach_scale(h, 0), std::runtime_error);  // scale not 1-D
}

// ---------------------------------------------------------------------------------
// Run file layout: netCDF-4 style, so xarray indexes /series by t and /cycles by cycle.

TEST_F(H5Test, RunFileSeriesOnTimeAndCyclesAsColumns) {
  lub::RunResult r;
  r.series.names = {"t", "eps", "slider_a"};
  r.series.units = {"s", "1", "m/s^2"};
  r.series.data = {{0.0, 1e-5, 2e-5}, {0.1, 0.2, 0.3}, {1.0, 2.0, 3.0}};
  r.cycles.resize(2);
  r.cycles[1].min_film_thickness_m = 1e-5;
  const std::string scene =
      R"({"outputs": {"channels": [{"name": "eps", "joint": "rod_slider", "quantity": "eps"},
                                   {"name": "slider_a", "body": "slider", "quantity": "ax"}]}})";
  const std::string path = file("run.h5");
  lub::write_run_file(path, scene, "test", r);
  File f = File::open(path);
  EXPECT_EQ(f.attribute_string("format"), lub::kRunFormat);
  EXPECT_TRUE(f.open_dataset("series/t").is_scale());
  EXPECT_EQ(f.open_dataset("series/t").attribute_string("long_name"), "time");
  const Dataset a = f.open_dataset("series/slider_a");
  EXPECT_TRUE(a.has_attribute("DIMENSION_LIST"));
  EXPECT_EQ(a.units(), "m s-2");  // CF style
  EXPECT_EQ(a.attribute_string("long_name"), "ax of body slider: x acceleration of the centre of mass");
  EXPECT_EQ(f.open_dataset("series/eps").attribute_string("long_name"), "eps of joint rod_slider: eccentricity ratio |e|/c");
  const Table c = f.open_table("cycles");
  EXPECT_EQ(c.rows(), 2u);
  EXPECT_EQ(c.read_int64s("cycle"), (std::vector<std::int64_t>{1, 2}));
  EXPECT_TRUE(c.column("cycle").is_scale());
  EXPECT_EQ(c.read_doubles("min_film_thickness_m")[1], 1e-5);
  EXPECT_EQ(c.column("peak_acceleration_m_s2").units(), "m s-2");
}

TEST(CfUnits, MapsTheEngineUnits) {
  EXPECT_EQ(lub::cf_units("m/s^2"), "m s-2");
  EXPECT_EQ(lub::cf_units("rad/s"), "rad s-1");
  EXPECT_EQ(lub::cf_units(""), "1");
  EXPECT_EQ(lub::cf_units("Pa s"), "Pa s");
  EXPECT_EQ(lub::cf_units("1/s"), "1/s");
  for (const auto& f : lub::metric_fields()) EXPECT_EQ(lub::cf_units(f.unit), f.unit) << f.name;
  for (const auto& f : lub::solver_fields()) EXPECT_EQ(lub::cf_units(f.unit), f.unit) << f.name;
}
