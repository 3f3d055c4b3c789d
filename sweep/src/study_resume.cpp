// The resume reader: what an earlier study file at the output path holds for this grid
// (check_format, read_existing), and the series of its reused cases (study_parts.hpp).
#include <map>
#include <stdexcept>

#include "lub/io/json_reader.hpp"
#include "lub/run/run_io.hpp"
#include "lub/sweep/study_file.hpp"
#include "study_parts.hpp"

namespace lub::sweep {

namespace {

/// What -o errors add: how to get past a file that cannot be resumed.
constexpr const char* kResumeHint = " (use --restart to overwrite it, or another -o)";

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

/// The columns of /cases a resumed row is made of.
struct EarlierRows {
  explicit EarlierRows(const h5::Table& t)
      : hashes(t.read_strings("hash")),
        status(t.read_strings("status")),
        message(t.read_strings("message")),
        classification(t.read_strings("classification")),
        revision(t.read_strings("revision")),
        rank(t.read_int64s("rank")) {
    for (const auto& fld : result_fields()) values.push_back(t.read_doubles(fld.name));
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
    return r;
  }

  std::vector<std::string> hashes, status, message, classification, revision;
  std::vector<std::int64_t> rank;
  std::vector<std::vector<double>> values;  ///< per result field
};

}  // namespace

void check_format(const h5::File& f, const std::string& what, const std::string& hint) {
  const std::string format = f.has_attribute("format") ? f.attribute_string("format") : "(none)";
  if (format != kStudyFormat)
    throw InputError(what + ": a study file of format " + format + "; this lubsweep reads and writes format " +
                     kStudyFormat + " (/cases as columns, /grids as labelled variables)" + hint);
}

ResumeState read_existing(const std::string& path, const Grid& grid, bool retry_failed,
                          const std::string& build) {
  h5::File f;
  const h5::Table t = open_cases_table(path, f);
  ResumeState st;
  const std::size_t n = t.rows();
  if (!has_result_columns(t)) {
    st.incompatible_rows = n;
    return st;
  }
  const EarlierRows rows(t);
  std::map<std::string, int> id_of;
  for (const Case& c : grid.cases) id_of[c.hash] = c.id;
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
    if (retry_failed && rows.status[i] != "ok") {
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

}  // namespace detail
}  // namespace lub::sweep
