// The rules of a journal bearing's inputs, written once for their three readers: the scene
// (joints[i].bearing_radius_m, .reynolds_n_theta, ...: core/src/scene/scene.cpp), lubbearing
// (--radius-m, --n-theta, ...: core/apps/lubbearing.cpp) and the Python module (radius_m,
// n_theta, ...: core/python/bindings.cpp).
//
// Each check is a predicate and its rule text; the caller has read the value its own way (a
// JSON value, an option's text, a Python argument) and reports a broken rule under its own
// field name, with its own error (the bearing stage has none: lubbearing links it alone).
// The messages are pinned by tests/test_core_validation.cpp (scene), tests/test_core_lubbearing.cpp
// and tests/python/test_lubjoint.py.
#pragma once

#include <cmath>
#include <string>
#include <string_view>

namespace lub {

/// A closed range of integers [min, max].
struct IntRange {
  int min;
  int max;
  bool contains(long long value) const { return value >= min && value <= max; }
  /// "must be in [min, max]" (lubbearing, Python; the scene's JSON reader says "must be an
  /// integer in [min, max]").
  std::string rule() const {
    return "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  }
};

/// finite_reynolds' grid (FiniteBearingOptions): cells around the circumference and axial
/// nodes over half the length.
inline constexpr IntRange kReynoldsNThetaRange{8, 4096};
inline constexpr IntRange kReynoldsNZRange{1, 1024};

/// A radius, clearance, length [m], viscosity [Pa s] or load [N]: finite and > 0.
inline bool is_positive_input(double value) { return std::isfinite(value) && value > 0.0; }
/// The rule of is_positive_input: "must be > 0 <unit>".
inline std::string positive_rule(std::string_view unit) { return "must be > 0 " + std::string(unit); }

/// The eccentricity ratio a film force law is evaluated at: 0 <= ε < 1 (NaN is not).
inline bool is_film_eccentricity_ratio(double eps) { return eps >= 0.0 && eps < 1.0; }
inline constexpr std::string_view kFilmEccentricityRatioRule =
    "must be in [0, 1) (eps >= 1: the journal touches the bearing, no film law applies)";

/// A steady bearing's journal speed [rpm]: finite and not 0.
inline bool is_journal_speed(double rpm) { return std::isfinite(rpm) && rpm != 0.0; }
inline constexpr std::string_view kJournalSpeedRule = "must be != 0 rpm";

}  // namespace lub
