// Which steady cycles are periodic orbits: written once here, for lubsim's report, the
// sweep's columns and summary, and (through the sweep's CaseClass, as the study file's
// /cases attribute orbit_classifications) for the Python reader.
#pragma once

#include "lub/run/run.hpp"

namespace lub {

/// A periodic orbit was found, stable or not: the steady metrics are the orbit's and the
/// Floquet multipliers its own (docs/theory/steady-cycles.md).
constexpr bool has_orbit(SteadyClass k) { return k == SteadyClass::periodic || k == SteadyClass::periodic_unstable; }

}  // namespace lub
