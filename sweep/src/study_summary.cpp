// The summary printer (lubsweep --summary, and the table at the end of a sweep): one line
// per case of a study file, its axes, status, classification and key metrics, in columns.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <system_error>

#include <fmt/format.h>

#include "lub/bearing/law_validity.hpp"
#include "lub/io/data_path.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/sweep/study_file.hpp"

namespace lub::sweep {

namespace {

/// One column of the printed table: its heading and a cell per case.
struct SummaryColumn {
  std::string head;
  std::vector<std::string> cells;
};

/// Whether a status read from the file is ok (CaseStatus's table).
bool is_ok(const std::string& status) { return parse_name<CaseStatus>(status) == CaseStatus::ok; }

/// Whether a classification read from the file is a periodic orbit (an unknown name: not).
bool is_orbit(const std::string& cls) {
  const auto c = parse_name<CaseClass>(cls);
  return c && has_orbit(*c);
}

/// `x` in `format` ("{:.4f}"), a negative number that rounds to zero shown as zero: "0.0000",
/// not "-0.0000" (a metric of -3e-7 is no sign of anything).
std::string formatted(const char* format, double x) {
  std::string s = fmt::format(fmt::runtime(format), x);
  const std::size_t mantissa_end = std::min(s.find_first_of("eE"), s.size());
  if (!s.empty() && s[0] == '-' && s.find_first_not_of("0.", 1) >= mantissa_end) s.erase(0, 1);
  return s;
}

/// The columns of the table after `case`: the axes (numbers in {:g}, "-" where unset), status,
/// classification (`cls`), then the key metrics that `t` has, each scaled and formatted.
void add_columns(const h5::Table& t, const std::vector<std::string>& status, const std::vector<std::string>& cls,
                 std::vector<SummaryColumn>& cols) {
  const std::vector<std::string> axes = t.has_attribute("axes") ? t.attribute_strings("axes") : std::vector<std::string>();
  for (const auto& a : axes) {
    SummaryColumn c{a, {}};
    const auto& column = t.columns()[t.column_index(a)];
    if (column.type == h5::ColumnType::String) {
      c.cells = t.read_strings(a);
    } else {
      for (double v : t.read_doubles(a)) c.cells.push_back(std::isnan(v) ? "-" : formatted("{:g}", v));
    }
    cols.push_back(std::move(c));
  }
  cols.push_back({"status", status});
  cols.push_back({"classification", cls});
  // A metric's column; `without_orbit`: shown only for the cases with no steady cycle (where
  // it got to), "-" for those with one (whose metrics say it) and where it is 0 (not followed).
  // `if_used`: the column only if some case has a non-zero value (an effect's metric).
  auto numeric = [&](const std::string& head, const std::string& name, const char* format, double scale,
                     bool without_orbit = false, bool if_used = false) {
    SummaryColumn c{head, {}};
    if (!t.has_column(name)) return;
    const std::vector<double> v = t.read_doubles(name);
    if (if_used && std::none_of(v.begin(), v.end(), [](double x) { return std::isfinite(x) && x != 0.0; })) return;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const bool shown = !without_orbit || (!is_orbit(cls[i]) && v[i] != 0.0);
      c.cells.push_back(shown && std::isfinite(v[i]) ? formatted(format, v[i] * scale) : "-");
    }
    cols.push_back(std::move(c));
  };
  numeric("h_min[um]", "min_film_thickness_m", "{:.3f}", 1e6);
  numeric("max_eps", "max_eps", "{:.4f}", 1.0);
  numeric("peak_F[N]", "peak_reaction_N", "{:.4g}", 1.0);
  numeric("peak_a[m/s2]", "peak_acceleration_m_s2", "{:.4g}", 1.0);
  numeric("periodicity", "periodicity", "{:.2e}", 1.0);
  // Mixed lubrication (effects.mixed_lubrication): the asperities' peak load and its ratio to
  // the peak joint force; shown when a case has the effect and its asperities touch.
  numeric("W_asp[N]", "peak_asperity_load_N", "{:.3g}", 1.0, false, true);
  numeric("W_asp/F", "asperity_load_ratio", "{:.3g}", 1.0, false, true);
  // The film's power loss, and its peak pressure where the grid asks (metrics.peak_pressure).
  numeric("P_loss[W]", "film_power_loss_W", "{:.4g}", 1.0);
  numeric("p_max[MPa]", "peak_film_pressure_Pa", "{:.4g}", 1e-6, false, true);
  numeric("|mu|max", "multiplier_1_modulus", "{:.4f}", 1.0);
  // How well posed the orbit is: kappa = 1/min|1 - mu| and its slowest mode's e-folding
  // time in cycles (lub/run/orbit.hpp).
  numeric("kappa", "orbit_conditioning", "{:.3g}", 1.0);
  numeric("e-fold[cycles]", "slowest_mode_cycles", "{:.3g}", 1.0);
  // Where a case without a steady cycle got to: the last cycle's film, how fast it changes,
  // and how many cycles after the transient its slow flow followed it (docs/theory/
  // steady-cycles.md, slow flow).
  numeric("last_h[um]", "last_cycle_min_film_m", "{:.3g}", 1e6, true);
  numeric("last_W/F", "last_cycle_asperity_load_ratio", "{:.3g}", 1.0, true, true);
  numeric("dh/cycle[nm]", "min_film_drift_m_per_cycle", "{:.3g}", 1e9, true);
  numeric("dh_error[nm]", "min_film_drift_m_per_cycle_error", "{:.3g}", 1e9, true);
  numeric("flow[cycles]", "slow_flow_cycles", "{:.0f}", 1.0, true);
  // Where it drifts toward the wall: its law's exponent, and the cycle at which its film
  // crosses the safe film by that law, with the error bar (docs/theory/drift-law.md).
  numeric("p_drift", "drift_exponent", "{:.3g}", 1.0, true);
  numeric("unsafe_at[cycle]", "safe_film_cycle", "{:.0f}", 1.0, true);
  numeric("unsafe_error", "safe_film_cycle_error", "{:.0f}", 1.0, true);
  numeric("periods", "periods_integrated", "{:.0f}", 1.0);
  numeric("steps", "steps", "{:.0f}", 1.0);
  numeric("wall[s]", "wall_time_s", "{:.2f}", 1.0);
}

/// The two lines above the table: how many cases, how many ok, and the count of each
/// classification.
void print_counts(std::FILE* out, const std::string& path, std::size_t n, std::int64_t total,
                  const std::vector<std::string>& status, const std::vector<std::string>& cls) {
  std::size_t failed = 0;
  for (const auto& s : status) failed += !is_ok(s);
  fmt::print(out, "{}: {} of {} cases, {} ok, {} not ok{}\n", path, n, total, n - failed, failed,
             static_cast<std::int64_t>(n) < total ? " (incomplete: re-run to resume)" : "");
  std::map<std::string, std::size_t> by_class;
  for (const auto& c : cls) ++by_class[c];
  fmt::print(out, "classification:");
  for (const auto& [name, count] : by_class) fmt::print(out, " {} {},", name, count);
  fmt::print(out,
             " (h_min etc. only for periodic cycles; without one, last_h, dh/cycle and flow say where it got to:"
             " {})\n",
             data_path("docs/theory/steady-cycles.md"));
}

/// `s` and spaces up to `width` bytes (fmt's own padding would count UTF-8 characters, and
/// the widths are in bytes).
std::string padded(const std::string& s, std::size_t width) {
  return s.size() < width ? s + std::string(width - s.size(), ' ') : s;
}

/// The table: a heading line, then `n` rows, each column as wide as its widest cell.
void print_table(std::FILE* out, const std::vector<SummaryColumn>& cols, std::size_t n) {
  std::vector<std::size_t> width;
  for (const SummaryColumn& c : cols) {
    std::size_t w = c.head.size();
    for (const auto& s : c.cells) w = std::max(w, s.size());
    width.push_back(w);
  }
  for (std::size_t k = 0; k < cols.size(); ++k)
    fmt::print(out, "{}{}", k ? "  " : "", padded(cols[k].head, width[k]));
  fmt::print(out, "\n");
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < cols.size(); ++k)
      fmt::print(out, "{}{}", k ? "  " : "", padded(cols[k].cells[i], width[k]));
    fmt::print(out, "\n");
  }
}

