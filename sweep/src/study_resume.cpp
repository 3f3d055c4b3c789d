// The resume reader: what an earlier study file at the output path holds for this grid
// (check_format, read_existing), and the series of its reused cases (study_parts.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "lub/io/json_reader.hpp"
#include "lub/run/run_io.hpp"
#include "lub/sweep/study_file.hpp"
#include "study_parts.hpp"

namespace lub::sweep {

namespace {

/// What -o errors add: how to get past a file that cannot be resumed.
constexpr const char* kResumeHint = " (use --restart to overwrite it, or another -o)";

/// What a refusal to drop rows adds: nothing was changed, and the three ways on.
constexpr const char* kDropHint =
    ". Nothing was changed: to keep them, give another -o; to drop them, add --drop-other-cases; "
    "to start over, --restart";

/// The /cases table of the study file at `path`, opened as `f`; throws lub::InputError
/// unless it is a lubsweep study file of this build's format.
h5::Table open_cases_table(const std::string& path, h5::File& f) {
  const std::string hint = kResumeHint;
  try {
    f = h5::File::open(path, h5::File::Mode::ReadOnly);
  } catch (const std::exception&) {
    throw InputError("-o " + path + ": the file exists and is not an HDF5 file" + hint);
  }
  if (!f.has_attribute("program") || f.attribute_string("program") != "lubsweep" || !f.exists("cases"))
    throw InputError("-o " + path + ": the file exists and is not a lubsweep study file" + hint);
  check_format(f, "-o " + path, hint);
  try {
    return f.open_table("cases");
  } catch (const std::exception& e) {
    throw InputError("-o " + path + ": cannot read its /cases table: " + e.what() + hint);
  }
}

/// Whether `t` has every column a row of this build reads back.
bool has_result_columns(const h5::Table& t) {
  bool compatible = true;
  for (const char* col : {"hash", "status", "message", "classification", "rank", "revision"}) compatible = compatible && t.has_column(col);
  for (const auto& fld : result_fields()) compatible = compatible && t.has_column(fld.name);
  return compatible;
}

/// " (a=1 b=x)": row `i`'s values on the axes of the file's /cases (its attribute `axes`).
std::string row_label(const h5::Table& t, const std::vector<std::string>& axes, std::size_t i) {
  std::string label;
  for (const std::string& a : axes) {
    if (!t.has_column(a)) continue;
    std::string v;
    if (t.columns()[t.column_index(a)].type == h5::ColumnType::String) {
      v = t.read_strings(a).at(i);
    } else {
      const double x = t.read_doubles(a).at(i);
      v = std::isnan(x) ? "unset" : fmt::format("{:g}", x);
    }
    label += (label.empty() ? "" : " ") + a + "=" + v;
  }
  return label.empty() ? "" : " (" + label + ")";
}

/// "a, b" ("none" if empty).
std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

/// The refusal of a file whose rows `other` (row numbers) are not cases of `grid`: names
/// them (at most five, with their axis values) and how the axes differ.
InputError other_cases_error(const std::string& path, const h5::Table& t, const Grid& grid,
                             const std::vector<std::size_t>& other) {
  const std::vector<std::string> file_axes =
      t.has_attribute("axes") ? t.attribute_strings("axes") : std::vector<std::string>();
  std::vector<std::string> grid_axes, only_file, only_grid;
  for (const Axis& a : grid.axes) grid_axes.push_back(a.name);
  for (const auto& a : file_axes)
    if (std::find(grid_axes.begin(), grid_axes.end(), a) == grid_axes.end()) only_file.push_back(a);
  for (const auto& a : grid_axes)
    if (std::find(file_axes.begin(), file_axes.end(), a) == file_axes.end()) only_grid.push_back(a);
  const std::vector<std::string> names = t.read_strings("name");
  std::string msg = fmt::format("-o {}: the file holds {} computed case{} that {} of the grid {}: ", path, other.size(),
                                other.size() == 1 ? "" : "s", other.size() == 1 ? "is not a case" : "are not cases",
                                grid.file.empty() ? std::string("given") : grid.file);
  for (std::size_t k = 0; k < other.size() && k < 5; ++k)
    msg += (k ? ", " : "") + names.at(other[k]) + row_label(t, file_axes, other[k]);
  if (other.size() > 5) msg += fmt::format(", and {} more", other.size() - 5);
  if (only_file.empty() && only_grid.empty())
    msg += "; same axes (" + joined(grid_axes) + "), other values or settings";
  else
    msg += "; axes only in the file: " + joined(only_file) + "; only in this grid: " + joined(only_grid);
  return InputError(msg + kDropHint);
}

/// Each name of a string column as the enumerator it names (NameTable<E>); throws
/// lub::InputError naming the row and the value where it names none.
template <class E>
std::vector<E> named_column(const h5::Table& t, const char* column, const std::string& path) {
  std::vector<E> out;
  const std::vector<std::string> names = t.read_strings(column);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto value = parse_name<E>(names[i]);
    if (!value)
      throw InputError("-o " + path + ": /cases row " + std::to_string(i) + ": " + column + " = \"" + names[i] +
                       "\" is not one of " + names_list<E>() + kResumeHint);
    out.push_back(*value);
  }
  return out;
}

/// The columns of /cases a resumed row is made of.
struct EarlierRows {
  EarlierRows(const h5::Table& t, const std::string& path, const Grid& grid)
      : hashes(t.read_strings("hash")),
        status(named_column<CaseStatus>(t, "status", path)),
        message(t.read_strings("message")),
        classification(named_column<CaseClass>(t, "classification", path)),
        revision(t.read_strings("revision")),
        rank(t.read_int64s("rank")) {
    // Files of an earlier format have no orbits: their cases are continued from by none.
    if (t.has_column("orbit_seed")) orbit_seed = t.read_strings("orbit_seed");
    if (t.has_column("continued_from")) continued_from = t.read_int64s("continued_from");
    for (const auto& fld : result_fields()) {
      values.push_back(t.read_doubles(fld.name));
      if (fld.integer)  // the sentinel back to NaN, as run_case gives it
        for (double& v : values.back())
          if (v == static_cast<double>(kMissingInteger)) v = std::numeric_limits<double>::quiet_NaN();
    }
    // Sensitivities: a file written without them (another grid, an earlier build) resumes
    // its rows with NaN ones.
    const auto fields = sensitivity_fields(grid.parameters);
    n_sensitivities = fields.size();
    for (const auto& fld : fields)
      if (t.has_column(fld.name)) sensitivities.push_back(t.read_doubles(fld.name));
    if (t.has_column("sensitivity_periods")) sensitivity_periods = t.read_int64s("sensitivity_periods");
    if (sensitivities.size() != n_sensitivities) sensitivities.clear();
  }

