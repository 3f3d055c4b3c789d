// Which steady cycles are periodic orbits: written once here, for the run, lubsim's report,
// the sweep's columns and summary, and (as the study file's /cases attribute
// orbit_classifications) for the Python reader.
#pragma once

#include <string>
#include <vector>

#include "lub/common/name_table.hpp"
#include "lub/run/run.hpp"

namespace lub {

/// A periodic orbit was found, stable or not: the steady metrics are the orbit's and the
/// Floquet multipliers its own (docs/theory/steady-cycles.md).
constexpr bool has_orbit(SteadyClass k) { return k == SteadyClass::periodic || k == SteadyClass::periodic_unstable; }

/// The names of the steady cycles that are orbits, in SteadyClass's table order.
inline std::vector<std::string> orbit_class_names() {
  std::vector<std::string> out;
  for (const auto& [k, name] : NameTable<SteadyClass>::entries)
    if (has_orbit(k)) out.emplace_back(name);
  return out;
}

}  // namespace lub