/// Validity notes (lub/bearing/law_validity.hpp): the study's own (a law outside its L/D), and
/// how many cases of a full-film law saw their load reverse.
void print_notes(std::FILE* out, const h5::File& f, const h5::Table& t) {
  if (f.has_attribute("notes"))
    for (const std::string& n : f.attribute_strings("notes")) fmt::print(out, "note: {}\n", n);
  if (!t.has_column("force_law") || !t.has_column("load_reverses")) return;
  const auto law = t.read_strings("force_law");
  const auto reverses = t.read_int64s("load_reverses");
  std::size_t full = 0, reversed = 0;
  for (std::size_t i = 0; i < law.size(); ++i) {
    const auto l = parse_name<ForceLaw>(law[i]);
    if (!l || !is_full_film_law(*l)) continue;
    ++full;
    reversed += reverses[i] == 1;
  }
  if (reversed > 0)
    fmt::print(out,
               "note: the load reverses (load_reverses = 1) in {} of the {} cases of a full-film law (frene_long, "
               "frene_short): their sub-ambient half films hold the journal where a real film ruptures\n",
               reversed, full);
}

/// A period-count column's sum, its unknowns (-1) left out (0: no such column).
double sum_periods(const h5::Table& t, const char* column) {
  double sum = 0.0;
  if (t.has_column(column))
    for (const std::int64_t p : t.read_int64s(column)) sum += static_cast<double>(std::max<std::int64_t>(p, 0));
  return sum;
}

