// The expansion of a grid's blocks into cases (Expander, grid_parts.hpp): axes registered
// as columns, factorial blocks and explicit lists turned into scenes, each scene validated
// by the scene parser and the same scene found once (by its hash).
#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "grid_parts.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/sweep/hash.hpp"

namespace lub::sweep::detail {

using nlohmann::json;

/// Registers (or finds) an axis by name; `path` names its spec for errors.
int Expander::axis_index(Axis a, const std::string& path) {
  for (std::size_t i = 0; i < g_.axes.size(); ++i) {
    const Axis& b = g_.axes[i];
    if (b.name != a.name) continue;
    if (b.kind != a.kind || b.pointer != a.pointer)
      fail(path, json(a.name), "already names another axis (" + axis_origin(b) + ")");
    return static_cast<int>(i);
  }
  g_.axes.push_back(std::move(a));
  return static_cast<int>(g_.axes.size()) - 1;
}

/// Parses one axis spec of a factorial block; its values go to `values`.
int Expander::parse_axis(const json& spec, const std::string& path, std::vector<json>& values) {
  ObjectReader r(spec, path);
  const std::string name = r.string_or("name", "");
  const std::string pointer = r.string_or("pointer", "");
  const json& vals = require_array(r.raw("values"), r.child("values"));
  const json* units = r.raw_optional("units");
  r.finish();
  const std::optional<AxisKind> named = parse_name<AxisKind>(name);
  Axis a;
  if (pointer.empty()) {
    if (!named) {
      const std::string list = names_list<AxisKind>();
      if (name.empty()) throw InputError(path + ": needs a pointer (\"pointer\": \"/solver/rtol\") or a named axis (" + list + ")");
      fail(r.child("name"), json(name), "must be one of " + list + ", or the axis needs a pointer");
    }
    a = named_axis(*named, cx_, r.child("name"));
  } else {
    if (named) fail(r.child("name"), json(name), "is a named axis: it takes no pointer (rename the pointer axis)");
    a = pointer_axis(make_pointer(cx_.base, pointer, r.child("pointer")).to_string(), name, pointer);
  }
  if (!valid_name(a.name))
    fail(r.child("name"), json(a.name), "must be 1-64 letters, digits, '_', '-' or '.' (it names a column and a dataset)");
  if (reserved_column(a.name)) fail(r.child("name"), json(a.name), "is a column lubsweep writes itself: choose another name");
  if (units) {
    if (!units->is_string()) fail(r.child("units"), *units, "must be a string");
    a.units = units->get<std::string>();
  }
  if (vals.empty()) fail(r.child("values"), vals, "must list at least one value");
  for (std::size_t k = 0; k < vals.size(); ++k) {
    const std::string vp = index_path(r.child("values"), k);
    check_type(a, vals[k], vp);
    for (std::size_t j = 0; j < k; ++j)
      if (vals[j] == vals[k]) fail(vp, vals[k], "repeats " + index_path(r.child("values"), j));
    values.push_back(vals[k]);
  }
  return axis_index(a, r.child("name"));
}

void Expander::declare_axes(Block& b, const json& axes, const std::string& path) {
  require_array(axes, path);
  for (std::size_t i = 0; i < axes.size(); ++i) {
    std::vector<json> values;
    const int idx = parse_axis(axes[i], index_path(path, i), values);
    if (std::find(b.axes.begin(), b.axes.end(), idx) != b.axes.end())
      fail(index_path(path, i), axes[i], "varies axis \"" + g_.axes[static_cast<std::size_t>(idx)].name + "\" twice in one grid");
    b.axes.push_back(idx);
    b.shape.push_back(values.size());
    b.values.push_back(std::move(values));
  }
}

void Expander::factorial(Block& b, const std::string& path) {
  std::size_t n = 1;
  for (std::size_t e : b.shape) {
    if (n > kMaxCases / e) throw InputError(fmt::format("{}: the full factorial has more than {} cases", path, kMaxCases));
    n *= e;
  }
  std::vector<std::size_t> at(b.shape.size(), 0);
  for (std::size_t c = 0; c < n; ++c) {
    json scene = cx_.base;
    json shown = json::object();
    std::vector<Given> given;
    std::string label;
    for (std::size_t i = 0; i < b.axes.size(); ++i) {
      const Axis& a = g_.axes[static_cast<std::size_t>(b.axes[i])];
      const json& v = b.values[i][at[i]];
      const std::string vp = index_path(index_path(path, i) + ".values", at[i]);
      apply_value(scene, a, v, vp);
      label += (label.empty() ? "" : " ") + a.name + "=" + value_text(v);
      shown[a.name] = v;
      given.push_back({b.axes[i], v, vp});
    }
    b.case_ids.push_back(add_case(std::move(scene), label, path + ": the case " + brief(shown), given));
    for (std::size_t i = at.size(); i-- > 0;) {  // odometer: last axis fastest
      if (++at[i] < b.shape[i]) break;
      at[i] = 0;
    }
  }
}

/// Axis of an explicit case's key: a named axis, an axis declared by name, or a pointer.
int Expander::key_axis(const std::string& key, const std::string& path) {
  for (std::size_t i = 0; i < g_.axes.size(); ++i)
    if (g_.axes[i].name == key) return static_cast<int>(i);
  Axis a;
  if (const std::optional<AxisKind> named = parse_name<AxisKind>(key)) {
    a = named_axis(*named, cx_, path);
  } else if (!key.empty() && key.front() == '/') {
    const std::string pointer = make_pointer(cx_.base, key, path).to_string();
    for (std::size_t i = 0; i < g_.axes.size(); ++i)
      if (g_.axes[i].kind == AxisKind::pointer && g_.axes[i].pointer == pointer) return static_cast<int>(i);
    a = pointer_axis(pointer, "", key);
    if (!valid_name(a.name)) fail(path, json(key), "gives the column name \"" + a.name + "\", which is not valid: declare the axis with a name");
  } else {
    fail(path, json(key), "unknown key: must be a named axis (" + names_list<AxisKind>() +
                              "), an axis declared in the grid, or a JSON Pointer");
  }
  return axis_index(a, path);
}

void Expander::explicit_cases(Block& b, const json& cases, const std::string& path) {
  require_array(cases, path);
  if (cases.empty()) fail(path, cases, "must list at least one case");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string cp = index_path(path, i);
    if (!cases[i].is_object()) fail(cp, cases[i], "must be a JSON object {axis: value, ...}");
    json scene = cx_.base;
    std::vector<Given> given;
    std::string label;
    for (auto it = cases[i].begin(); it != cases[i].end(); ++it) {
      const std::string vp = key_path(cp, it.key());
      const int idx = key_axis(it.key(), vp);
      const Axis& a = g_.axes[static_cast<std::size_t>(idx)];
      check_type(a, it.value(), vp);
      apply_value(scene, a, it.value(), vp);
      label += (label.empty() ? "" : " ") + a.name + "=" + value_text(it.value());
      given.push_back({idx, it.value(), vp});
    }
    b.case_ids.push_back(add_case(std::move(scene), label, cp + " = " + brief(cases[i]), given));
  }
  b.factorial = false;
  b.shape = {cases.size()};
}

