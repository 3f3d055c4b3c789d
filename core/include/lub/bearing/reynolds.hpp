// Finite-length journal bearing: the two-dimensional Reynolds equation (paper Eq. 1) solved
// numerically for one bearing state — the `finite_reynolds` force law.
//
// ## Equation
// On the unwrapped film, θ from the line of maximum film thickness, z̄ = z/R_J ∈ [−λ, λ],
// λ = L/(2R_J) = L/D, with p = 6 μ (R_J/c)² P and H = h/c = 1 + ε cos θ:
//     ∂/∂θ (H³ ∂P/∂θ) + ∂/∂z̄ (H³ ∂P/∂z̄) = −w ε sin θ + 2 ε̇ cos θ          (wedge, squeeze)
// with P = 0 at both ends z̄ = ±λ (ambient), periodic in θ. The limits λ → 0 and λ → ∞ are
// Eqs. (3) and (5) (up to the gauge of the long limit, below). Forces on the journal:
//     F_r = 6 μ R_J⁴/c² ∫∫ P cos θ dθ dz̄,   F_t = 6 μ R_J⁴/c² ∫∫ P sin θ dθ dz̄.
//
// Cavitation (`Cavitation`):
//  - sommerfeld: the full-film solution (linear), negative pressures kept;
//  - gumbel: the same solution, only its positive part integrated (half-Sommerfeld);
//  - reynolds: Swift–Stieber, the complementarity problem P >= 0, (A P − b) >= 0,
//    P·(A P − b) = 0 (the discrete obstacle problem: its solution has p = ∂p/∂n = 0 on the
//    rupture boundary in the limit), solved exactly by a primal–dual active-set method.
//
// ## Discretization
// Finite volumes on a grid uniform in the eccentric anomaly ψ (1 + ε cos θ = s²/(1 − ε cos ψ)):
// the cells crowd where the film is thin (by (1−ε)/(1+ε))^(1/2) at θ = π) and the long-bearing
// pressure is a trigonometric polynomial in ψ. In ψ the equation reads
//     ∂ψ(k ∂ψ P) + m ∂z̄z̄ P = J·rhs,   k = H³/J = s⁵/(1 − ε cos ψ)²,  m = J H³,  J = dθ/dψ,
// and each cell's source ∫ rhs dθ and z-weight ∫ H³ dθ are integrated exactly; face
// coefficients k are exact at the faces. Axially, half the length is meshed (mid-plane
// symmetry) with nodes z̄_j = j λ/n_z, j = 0..n_z − 1, and P = 0 on the node at the end:
// vertex-centred, so the parabolic axial profile of the short bearing is reproduced exactly.
// Second order overall. Forces: exact cell integrals of cos θ, sin θ times the cell
// pressure, Simpson's rule along z (exact for that parabola).
//
// ## Solvers (sized at construction; the full-film and banded paths do not allocate)
//  - Full film: H depends on θ only, so the discrete operator separates: the axial
//    operator's eigenvectors cos((m + 1/2)π j/n_z) diagonalize it and the problem becomes
//    n_z cyclic tridiagonal systems of size n_theta (Sherman–Morrison + Thomas), solved
//    together with the mode index innermost: O(n_theta n_z²).
//  - Reynolds: primal–dual active-set iteration (Hintermüller, Ito & Kunisch 2003) started
//    from the last call's converged set (warm) or from the cavitated cells of the full-film
//    solution; each step factorizes the system with the active rows replaced by P = 0: a
//    banded Cholesky (half-bandwidth n_z) whenever a fully cavitated column (the usual case)
//    or the groove cuts the ring, else Eigen's SimplicialLDLT (symbolic analysis done once).
//    For an M-matrix (this one is) the iteration terminates in finitely many steps at the
//    exact discrete solution whatever the start, so the result does not depend on the
//    history of calls (tested to 1e-12). Cap: max(50, n_theta + n_z) steps, reached only
//    where the grid cannot resolve the film (ε ≳ 0.99999 on the default grid); `stats()`
//    reports it.
//
// Gauge of the long limit: with ambient pressure at the ends, the long-bearing limit of the
// full-film pressure is the Sommerfeld field with zero H³-weighted circumferential mean
// (the only constant the end boundary layers let through), not the p(0) = 0 gauge of Eq. (5).
// Both give the same full-film force; the positive parts differ when ε̇ ≠ 0 (for pure wedge
// the two gauges coincide, Eq. (5)'s wedge term being odd in θ).
//
// Measured (tests/bench/bench_force_laws.cpp, tests/test_core_reynolds.cpp; docs/theory/force-laws.md):
//  - cost per evaluation on the default 48 × 8 grid: full film or Gümbel ≈ 6 µs; Reynolds
//    ≈ 35–45 µs along a trajectory (warm start: ~1.2 factorizations per call), ≈ 220 µs from
//    a cold start (~8); on 32 × 4: ≈ 3 µs and ≈ 10 µs;
//  - convergence order 1.9–2.2 for all three cavitation conditions (n_theta = 32…256,
//    n_z = n_theta/8); the default grid is within 0.8 % of the converged force at the paper's
//    bearing for ε <= 0.95;
//  - validity: the film near θ = π must be resolved; beyond ε ≈ 0.999 (default grid) the
//    result stays finite but is not accurate, and the Reynolds iteration may hit its cap:
//    hand over to the contact effect (lub/bearing/contact.hpp) before that.
#pragma once

