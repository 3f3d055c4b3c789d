// A study file as the refinement reads it (refine_parts.hpp): its grid rebuilt from the
// file itself (no grid file needed), its rows as points, its lattice, and what an earlier
// refinement left in /refinement/cases.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <system_error>

#include <fmt/format.h>

#include "grid_parts.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/run/run.hpp"
#include "lub/run/run_io.hpp"
#include "lub/sweep/hash.hpp"
#include "lub/sweep/study_file.hpp"
#include "refine_parts.hpp"

namespace lub::sweep::detail {

namespace {

using nlohmann::json;

/// Every row of `t`, cell by cell in column order.
std::vector<h5::Row> read_rows(const h5::Table& t) {
  std::vector<h5::Row> rows(t.rows());
  for (const h5::Column& c : t.columns()) {
    if (c.type == h5::ColumnType::Float64) {
      const auto v = t.read_doubles(c.name);
      for (std::size_t i = 0; i < rows.size(); ++i) rows[i].emplace_back(v[i]);
    } else if (c.type == h5::ColumnType::Int64) {
      const auto v = t.read_int64s(c.name);
      for (std::size_t i = 0; i < rows.size(); ++i) rows[i].emplace_back(v[i]);
    } else {
      const auto v = t.read_strings(c.name);
      for (std::size_t i = 0; i < rows.size(); ++i) rows[i].emplace_back(v[i]);
    }
  }
  return rows;
}

/// A cell as a number (NaN for a string).
double number(const h5::Cell& c) {
  if (const double* d = std::get_if<double>(&c)) return *d;
  if (const std::int64_t* i = std::get_if<std::int64_t>(&c)) return static_cast<double>(*i);
  return std::nan("");
}

/// An axis cell as the grid's value: NaN or "" is unset, an integral number an integer
/// (as the grid would have written it: axis_parameter tells counts by it).
json axis_json(const h5::Cell& c) {
  if (const std::string* s = std::get_if<std::string>(&c)) return s->empty() ? json() : json(*s);
  const double x = number(c);
  if (!std::isfinite(x)) return json();
  if (x == std::floor(x) && std::abs(x) < 9.0e15) return json(static_cast<std::int64_t>(x));
  return json(x);
}

/// The file opened read-only if it is a complete lubsweep study of this format; else
/// lub::InputError saying why.
h5::File open_study(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": a directory, not a study file");
  h5::File f;
  try {
    f = h5::File::open(path, h5::File::Mode::ReadOnly);
  } catch (const std::exception&) {
    throw InputError(path + ": not an HDF5 file, so not a lubsweep study file");
  }
  if (!f.has_attribute("program") || f.attribute_string("program") != "lubsweep" || !f.exists("cases"))
    throw InputError(path + ": not a lubsweep study file (root attribute program = lubsweep, a /cases table)");
  check_format(f, path, "");
  for (const char* what : {"lattice", "scene_patches"})
    if (!f.exists(what))
      throw InputError(fmt::format("{}: has no /{}, which the refinement reads (re-run the sweep with this build)",
                                   path, what));
  const std::int64_t total = f.attribute_int64("cases_total");
  const std::size_t rows = f.open_table("cases").rows();
  if (f.attribute_int64("complete") != 1 || static_cast<std::int64_t>(rows) != total)
    throw InputError(fmt::format("{}: the study is incomplete ({} of {} cases; complete = 0): finish the sweep "
                                 "first (run it again to resume), then refine",
                                 path, rows, total));
  return f;
}

/// The grid's axes, as /cases describes them (its attribute `axes`, each column's pointer,
/// units and type).
std::vector<Axis> axes_of(const h5::Table& t) {
  std::vector<Axis> axes;
  if (!t.has_attribute("axes")) return axes;
  for (const std::string& name : t.attribute_strings("axes")) {
    Axis a;
    a.name = name;
    a.kind = parse_name<AxisKind>(name).value_or(AxisKind::pointer);
    const h5::Dataset d = t.column(name);
    a.pointer = d.attribute_string("pointer");
    a.units = d.units();
    a.numeric = t.columns()[t.column_index(name)].type == h5::ColumnType::Float64;
    axes.push_back(std::move(a));
  }
  return axes;
}

/// The study's cases (id = row `rows` of /cases), each scene its patch applied to the
/// reference scene.
void read_cases(const h5::File& f, const h5::Table& t, const std::vector<h5::Row>& rows, RefineStudy& s) {
  const std::vector<std::string> patches = f.open_dataset("scene_patches").read_strings();
  const json reference = json::parse(s.reference_scene);
  const std::size_t id_col = t.column_index("case"), name_col = t.column_index("name"), hash_col = t.column_index("hash");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    Case c;
    c.id = static_cast<int>(number(rows[i][id_col]));
    if (c.id != static_cast<int>(i) || i >= patches.size())
      throw InputError(fmt::format("{}: /cases row {} holds case {}: not a finished study (run the sweep again)",
                                   s.path, i, c.id));
    c.name = std::get<std::string>(rows[i][name_col]);
    c.hash = std::get<std::string>(rows[i][hash_col]);
    c.scene = canonical_json(reference.patch(json::parse(patches[i])));
    for (const Axis& a : s.grid.axes) c.axis_values.push_back(axis_json(rows[i][t.column_index(a.name)]));
    s.grid.cases.push_back(std::move(c));
  }
  s.study_cases = rows.size();
}

