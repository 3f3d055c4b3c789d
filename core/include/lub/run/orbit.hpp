// Which steady cycles are periodic orbits: written once here, for lubsim's report, the
// sweep's columns and summary, and (through the sweep's CaseClass, as the study file's
// /cases attribute orbit_classifications) for the Python reader.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include "lub/run/run.hpp"

namespace lub {

/// A periodic orbit was found, stable or not: the steady metrics are the orbit's and the
/// Floquet multipliers its own (docs/theory/steady-cycles.md).
constexpr bool has_orbit(SteadyClass k) { return k == SteadyClass::periodic || k == SteadyClass::periodic_unstable; }

/// How well posed an orbit's place is (docs/theory/steady-cycles.md, how well posed). To first
/// order the computed orbit is off by (I − M)⁻¹ (P_h − P)(z*), and a parameter λ moves it by
/// (I − M)⁻¹ ∂P/∂λ: along the eigenvector of a multiplier μ both are divided by 1 − μ. So
///     κ = 1 / min_k |1 − μ_k|   [1]
/// over the Floquet multipliers μ_k: the factor by which the orbit's place amplifies its period
/// map's error or a parameter's change. |1 − μ|, not 1 − |μ|: a complex pair near the unit
/// circle at a large angle is well conditioned. NaN without multipliers; +inf at μ = 1.
inline double orbit_conditioning(const std::vector<std::complex<double>>& mu) {
  if (mu.empty()) return std::numeric_limits<double>::quiet_NaN();
  double nearest = std::numeric_limits<double>::infinity();
  for (const std::complex<double>& m : mu) nearest = std::min(nearest, std::abs(1.0 - m));
  return 1.0 / nearest;
}

/// The e-folding time of the slowest Floquet mode, in crank cycles [1]:
///     1 / min_k |ln |μ_k||
/// how many cycles a disturbance along it takes to shrink (|μ| < 1) or grow (|μ| > 1) by a
/// factor e: how long a real mechanism takes to settle onto the orbit. NaN without
/// multipliers; +inf at |μ| = 1.
inline double slowest_mode_cycles(const std::vector<std::complex<double>>& mu) {
  if (mu.empty()) return std::numeric_limits<double>::quiet_NaN();
  double slowest = std::numeric_limits<double>::infinity();
  for (const std::complex<double>& m : mu) slowest = std::min(slowest, std::abs(std::log(std::abs(m))));
  return 1.0 / slowest;
}

}  // namespace lub
