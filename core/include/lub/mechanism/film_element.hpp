// The film element, once: a lubricated revolute joint's bearing kinematics (e, ė, ε, ε̇,
// wedge speed) → its force (force law on the film mode's branch, contact hand-over) → the
// generalised force it adds to g. evaluate() and every Jacobian (the structured
// Jacobians' film derivatives) call these functions, so both see the same arithmetic.
//
// Generalised force of the film force F on the journal at P_j (−F on the bearing at P_i),
// with a_i, a_j the bearing and journal points from their bodies' centres of mass, global:
//     bearing body: (−F_x, −F_y, −a_i × F),     journal body: (F_x, F_y, a_j × F).
// With the film-friction effect the torques T_J (on the journal, against the sliding
// ω_s = ω_J − ω_B) and T_B (on the bearing, along it) add −T_J and +T_B to the φ entries.
#pragma once

#include "lub/bearing/film_outputs.hpp"
#include "lub/mechanism/model.hpp"
#include "lub/mechanism/planar.hpp"

namespace lub {

/// Bearing kinematics (no force) of film f between bearing body state bi and journal body
/// state bj; ai, aj receive the bearing and journal points from their bodies' centres
/// (global). At a centred journal the line of centres is taken along ė (or x).
FilmKinematics film_kinematics(const FilmElement& f, const BodyState& bi, const BodyState& bj,
                               Eigen::Vector2d& ai, Eigen::Vector2d& aj);

/// Bearing kinematics (no force) of film element `k` at (q, v).
FilmKinematics film_kinematics(const Model& m, int k, const double* q, const double* v);

/// Force of film element k on the journal (radial, tangential) at bearing state `state`
/// with the law evaluated on the branch `mode` selects (FilmMode::sliding: at ε̇ = 0),
/// including the contact hand-over if the scene has it. Pure but for ws's solver scratch;
/// each call of the law increments *law_calls (if given).
FilmForce film_element_force(const Model& m, Workspace& ws, int k, const BearingState& state, FilmMode mode,
                             long long* law_calls = nullptr);

/// Friction torques of film element f at kinematics fk (fk.force evaluated) and shaft rates
/// ω_J (journal body), ω_B (bearing body) [rad/s]: the film's shear (film_friction_torques,
/// with the law's F_t, weighted as the film over a contact hand-over band) plus, with mixed
/// lubrication, the asperities' μ_b W_a R_J, the same on both bodies, against ω_s (Coulomb's
/// law, its sign regularised as ω_s/(ω_s² + ω₀²)^½ with ω₀ = 1e-3 rad/s). Zero past the wall.
FrictionTorques film_element_friction(const FilmElement& f, const FilmKinematics& fk, double omega_journal,
                                      double omega_bearing);

/// Film element k at the body states bi (bearing body), bj (journal body): kinematics and
/// force into `fk` (fk.force, fk.F), the force on the branch of the film's current mode
/// (ws.film_mode[k]) with a sliding film's radial force replaced by `sliding_radial_N`,
/// and its generalised force into `load`: load[0..2] on the bearing body (x, y, φ),
/// load[3..5] on the journal body (with the friction torques if the film-friction effect
/// covers the film; fk.torque_power_W their power). False outside the model's domain (ε >= 1 without the
/// contact effect, or a force that is not finite).
bool film_element_load(const Model& m, Workspace& ws, int k, const BodyState& bi, const BodyState& bj,
                       double sliding_radial_N, long long* law_calls, FilmKinematics& fk, double load[6]);

}  // namespace lub