/// The physical axes' parameters (those the study has sensitivities for), and whether each
/// axis's midpoints are geometric.
void read_parameters(const h5::Table& t, RefineStudy& s) {
  const std::string first = steady_metrics().front().name;
  for (std::size_t i = 0; i < s.grid.axes.size(); ++i) {
    int index = -1;
    if (const auto p = axis_parameter(s.grid, i)) {
      s.physical_axes = true;
      if (t.has_column("d_" + first + "_per_" + p->name)) {
        index = static_cast<int>(s.grid.parameters.size());
        s.grid.parameters.push_back(*p);
      }
    }
    s.parameter.push_back(index);
    std::vector<double> levels;
    for (const Case& c : s.grid.cases)
      if (c.axis_values[i].is_number()) levels.push_back(c.axis_values[i].get<double>());
    std::sort(levels.begin(), levels.end());
    levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
    s.geometric.push_back(geometric_axis(levels));
  }
}

/// /lattice's edges along the physical numeric axes: round 0.
void read_lattice(const h5::File& f, RefineStudy& s) {
  const auto a = f.open_dataset("lattice/case_a").read_int64s();
  const auto b = f.open_dataset("lattice/case_b").read_int64s();
  const auto axis = f.open_dataset("lattice/axis").read_strings();
  for (std::size_t e = 0; e < a.size(); ++e) {
    const auto it = std::find_if(s.grid.axes.begin(), s.grid.axes.end(), [&](const Axis& x) { return x.name == axis[e]; });
    if (it == s.grid.axes.end()) continue;
    const std::size_t k = static_cast<std::size_t>(it - s.grid.axes.begin());
    if (axis_parameter(s.grid, k)) s.lattice.push_back({static_cast<int>(a[e]), static_cast<int>(b[e]), static_cast<int>(k), 0});
  }
}

}  // namespace

RefineStudy read_refine_study(const std::string& path) {
  const h5::File f = open_study(path);
  RefineStudy s;
  s.path = path;
  s.reference_scene = f.attribute_string("reference_scene");
  const h5::Table t = f.open_table("cases");
  s.grid.file = f.attribute_string("grid_file");
  s.grid.axes = axes_of(t);
  const std::vector<h5::Row> rows = read_rows(t);
  read_cases(f, t, rows, s);
  read_parameters(t, s);  // before the points: point_of reads the parameters' slopes
  for (std::size_t i = 0; i < rows.size(); ++i) {
    s.points.push_back(point_of(s, t.columns(), rows[i]));
    s.points.back().scene = s.grid.cases[i].scene;
  }
  read_lattice(f, s);
  return s;
}

RefinePoint point_of(const RefineStudy& s, const std::vector<h5::Column>& columns, const h5::Row& row) {
  std::map<std::string, std::size_t> at;
  for (std::size_t k = 0; k < columns.size(); ++k) at[columns[k].name] = k;
  const auto cell = [&](const std::string& name) -> const h5::Cell* {
    const auto it = at.find(name);
    return it == at.end() ? nullptr : &row[it->second];
  };
  const auto value = [&](const std::string& name) { return cell(name) ? number(*cell(name)) : std::nan(""); };
  RefinePoint p;
  p.id = static_cast<int>(value("case"));
  p.hash = std::get<std::string>(*cell("hash"));
  for (const Axis& a : s.grid.axes) p.axis_values.push_back(axis_json(*cell(a.name)));
  p.ok = parse_name<CaseStatus>(std::get<std::string>(*cell("status"))) == CaseStatus::ok;
  p.classification = std::get<std::string>(*cell("classification"));
  const h5::Cell* seed = cell("orbit_seed");
  if (seed && !std::get<std::string>(*seed).empty())
    p.orbit_seed = json::parse(std::get<std::string>(*seed)).get<std::vector<double>>();
  p.below_safe_film = value("below_safe_film");
  if (!std::isfinite(p.below_safe_film)) p.below_safe_film = -1.0;
  for (const SteadyMetric& m : steady_metrics()) {
    p.metric.push_back(value(m.name));
    p.metric_error.push_back(value(std::string(m.name) + "_error"));
  }
  for (const AxisParameter& par : s.grid.parameters)
    for (const SteadyMetric& m : steady_metrics()) {
      const std::string name = std::string("d_") + m.name + "_per_" + par.name;
      p.slope.push_back(value(name));
      p.slope_error.push_back(value(name + "_error"));
    }
  return p;
}

