// Each axis kind's meaning, in one place: what a named axis sets in the scene (a key of the
// metric joint or of the driver), its unit and long name; a pointer axis's default column
// name and unit; how a value is checked, applied to a scene and read back from one.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "grid_parts.hpp"
#include "lub/io/json_reader.hpp"

namespace lub::sweep {

using nlohmann::json;

namespace {

/// What a named axis's key belongs to: the metric joint (grid.joint) or the driver (grid.driver).
enum class Owner { joint, driver };

/// A named axis's meaning: the key it sets under its owner, its unit (CF) and long name. A
/// clearance c sets the journal radius, bearing_radius_m - c (apply_value).
struct NamedAxisMeaning {
  AxisKind kind;
  Owner owner;
  const char* key;
  const char* units;
  const char* long_name;
};

constexpr std::array<NamedAxisMeaning, 4> kNamedAxes{{
    {AxisKind::clearance_m, Owner::joint, "journal_radius_m", "m",
     "radial clearance c = bearing radius - journal radius"},
    {AxisKind::viscosity_Pa_s, Owner::joint, "viscosity_Pa_s", "Pa s", "lubricant dynamic viscosity"},
    {AxisKind::speed_rpm, Owner::driver, "speed_rpm", "min-1",  // CF: revolutions per minute
     "driver speed in revolutions per minute"},
    {AxisKind::force_law, Owner::joint, "force_law", "", "hydrodynamic force law of the lubricated joint"},
}};

const NamedAxisMeaning& meaning_of(AxisKind kind) {
  for (const auto& m : kNamedAxes)
    if (m.kind == kind) return m;
  throw std::logic_error("lubsweep: AxisKind::pointer has no named meaning");
}

/// Rounds to `digits` significant digits, so that R − c of two short decimals is the short
/// decimal a person would write (0.0100 − 0.0005 → 0.0095 exactly, not 0.009500000000000001).
double round_to(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return std::strtod(buf, nullptr);
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

/// The journal radius next to a clearance axis's pointer.
json::json_pointer bearing_radius_of(const Axis& clearance) {
  return json::json_pointer(clearance.pointer).parent_pointer() / "bearing_radius_m";
}

}  // namespace

std::string axis_long_name(const Axis& a) {
  if (a.kind == AxisKind::pointer) return "scene value " + a.pointer;
  return meaning_of(a.kind).long_name;
}

namespace detail {

Axis named_axis(AxisKind kind, const Context& cx, const std::string& path) {
  const NamedAxisMeaning& m = meaning_of(kind);
  Axis axis;
  axis.kind = kind;
  axis.name = std::string(name_of(kind));
  if (m.owner == Owner::driver) {
    if (!cx.driver)
      fail(path, json(axis.name), "the base scene has no driver" +
                                      (cx.driver_name.empty() ? std::string() : " named \"" + cx.driver_name + "\"") +
                                      " (set grid.driver)");
    axis.pointer = fmt::format("/drivers/{}/{}", *cx.driver, m.key);
  } else {
    if (!cx.joint)
      fail(path, json(axis.name),
           "the base scene has no lubricated_revolute joint" +
               (cx.joint_name.empty() ? std::string(" named by metrics.joint") : " named \"" + cx.joint_name + "\"") +
               " (set grid.joint)");
    axis.pointer = fmt::format("/joints/{}/{}", *cx.joint, m.key);
  }
  axis.units = m.units;
  axis.numeric = kind != AxisKind::force_law;
  return axis;
}

Axis pointer_axis(const std::string& pointer, const std::string& name, const std::string& as_written) {
  Axis axis;
  axis.kind = AxisKind::pointer;
  axis.pointer = pointer;
  axis.name = name.empty() ? default_axis_name(as_written) : name;
  axis.units = unit_of_key(pointer);
  return axis;
}

std::string axis_origin(const Axis& axis) {
  return axis.kind == AxisKind::pointer ? axis.pointer : std::string(name_of(axis.kind));
}

/// Checks one value of an axis for what the grid itself needs: its JSON type (it decides the
/// /cases column's type, and a clearance is subtracted from the bearing radius), and a crank
/// cycle (a study's metrics are per cycle; the scene parser accepts a driver at rest, whose
/// scene may run for a duration_s). Every other rule is the scene's: the scene parser
/// checks it once the value is applied (Expander::parse_or_blame).
void check_type(const Axis& axis, const json& v, const std::string& path) {
  if (axis.kind == AxisKind::pointer) return;
  if (axis.kind == AxisKind::force_law) {
    if (!v.is_string()) fail(path, v, "must be a string (a force law name)");
  } else if (!v.is_number()) {
    fail(path, v, "must be a number, not " + std::string(v.type_name()));
  } else if (axis.kind == AxisKind::speed_rpm && v.get<double>() == 0.0) {
    fail(path, v, "must not be 0 rpm");
  }
}

void apply_value(json& scene, const Axis& axis, const json& v, const std::string& path) {
  const json::json_pointer ptr(axis.pointer);
  if (axis.kind == AxisKind::clearance_m) {
    const json::json_pointer radius = bearing_radius_of(axis);
    if (!scene.contains(radius) || !scene.at(radius).is_number())
      fail(path, v, "the joint has no numeric bearing_radius_m to keep");
    scene[ptr] = round_to(scene.at(radius).get<double>() - v.get<double>(), 15);
    return;
  }
  set_pointer(scene, ptr, v, path, v);
}

/// (For the /cases column of a case whose grid does not set the axis.) A clearance is
/// R − J to 12 digits (the difference loses digits).
json read_value(const json& scene, const Axis& axis) {
  const json::json_pointer ptr(axis.pointer);
  if (!scene.contains(ptr)) return json();
  if (axis.kind == AxisKind::clearance_m) {
    const json::json_pointer radius = bearing_radius_of(axis);
    const json& J = scene.at(ptr);
    if (!scene.contains(radius) || !J.is_number() || !scene.at(radius).is_number()) return json();
    return round_to(scene.at(radius).get<double>() - J.get<double>(), 12);
  }
  return scene.at(ptr);
}

std::optional<AxisParameter> axis_parameter(const Grid& g, std::size_t i) {
  const Axis& a = g.axes.at(i);
  if (!a.numeric || a.kind == AxisKind::force_law) return std::nullopt;
  const bool setting = a.pointer.rfind("/solver/", 0) == 0 || a.pointer.rfind("/simulation/", 0) == 0 ||
                       a.pointer.rfind("/outputs/", 0) == 0;
  const bool counts = (a.units.empty() || a.units == "1") &&
                      std::all_of(g.cases.begin(), g.cases.end(), [i](const Case& c) {
                        return i >= c.axis_values.size() || c.axis_values[i].is_null() ||
                               c.axis_values[i].is_number_integer();
                      });
  if (setting || counts) return std::nullopt;
  AxisParameter p{a.name, a.units.empty() ? "1" : a.units, a.pointer, "", 1.0};
  if (a.kind == AxisKind::clearance_m) {  // the journal radius R_B − c
    p.base_pointer = bearing_radius_of(a).to_string();
    p.sign = -1.0;
  }
  return p;
}

std::vector<AxisParameter> axis_parameters(const Grid& g) {
  std::vector<AxisParameter> out;
  for (std::size_t i = 0; i < g.axes.size(); ++i)
    if (auto p = axis_parameter(g, i)) out.push_back(std::move(*p));
  return out;
}

/// A clearance sets the journal radius: the scene parser's message speaks of that.
std::string applied_as(const Axis& axis, const json& v, const Context& cx) {
  if (axis.kind != AxisKind::clearance_m) return "";
  return " (joint " + cx.joint_name + ": journal_radius_m = bearing_radius_m - clearance = " +
         value_text(cx.base.at(bearing_radius_of(axis))) + " m - " + value_text(v) + " m)";
}

}  // namespace detail
}  // namespace lub::sweep