  /// Row `i` as the result of case `case_id`.
  CaseResult result(std::size_t i, int case_id) const {
    CaseResult r;
    r.case_id = case_id;
    r.rank = static_cast<int>(rank[i]);
    r.status = status[i];
    r.message = message[i];
    r.classification = classification[i];
    r.revision = revision[i];
    for (const auto& column : values) r.values.push_back(column[i]);
    if (i < orbit_seed.size() && !orbit_seed[i].empty())
      r.orbit_seed = nlohmann::json::parse(orbit_seed[i]).get<std::vector<double>>();
    if (i < continued_from.size()) r.continued_from = static_cast<int>(continued_from[i]);
    if (n_sensitivities > 0) {
      r.sensitivities.assign(n_sensitivities, std::numeric_limits<double>::quiet_NaN());
      for (std::size_t k = 0; k < sensitivities.size(); ++k) r.sensitivities[k] = sensitivities[k][i];
      if (i < sensitivity_periods.size()) r.sensitivity_periods = sensitivity_periods[i];
    }
    return r;
  }

  std::vector<std::string> hashes;
  std::vector<CaseStatus> status;
  std::vector<std::string> message;
  std::vector<CaseClass> classification;
  std::vector<std::string> revision, orbit_seed;
  std::vector<std::int64_t> rank, continued_from;
  std::vector<std::vector<double>> values;  ///< per result field
  std::vector<std::vector<double>> sensitivities;  ///< per sensitivity field (empty: the file has none)
  std::vector<std::int64_t> sensitivity_periods;
  std::size_t n_sensitivities = 0;
};

}  // namespace