std::vector<h5::Column> refine_extra_columns() {
  using h5::ColumnType;
  return {{"case_a", ColumnType::Int64, "1", "case id (/cases, or a refinement case) at the lower end of the refined edge"},
          {"case_b", ColumnType::Int64, "1", "case id at the upper end of the refined edge"},
          {"axis", ColumnType::String, "", "the numeric axis (a /cases column) the edge runs along"},
          {"round", ColumnType::Int64, "1", "refinement round: 0 a lattice edge, r + 1 a half of an edge of round r"},
          {"reason", ColumnType::String, "", "why the edge was refined: " + names_list<RefineReason>()},
          {"score", ColumnType::Float64, "1",
           "labels: how many differ; metric: the largest miss of the sensitivities' prediction over its allowance, "
           "minus 1"},
          {"score_metric", ColumnType::String, "", "the metric that scored (reason metric)"},
          {"scene_patch", ColumnType::String, "",
           "the case's effective scene: a JSON Patch (RFC 6902) of the root attribute reference_scene"}};
}

h5::Row refine_row(const RefineStudy& s, const CaseResult& r, const RefineCandidate& c) {
  h5::Row row = case_row(s.grid, r);
  const Case& self = s.grid.cases.at(static_cast<std::size_t>(r.case_id));
  const std::string patch = json::diff(json::parse(s.reference_scene), json::parse(self.scene)).dump();
  for (h5::Cell cell : h5::Row{static_cast<std::int64_t>(c.edge.a), static_cast<std::int64_t>(c.edge.b),
                               s.grid.axes.at(static_cast<std::size_t>(c.edge.axis)).name,
                               static_cast<std::int64_t>(c.edge.round), std::string(name_of(c.reason)), c.score,
                               c.metric, patch})
    row.push_back(std::move(cell));
  return row;
}

std::vector<RefinedRow> read_refined(const RefineStudy& s, double tolerance) {
  std::vector<RefinedRow> out;
  const h5::File f = h5::File::open(s.path, h5::File::Mode::ReadOnly);
  if (!f.exists("refinement/cases")) return out;
  const h5::Group g = f.open_group("refinement");
  const double made_with = g.attribute_double(kToleranceAttribute);
  if (made_with != tolerance)
    throw InputError(fmt::format("{}: --metric-tolerance = {:g}: its /refinement was made with {:g}; a refinement "
                                 "continues with the tolerance it started with (give --metric-tolerance {:g}, or "
                                 "delete /refinement to start another)",
                                 s.path, tolerance, made_with, made_with));
  const h5::Table t = f.open_table("refinement/cases");
  const std::vector<h5::Row> rows = read_rows(t);
  const std::size_t axis_col = t.column_index("axis"), revision_col = t.column_index("revision");
  for (const h5::Row& row : rows) {
    const std::string revision = std::get<std::string>(row[revision_col]);
    if (revision != build_revision())
      throw InputError(fmt::format("{}: /refinement/cases holds cases of build revision {}, this lubsweep is {}: "
                                   "refine with that build, or delete /refinement to start another",
                                   s.path, revision, build_revision()));
    RefinedRow r{point_of(s, t.columns(), row), {}};
    const auto it = std::find_if(s.grid.axes.begin(), s.grid.axes.end(),
                                 [&](const Axis& a) { return a.name == std::get<std::string>(row[axis_col]); });
    r.edge = {static_cast<int>(number(row[t.column_index("case_a")])), static_cast<int>(number(row[t.column_index("case_b")])),
              static_cast<int>(it - s.grid.axes.begin()), static_cast<int>(number(row[t.column_index("round")]))};
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace lub::sweep::detail
