// Reading a grid (grid.hpp), one step a function, called in order by parse_grid: the base
// scene, its fixed overrides (`set`), the study settings, the joint and driver the named
// axes address, the blocks, and their expansion into cases (Expander, grid_expand.cpp).
// Each axis kind's meaning is in grid_axis.cpp.
#include "lub/sweep/grid.hpp"

#include <algorithm>
#include <cctype>
#include <utility>

#include <fmt/format.h>

#include "grid_parts.hpp"
#include "lub/io/data_path.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/run/run_io.hpp"
#include "lub/scene/scene.hpp"

namespace lub::sweep {

using nlohmann::json;

namespace detail {

std::string index_path(const std::string& path, std::size_t i) {
  return fmt::format("{}[{}]", path, i);
}

std::string key_path(const std::string& path, const std::string& key) {
  return path + "[" + json(key).dump() + "]";
}

json::json_pointer make_pointer(const json& doc, const std::string& text, const std::string& path) {
  if (text.empty() || text.front() != '/')
    fail(path, json(text), "must be a JSON Pointer (RFC 6901) starting with '/', e.g. /solver/rtol");
  try {
    json::json_pointer syntax_only(text);
  } catch (const json::exception& e) {
    fail(path, json(text), std::string("is not a JSON Pointer (RFC 6901): ") + e.what());
  }
  try {
    return resolve_pointer(doc, text);  // /joints/rod_slider/... is /joints/3/...
  } catch (const InputError& e) {
    fail(path, json(text), e.what());
  }
}

void set_pointer(json& doc, const json::json_pointer& ptr, const json& value, const std::string& what,
                 const json& shown) {
  if (!doc.contains(ptr)) {
    const json::json_pointer parent = ptr.parent_pointer();
    if (!doc.contains(parent) || !doc.at(parent).is_object())
      fail(what, shown, ptr.to_string() + " names no value of the scene, and its parent is not an object");
  }
  doc[ptr] = value;
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

}  // namespace detail

namespace {

using detail::Context;
using detail::index_path;

std::string dir_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
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

/// grid.scene: a scene file (relative to the grid's folder `base_dir`) or an inline scene
/// object, checked by the scene parser; it becomes the base of every case.
void read_base_scene(ObjectReader& r, const std::string& base_dir, Grid& g, Context& cx) {
  const json& sc = r.raw("scene");
  if (sc.is_string()) {
    std::string p = sc.get<std::string>();
    if (p.empty()) fail(r.child("scene"), sc, "must name a scene file (relative to the grid) or be a scene object");
    if (p.front() != '/') p = base_dir + "/" + p;
    g.base_scene_file = p;
    try {
      g.base_scene_text = read_text_file(p);
      cx.base = parse_json(g.base_scene_text);
    } catch (const InputError& e) {  // no such file, syntax, a key twice, a number beyond a double
      fail(r.child("scene"), sc, p + ": " + e.what());
    }
  } else if (sc.is_object()) {
    cx.base = sc;
    g.base_scene_text = sc.dump(2);
  } else {
    fail(r.child("scene"), sc, "must name a scene file (relative to the grid) or be a scene object");
  }
  if (!cx.base.is_object()) fail(r.child("scene"), sc, "the base scene must be a JSON object");
  parse_case(cx.base, r.child("scene"), sc);
}

/// grid.set: fixed overrides of the base scene, each value at a JSON Pointer.
void apply_set(ObjectReader& r, Context& cx) {
  const json* set = r.raw_optional("set");
  if (!set) return;
  if (!set->is_object()) fail(r.child("set"), *set, "must be an object {\"/json/pointer\": value, ...}");
  for (auto it = set->begin(); it != set->end(); ++it) {
    const std::string p = detail::key_path(r.child("set"), it.key());
    detail::set_pointer(cx.base, detail::make_pointer(cx.base, it.key(), p), it.value(), p, it.value());
  }
  parse_case(cx.base, r.child("set"), *set);
}

/// The member `key` of the base scene as an object (created if absent).
json& object_at(json& base, const char* key) {
  if (base.contains(key) && !base[key].is_object()) fail(std::string(key), base[key], "must be a JSON object");
  return base[key];
}

/// grid.study.channels: the base scene's channels the grid stores (none unless the grid
/// names some; "all": the scene's own list).
json chosen_channels(ObjectReader& s, const json& base_channels) {
  json kept = json::array();
  const json* ch = s.raw_optional("channels");
  if (!ch) return kept;
  const std::string path = s.child("channels");
  if (ch->is_string() && ch->get<std::string>() == "all") return base_channels;
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
  return kept;
}

/// Applies grid.study to the base scene; returns the settings that are not scene values.
void apply_study(const json& study, Context& cx, FailurePolicy& policy, bool& sensitivities) {
  ObjectReader s(study, "grid.study");
  json& b = cx.base;
  if (s.has("max_cycles")) object_at(b, "simulation")["max_cycles"] = s.integer("max_cycles", 1, 1'000'000);
  if (s.has("max_periods"))
    object_at(b, "simulation")["max_periods"] = s.integer("max_periods", 1, 1'000'000'000);
  if (s.has("stop_when_steady")) object_at(b, "simulation")["stop_when_steady"] = s.boolean_or("stop_when_steady", true);
  if (s.has("steady_tolerance"))
    object_at(b, "simulation")["steady_tolerance"] = s.number("steady_tolerance", positive, "must be > 0");
  if (s.has("metric_cycles")) object_at(b, "simulation")["metric_cycles"] = s.integer("metric_cycles", 1, 1'000'000);
  if (s.has("last_cycles")) object_at(b, "outputs")["last_cycles"] = s.integer("last_cycles", 0, 1'000'000);
  if (s.has("samples_per_cycle")) cx.samples_per_cycle = static_cast<int>(s.integer("samples_per_cycle", 2, 100'000'000));

  json base_channels = json::array();
  if (b.contains("outputs") && b["outputs"].is_object() && b["outputs"].contains("channels"))
    base_channels = b["outputs"]["channels"];
  const json kept = chosen_channels(s, base_channels);
  if (!kept.empty() || b.contains("outputs")) object_at(b, "outputs")["channels"] = kept;
  cx.stores_series = !kept.empty();
  policy = s.choice("on_failure", {"continue", "abort"}, std::string("continue")) == "abort"
               ? FailurePolicy::abort_on_failure
               : FailurePolicy::continue_on_failure;
  sensitivities = s.boolean_or("sensitivities", true);
  s.finish();
}

/// grid.study applied to the base scene. simulation.steady is whatever the scene, `set` or
/// an axis says, and where none says, the scene parser's default, as lubsim runs the scene:
/// a grid that asks for steady cycles says so ("set": {"/simulation/steady": "auto"}, as
/// the grids in configs/grids do; docs/theory/steady-cycles.md).
void apply_study_settings(ObjectReader& r, Context& cx, FailurePolicy& policy, bool& sensitivities) {
  apply_study(r.has("study") ? r.raw("study") : json::object(), cx, policy, sensitivities);
  parse_case(cx.base, r.child("study"), r.has("study") ? r.raw("study") : json::object());
}

/// The joint and the driver the named axes address: grid.joint (default: metrics.joint),
/// grid.driver (default: the first driver).
void find_targets(ObjectReader& r, Context& cx) {
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
}

/// A block read but not yet expanded: its spec (the axes or the cases) and where it is.
struct PendingBlock {
  Block block;
  const json* spec;
  std::string path;
};

/// grid.grids[i] at `path`: a named sub-grid with either axes or cases; `earlier`: the
/// blocks read before it (their names are taken).
PendingBlock read_sub_grid(const json& spec, const std::string& path, const std::vector<PendingBlock>& earlier) {
  ObjectReader b(spec, path);
  Block blk;
  blk.name = b.string("name");
  if (!detail::valid_name(blk.name))
    fail(b.child("name"), json(blk.name), "must be 1-64 letters, digits, '_', '-' or '.' (it names a group)");
  for (const auto& p : earlier)
    if (p.block.name == blk.name) fail(b.child("name"), json(blk.name), "is the name of another sub-grid");
  const json* axes = b.raw_optional("axes");
  const json* cases = b.raw_optional("cases");
  b.finish();
  if ((axes == nullptr) == (cases == nullptr))
    throw InputError(path + ": needs either axes (a full factorial) or cases (an explicit list), not " +
                     (axes ? "both" : "neither"));
  blk.factorial = axes != nullptr;
  return {blk, axes ? axes : cases, axes ? b.child("axes") : b.child("cases")};
}

/// The blocks: the top-level axes ("grid") and cases ("cases"), then the named sub-grids.
std::vector<PendingBlock> read_blocks(ObjectReader& r) {
  std::vector<PendingBlock> pending;
  if (const json* axes = r.raw_optional("axes")) pending.push_back({Block{"grid", true, {}, {}, {}, {}}, axes, r.child("axes")});
  if (const json* cases = r.raw_optional("cases"))
    pending.push_back({Block{"cases", false, {}, {}, {}, {}}, cases, r.child("cases")});
  if (const json* grids = r.raw_optional("grids")) {
    require_array(*grids, r.child("grids"));
    if (grids->empty()) fail(r.child("grids"), *grids, "must list at least one sub-grid");
    for (std::size_t i = 0; i < grids->size(); ++i)
      pending.push_back(read_sub_grid(grids->at(i), index_path(r.child("grids"), i), pending));
  }
  return pending;
}

/// Expands the blocks into the grid's cases. Axes first (all blocks), so that an explicit
/// case may use an axis a later sub-grid declares.
void expand_blocks(Grid& g, Context& cx, std::vector<PendingBlock>& pending) {
  detail::Expander ex(g, cx);
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
}

}  // namespace

std::string case_name(int id, std::size_t total) {
  int width = 4;
  for (std::size_t t = total > 0 ? total - 1 : 0; t >= 10000; t /= 10) ++width;
  return fmt::format("case_{:0{}d}", id, width);
}

std::string value_text(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) return fmt::format("{:g}", v.get<double>());
  if (v.is_null()) return "-";
  return v.dump();
}

Grid parse_grid(const std::string& text, const std::string& base_dir, const std::string& file) {
  Grid g;
  g.file = file;
  g.text = text;
  const json doc = parse_json(text);  // its messages name no file: the caller names it
  ObjectReader r(doc, "grid");
  g.description = r.string_or("description", "");
  Context cx;
  read_base_scene(r, base_dir, g, cx);
  apply_set(r, cx);
  apply_study_settings(r, cx, g.on_failure, g.sensitivities);
  find_targets(r, cx);
  std::vector<PendingBlock> pending = read_blocks(r);
  r.finish();
  if (pending.empty()) throw InputError("grid: needs axes, cases or grids (" + data_path("docs/guide/grids.md") + ")");
  expand_blocks(g, cx, pending);
  if (g.sensitivities) g.parameters = detail::axis_parameters(g);
  return g;
}

Grid load_grid(const std::string& path) {
  const std::string text = read_text_file(path);
  return parse_grid(text, dir_of(path), path);
}

}  // namespace lub::sweep
