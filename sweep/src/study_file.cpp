#include "lub/sweep/study_file.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "lub/io/json_reader.hpp"
#include "lub/run/run_io.hpp"

namespace lub::sweep {

using nlohmann::json;

namespace {

/// Owner of a temporary HDF5 id (for the few calls lub::h5 does not offer).
class Hid {
 public:
  explicit Hid(hid_t id) : id_(id) {}
  Hid(const Hid&) = delete;
  Hid& operator=(const Hid&) = delete;
  Hid(Hid&& o) noexcept : id_(o.id_) { o.id_ = -1; }
  ~Hid() {
    if (id_ < 0) return;
    switch (H5Iget_type(id_)) {
      case H5I_DATASET: H5Dclose(id_); break;
      case H5I_DATATYPE: H5Tclose(id_); break;
      case H5I_DATASPACE: H5Sclose(id_); break;
      case H5I_GENPROP_LST: H5Pclose(id_); break;
      default: break;
    }
  }
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
};

[[noreturn]] void h5_fail(const h5::Group& g, const std::string& name, const std::string& what) {
  H5Eclear2(H5E_DEFAULT);
  throw std::runtime_error("lubsweep: " + g.file_name() + ":" + g.path() + "/" + name + ": " + what);
}

Hid string_type() {
  Hid t(H5Tcopy(H5T_C_S1));
  if (!t.ok() || H5Tset_size(t.get(), H5T_VARIABLE) < 0 || H5Tset_cset(t.get(), H5T_CSET_UTF8) < 0)
    throw std::runtime_error("lubsweep: cannot build the HDF5 string type");
  return t;
}

h5::Cell axis_cell(const Axis& a, const json& v) {
  if (a.numeric) return v.is_number() ? v.get<double>() : std::nan("");
  if (v.is_null()) return std::string();
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}

std::string policy_text(FailurePolicy p) {
  return p == FailurePolicy::abort_on_failure ? "abort" : "continue";
}

void write_header(h5::File& f, const Grid& g, bool complete) {
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

  h5::Table t = f.create_table("cases", case_columns(g));
  std::vector<std::string> axes, metrics, solver;
  for (const Axis& a : g.axes) axes.push_back(a.name);
  for (const auto& fld : metric_fields()) metrics.push_back(fld.name);
  for (const auto& fld : solver_fields()) solver.push_back(fld.name);
  if (!axes.empty()) t.set_attribute("axes", axes);
  t.set_attribute("metrics", metrics);
  t.set_attribute("solver", solver);

  std::vector<std::string> scenes;
  for (const Case& c : g.cases) scenes.push_back(c.scene);
  write_strings(f, "scenes", scenes);

  h5::Group grids = f.require_group("grids");
  for (const Block& b : g.blocks) {
    h5::Group bg = grids.require_group(b.name);
    bg.set_attribute("kind", b.factorial ? "factorial" : "cases");
    std::vector<std::int64_t> ids(b.case_ids.begin(), b.case_ids.end());
    std::vector<std::size_t> shape = b.shape.empty() ? std::vector<std::size_t>{ids.size()} : b.shape;
    write_int64s(bg, "case_id", ids, shape);
    if (!b.factorial) continue;
    std::vector<std::string> names;
    h5::Dataset index = bg.open_dataset("case_id");
    for (std::size_t i = 0; i < b.axes.size(); ++i) {
      const Axis& a = g.axes[static_cast<std::size_t>(b.axes[i])];
      names.push_back(a.name);
      if (a.numeric) {
        std::vector<double> v;
        for (const json& x : b.values[i]) v.push_back(x.get<double>());
        bg.write_dataset(a.name, v, a.units);
      } else {
        std::vector<std::string> v;
        for (const json& x : b.values[i]) v.push_back(x.is_string() ? x.get<std::string>() : x.dump());
        write_strings(bg, a.name, v);
      }
      h5::Dataset scale = bg.open_dataset(a.name);
      scale.set_attribute("pointer", a.pointer);
      index.attach_scale(scale, static_cast<unsigned>(i), a.name);
    }
    if (!names.empty()) bg.set_attribute("axes", names);
  }
}

void write_series(h5::File& f, const Grid& g, const CaseResult& r) {
  if (r.series.names.empty()) return;
  const Case& c = g.cases.at(static_cast<std::size_t>(r.case_id));
  h5::Group s = f.require_group("series/" + c.name);
  s.set_attribute("channels", r.series.names);
  s.set_attribute("case_id", static_cast<std::int64_t>(c.id));
  s.set_attribute("hash", c.hash);
  for (std::size_t i = 0; i < r.series.names.size(); ++i)
    s.write_dataset(r.series.names[i], r.series.data[i], r.series.units[i]);
}

void rename_over(const std::string& from, const std::string& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0) {
    std::remove(from.c_str());
    throw std::runtime_error("lubsweep: cannot rename " + from + " to " + to);
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------

void write_strings(h5::Group& group, const std::string& name, const std::vector<std::string>& values) {
  Hid type = string_type();
  const hsize_t dims[1] = {values.size()};
  Hid space(H5Screate_simple(1, dims, nullptr));
  Hid ds(H5Dcreate2(group.id(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  if (!space.ok() || !ds.ok()) h5_fail(group, name, "cannot create the string dataset");
  std::vector<const char*> p;
  for (const auto& s : values) p.push_back(s.c_str());
  if (!values.empty() && H5Dwrite(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data()) < 0)
    h5_fail(group, name, "cannot write the string dataset");
}

std::vector<std::string> read_strings(const h5::Group& group, const std::string& name) {
  Hid ds(H5Dopen2(group.id(), name.c_str(), H5P_DEFAULT));
  if (!ds.ok()) h5_fail(group, name, "cannot open the dataset");
  Hid space(H5Dget_space(ds.get()));
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  Hid type = string_type();
  std::vector<char*> buf(static_cast<std::size_t>(std::max<hssize_t>(n, 0)), nullptr);
  if (n > 0 && H5Dread(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0)
    h5_fail(group, name, "cannot read the string dataset");
  std::vector<std::string> out;
  for (char* s : buf) out.emplace_back(s ? s : "");
  if (n > 0) H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, buf.data());
  return out;
}

void write_int64s(h5::Group& group, const std::string& name, const std::vector<std::int64_t>& values,
                  const std::vector<std::size_t>& shape) {
  std::vector<hsize_t> dims(shape.begin(), shape.end());
  std::size_t n = 1;
  for (std::size_t e : shape) n *= e;
  if (n != values.size()) h5_fail(group, name, "shape does not match the number of values");
  Hid space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
  Hid ds(H5Dcreate2(group.id(), name.c_str(), H5T_STD_I64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  if (!space.ok() || !ds.ok()) h5_fail(group, name, "cannot create the dataset");
  if (n > 0 && H5Dwrite(ds.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    h5_fail(group, name, "cannot write the dataset");
}

std::vector<h5::Column> case_columns(const Grid& g) {
  using h5::ColumnType;
  std::vector<h5::Column> c = {{"case_id", ColumnType::Int64, ""},
                               {"case", ColumnType::String, ""},
                               {"hash", ColumnType::String, ""}};
  for (const Axis& a : g.axes)
    c.push_back({a.name, a.numeric ? ColumnType::Float64 : ColumnType::String, a.units});
  c.push_back({"status", ColumnType::String, ""});
  c.push_back({"message", ColumnType::String, ""});
  for (const auto& f : result_fields())
    c.push_back({f.name, f.integer ? ColumnType::Int64 : ColumnType::Float64, f.unit});
  c.push_back({"rank", ColumnType::Int64, ""});
  c.push_back({"revision", ColumnType::String, ""});
  return c;
}

h5::Row case_row(const Grid& g, const CaseResult& r) {
  const Case& c = g.cases.at(static_cast<std::size_t>(r.case_id));
  h5::Row row = {static_cast<std::int64_t>(c.id), c.name, c.hash};
  for (std::size_t i = 0; i < g.axes.size(); ++i) row.push_back(axis_cell(g.axes[i], c.axis_values[i]));
  row.push_back(r.status);
  row.push_back(r.message);
  const auto fields = result_fields();
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const double v = i < r.values.size() ? r.values[i] : std::nan("");
    if (fields[i].integer)
      row.push_back(static_cast<std::int64_t>(std::isfinite(v) ? v : -1.0));
    else
      row.push_back(v);
  }
  row.push_back(static_cast<std::int64_t>(r.rank));
  row.push_back(r.revision);
  return row;
}

ResumeState read_existing(const std::string& path, const Grid& grid, bool retry_failed,
                          const std::string& build) {
  const std::string hint = " (use --restart to overwrite it, or another -o)";
  h5::File f;
  try {
    f = h5::File::open(path, h5::File::Mode::ReadOnly);
  } catch (const std::exception&) {
    throw InputError("-o " + path + ": the file exists and is not an HDF5 file" + hint);
  }
  if (!f.has_attribute("program") || f.attribute_string("program") != "lubsweep" || !f.exists("cases"))
    throw InputError("-o " + path + ": the file exists and is not a lubsweep study file" + hint);
  ResumeState st;
  h5::Table t;
  try {
    t = f.open_table("cases");
  } catch (const std::exception& e) {
    throw InputError("-o " + path + ": cannot read its /cases table: " + e.what() + hint);
  }
  const std::size_t n = t.rows();
  const auto fields = result_fields();
  bool compatible = true;
  for (const char* col : {"hash", "status", "message", "rank", "revision"}) compatible = compatible && t.has_column(col);
  for (const auto& fld : fields) compatible = compatible && t.has_column(fld.name);
  if (!compatible) {
    st.incompatible_rows = n;
    return st;
  }
  const auto hashes = t.read_strings("hash");
  const auto status = t.read_strings("status");
  const auto message = t.read_strings("message");
  const auto revision = t.read_strings("revision");
  const auto rank = t.read_int64s("rank");
  std::vector<std::vector<double>> cols;
  for (const auto& fld : fields) cols.push_back(t.read_doubles(fld.name));

  std::map<std::string, int> id_of;
  for (const Case& c : grid.cases) id_of[c.hash] = c.id;
  for (std::size_t i = 0; i < n; ++i) {
    const auto it = id_of.find(hashes[i]);
    if (it == id_of.end()) {
      ++st.other_rows;
      continue;
    }
    if (st.done.count(it->second)) continue;
    if (revision[i] != build) {
      ++st.other_revision;
      continue;
    }
    if (retry_failed && status[i] != "ok") {
      ++st.retried;
      continue;
    }
    CaseResult r;
    r.case_id = it->second;
    r.rank = static_cast<int>(rank[i]);
    r.status = status[i];
    r.message = message[i];
    r.revision = revision[i];
    for (std::size_t k = 0; k < fields.size(); ++k) r.values.push_back(cols[k][i]);
    st.done[r.case_id] = std::move(r);
  }
  return st;
}

// Copies series/<from_name> of `from` to the series of case `to_case` in `to`. The names
// differ when the file being resumed came from another grid: a case keeps its hash but
// its id and name follow its place in the new grid.
void copy_series(const h5::File& from, const std::string& from_name, h5::File& to, const Case& to_case) {
  const std::string g = "series/" + from_name;
  if (!from.exists("series") || !from.exists(g)) return;
  h5::Group src = from.open_group(g);
  h5::Group dst = to.require_group("series/" + to_case.name);
  dst.set_attribute("case_id", static_cast<std::int64_t>(to_case.id));
  dst.set_attribute("hash", to_case.hash);
  std::vector<std::string> names = src.has_attribute("channels") ? src.attribute_strings("channels") : src.list();
  dst.set_attribute("channels", names);
  for (const std::string& name : names) {
    h5::Dataset d = src.open_dataset(name);
    dst.write_dataset(name, d.read_doubles(), d.units());
  }
}

// ---------------------------------------------------------------------------------------

StudyWriter::StudyWriter(std::string path, const Grid& grid, const std::map<int, CaseResult>& reused,
                         const std::string& reuse_from)
    : path_(std::move(path)), grid_(grid), results_(reused) {
  const std::string tmp = path_ + ".partial";
  {
    h5::File f = h5::File::create(tmp);
    write_header(f, grid_, false);
    if (!reuse_from.empty() && !reused.empty()) {
      const h5::File old = h5::File::open(reuse_from, h5::File::Mode::ReadOnly);
      // The old file's series by hash (its case names are those of the grid it was made from).
      std::map<std::string, std::string> old_group;
      if (old.exists("series"))
        for (const std::string& name : old.open_group("series").list()) {
          const h5::Group g = old.open_group("series/" + name);
          if (g.has_attribute("hash")) old_group[g.attribute_string("hash")] = name;
        }
      for (const auto& [id, r] : reused) {
        const Case& c = grid_.cases.at(static_cast<std::size_t>(id));
        const auto it = old_group.find(c.hash);
        if (it != old_group.end()) copy_series(old, it->second, f, c);
      }
    }
    std::vector<h5::Row> rows;
    for (const auto& [id, r] : reused) rows.push_back(case_row(grid_, r));
    h5::Table t = f.open_table("cases");
    t.append(rows);
    t = h5::Table();
    f.close();
  }
  rename_over(tmp, path_);
  file_ = h5::File::open(path_, h5::File::Mode::ReadWrite);
  table_ = file_.open_table("cases");
}

void StudyWriter::append(const CaseResult& r) {
  write_series(file_, grid_, r);  // series first: a row on disk implies its series
  table_.append(case_row(grid_, r));
  CaseResult kept = r;
  kept.series = Series();
  results_[r.case_id] = std::move(kept);
}

void StudyWriter::finalize() {
  const std::string tmp = path_ + ".partial";
  {
    h5::File f = h5::File::create(tmp);
    write_header(f, grid_, complete());
    std::vector<h5::Row> rows;
    for (const auto& [id, r] : results_) {
      const Case& c = grid_.cases.at(static_cast<std::size_t>(id));
      copy_series(file_, c.name, f, c);
      rows.push_back(case_row(grid_, r));
    }
    h5::Table t = f.open_table("cases");
    t.append(rows);
    t = h5::Table();
    f.close();
  }
  table_ = h5::Table();
  file_.close();
  rename_over(tmp, path_);
}

// ---------------------------------------------------------------------------------------

void print_summary(const std::string& path, std::FILE* out) {
  const h5::File f = h5::File::open(path, h5::File::Mode::ReadOnly);
  const h5::Table t = f.open_table("cases");
  const std::size_t n = t.rows();
  std::vector<std::string> axes;
  if (t.has_attribute("axes")) axes = t.attribute_strings("axes");
  const auto names = t.read_strings("case");
  const auto status = t.read_strings("status");
  const auto message = t.read_strings("message");

  struct Col {
    std::string head;
    std::vector<std::string> cells;
  };
  std::vector<Col> cols;
  cols.push_back({"case", names});
  auto fmt = [](const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return std::string(buf);
  };
  for (const auto& a : axes) {
    Col c{a, {}};
    const auto& column = t.columns()[t.column_index(a)];
    if (column.type == h5::ColumnType::String) {
      c.cells = t.read_strings(a);
    } else {
      for (double v : t.read_doubles(a)) c.cells.push_back(std::isnan(v) ? "-" : fmt("%g", v));
    }
    cols.push_back(std::move(c));
  }
  cols.push_back({"status", status});
  auto numeric = [&](const std::string& head, const std::string& name, const char* f, double scale) {
    Col c{head, {}};
    if (!t.has_column(name)) return;
    for (double v : t.read_doubles(name)) c.cells.push_back(std::isfinite(v) ? fmt(f, v * scale) : "-");
    cols.push_back(std::move(c));
  };
  numeric("h_min[um]", "min_film_thickness_m", "%.3f", 1e6);
  numeric("max_eps", "max_eps", "%.4f", 1.0);
  numeric("peak_F[N]", "peak_reaction_N", "%.4g", 1.0);
  numeric("peak_a[m/s2]", "peak_acceleration_m_s2", "%.4g", 1.0);
  numeric("periodicity", "periodicity", "%.2e", 1.0);
  numeric("steady", "steady", "%.0f", 1.0);
  numeric("cycles", "cycles_run", "%.0f", 1.0);
  numeric("steps", "steps", "%.0f", 1.0);
  numeric("wall[s]", "wall_time_s", "%.2f", 1.0);

  std::vector<std::size_t> width;
  for (const Col& c : cols) {
    std::size_t w = c.head.size();
    for (const auto& s : c.cells) w = std::max(w, s.size());
    width.push_back(w);
  }
  std::size_t failed = 0;
  for (const auto& s : status) failed += s != "ok";
  const std::int64_t total = f.has_attribute("cases_total") ? f.attribute_int64("cases_total") : static_cast<std::int64_t>(n);
  std::fprintf(out, "%s: %zu of %lld cases, %zu ok, %zu not ok%s\n", path.c_str(), n, static_cast<long long>(total),
               n - failed, failed, static_cast<std::int64_t>(n) < total ? " (incomplete: re-run to resume)" : "");
  for (std::size_t k = 0; k < cols.size(); ++k)
    std::fprintf(out, "%s%-*s", k ? "  " : "", static_cast<int>(width[k]), cols[k].head.c_str());
  std::fprintf(out, "\n");
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < cols.size(); ++k)
      std::fprintf(out, "%s%-*s", k ? "  " : "", static_cast<int>(width[k]), cols[k].cells[i].c_str());
    std::fprintf(out, "\n");
  }
  for (std::size_t i = 0; i < n; ++i)
    if (status[i] != "ok") std::fprintf(out, "%s: %s: %s\n", names[i].c_str(), status[i].c_str(), message[i].c_str());
}

}  // namespace lub::sweep