/// Adds a case (or finds the same scene); `what` starts an error message; `given`: the
/// axis values as the grid wrote them (the case's columns for those axes). The case's
/// scene is parsed here to validate it, and not kept: every rank, rank 0 included, parses
/// the canonical JSON it runs (a parsed scene costs rank 0 ~5 kB a case: 0.5 GB for 10⁵).
/// What the sweep itself asks of a case's scene is kept on the Case (Case::steady).
int Expander::add_case(json scene, const std::string& label, const std::string& what, const std::vector<Given>& given) {
  bool valid = false;
  std::vector<std::string> warnings;  // the plausibility warnings of the scene that runs
  std::vector<std::string> notes;     // and its validity notes
  SteadyMethod steady = SimulationSpec().steady;  // and its simulation.steady
  if (cx_.samples_per_cycle && cx_.stores_series) {
    // The sample interval follows the case's cycle period, which only the parsed scene
    // knows: when it sets one, the scene that runs is parsed again below.
    const Scene s = parse_or_blame(scene, what, given);
    if (const auto period = s.cycle_period_s())
      scene["outputs"]["sample_interval_s"] = *period / *cx_.samples_per_cycle;
    else {
      valid = true;
      warnings = s.warnings;
      notes = s.validity_notes;
      steady = s.simulation.steady;
    }
  }
  Case c;
  c.scene = canonical_json(scene);
  c.hash = sha256_hex(c.scene);
  const auto found = by_hash_.find(c.hash);
  if (found != by_hash_.end()) {  // the same scene: parsed and valid already
    for (const Given& g : given) given_[static_cast<std::size_t>(found->second)].emplace(g.axis, g.value);
    return found->second;
  }
  if (!valid) {
    const Scene s = parse_or_blame(scene, what, given);
    warnings = s.warnings;
    notes = s.validity_notes;
    steady = s.simulation.steady;
  }
  if (g_.cases.size() >= kMaxCases) throw InputError(fmt::format("grid: more than {} cases", kMaxCases));
  c.id = static_cast<int>(g_.cases.size());
  c.label = label.empty() ? "base scene" : label;
  c.steady = steady;
  by_hash_[c.hash] = c.id;
  std::map<int, json>& columns = given_.emplace_back();
  for (const Given& g : given) columns[g.axis] = g.value;  // two keys of one axis: the last, as applied
  warnings_.push_back(std::move(warnings));
  notes_.push_back(std::move(notes));
  g_.cases.push_back(std::move(c));
  return g_.cases.back().id;
}

