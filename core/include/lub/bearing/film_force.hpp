// Any force law by its enum: the dispatcher over the closed-form laws (force_laws.hpp) and
// the finite-length Reynolds solver (reynolds.hpp). It sits above both, so that the laws
// and the solver depend on nothing but the bearing's types.
#pragma once

#include "lub/bearing/force_laws.hpp"
#include "lub/bearing/reynolds.hpp"

namespace lub {

/// Film force of `law`. Requires 0 <= eps < 1, finite eps_dot and wedge, positive
/// geometry and viscosity (the caller validates; see each law for its limits:
/// ε = 0 and ε̇ = 0 are evaluated by their limits, never NaN).
/// For `finite_reynolds` this overload builds a solver with default options each call
/// (allocates: for checks and tools; inside a right-hand side use the overload below).
FilmForce film_force(ForceLaw law, const BearingGeometry& g, double viscosity_Pa_s,
                     const BearingState& s);

/// Same, for `finite_reynolds` with the given solver (its options and preallocated scratch;
/// no allocation); `solver` is ignored (may be null) for the closed-form laws.
FilmForce film_force(ForceLaw law, const BearingGeometry& g, double viscosity_Pa_s,
                     const BearingState& s, FiniteBearingSolver* solver);

}  // namespace lub
