// How fast a transient approaches its steady cycle, from its own cycles (the steady stage).
//
// Near a stable periodic orbit the cycle map contracts: the distance between successive
// cycles shrinks as δ_k ≈ C ρ^k, ρ = |μ|max the dominant Floquet multiplier's modulus.
// The distance still to go from cycle k to the orbit is then at most
//     Σ_{j>k} δ_j = δ_k ρ / (1 − ρ),
// which is what a steady stop must test (a fixed threshold on δ_k alone calls a slow
// drift steady: δ = 2e-4 c per cycle with ρ = 0.99 is still 0.02 c from its cycle).
#pragma once

#include <vector>

namespace lub::steady {

struct ContractionEstimate {
  bool known = false;       ///< enough cycles, and a fit that says something
  double rate = 1.0;        ///< ρ: δ_{k+1} ≈ ρ δ_k (least squares of log δ over the window)
  double remaining = 0.0;   ///< δ_k ρ / (1 − ρ) (same unit as δ); +inf when ρ >= 1
  double last = 0.0;        ///< δ_k
};

/// ρ from the last `window` cycle distances (values < 0 are "unknown", first cycle),
/// fitted as a straight line in log δ against the cycle number. A complex dominant pair
/// makes log δ oscillate about that line: the window should span a few of its turns.
/// Distances at or below `floor` (the integration's own noise, same unit) count as the
/// floor: a converged transient's δ stalls there and would read as ρ → 1.
ContractionEstimate estimate_contraction(const std::vector<double>& distances, int window, double floor);

/// Whether a transient has reached its steady cycle within `tolerance`: ρ known and < 1,
/// and δ_k ρ / (1 − ρ) <= tolerance; or every distance of the window at the noise floor.
bool transient_converged(const ContractionEstimate& e, double tolerance);

/// Least-squares slope per cycle of the last `window` values (e.g. the minimum film
/// thickness of each cycle: its drift per cycle). 0 with fewer than two values.
double trend_per_cycle(const std::vector<double>& values, int window);

/// Cycles still needed until δ ρ/(1 − ρ) <= tolerance (+inf if ρ >= 1 or unknown).
double cycles_to_converge(const ContractionEstimate& e, double tolerance);

}  // namespace lub::steady