/// Parses a case's scene. If the scene parser refuses it, the message names the grid's
/// value that gives an invalid scene on its own (applied to the base scene), else the
/// case (`what`): the rules are the scene parser's, the grid only says where.
Scene Expander::parse_or_blame(const json& scene, const std::string& what, const std::vector<Given>& given) {
  try {
    return parse_scene(scene);
  } catch (const InputError& e) {
    for (const Given& g : given) {
      const Axis& a = g_.axes[static_cast<std::size_t>(g.axis)];
      json alone = cx_.base;
      apply_value(alone, a, g.value, g.path);
      try {
        parse_scene(alone);
      } catch (const InputError& own) {
        throw InputError(g.path + " = " + brief(g.value) + ": gives an invalid scene" + applied_as(a, g.value, cx_) +
                         ": " + own.what());
      }
    }
    throw InputError(what + ": gives an invalid scene: " + e.what());
  }
}

void Expander::finish() {
  for (Case& c : g_.cases) {
    const json scene = json::parse(c.scene);
    const auto& given = given_[static_cast<std::size_t>(c.id)];
    for (std::size_t i = 0; i < g_.axes.size(); ++i) {
      const auto it = given.find(static_cast<int>(i));
      c.axis_values.push_back(it != given.end() ? it->second : read_value(scene, g_.axes[i]));
    }
  }
  set_column_types();
  std::size_t total = g_.cases.size();
  for (Case& c : g_.cases) c.name = case_name(c.id, total);
  g_.warnings = distinct_warnings(g_, warnings_);
  g_.notes = distinct_warnings(g_, notes_);
}

/// An axis column is float64 if every value it holds is a number (and it holds one); a
/// force law is always a string.
void Expander::set_column_types() {
  for (std::size_t i = 0; i < g_.axes.size(); ++i) {
    Axis& a = g_.axes[i];
    if (a.kind == AxisKind::force_law) continue;
    bool numeric = true, any = false;
    for (const Case& c : g_.cases) {
      const json& v = c.axis_values[i];
      if (v.is_null()) continue;
      any = true;
      numeric = numeric && v.is_number();
    }
    a.numeric = numeric && any;
  }
}

}  // namespace lub::sweep::detail
