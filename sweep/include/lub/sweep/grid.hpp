// A grid: which scenes a study runs. Read from JSON (docs/guide/grids.md), strictly
// validated, and expanded into cases before any work starts, so bad input never costs a
// simulation and never touches an output file.
//
//   {
//     "description": "...",
//     "scene": "../scenes/slider_crank.json",     // base scene: path (relative to the grid) or object
//     "joint": "rod_slider",                       // joint of the named axes (default: metrics.joint)
//     "driver": "crank_speed",                     // driver of speed_rpm (default: the first)
//     "set": {"/solver/rtol": 1e-7},               // fixed overrides of the base scene
//     "study": {"max_cycles": 40, "stop_when_steady": true, "channels": [], "on_failure": "continue"},
//     "axes":  [{"name": "clearance_m", "values": [5e-4, 1e-4]},
//               {"pointer": "/solver/method", "name": "method", "values": ["cvode_bdf", "cvode_adams"]}],
//     "cases": [{"clearance_m": 5e-5, "/solver/rtol": 1e-8}],
//     "grids": [{"name": "clearance", "axes": [...]}, {"name": "speed", "axes": [...]}]
//   }
//
// `axes` is a full factorial (the first axis varies slowest), `cases` an explicit list,
// `grids` a union of named sub-grids (each with `axes` or `cases`). Cases with the same
// effective scene are run once (the paper's reference case belongs to every one-axis study).
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lub/common/name_table.hpp"
#include "lub/scene/scene.hpp"

namespace lub::sweep {

enum class FailurePolicy { continue_on_failure, abort_on_failure };

/// What an axis varies: one of the four named axes (the paper's study axes, which a grid
/// names without a pointer), or the scene value at a JSON Pointer.
enum class AxisKind { clearance_m, viscosity_Pa_s, speed_rpm, force_law, pointer };

}  // namespace lub::sweep

namespace lub {
/// The names a grid may give an axis without a pointer. `pointer` has no entry on purpose:
/// a grid never names it (a pointer axis is given by its "pointer"), so parsing a name
/// never yields it and the "must be one of" messages list the named axes only.
template <>
struct NameTable<sweep::AxisKind> {
  static constexpr std::array<std::pair<sweep::AxisKind, std::string_view>, 4> entries{{
      {sweep::AxisKind::clearance_m, "clearance_m"},
      {sweep::AxisKind::viscosity_Pa_s, "viscosity_Pa_s"},
      {sweep::AxisKind::speed_rpm, "speed_rpm"},
      {sweep::AxisKind::force_law, "force_law"},
  }};
};
}  // namespace lub

namespace lub::sweep {

/// One varied quantity: a column of /cases.
struct Axis {
  std::string name;     ///< column name; the named axes carry their unit in the name
  AxisKind kind = AxisKind::pointer;  ///< a named axis, or the scene value at `pointer`
  std::string pointer;  ///< the scene value it sets (clearance_m: the journal radius)
  std::string units;    ///< SI unit ("m", "Pa s", "rpm", "" ...)
  bool numeric = true;  ///< every value a number: a float64 column (else strings)
};

/// A numeric axis of a grid as a parameter λ of the case's scene: the scene's number at
/// `pointer` is base + sign λ, base the number at `base_pointer` ("": 0). A clearance c
/// sets the journal radius R_B − c: base the bearing radius, sign −1.
struct AxisParameter {
  std::string name;          ///< the axis's column name (clearance_m, viscosity_Pa_s, ...)
  std::string unit;          ///< its unit (CF)
  std::string pointer;
  std::string base_pointer;
  double sign = 1.0;
};

/// One sub-grid: a full factorial over some axes, or an explicit list of cases.
struct Block {
  std::string name;
  bool factorial = true;
  std::vector<int> axes;                            ///< factorial: indices into Grid::axes
  std::vector<std::vector<nlohmann::json>> values;  ///< factorial: each axis's values, as listed
  std::vector<std::size_t> shape;                   ///< factorial: extents; explicit: {cases}
  std::vector<int> case_ids;                        ///< row-major over `shape`
};

/// One simulation of the study.
struct Case {
  int id = 0;                                ///< row of /cases in the finished file
  std::string name;                          ///< "case_0007": its /series group
  std::string scene;                         ///< canonical JSON of the effective scene: what runs
  std::string hash;                          ///< SHA-256 of `scene`: identity for resume
  std::vector<nlohmann::json> axis_values;   ///< per Grid::axes, read back from the scene (null: unset)
  std::string label;                         ///< "clearance_m=0.0001" (the values its grid varies)
  /// Its parsed scene's simulation.steady (read where the case is built: what the sweep
  /// asks of a case's scene, it asks the parsed scene, never the JSON text).
  SteadyMethod steady = SimulationSpec().steady;
};

struct Grid {
  std::string file;             ///< grid file ("" if parsed from text)
  std::string text;             ///< the grid as given
  std::string description;
  std::string base_scene_file;  ///< "" if inline
  std::string base_scene_text;  ///< the base scene as given (its file's text, or the inline object)
  FailurePolicy on_failure = FailurePolicy::continue_on_failure;
  std::vector<Axis> axes;
  std::vector<Block> blocks;
  std::vector<Case> cases;
  /// The plausibility warnings of its cases (Scene::warnings, lub/bearing/plausibility.hpp),
  /// each distinct warning once: "W; in 3 of 16 cases (the first case_0004)".
  std::vector<std::string> warnings;
  /// The validity notes of its cases (Scene::validity_notes, lub/bearing/law_validity.hpp),
  /// each distinct note once, as the warnings. Informative: --strict does not refuse them.
  std::vector<std::string> notes;
  /// grid.study.sensitivities (default true): each located orbit's steady metrics
  /// differentiated by `parameters`, its numeric axes of physical numbers.
  bool sensitivities = true;
  std::vector<AxisParameter> parameters;
};

/// Reads, validates and expands a grid file. Throws lub::InputError naming the field, the
/// value and the rule. The grid checks its own shape and the types of the named axes'
/// values; every scene rule is the scene parser's, run on each case's scene, its message
/// prefixed with the grid's value that breaks it ("grid.axes[0].values[2] = 0: gives an
/// invalid scene: joints[3].viscosity_Pa_s = 0: must be > 0 Pa s"). The messages do not name
/// the grid's file ("no such file", "line 3, column 7: not valid JSON: ..."): the caller does.
Grid load_grid(const std::string& path);

/// The same from the grid's text; relative scene paths are resolved against `base_dir`,
/// `file` is recorded as the grid's file name.
Grid parse_grid(const std::string& text, const std::string& base_dir, const std::string& file = "");

/// The long_name attribute of an axis's column and dimension scale.
std::string axis_long_name(const Axis& axis);

/// "case_0007": zero-padded to at least four digits and to the width of the largest id.
std::string case_name(int id, std::size_t total);

/// A JSON value for a message or a label: strings without quotes, numbers in %g.
std::string value_text(const nlohmann::json& v);

}  // namespace lub::sweep
