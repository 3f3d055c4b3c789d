#include "lub/sweep/grid.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "lub/io/json_reader.hpp"
#include "lub/run/run_io.hpp"
#include "lub/scene/scene.hpp"
#include "lub/sweep/hash.hpp"

namespace lub::sweep {

using nlohmann::json;

namespace {

constexpr std::size_t kMaxCases = 1'000'000;

std::string index_path(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

/// grid.set["/a/b"]: a member whose key is a pointer.
std::string key_path(const std::string& path, const std::string& key) {
  return path + "[" + json(key).dump() + "]";
}

/// Rounds to 15 significant digits, so that R − c of two short decimals is the short
/// decimal a person would write (0.0100 − 0.0005 → 0.0095 exactly, not 0.009500000000000001).
double round_to(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return std::strtod(buf, nullptr);
}
double round15(double x) { return round_to(x, 15); }

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string dir_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

json::json_pointer make_pointer(const std::string& text, const std::string& path) {
  if (text.empty() || text.front() != '/')
    fail(path, json(text), "must be a JSON Pointer (RFC 6901) starting with '/', e.g. /solver/rtol");
  try {
    return json::json_pointer(text);
  } catch (const json::exception& e) {
    fail(path, json(text), std::string("is not a JSON Pointer (RFC 6901): ") + e.what());
  }
}

/// Sets the value at `ptr`: it must name an existing value, or a new key of an existing
/// object (the rule of lubsim's --set). `what` names the source in an error.
void set_pointer(json& doc, const json::json_pointer& ptr, const json& value, const std::string& what,
                 const json& shown) {
  if (!doc.contains(ptr)) {
    const json::json_pointer parent = ptr.parent_pointer();
    if (!doc.contains(parent) || !doc.at(parent).is_object())
      fail(what, shown, ptr.to_string() + " names no value of the scene, and its parent is not an object");
  }
  doc[ptr] = value;
}

/// Column name of a pointer axis without a name: "/solver/rtol" → "solver.rtol".
std::string default_axis_name(const std::string& pointer) {
  std::string s = pointer.substr(1);
  std::replace(s.begin(), s.end(), '/', '.');
  return s;
}

/// Unit of a scene key from its suffix (the scene's keys carry their unit).
std::string unit_of_key(const std::string& pointer) {
  const auto slash = pointer.find_last_of('/');
  const std::string key = slash == std::string::npos ? pointer : pointer.substr(slash + 1);
  static const std::vector<std::pair<std::string, std::string>> suffixes = {
      {"_Pa_s", "Pa s"}, {"_rpm", "min-1"}, {"_rad_s", "rad s-1"}, {"_m_s2", "m s-2"}, {"_kg_m2", "kg m2"},
      {"_m", "m"},       {"_s", "s"},     {"_rad", "rad"},     {"_kg", "kg"},     {"_N", "N"},
      {"_J", "J"}};
  for (const auto& [suffix, unit] : suffixes)
    if (key.size() > suffix.size() && key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0)
      return unit;
  if (key == "rtol" || key == "steady_tolerance") return "1";
  return "";
}

bool reserved_column(const std::string& name) {
  static const std::vector<std::string> own = {"case_id", "case", "name", "hash", "status", "message", "rank", "revision"};
  if (std::find(own.begin(), own.end(), name) != own.end()) return true;
  for (const auto& f : metric_fields())
    if (name == f.name) return true;
  for (const auto& f : solver_fields())
    if (name == f.name) return true;
  return false;
}

bool valid_name(const std::string& s) {
  if (s.empty() || s.size() > 64) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return s != "." && s != "..";
}

/// Everything the expansion needs to know about the base scene.
struct Context {
  json base;                   ///< base scene after `set` and `study`
  std::string joint_name;      ///< of the named axes
  std::optional<int> joint;    ///< its index in joints[]
  std::string driver_name;
  std::optional<int> driver;   ///< index in drivers[]
  std::optional<int> samples_per_cycle;
  bool stores_series = false;
};

/// The named axes' pointers, resolved against the base scene. `path`/`name` for errors.
void resolve_named(Axis& axis, const Context& cx, const std::string& path) {
  const std::string& k = axis.kind;
  if (k == "speed_rpm") {
    if (!cx.driver)
      fail(path, json(axis.name), "the base scene has no driver" +
                                      (cx.driver_name.empty() ? std::string() : " named \"" + cx.driver_name + "\"") +
                                      " (set grid.driver)");
    axis.pointer = "/drivers/" + std::to_string(*cx.driver) + "/speed_rpm";
    axis.units = "min-1";  // CF: revolutions per minute
    return;
  }
  if (!cx.joint)
    fail(path, json(axis.name),
         "the base scene has no lubricated_revolute joint" +
             (cx.joint_name.empty() ? std::string(" named by metrics.joint") : " named \"" + cx.joint_name + "\"") +
             " (set grid.joint)");
  const std::string j = "/joints/" + std::to_string(*cx.joint) + "/";
  if (k == "clearance_m") axis.pointer = j + "journal_radius_m", axis.units = "m";
  if (k == "viscosity_Pa_s") axis.pointer = j + "viscosity_Pa_s", axis.units = "Pa s";
  if (k == "force_law") axis.pointer = j + "force_law", axis.units = "", axis.numeric = false;
}

/// Checks one value of a named axis for what the grid itself needs: its JSON type (it
/// decides the /cases column's type, and a clearance is subtracted from the bearing
/// radius), and a crank cycle (a study's metrics are per cycle; the scene parser accepts a
/// driver at rest, whose scene may run for a duration_s). Every other rule is the scene's:
/// the scene parser checks it once the value is applied (Expander::parse_or_blame).
void check_type(const Axis& axis, const json& v, const std::string& path) {
  if (axis.kind == "pointer") return;
  if (axis.kind == "force_law") {
    if (!v.is_string()) fail(path, v, "must be a string (a force law name)");
  } else if (!v.is_number()) {
    fail(path, v, "must be a number, not " + std::string(v.type_name()));
  } else if (axis.kind == "speed_rpm" && v.get<double>() == 0.0) {
    fail(path, v, "must not be 0 rpm");
  }
}

/// Applies one axis value to a scene. `path` names the value for errors.
void apply_value(json& scene, const Axis& axis, const json& v, const std::string& path) {
  const json::json_pointer ptr(axis.pointer);
  if (axis.kind == "clearance_m") {
    const json::json_pointer radius = ptr.parent_pointer() / "bearing_radius_m";
    if (!scene.contains(radius) || !scene.at(radius).is_number())
      fail(path, v, "the joint has no numeric bearing_radius_m to keep");
    scene[ptr] = round15(scene.at(radius).get<double>() - v.get<double>());
    return;
  }
  set_pointer(scene, ptr, v, path, v);
}

/// The value an axis has in a scene (for the /cases column of a case whose grid does not
/// set it): null if unset. A clearance is R − J to 12 digits (the difference loses digits).
json read_value(const json& scene, const Axis& axis) {
  const json::json_pointer ptr(axis.pointer);
  if (!scene.contains(ptr)) return json();
  if (axis.kind == "clearance_m") {
    const json::json_pointer radius = ptr.parent_pointer() / "bearing_radius_m";
    const json& J = scene.at(ptr);
    if (!scene.contains(radius) || !J.is_number() || !scene.at(radius).is_number()) return json();
    return round_to(scene.at(radius).get<double>() - J.get<double>(), 12);
  }
  return scene.at(ptr);
}

/// Validates a scene with the core parser; a failure's message starts with `prefix`.
Scene parse_case(const json& scene, const std::string& prefix) {
  try {
    return parse_scene(scene);
  } catch (const InputError& e) {
    throw InputError(prefix + ": gives an invalid scene: " + e.what());
  }
}

/// The same, the failure naming `what` = `shown`.
Scene parse_case(const json& scene, const std::string& what, const json& shown) {
  return parse_case(scene, what + " = " + brief(shown));
}

/// Applies grid.study to the base scene; returns the settings that are not scene values.
void apply_study(const json& study, Context& cx, FailurePolicy& policy) {
  ObjectReader s(study, "grid.study");
  json& b = cx.base;
  auto object_at = [&](const char* key) -> json& {
    if (b.contains(key) && !b[key].is_object()) fail(std::string(key), b[key], "must be a JSON object");
    return b[key];
  };
  if (s.has("max_cycles")) object_at("simulation")["max_cycles"] = s.integer("max_cycles", 1, 1'000'000);
  if (s.has("stop_when_steady")) object_at("simulation")["stop_when_steady"] = s.boolean_or("stop_when_steady", true);
  if (s.has("steady_tolerance"))
    object_at("simulation")["steady_tolerance"] = s.number("steady_tolerance", positive, "must be > 0");
  if (s.has("metric_cycles")) object_at("simulation")["metric_cycles"] = s.integer("metric_cycles", 1, 1'000'000);
  if (s.has("last_cycles")) object_at("outputs")["last_cycles"] = s.integer("last_cycles", 0, 1'000'000);
  if (s.has("samples_per_cycle")) cx.samples_per_cycle = static_cast<int>(s.integer("samples_per_cycle", 2, 100'000'000));

  // Channels: none unless the grid names some ("all": the scene's own list).
  json base_channels = json::array();
  if (b.contains("outputs") && b["outputs"].is_object() && b["outputs"].contains("channels"))
    base_channels = b["outputs"]["channels"];
  json kept = json::array();
  if (const json* ch = s.raw_optional("channels")) {
    const std::string path = s.child("channels");
    if (ch->is_string() && ch->get<std::string>() == "all") {
      kept = base_channels;
    } else {
      if (!ch->is_array()) fail(path, *ch, "must be \"all\" or an array of channel names of the base scene");
      std::string known;
      for (const auto& c : base_channels)
        if (c.is_object() && c.contains("name") && c["name"].is_string())
          known += (known.empty() ? "" : ", ") + c["name"].get<std::string>();
      for (std::size_t i = 0; i < ch->size(); ++i) {
        const json& name = (*ch)[i];
        if (!name.is_string()) fail(index_path(path, i), name, "must be a channel name (a string)");
        for (std::size_t j = 0; j < i; ++j)
          if ((*ch)[j] == name) fail(index_path(path, i), name, "repeats " + index_path(path, j));
        bool found = false;
        for (const auto& c : base_channels)
          if (c.is_object() && c.value("name", json()) == name) kept.push_back(c), found = true;
        if (!found)
          fail(index_path(path, i), name,
               "is not a channel of the base scene (" + (known.empty() ? std::string("it has none") : known) + ")");
      }
    }
  }
  if (!kept.empty() || b.contains("outputs")) object_at("outputs")["channels"] = kept;
  cx.stores_series = !kept.empty();
  policy = s.choice("on_failure", {"continue", "abort"}, std::string("continue")) == "abort"
               ? FailurePolicy::abort_on_failure
               : FailurePolicy::continue_on_failure;
  s.finish();
}

/// One value a case takes from the grid: its axis, the value as written, where it is written.
struct Given {
  int axis;
  json value;
  std::string path;
};

class Expander {
 public:
  Expander(Grid& g, Context& cx) : g_(g), cx_(cx) {}

  /// Registers (or finds) an axis by name; `path` names its spec for errors.
  int axis_index(Axis a, const std::string& path) {
    for (std::size_t i = 0; i < g_.axes.size(); ++i) {
      const Axis& b = g_.axes[i];
      if (b.name != a.name) continue;
      if (b.kind != a.kind || b.pointer != a.pointer)
        fail(path, json(a.name), "already names another axis (" + (b.kind == "pointer" ? b.pointer : b.kind) + ")");
      return static_cast<int>(i);
    }
    g_.axes.push_back(std::move(a));
    return static_cast<int>(g_.axes.size()) - 1;
  }

  /// Parses one axis spec of a factorial block.
  int parse_axis(const json& spec, const std::string& path, std::vector<json>& values) {
    ObjectReader r(spec, path);
    Axis a;
    const std::string name = r.string_or("name", "");
    const std::string pointer = r.string_or("pointer", "");
    const json& vals = require_array(r.raw("values"), r.child("values"));
    const json* units = r.raw_optional("units");
    r.finish();
    const auto& named = named_axes();
    const bool is_named = std::find(named.begin(), named.end(), name) != named.end();
    if (pointer.empty()) {
      if (!is_named) {
        std::string list;
        for (const auto& n : named) list += (list.empty() ? "" : ", ") + n;
        if (name.empty()) throw InputError(path + ": needs a pointer (\"pointer\": \"/solver/rtol\") or a named axis (" + list + ")");
        fail(r.child("name"), json(name), "must be one of " + list + ", or the axis needs a pointer");
      }
      a.kind = name;
      a.name = name;
      resolve_named(a, cx_, r.child("name"));
    } else {
      if (is_named)
        fail(r.child("name"), json(name), "is a named axis: it takes no pointer (rename the pointer axis)");
      make_pointer(pointer, r.child("pointer"));
      a.kind = "pointer";
      a.pointer = pointer;
      a.name = name.empty() ? default_axis_name(pointer) : name;
      a.units = unit_of_key(pointer);
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

  /// Reads the axes of a factorial block (registering them as columns).
  void declare_axes(Block& b, const json& axes, const std::string& path) {
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

  /// Expands a declared factorial block into cases.
  void factorial(Block& b, const std::string& path) {
    std::size_t n = 1;
    for (std::size_t e : b.shape) {
      if (n > kMaxCases / e) throw InputError(path + ": the full factorial has more than " + std::to_string(kMaxCases) + " cases");
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
  int key_axis(const std::string& key, const std::string& path) {
    for (std::size_t i = 0; i < g_.axes.size(); ++i)
      if (g_.axes[i].name == key) return static_cast<int>(i);
    const auto& named = named_axes();
    Axis a;
    if (std::find(named.begin(), named.end(), key) != named.end()) {
      a.kind = a.name = key;
      resolve_named(a, cx_, path);
    } else if (!key.empty() && key.front() == '/') {
      make_pointer(key, path);
      for (std::size_t i = 0; i < g_.axes.size(); ++i)
        if (g_.axes[i].kind == "pointer" && g_.axes[i].pointer == key) return static_cast<int>(i);
      a.kind = "pointer";
      a.pointer = key;
      a.name = default_axis_name(key);
      a.units = unit_of_key(key);
      if (!valid_name(a.name)) fail(path, json(key), "gives the column name \"" + a.name + "\", which is not valid: declare the axis with a name");
    } else {
      std::string list;
      for (const auto& n : named) list += (list.empty() ? "" : ", ") + n;
      fail(path, json(key), "unknown key: must be a named axis (" + list + "), an axis declared in the grid, or a JSON Pointer");
    }
    return axis_index(a, path);
  }

  void explicit_cases(Block& b, const json& cases, const std::string& path) {
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
  int add_case(json scene, const std::string& label, const std::string& what, const std::vector<Given>& given) {
    bool valid = false;
    if (cx_.samples_per_cycle && cx_.stores_series) {
      // The sample interval follows the case's cycle period, which only the parsed scene
      // knows: when it sets one, the scene that runs is parsed again below.
      const Scene s = parse_or_blame(scene, what, given);
      if (const auto period = s.cycle_period_s())
        scene["outputs"]["sample_interval_s"] = *period / *cx_.samples_per_cycle;
      else
        valid = true;
    }
    Case c;
    c.scene = canonical_json(scene);
    c.hash = sha256_hex(c.scene);
    const auto found = by_hash_.find(c.hash);
    if (found != by_hash_.end()) {  // the same scene: parsed and valid already
      for (const Given& g : given) given_[static_cast<std::size_t>(found->second)].emplace(g.axis, g.value);
      return found->second;
    }
    if (!valid) parse_or_blame(scene, what, given);
    if (g_.cases.size() >= kMaxCases) throw InputError("grid: more than " + std::to_string(kMaxCases) + " cases");
    c.id = static_cast<int>(g_.cases.size());
    c.label = label.empty() ? "base scene" : label;
    by_hash_[c.hash] = c.id;
    std::map<int, json>& columns = given_.emplace_back();
    for (const Given& g : given) columns[g.axis] = g.value;  // two keys of one axis: the last, as applied
    g_.cases.push_back(std::move(c));
    return g_.cases.back().id;
  }

  /// Parses a case's scene. If the scene parser refuses it, the message names the grid's
  /// value that gives an invalid scene on its own (applied to the base scene), else the
  /// case (`what`): the rules are the scene parser's, the grid only says where.
  Scene parse_or_blame(const json& scene, const std::string& what, const std::vector<Given>& given) {
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
          throw InputError(g.path + " = " + brief(g.value) + ": gives an invalid scene" + applied_as(a, g.value) + ": " +
                           own.what());
        }
      }
      throw InputError(what + ": gives an invalid scene: " + e.what());
    }
  }

  /// How an axis value reaches the scene, where the scene parser's message needs it: a
  /// clearance sets the journal radius.
  std::string applied_as(const Axis& axis, const json& v) const {
    if (axis.kind != "clearance_m") return "";
    const json::json_pointer radius = json::json_pointer(axis.pointer).parent_pointer() / "bearing_radius_m";
    return " (joint " + cx_.joint_name + ": journal_radius_m = bearing_radius_m - clearance = " +
           value_text(cx_.base.at(radius)) + " m - " + value_text(v) + " m)";
  }

  /// Column values, once every axis is known.
  void finish() {
    for (Case& c : g_.cases) {
      const json scene = json::parse(c.scene);
      const auto& given = given_[static_cast<std::size_t>(c.id)];
      for (std::size_t i = 0; i < g_.axes.size(); ++i) {
        const auto it = given.find(static_cast<int>(i));
        c.axis_values.push_back(it != given.end() ? it->second : read_value(scene, g_.axes[i]));
      }
    }
    for (std::size_t i = 0; i < g_.axes.size(); ++i) {
      Axis& a = g_.axes[i];
      if (a.kind == "force_law") continue;
      bool numeric = true, any = false;
      for (const Case& c : g_.cases) {
        const json& v = c.axis_values[i];
        if (v.is_null()) continue;
        any = true;
        numeric = numeric && v.is_number();
      }
      a.numeric = numeric && any;
    }
    std::size_t total = g_.cases.size();
    for (Case& c : g_.cases) c.name = case_name(c.id, total);
  }

 private:
  Grid& g_;
  Context& cx_;
  std::map<std::string, int> by_hash_;
  std::vector<std::map<int, json>> given_;  ///< per case id
};

}  // namespace

const std::vector<std::string>& named_axes() {
  static const std::vector<std::string> n = {"clearance_m", "viscosity_Pa_s", "speed_rpm", "force_law"};
  return n;
}

std::string case_name(int id, std::size_t total) {
  int width = 4;
  for (std::size_t t = total > 0 ? total - 1 : 0; t >= 10000; t /= 10) ++width;
  char buf[32];
  std::snprintf(buf, sizeof buf, "case_%0*d", width, id);
  return buf;
}

std::string value_text(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v.get<double>());
    return buf;
  }
  if (v.is_null()) return "-";
  return v.dump();
}

Grid parse_grid(const std::string& text, const std::string& base_dir, const std::string& file) {
  Grid g;
  g.file = file;
  g.text = text;
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError((file.empty() ? std::string("grid") : file) + ": not valid JSON: " + e.what());
  }
  ObjectReader r(doc, "grid");
  g.description = r.string_or("description", "");

  // Base scene.
  Context cx;
  const json& sc = r.raw("scene");
  if (sc.is_string()) {
    std::string p = sc.get<std::string>();
    if (p.empty()) fail(r.child("scene"), sc, "must name a scene file (relative to the grid) or be a scene object");
    if (p.front() != '/') p = base_dir + "/" + p;
    g.base_scene_file = p;
    try {
      g.base_scene_text = read_text(p);
      cx.base = json::parse(g.base_scene_text);
    } catch (const json::parse_error& e) {
      fail(r.child("scene"), sc, p + ": not valid JSON: " + e.what());
    } catch (const InputError& e) {
      fail(r.child("scene"), sc, e.what());
    }
  } else if (sc.is_object()) {
    cx.base = sc;
    g.base_scene_text = sc.dump(2);
  } else {
    fail(r.child("scene"), sc, "must name a scene file (relative to the grid) or be a scene object");
  }
  if (!cx.base.is_object()) fail(r.child("scene"), sc, "the base scene must be a JSON object");
  parse_case(cx.base, r.child("scene"), sc);

  // Fixed overrides, then the study settings.
  if (const json* set = r.raw_optional("set")) {
    if (!set->is_object()) fail(r.child("set"), *set, "must be an object {\"/json/pointer\": value, ...}");
    for (auto it = set->begin(); it != set->end(); ++it) {
      const std::string p = key_path(r.child("set"), it.key());
      set_pointer(cx.base, make_pointer(it.key(), p), it.value(), p, it.value());
    }
    parse_case(cx.base, r.child("set"), *set);
  }
  apply_study(r.has("study") ? r.raw("study") : json::object(), cx, g.on_failure);
  // A study reports steady cycles: simulation.steady is "auto" unless the scene, `set` or
  // an axis says otherwise (README "Steady cycles"); a run of fixed duration has no cycle.
  if (json& sim = cx.base["simulation"]; !sim.contains("steady") && !sim.contains("duration_s"))
    sim["steady"] = "auto";
  parse_case(cx.base, r.child("study"), r.has("study") ? r.raw("study") : json::object());

  // Joint and driver of the named axes.
  const json& joints = cx.base.value("joints", json::array());
  const json& drivers = cx.base.value("drivers", json::array());
  const bool joint_given = r.has("joint"), driver_given = r.has("driver");
  if (joint_given) {
    cx.joint_name = r.string("joint");
  } else if (cx.base.contains("metrics") && cx.base["metrics"].is_object() && cx.base["metrics"].contains("joint") &&
             cx.base["metrics"]["joint"].is_string()) {
    cx.joint_name = cx.base["metrics"]["joint"].get<std::string>();
  }
  for (std::size_t k = 0; k < joints.size(); ++k)
    if (joints[k].value("name", json()) == json(cx.joint_name) &&
        joints[k].value("type", json()) == json("lubricated_revolute"))
      cx.joint = static_cast<int>(k);
  if (joint_given && !cx.joint)
    fail(r.child("joint"), json(cx.joint_name), "must name a lubricated_revolute joint of the base scene");
  if (driver_given) {
    cx.driver_name = r.string("driver");
    for (std::size_t k = 0; k < drivers.size(); ++k)
      if (drivers[k].value("name", json()) == json(cx.driver_name)) cx.driver = static_cast<int>(k);
    if (!cx.driver) fail(r.child("driver"), json(cx.driver_name), "must name a driver of the base scene");
  } else if (!drivers.empty()) {
    cx.driver = 0;
    cx.driver_name = drivers[0].value("name", std::string());
  }

  // Blocks: top-level axes and cases, and the named sub-grids. Axes first (all blocks),
  // so that an explicit case may use an axis a later sub-grid declares.
  Expander ex(g, cx);
  struct Pending {
    Block block;
    const json* spec;
    std::string path;
  };
  std::vector<Pending> pending;
  if (const json* axes = r.raw_optional("axes")) pending.push_back({Block{"grid", true, {}, {}, {}, {}}, axes, r.child("axes")});
  if (const json* cases = r.raw_optional("cases"))
    pending.push_back({Block{"cases", false, {}, {}, {}, {}}, cases, r.child("cases")});
  if (const json* grids = r.raw_optional("grids")) {
    require_array(*grids, r.child("grids"));
    if (grids->empty()) fail(r.child("grids"), *grids, "must list at least one sub-grid");
    for (std::size_t i = 0; i < grids->size(); ++i) {
      const std::string gp = index_path(r.child("grids"), i);
      ObjectReader b(grids->at(i), gp);
      Block blk;
      blk.name = b.string("name");
      if (!valid_name(blk.name))
        fail(b.child("name"), json(blk.name), "must be 1-64 letters, digits, '_', '-' or '.' (it names a group)");
      for (const auto& p : pending)
        if (p.block.name == blk.name) fail(b.child("name"), json(blk.name), "is the name of another sub-grid");
      const json* axes = b.raw_optional("axes");
      const json* cases = b.raw_optional("cases");
      b.finish();
      if ((axes == nullptr) == (cases == nullptr))
        throw InputError(gp + ": needs either axes (a full factorial) or cases (an explicit list), not " +
                         (axes ? "both" : "neither"));
      blk.factorial = axes != nullptr;
      pending.push_back({blk, axes ? axes : cases, axes ? b.child("axes") : b.child("cases")});
    }
  }
  r.finish();
  if (pending.empty()) throw InputError("grid: needs axes, cases or grids (see the README, \"Writing a grid\")");
  for (auto& p : pending)
    if (p.block.factorial) ex.declare_axes(p.block, *p.spec, p.path);
  for (auto& p : pending) {
    if (p.block.factorial)
      ex.factorial(p.block, p.path);
    else
      ex.explicit_cases(p.block, *p.spec, p.path);
  }
  for (auto& p : pending) g.blocks.push_back(std::move(p.block));
  ex.finish();
  return g;
}

Grid load_grid(const std::string& path) {
  const std::string text = read_text(path);
  return parse_grid(text, dir_of(path), path);
}

}  // namespace lub::sweep