void check_format(const h5::File& f, const std::string& what, const std::string& hint) {
  const std::string format = f.has_attribute("format") ? f.attribute_string("format") : "(none)";
  if (format != kStudyFormat)
    throw InputError(what + ": a study file of format " + format + "; this lubsweep reads and writes format " +
                     kStudyFormat + (hint.empty() ? std::string(" (re-run the sweep with --restart to rewrite it)") : hint));
}

ResumeState read_existing(const std::string& path, const Grid& grid, bool retry_failed,
                          const std::string& build, bool drop_other_cases) {
  h5::File f;
  const h5::Table t = open_cases_table(path, f);
  ResumeState st;
  st.added_groups = detail::study_added_groups(f);
  const std::size_t n = t.rows();
  if (!has_result_columns(t)) {
    if (n > 0 && !drop_other_cases)
      throw InputError(fmt::format("-o {}: its {} rows lack result columns of this build (another version?), so they "
                                   "cannot be reused{}",
                                   path, n, kDropHint));
    st.incompatible_rows = n;
    return st;
  }
  const EarlierRows rows(t, path, grid);
  std::map<std::string, int> id_of;
  for (const Case& c : grid.cases) id_of[c.hash] = c.id;
  std::vector<std::size_t> other;
  for (std::size_t i = 0; i < n; ++i)
    if (!id_of.count(rows.hashes[i])) other.push_back(i);
  if (!other.empty() && !drop_other_cases) throw other_cases_error(path, t, grid, other);
  for (std::size_t i = 0; i < n; ++i) {
    const auto it = id_of.find(rows.hashes[i]);
    if (it == id_of.end()) {
      ++st.other_rows;
      continue;
    }
    if (st.done.count(it->second)) continue;
    if (rows.revision[i] != build) {
      ++st.other_revision;
      continue;
    }
    if (retry_failed && rows.status[i] != CaseStatus::ok) {
      ++st.retried;
      continue;
    }
    st.done[it->second] = rows.result(i, it->second);
  }
  return st;
}

namespace detail {

void copy_series(const h5::File& from, const std::string& from_name, h5::File& to, const Case& to_case) {
  const std::string g = "series/" + from_name;
  if (!from.exists("series") || !from.exists(g)) return;
  h5::Group src = from.open_group(g);
  h5::Group dst = to.require_group("series/" + to_case.name);
  dst.set_attribute("case_id", static_cast<std::int64_t>(to_case.id));
  dst.set_attribute("hash", to_case.hash);
  Series s;
  std::vector<std::string> long_names;
  s.names = src.has_attribute("channels") ? src.attribute_strings("channels") : src.list();
  for (const std::string& name : s.names) {
    h5::Dataset d = src.open_dataset(name);
    s.data.push_back(d.read_doubles());
    s.units.push_back(d.units());
    long_names.push_back(d.has_attribute("long_name") ? d.attribute_string("long_name") : std::string());
  }
  lub::write_series(dst, s, long_names);
}

void copy_reused_series(const h5::File& from, const Grid& grid, const std::map<int, CaseResult>& reused,
                        h5::File& to) {
  std::map<std::string, std::string> group_of_hash;
  if (from.exists("series"))
    for (const std::string& name : from.open_group("series").list()) {
      const h5::Group g = from.open_group("series/" + name);
      if (g.has_attribute("hash")) group_of_hash[g.attribute_string("hash")] = name;
    }
  for (const auto& [id, r] : reused) {
    const Case& c = grid.cases.at(static_cast<std::size_t>(id));
    const auto it = group_of_hash.find(c.hash);
    if (it != group_of_hash.end()) copy_series(from, it->second, to, c);
  }
}

std::vector<std::string> study_added_groups(const h5::File& from) {
  std::vector<std::string> out;
  for (const char* g : {"refinement", "boundaries"})
    if (from.exists(g)) out.emplace_back(g);
  return out;
}

void copy_added_groups(const h5::File& from, h5::File& to) {
  for (const std::string& g : study_added_groups(from)) from.copy_to(g, to);
}

}  // namespace detail
}  // namespace lub::sweep
