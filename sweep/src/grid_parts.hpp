// Private to the grid's sources: what reading a grid (grid.cpp), the axes' meanings
// (grid_axis.cpp) and the expansion into cases (grid_expand.cpp) share. Not installed, not
// included outside sweep/src.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lub/scene/scene.hpp"
#include "lub/sweep/grid.hpp"

namespace lub::sweep::detail {

/// The most cases a grid may expand to.
inline constexpr std::size_t kMaxCases = 1'000'000;

/// "grid.axes[3]": element `i` of the array at `path`.
std::string index_path(const std::string& path, std::size_t i);
/// grid.set["/a/b"]: a member whose key is a pointer.
std::string key_path(const std::string& path, const std::string& key);
/// The JSON Pointer `text` into `doc`, an element of an array of objects named by its index
/// or its "name" (lub::resolve_pointer: the result has indices only); an error names `path`
/// if it is not a pointer or names an element no element has.
nlohmann::json::json_pointer make_pointer(const nlohmann::json& doc, const std::string& text, const std::string& path);
/// Sets the value at `ptr`: it must name an existing value, or a new key of an existing
/// object (the rule of lubsim's --set). `what` = `shown` names the source in an error.
void set_pointer(nlohmann::json& doc, const nlohmann::json::json_pointer& ptr, const nlohmann::json& value,
                 const std::string& what, const nlohmann::json& shown);
/// 1-64 letters, digits, '_', '-' or '.', and not "." or "..": it names a column or a group.
bool valid_name(const std::string& s);
/// A /cases column lubsweep writes itself (an axis may not take its name).
bool reserved_column(const std::string& name);

/// Everything the expansion needs to know about the base scene.
struct Context {
  nlohmann::json base;         ///< base scene after `set` and `study`
  std::string joint_name;      ///< of the named axes
  std::optional<int> joint;    ///< its index in joints[]
  std::string driver_name;
  std::optional<int> driver;   ///< index in drivers[]
  std::optional<int> samples_per_cycle;
  bool stores_series = false;
};

// --- Each axis kind's meaning (grid_axis.cpp) -----------------------------------------

/// A named axis resolved against the base scene: its pointer (into the metric joint or the
/// driver), unit and column type. `path` names the axis for errors.
Axis named_axis(AxisKind kind, const Context& cx, const std::string& path);
/// An axis at `pointer` (indices only: make_pointer): column `name` ("" gives the default
/// name of the pointer `as_written`, "/joints/rod_slider/x" → joints.rod_slider.x), the
/// unit of the pointer's key.
Axis pointer_axis(const std::string& pointer, const std::string& name, const std::string& as_written);
/// What an axis varies, for a message: its pointer, or the named axis's name.
std::string axis_origin(const Axis& axis);
/// Checks one value of an axis for what the grid itself needs (see grid_axis.cpp).
void check_type(const Axis& axis, const nlohmann::json& v, const std::string& path);
/// Applies one axis value to a scene. `path` names the value for errors.
void apply_value(nlohmann::json& scene, const Axis& axis, const nlohmann::json& v, const std::string& path);
/// The value an axis has in a scene: null if unset.
nlohmann::json read_value(const nlohmann::json& scene, const Axis& axis);
/// The grid's axes a located orbit's metrics are differentiated by: every numeric axis
/// of a physical number (not under /solver, /simulation or /outputs, which are settings
/// a result must not depend on) that is not a dimensionless count (integers without unit).
std::vector<AxisParameter> axis_parameters(const Grid& g);
/// Axis `i` of `g` as such a parameter, or nullopt if it is not one (axis_parameters' rule).
std::optional<AxisParameter> axis_parameter(const Grid& g, std::size_t i);
/// How an axis value reaches the scene, where the scene parser's message needs it ("" if
/// it is set as written).
std::string applied_as(const Axis& axis, const nlohmann::json& v, const Context& cx);

// --- Expansion into cases (grid_expand.cpp) --------------------------------------------

/// One value a case takes from the grid: its axis, the value as written, where it is written.
struct Given {
  int axis;
  nlohmann::json value;
  std::string path;
};

/// Registers a grid's axes and expands its blocks into cases, each validated by the scene
/// parser, the same scene found once.
class Expander {
 public:
  Expander(Grid& g, Context& cx) : g_(g), cx_(cx) {}

  /// Reads the axes of a factorial block (registering them as columns).
  void declare_axes(Block& b, const nlohmann::json& axes, const std::string& path);
  /// Expands a declared factorial block into cases.
  void factorial(Block& b, const std::string& path);
  /// Reads and expands an explicit list of cases.
  void explicit_cases(Block& b, const nlohmann::json& cases, const std::string& path);
  /// Column values, once every axis is known.
  void finish();

 private:
  int axis_index(Axis a, const std::string& path);
  int parse_axis(const nlohmann::json& spec, const std::string& path, std::vector<nlohmann::json>& values);
  int key_axis(const std::string& key, const std::string& path);
  int add_case(nlohmann::json scene, const std::string& label, const std::string& what,
               const std::vector<Given>& given);
  Scene parse_or_blame(const nlohmann::json& scene, const std::string& what, const std::vector<Given>& given);
  void set_column_types();

  Grid& g_;
  Context& cx_;
  std::map<std::string, int> by_hash_;
  std::vector<std::map<int, nlohmann::json>> given_;  ///< per case id
  std::vector<std::vector<std::string>> warnings_;    ///< per case id: its scene's plausibility warnings
  std::vector<std::vector<std::string>> notes_;       ///< per case id: its scene's validity notes
};

/// Grid::warnings from each case's (by case id): each distinct warning once, in the order
/// first met, with how many cases give it: "W; in 3 of 16 cases (the first case_0004)".
std::vector<std::string> distinct_warnings(const Grid& g, const std::vector<std::vector<std::string>>& per_case);

}  // namespace lub::sweep::detail