/// The boundaries located between grid points, where the study file has them
/// (`python3 -m lubjoint.boundaries STUDY.h5` stores them as /boundaries): one line each.
void print_boundaries(std::FILE* out, const h5::File& f, const h5::Table& cases) {
  if (!f.exists("boundaries")) return;
  const h5::Table b = f.open_table("boundaries");
  const std::size_t n = b.rows();
  if (n == 0) {
    fmt::print(out, "boundaries: none between grid points (lubjoint.boundaries)\n");
    return;
  }
  const auto axis = b.read_strings("axis"), unit = b.read_strings("unit"), kind = b.read_strings("kind");
  const auto value = b.read_doubles("value"), error = b.read_doubles("error");
  const auto a = b.read_int64s("case_a"), c = b.read_int64s("case_b"), converged = b.read_int64s("converged");
  // Found by following case_a's safe orbit towards a neighbour without one (files since
  // the column came).
  const auto edge = b.has_column("edge") ? b.read_int64s("edge") : std::vector<std::int64_t>(n, 0);
  static const std::vector<std::string> fixed = {"axis", "value",   "error",     "unit", "kind", "case_a", "case_b",
                                                 "runs", "periods", "converged", "edge", "lost", "reason"};
  // Why a row has not converged (files since the column came).
  const auto reason = b.has_column("reason") ? b.read_strings("reason") : std::vector<std::string>(n);
  // Each row's other axes ("name = value"), a column at a time.
  std::vector<std::string> others(n);
  for (const h5::Column& col : b.columns()) {
    if (std::find(fixed.begin(), fixed.end(), col.name) != fixed.end()) continue;
    std::vector<std::string> text(n);
    if (col.type == h5::ColumnType::String) {
      text = b.read_strings(col.name);
    } else if (col.type == h5::ColumnType::Float64) {
      const std::vector<double> v = b.read_doubles(col.name);
      for (std::size_t i = 0; i < n; ++i)
        if (std::isfinite(v[i])) text[i] = fmt::format("{:g}", v[i]);
    }
    for (std::size_t i = 0; i < n; ++i)
      if (!text[i].empty()) others[i] += (others[i].empty() ? "" : ", ") + col.name + " = " + text[i];
  }
  // What they cost, against the study's own periods (its cases' and their sensitivities').
  const double study = sum_periods(cases, "periods_integrated") + sum_periods(cases, "sensitivity_periods");
  const double spent = sum_periods(b, "periods");
  fmt::print(out, "boundaries located between grid points ({:.0f} periods, {:.1f} % of the study's {:.0f}; {}):\n",
             spent, study > 0.0 ? 100.0 * spent / study : 0.0, study, data_path("docs/theory/sensitivities.md"));
  for (std::size_t i = 0; i < n; ++i) {
    const char* lost = !edge[i] || kind[i] == "safe_film" ? ""
                       : kind[i] == "orbit_end"          ? "; the safe orbit's branch ends"
                                                         : "; the safe orbit turns unstable";
    const std::string why = converged[i] ? "" : ", not converged" + (reason[i].empty() ? "" : ": " + reason[i]);
    fmt::print(out, "  {}: {} = {:.6g} ± {:.2g} {} between cases {} and {} ({}{}){}\n", kind[i], axis[i], value[i],
               error[i], unit[i], a[i], c[i], others[i], lost, why);
  }
}

/// What the sensitivities cost, where the study has them: their periods against the steady
/// stages' (issue 44 bounds them at 30 %).
void print_sensitivity_cost(std::FILE* out, const h5::Table& t) {
  if (!t.has_column("sensitivity_periods") || !t.has_column("periods_integrated")) return;
  const double spent = sum_periods(t, "sensitivity_periods"), steady = sum_periods(t, "periods_integrated");
  fmt::print(out,
             "sensitivities: d_<metric>_per_<axis> of each located orbit in /cases and /grids; {:.0f} periods, {:.1f} % "
             "of the steady stages' {:.0f} ({})\n",
             spent, steady > 0.0 ? 100.0 * spent / steady : 0.0, steady, data_path("docs/theory/sensitivities.md"));
}

