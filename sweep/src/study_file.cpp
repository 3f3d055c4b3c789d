// The study writer (StudyWriter): the file's header, its /cases rows as results arrive,
// the sub-grids' results and the series, and the canonical rewrite at the end. The resume
// reader is study_resume.cpp, the summary printer study_summary.cpp.
#include "lub/sweep/study_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "lub/common/constants.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/run/orbit_seed_fields.hpp"
#include "lub/run/run_io.hpp"
#include "lub/sweep/continuation_tree.hpp"
#include "study_parts.hpp"

namespace lub::sweep {

using nlohmann::json;

namespace {

constexpr const char* kClassificationLongName =
    "steady cycle: periodic (converged, stable), periodic_unstable (an orbit with a Floquet multiplier "
    "above 1), drifting (no periodic orbit inside the clearance), not_converged; for a case that is "
    "not ok its status";

/// The status and classification of a sub-grid's point without a row (never a case's).
constexpr const char* kNotRun = "not_run";

/// The status columns' long_name: "outcome: " and every CaseStatus.
std::string status_long_name() { return "outcome: " + names_list<CaseStatus>(); }

h5::Cell axis_cell(const Axis& a, const json& v) {
  if (a.numeric) return v.is_number() ? v.get<double>() : std::nan("");
  if (v.is_null()) return std::string();
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}

std::string policy_text(FailurePolicy p) {
  return p == FailurePolicy::abort_on_failure ? "abort" : "continue";
}

/// Writes an axis's values as a dimension scale `name` in `g`.
h5::Dataset write_axis(h5::Group& g, const Axis& a, const std::vector<json>& values) {
  h5::Dataset d;
  if (a.numeric) {
    std::vector<double> v;
    for (const json& x : values) v.push_back(x.is_number() ? x.get<double>() : std::nan(""));
    d = g.write_dataset(a.name, v, a.units);
  } else {
    std::vector<std::string> v;
    for (const json& x : values) v.push_back(x.is_null() ? std::string() : x.is_string() ? x.get<std::string>() : x.dump());
    d = g.write_strings(a.name, v);
  }
  d.set_attribute("long_name", axis_long_name(a));
  d.set_attribute("pointer", a.pointer);
  return d;
}

/// Each case's effective scene as a JSON Patch (RFC 6902) of case 0's: ~100 bytes a case
/// instead of its whole scene (~2.2 kB). Computed once per writer (~35 µs a case).
std::vector<std::string> scene_patches(const Grid& g) {
  std::vector<std::string> patches;
  if (g.cases.empty()) return patches;
  patches.reserve(g.cases.size());
  const nlohmann::json reference = nlohmann::json::parse(g.cases.front().scene);
  for (const Case& c : g.cases) patches.push_back(nlohmann::json::diff(reference, nlohmann::json::parse(c.scene)).dump());
  return patches;
}

/// The root attributes: what made the file, from which grid and base scene.
void write_root_attributes(h5::File& f, const Grid& g, bool complete) {
  f.set_attribute("program", "lubsweep");
  f.set_attribute("format", kStudyFormat);
  f.set_attribute("version", program_version());
  f.set_attribute("revision", build_revision());
  f.set_attribute("description", g.description);
  f.set_attribute("grid", g.text);
  f.set_attribute("grid_file", g.file);
  f.set_attribute("base_scene", g.base_scene_text);
  f.set_attribute("base_scene_file", g.base_scene_file);
  f.set_attribute("on_failure", policy_text(g.on_failure));
  f.set_attribute("cases_total", static_cast<std::int64_t>(g.cases.size()));
  f.set_attribute_int64("complete", complete ? 1 : 0);
  f.set_attribute("warnings", g.warnings);  // plausibility warnings of the cases (Grid::warnings)
  f.set_attribute("notes", g.notes);        // validity notes of the cases (Grid::notes)
}

/// The missing-value convention (run_io.hpp) on /cases: a float column declares NaN
/// (`_FillValue`), an integer result column its sentinel (`missing_value` = -1).
void declare_missing_values(h5::Table& t, const Grid& g) {
  for (const Axis& a : g.axes)
    if (a.numeric) t.column(a.name).set_attribute("_FillValue", kNaN);
  for (const auto& fld : result_fields()) {
    h5::Dataset d = t.column(fld.name);
    if (fld.integer)
      d.set_attribute_int64("missing_value", kMissingInteger);
    else
      d.set_attribute("_FillValue", kNaN);
  }
  for (const auto& fld : sensitivity_fields(g.parameters)) t.column(fld.name).set_attribute("_FillValue", kNaN);
}

/// Which classifications a reader must tell apart, from CaseClass's table and has_orbit
/// (lubjoint.bifurcations reads them): those of a case with a periodic orbit, and those of a
/// run that ended without one. The rest (invalid_scene, error; not_run in /grids) say
/// nothing about the journal.
void describe_classifications(h5::Table& t) {
  std::vector<std::string> orbit, no_orbit;
  for (const auto& [c, name] : NameTable<CaseClass>::entries) {
    if (has_orbit(c))
      orbit.emplace_back(name);
    else if (ran(c))
      no_orbit.emplace_back(name);
  }
  t.set_attribute("orbit_classifications", orbit);
  t.set_attribute("no_orbit_classifications", no_orbit);
}

/// How a row of the orbit_seed column is packed, field by field, from lub::orbit_seed_fields()
/// (the list pack_seed walks): a reader decodes it by these names (lubjoint.study.orbit_seed).
void describe_orbit_seed(h5::Dataset d) {
  std::vector<std::string> names, shapes, types, units, long_names;
  for (const OrbitSeedField& f : orbit_seed_fields()) {
    names.emplace_back(f.name);
    shapes.emplace_back(name_of(f.shape));
    types.emplace_back(f.integer ? "int64" : "float64");
    units.emplace_back(f.unit);
    long_names.emplace_back(f.long_name);
  }
  d.set_attribute("layout", static_cast<std::int64_t>(orbit_seed_layout()));
  d.set_attribute("fields", names);
  d.set_attribute("field_shapes", shapes);
  d.set_attribute("field_types", types);
  d.set_attribute("field_units", units);
  d.set_attribute("field_long_names", long_names);
  d.set_attribute("packing",
                  "a JSON array of numbers: `layout`, then the count of each field whose shape is not scalar, in "
                  "field order, then those fields' values, in field order, then each scalar field; a "
                  "square_matrix_column_major of count n*n is n x n, column by column; int64 fields hold integers");
}

}  // namespace

namespace detail {

h5::Table create_cases_table(h5::Group& parent, const Grid& g, const std::vector<h5::Column>& extra) {
  std::vector<h5::Column> columns = case_columns(g);
  columns.insert(columns.end(), extra.begin(), extra.end());
  h5::Table t = parent.create_table("cases", columns);
  std::vector<std::string> axes, metrics, solver;
  for (const Axis& a : g.axes) axes.push_back(a.name);
  for (const auto& fld : metric_fields()) metrics.push_back(fld.name);
  for (const auto& fld : solver_fields()) solver.push_back(fld.name);
  if (!axes.empty()) t.set_attribute("axes", axes);
  t.set_attribute("metrics", metrics);
  t.set_attribute("solver", solver);
  for (const Axis& a : g.axes) t.column(a.name).set_attribute("pointer", a.pointer);
  declare_missing_values(t, g);
  describe_classifications(t);
  describe_orbit_seed(t.column("orbit_seed"));
  return t;
}

}  // namespace detail

namespace {

/// /lattice: the grid's lattice neighbours (lattice_edges, the lattice the continuation
/// tree walks), one edge per entry of the dimension `edge`: case_a at the lower value of
/// `axis`, case_b one level up. What lubjoint.bifurcations reads as the grid's edges.
void write_lattice(h5::File& f, const Grid& g) {
  std::vector<std::int64_t> number, lower, upper;
  std::vector<std::string> axis;
  for (const LatticeEdge& e : lattice_edges(g)) {
    number.push_back(static_cast<std::int64_t>(number.size()));
    lower.push_back(e.lower);
    upper.push_back(e.upper);
    axis.push_back(g.axes.at(static_cast<std::size_t>(e.axis)).name);
  }
  h5::Group lg = f.require_group("lattice");
  lg.set_attribute("long_name",
                   "lattice neighbours: two cases with equal non-numeric axes that differ on one numeric axis by one "
                   "step of its sorted values over the grid (docs/theory/continuation.md)");
  h5::Dataset edge = lg.write_dataset("edge", number, "1");
  edge.set_attribute("long_name", "edge number");
  edge.make_scale("edge");
  const auto on_edge = [&](h5::Dataset d, const char* long_name) {
    d.set_attribute("long_name", long_name);
    d.attach_scale(edge, 0);
  };
  on_edge(lg.write_dataset("case_a", lower, "1"), "case id (the coordinate of /cases) at the lower value of axis");
  on_edge(lg.write_dataset("case_b", upper, "1"), "case id one step of axis above case_a");
  on_edge(lg.write_strings("axis", axis), "the numeric axis (a /cases column) case_a and case_b differ on");
}

/// /scene_patches on the root's own `scene` dimension (the case ids of the grid), so the
/// root group opens in netCDF readers too: each case's effective scene as a JSON Patch
/// of the root attribute reference_scene (case 0's scene, scene_patches).
void write_scene_patches(h5::File& f, const Grid& g, const std::vector<std::string>& patches) {
  std::vector<std::int64_t> all_ids;
  for (const Case& c : g.cases) all_ids.push_back(c.id);
  if (!g.cases.empty()) f.set_attribute("reference_scene", g.cases.front().scene);
  h5::Dataset scene_ids = f.write_dataset("scene", all_ids, {all_ids.size()}, "1");
  scene_ids.set_attribute("long_name", "case id of each scene");
  scene_ids.make_scale("scene");
  h5::Dataset sc = f.write_strings("scene_patches", patches);
  sc.set_attribute("long_name",
                   "effective scene of each case: a JSON Patch (RFC 6902) of the root attribute reference_scene");
  sc.attach_scale(scene_ids, 0);
}

/// /grids/<name> of one block: its case ids over its axes (factorial: the axes as
/// dimension scales, values as listed; explicit list: the dimension `case`, each axis a
/// variable over it).
void write_block_index(h5::Group& grids, const Grid& g, const Block& b) {
  h5::Group bg = grids.require_group(b.name);
  bg.set_attribute("kind", b.factorial ? "factorial" : "cases");
  std::vector<std::int64_t> ids(b.case_ids.begin(), b.case_ids.end());
  std::vector<std::size_t> shape = b.shape.empty() ? std::vector<std::size_t>{ids.size()} : b.shape;
  h5::Dataset index = bg.write_dataset("case_id", ids, shape, "1");
  index.set_attribute("long_name", "case id (the coordinate of /cases) of each grid point");
  std::vector<std::string> names;
  if (b.factorial) {
    for (std::size_t i = 0; i < b.axes.size(); ++i) {
      const Axis& a = g.axes[static_cast<std::size_t>(b.axes[i])];
      names.push_back(a.name);
      h5::Dataset scale = write_axis(bg, a, b.values[i]);
      scale.make_scale(a.name);
      index.attach_scale(scale, static_cast<unsigned>(i), a.name);
    }
  } else {
    h5::Dataset scale = bg.write_dataset("case", ids, {ids.size()}, "1");
    scale.set_attribute("long_name", "case id");
    scale.make_scale("case");
    index.attach_scale(scale, 0, "case");
    for (std::size_t k = 0; k < g.axes.size(); ++k) {
      std::vector<json> v;
      for (int id : b.case_ids) v.push_back(g.cases.at(static_cast<std::size_t>(id)).axis_values[k]);
      h5::Dataset d = write_axis(bg, g.axes[k], v);
      if (g.axes[k].numeric) d.set_attribute("_FillValue", kNaN);  // unset
      d.attach_scale(scale, 0);
    }
  }
  if (!names.empty()) bg.set_attribute("axes", names);
}

/// Everything but the rows, the sub-grids' results and the series.
void write_header(h5::File& f, const Grid& g, const std::vector<std::string>& patches, bool complete) {
  write_root_attributes(f, g, complete);
  detail::create_cases_table(f, g);
  write_scene_patches(f, g, patches);
  write_lattice(f, g);
  h5::Group grids = f.require_group("grids");
  for (const Block& b : g.blocks) write_block_index(grids, g, b);
}

/// Attaches the dimension scales of sub-grid `bg` (those of its `case_id`) to `d`.
void attach_like_index(h5::Group& bg, const Block& b, const Grid& g, h5::Dataset& d) {
  if (!b.factorial) {
    h5::Dataset scale = bg.open_dataset("case");
    d.attach_scale(scale, 0);
    return;
  }
  for (std::size_t i = 0; i < b.axes.size(); ++i) {
    h5::Dataset scale = bg.open_dataset(g.axes[static_cast<std::size_t>(b.axes[i])].name);
    d.attach_scale(scale, static_cast<unsigned>(i));
  }
}

/// Every sub-grid's results as labelled N-d variables on its axes: each result field
/// (float64; NaN for the metrics of a case that is not ok, and for every field of a
/// case without a row), `status` ("not_run" without a row) and `message`.
void write_grid_results(h5::File& f, const Grid& g, const std::map<int, CaseResult>& results) {
  const auto fields = result_fields();
  const std::size_t n_metrics = metric_fields().size();
  for (const Block& b : g.blocks) {
    h5::Group bg = f.open_group("grids/" + b.name);
    const std::vector<std::size_t> shape = b.shape.empty() ? std::vector<std::size_t>{b.case_ids.size()} : b.shape;
    std::vector<const CaseResult*> rs;
    for (int id : b.case_ids) {
      const auto it = results.find(id);
      rs.push_back(it == results.end() ? nullptr : &it->second);
    }
    for (std::size_t k = 0; k < fields.size(); ++k) {
      std::vector<double> v;
      for (const CaseResult* r : rs) {
        const bool have = r != nullptr && k < r->values.size() && (k >= n_metrics || r->ok());
        v.push_back(have ? r->values[k] : kNaN);
      }
      h5::Dataset d = bg.write_dataset(fields[k].name, v, shape, fields[k].unit, h5::WriteOptions{0});
      d.set_attribute("_FillValue", kNaN);  // float64 here, integer fields included
      d.set_attribute("long_name", std::string(fields[k].long_name) +
                                       (fields[k].steady_metric ? " (NaN: no steady cycle, see classification)"
                                        : k < n_metrics      ? " (NaN: the case is not ok, see status)"
                                                             : ""));
      attach_like_index(bg, b, g, d);
    }
    const auto sfields = sensitivity_fields(g.parameters);
    for (std::size_t k = 0; k < sfields.size(); ++k) {
      std::vector<double> v;
      for (const CaseResult* r : rs) v.push_back(r != nullptr && k < r->sensitivities.size() ? r->sensitivities[k] : kNaN);
      h5::Dataset d = bg.write_dataset(sfields[k].name, v, shape, sfields[k].unit, h5::WriteOptions{0});
      d.set_attribute("_FillValue", kNaN);
      d.set_attribute("long_name", sfields[k].long_name + " (NaN: no located orbit, see classification)");
      attach_like_index(bg, b, g, d);
    }
    std::vector<std::string> status, message, cls;
    for (const CaseResult* r : rs) {
      status.push_back(r ? r->status.str() : std::string(kNotRun));
      message.push_back(r ? r->message : "");
      cls.push_back(r ? r->classification.str() : std::string(kNotRun));
    }
    h5::Dataset cl = bg.write_strings("classification", cls, shape);
    cl.set_attribute("long_name", std::string(kClassificationLongName));
    attach_like_index(bg, b, g, cl);
    h5::Dataset st = bg.write_strings("status", status, shape);
    st.set_attribute("long_name", status_long_name() + ", or " + kNotRun);
    attach_like_index(bg, b, g, st);
    h5::Dataset msg = bg.write_strings("message", message, shape);
    msg.set_attribute("long_name", "why a case is not ok");
    attach_like_index(bg, b, g, msg);
  }
}

void write_series(h5::File& f, const Grid& g, const CaseResult& r) {
  if (r.series.names.empty()) return;
  const Case& c = g.cases.at(static_cast<std::size_t>(r.case_id));
  h5::Group s = f.require_group("series/" + c.name);
  s.set_attribute("case_id", static_cast<std::int64_t>(c.id));
  s.set_attribute("hash", c.hash);
  lub::write_series(s, r.series, channel_long_names(c.scene, r.series.names));
}

/// Appends the rows of `results` (in case-id order) in chunks: a row of cells is ~3 kB, so
/// 10⁵ rows at once would hold 0.3 GB on rank 0 for a moment.
void append_rows(h5::Table& t, const Grid& g, const std::map<int, CaseResult>& results) {
  constexpr std::size_t kChunk = 4096;
  std::vector<h5::Row> rows;
  rows.reserve(std::min(kChunk, results.size()));
  for (const auto& [id, r] : results) {
    rows.push_back(case_row(g, r));
    if (rows.size() == kChunk) t.append(rows), rows.clear();
  }
  if (!rows.empty()) t.append(rows);
}

void rename_over(const std::string& from, const std::string& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0) {
    std::remove(from.c_str());
    throw std::runtime_error("lubsweep: cannot rename " + from + " to " + to);
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------

std::vector<h5::Column> case_columns(const Grid& g) {
  using h5::ColumnType;
  std::vector<h5::Column> c = {{"case", ColumnType::Int64, "1", "case id (row in case-id order once the study is complete)"},
                               {"name", ColumnType::String, "", "case name, its /series group"},
                               {"hash", ColumnType::String, "", "SHA-256 of the effective scene (canonical JSON)"}};
  for (const Axis& a : g.axes)
    c.push_back({a.name, a.numeric ? ColumnType::Float64 : ColumnType::String, a.numeric ? a.units : "",
                 axis_long_name(a)});
  c.push_back({"status", ColumnType::String, "", status_long_name()});
  c.push_back({"message", ColumnType::String, "", "why a case is not ok"});
  c.push_back({"classification", ColumnType::String, "", kClassificationLongName});
  for (const auto& f : result_fields())
    c.push_back({f.name, f.integer ? ColumnType::Int64 : ColumnType::Float64, f.unit, f.long_name});
  for (const auto& f : sensitivity_fields(g.parameters))
    c.push_back({f.name, ColumnType::Float64, f.unit, f.long_name + " (NaN: no located orbit, or not computed)"});
  if (!g.parameters.empty())
    c.push_back({"sensitivity_periods", ColumnType::Int64, "1", "crank periods the sensitivities integrated"});
  c.push_back({"continued_from", ColumnType::Int64, "1",
               "case whose periodic orbit this case's Newton started from (simulation.steady = continuation); -1: none"});
  c.push_back({"orbit_seed", ColumnType::String, "",
               "the periodic orbit found, as a JSON array (lubjoint.study.orbit_seed; layout: lub::pack_seed): "
               "its state at crank angle 0 and its monodromy, each coordinate in its own unit; \"\": none"});
  c.push_back({"rank", ColumnType::Int64, "1", "MPI rank that computed the case"});
  c.push_back({"revision", ColumnType::String, "", "build revision that computed the case"});
  return c;
}

h5::Row case_row(const Grid& g, const CaseResult& r) {
  const Case& c = g.cases.at(static_cast<std::size_t>(r.case_id));
  h5::Row row = {static_cast<std::int64_t>(c.id), c.name, c.hash};
  for (std::size_t i = 0; i < g.axes.size(); ++i) row.push_back(axis_cell(g.axes[i], c.axis_values[i]));
  row.push_back(r.status.str());
  row.push_back(r.message);
  row.push_back(r.classification.str());
  const auto fields = result_fields();
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const double v = i < r.values.size() ? r.values[i] : std::nan("");
    if (fields[i].integer)
      row.push_back(std::isfinite(v) ? static_cast<std::int64_t>(v) : kMissingInteger);
    else
      row.push_back(v);
  }
  const std::size_t ns = sensitivity_fields(g.parameters).size();
  for (std::size_t i = 0; i < ns; ++i) row.push_back(i < r.sensitivities.size() ? r.sensitivities[i] : std::nan(""));
  if (!g.parameters.empty()) row.push_back(static_cast<std::int64_t>(r.sensitivity_periods));
  row.push_back(static_cast<std::int64_t>(r.continued_from));
  row.push_back(r.orbit_seed.empty() ? std::string() : nlohmann::json(r.orbit_seed).dump());
  row.push_back(static_cast<std::int64_t>(r.rank));
  row.push_back(r.revision);
  return row;
}

// ---------------------------------------------------------------------------------------

StudyWriter::StudyWriter(std::string path, const Grid& grid, const std::map<int, CaseResult>& reused,
                         const std::string& reuse_from, double flush_interval_s)
    : path_(std::move(path)),
      grid_(grid),
      results_(reused),
      patches_(scene_patches(grid)),
      flush_interval_s_(flush_interval_s),
      last_flush_(std::chrono::steady_clock::now()) {
  const std::string tmp = path_ + ".partial";
  {
    h5::File f = h5::File::create(tmp);
    write_header(f, grid_, patches_, false);
    if (!reuse_from.empty() && !reused.empty()) {
      const h5::File from = h5::File::open(reuse_from, h5::File::Mode::ReadOnly);
      detail::copy_reused_series(from, grid_, reused, f);
      // The refinement and the boundaries of a complete study stay with it while the grid
      // is the one they were made from: every case reused (else the sweep says they go).
      if (reused.size() == grid_.cases.size()) detail::copy_added_groups(from, f);
    }
    h5::Table t = f.open_table("cases");
    append_rows(t, grid_, reused);
    t = h5::Table();
    f.close();
  }
  rename_over(tmp, path_);
  file_ = h5::File::open(path_, h5::File::Mode::ReadWrite);
  table_ = file_.open_table("cases");
}

StudyWriter::~StudyWriter() {
  if (pending_.empty() || !file_.valid()) return;
  try {
    flush();
  } catch (const std::exception&) {
    // a destructor must not throw: the rows are lost, the file stays as last flushed
  }
}

void StudyWriter::append(const CaseResult& r) {
  pending_.push_back(r);
  flush_if_due();
}

bool StudyWriter::flush_if_due(std::chrono::steady_clock::time_point now) {
  if (pending_.empty()) return false;
  const std::chrono::duration<double> since = now - last_flush_;
  if (since.count() < flush_interval_s_) return false;
  flush();
  return true;
}

void StudyWriter::flush() {
  last_flush_ = std::chrono::steady_clock::now();
  if (pending_.empty()) return;
  std::vector<h5::Row> rows;
  rows.reserve(pending_.size());
  for (const CaseResult& r : pending_) {
    write_series(file_, grid_, r);  // series first: a row on disk implies its series
    rows.push_back(case_row(grid_, r));
  }
  table_.append(rows);  // flushes the file
  for (CaseResult& r : pending_) {
    r.series = Series();
    results_[r.case_id] = std::move(r);
  }
  pending_.clear();
}

void StudyWriter::finalize() {
  flush();
  const std::string tmp = path_ + ".partial";
  {
    h5::File f = h5::File::create(tmp);
    write_header(f, grid_, patches_, complete());
    write_grid_results(f, grid_, results_);
    for (const auto& [id, r] : results_) {
      const Case& c = grid_.cases.at(static_cast<std::size_t>(id));
      detail::copy_series(file_, c.name, f, c);
    }
    detail::copy_added_groups(file_, f);
    h5::Table t = f.open_table("cases");
    append_rows(t, grid_, results_);
    t = h5::Table();
    f.close();
  }
  table_ = h5::Table();
  file_.close();
  rename_over(tmp, path_);
}

}  // namespace lub::sweep
