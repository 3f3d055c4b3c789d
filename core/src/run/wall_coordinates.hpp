// Shooting's wall-safe coordinates of a journal in its bearing (internal to the run stage;
// docs/theory/steady-cycles.md, "Coordinates that keep Newton inside the clearance").
//
// The eccentricity u = e / c (the journal centre's offset from the bearing centre in
// clearances, |u| = ε < 1) is mapped onto the whole plane by
//     w = g(ε) u,        g(ε) = atanh(ε) / ε     (g(0) = 1),
// and back by u = tanh(|w|) w / |w|. Every w is a journal inside the clearance, so Newton's
// iterates and its difference steps cannot cross the wall; near it |w| ≈ ½ ln(2 / (1 − ε)):
// a step in w is a relative change of the gap 1 − ε, however thin the film. Away from the
// wall w ≈ u (g = 1 + ε²/3 + …). Rates follow by the chain rule:
//     ẇ = g u̇ + (g'(ε)/ε) (u·u̇) u,      u̇ = f ẇ + (f'(ρ)/ρ) (w·ẇ) w,   f(ρ) = tanh ρ / ρ,
// ρ = |w|; u̇ = ė / c [1/s], ẇ [1/s]. The ratios g'/ε and f'/ρ are even functions, taken
// from their Taylor series near 0 where the closed forms cancel.
#pragma once

#include <Eigen/Core>

namespace lub::detail {

/// (u, u̇) → (w, ẇ). Requires |u| < 1.
void to_wall_coordinates(const Eigen::Vector2d& u, const Eigen::Vector2d& u_dot, Eigen::Vector2d& w,
                         Eigen::Vector2d& w_dot);

/// (w, ẇ) → (u, u̇). False where tanh |w| rounds to 1 (a gap below 1e-15 c).
bool from_wall_coordinates(const Eigen::Vector2d& w, const Eigen::Vector2d& w_dot, Eigen::Vector2d& u,
                           Eigen::Vector2d& u_dot);

/// d|w|/dε = 1/(1 − ε²): how much the radial wall coordinate stretches a change of ε.
double wall_stretch(double eps);

}  // namespace lub::detail