/// The refinement's table (`t`: /refinement/cases): one line per case, what it refines and
/// what it found.
void print_refinement_table(std::FILE* out, const h5::Table& t) {
  const std::size_t n = t.rows();
  const auto names = t.read_strings("name"), axis = t.read_strings("axis"), reason = t.read_strings("reason");
  const auto a = t.read_int64s("case_a"), b = t.read_int64s("case_b"), round = t.read_int64s("round");
  const auto status = t.read_strings("status"), cls = t.read_strings("classification");
  std::vector<SummaryColumn> cols = {{"case", names}, {"edge", {}}, {"axis", axis}, {"value", {}}, {"round", {}},
                                     {"reason", reason}, {"status", status}, {"classification", cls}};
  std::map<std::string, std::vector<double>> values;  // each refined axis's column, read once
  for (std::size_t i = 0; i < n; ++i) {
    if (!values.count(axis[i])) values[axis[i]] = t.read_doubles(axis[i]);
    cols[1].cells.push_back(fmt::format("{}-{}", a[i], b[i]));
    cols[3].cells.push_back(formatted("{:.6g}", values[axis[i]].at(i)));
    cols[4].cells.push_back(fmt::format("{}", round[i]));
  }
  const auto metric = [&](const std::string& head, const char* name, const char* format, double scale) {
    SummaryColumn c{head, {}};
    for (double v : t.read_doubles(name)) c.cells.push_back(std::isfinite(v) ? formatted(format, v * scale) : "-");
    cols.push_back(std::move(c));
  };
  metric("h_min[um]", "min_film_thickness_m", "{:.3f}", 1e6);
  SummaryColumn below{"below_safe", {}};
  for (std::int64_t v : t.read_int64s("below_safe_film")) below.cells.push_back(v < 0 ? "-" : fmt::format("{}", v));
  cols.push_back(std::move(below));
  metric("|mu|max", "multiplier_1_modulus", "{:.4f}", 1.0);
  metric("periods", "periods_integrated", "{:.0f}", 1.0);
  print_table(out, cols, n);
}

}  // namespace

void print_refinement(const std::string& path, std::FILE* out) {
  const h5::File f = h5::File::open(path, h5::File::Mode::ReadOnly);
  if (!f.exists("refinement/cases")) return;
  const h5::Table t = f.open_table("refinement/cases");
  const h5::Group g = f.open_group("refinement");
  fmt::print(out, "refinement: {} cases between lattice neighbours (lubsweep refine, --metric-tolerance {:g}; {}):\n",
             t.rows(), g.attribute_double("metric_tolerance"), data_path("docs/guide/lubsweep.md"));
  print_refinement_table(out, t);
}

void print_summary(const std::string& path, std::FILE* out) {
  // One line for a path that is not a study (lubsweep --summary): not HDF5's error stack.
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError("no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError("a directory, not a study file");
  h5::File f;
  try {
    f = h5::File::open(path, h5::File::Mode::ReadOnly);
  } catch (const std::exception&) {
    throw InputError("not an HDF5 file, so not a lubsweep study file");
  }
  if (!f.has_attribute("program") || f.attribute_string("program") != "lubsweep")
    throw InputError("not a lubsweep study file");
  check_format(f, path, "");
  const h5::Table t = f.open_table("cases");
  const std::size_t n = t.rows();
  const auto names = t.read_strings("name");
  const auto status = t.read_strings("status");
  const auto message = t.read_strings("message");
  const auto cls = t.has_column("classification") ? t.read_strings("classification") : status;
  std::vector<SummaryColumn> cols = {{"case", names}};
  add_columns(t, status, cls, cols);

  const std::int64_t total = f.has_attribute("cases_total") ? f.attribute_int64("cases_total") : static_cast<std::int64_t>(n);
  print_counts(out, path, n, total, status, cls);
  print_table(out, cols, n);
  print_sensitivity_cost(out, t);
  print_boundaries(out, f, t);
  print_notes(out, f, t);
  for (std::size_t i = 0; i < n; ++i)
    if (!is_ok(status[i])) fmt::print(out, "{}: {}: {}\n", names[i], status[i], message[i]);
  print_refinement(path, out);
}

}  // namespace lub::sweep