#include <memory>

#include "lub/bearing/film_outputs.hpp"
#include "lub/bearing/force_laws.hpp"

namespace lub {

/// Diagnostics of the last `FiniteBearingSolver::solve`.
struct FiniteBearingStats {
  int active_set_iterations = 0;  ///< Reynolds cavitation: factorizations done (0 otherwise)
  bool converged = true;          ///< false if the active-set cap was reached
  int cavitated_cells = 0;        ///< cells with P = 0 (Reynolds) or P < 0 (Gümbel)
};

/// The finite-length solver with its preallocated scratch (one per film element and thread).
/// Copying gives a solver with the same options and fresh scratch.
class FiniteBearingSolver {
 public:
  /// Throws std::invalid_argument if n_theta < 8 or n_z < 1.
  explicit FiniteBearingSolver(const FiniteBearingOptions& options = FiniteBearingOptions{});
  FiniteBearingSolver(const FiniteBearingSolver& other);
  FiniteBearingSolver& operator=(const FiniteBearingSolver& other);
  FiniteBearingSolver(FiniteBearingSolver&&) noexcept;
  FiniteBearingSolver& operator=(FiniteBearingSolver&&) noexcept;
  ~FiniteBearingSolver();

  const FiniteBearingOptions& options() const;

  /// Film force on the journal for the state (same conventions and preconditions as every
  /// force law: 0 <= ε < 1, finite ε̇ and w, positive geometry and viscosity).
  FilmForce solve(const BearingGeometry& g, double viscosity_Pa_s, const BearingState& s);

  const FiniteBearingStats& stats() const;

  /// The last solution: pressure [Pa] at (i, j), i < n_theta around the circle (cell
  /// centres), j < n_z axial nodes from the mid-plane towards one end (the field is
  /// symmetric; the end node, P = 0, is not stored), negative values included for
  /// `sommerfeld`/`gumbel`. θ [rad] of cell centre i and z [m] of node j.
  double pressure_Pa(int i, int j) const;
  double theta_rad(int i) const;
  double z_m(int j) const;

  /// Friction torques, flows and peak pressure of the last solution (lub/bearing/film_outputs.hpp)
  /// for the sliding speed ω_J − ω_B [rad/s]. Discrete like the force: the Couette integral
  /// over the cells the film fills, the side flow by a second-order one-sided difference at the
  /// ends (exact for the short bearing's parabola), the inflow by the flux through the face at
  /// θ = 0, the peak by a parabola in ψ through the largest mid-plane cell and its neighbours.
  FilmOutputs outputs(double sliding_rad_s) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lub
