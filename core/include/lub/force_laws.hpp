// Hydrodynamic force laws of a lubricated revolute joint (journal bearing).
//
// A force law is a pure function of the bearing state: geometry, viscosity, the
// eccentricity ratio ε, its rate ε̇ and the wedge speed w. It knows nothing of any
// mechanism, and is tested on its own against quadrature of its own pressure field.
//
// ## Conventions (shared by every law here; see README "Force laws")
//
//  - Journal radius R_J, bearing radius R_B, radial clearance c = R_B − R_J > 0 [m],
//    bearing length L [m], dynamic viscosity μ [Pa s].
//  - Eccentricity vector e = journal centre − bearing centre; ε = |e|/c ∈ [0, 1).
//  - ε̇ = d|e|/dt / c [1/s]; positive when the journal moves towards the wall.
//  - The wedge speed w = ω_J + ω_B − 2γ̇ [rad/s]: ω_J, ω_B the absolute angular
//    velocities of journal and bearing bodies, γ̇ the rate of the line of centres in the
//    global frame. The paper writes it ω − 2γ̇ with ω relative and γ measured from the
//    bearing body: the same number, but only this form is right when the bearing body
//    rotates.
//  - θ is measured from the line of maximum film thickness: h = c (1 + ε cos θ).
//  - The result is the force ON THE JOURNAL, resolved along r = e/|e| (radial, from
//    bearing centre to journal centre) and t = r rotated +90° (tangential):
//      F_r = ∫ p cos θ R_J dθ dz,  F_t = ∫ p sin θ R_J dθ dz.
//    The force on the bearing is the opposite.
//
// Units: SI throughout.
#pragma once

#include <string>
#include <string_view>

namespace lub {

/// Geometry of a journal bearing [m].
struct BearingGeometry {
  double journal_radius_m = 0.0;  ///< R_J
  double bearing_radius_m = 0.0;  ///< R_B
  double length_m = 0.0;          ///< L
  double clearance_m() const { return bearing_radius_m - journal_radius_m; }
};

/// The state a force law sees.
struct BearingState {
  double eps = 0.0;      ///< ε = |e|/c, dimensionless, in [0, 1)
  double eps_dot = 0.0;  ///< ε̇ [1/s]
  double wedge = 0.0;    ///< w = ω_J + ω_B − 2γ̇ [rad/s]
};

/// Film force on the journal, radial (along e) and tangential (e rotated +90°) [N].
struct FilmForce {
  double radial_N = 0.0;
  double tangential_N = 0.0;
};

/// The force laws a scene can name.
///
/// All three are closed forms of the paper (Eqs. 6–14). Common symbols, SI units:
///
/// | symbol | meaning                                              | unit    | sign                         |
/// |--------|------------------------------------------------------|---------|------------------------------|
/// | μ      | dynamic viscosity                                     | Pa s    | > 0                          |
/// | L      | bearing length                                        | m       | > 0                          |
/// | R_J    | journal radius (the R of the paper's formulas)        | m       | > 0                          |
/// | c      | radial clearance R_B − R_J                            | m       | > 0                          |
/// | ε      | eccentricity ratio ‖e‖/c                              | –       | 0 <= ε < 1                   |
/// | ε̇      | rate of ε                                             | 1/s     | > 0 journal moving to wall   |
/// | w      | wedge speed ω_J + ω_B − 2γ̇ (paper: ω − 2γ̇)            | rad/s   | either                       |
/// | F_r    | film force on the journal along e (outward)           | N       | < 0 pushes towards the centre|
/// | F_t    | film force on the journal along e rotated +90°        | N       | same sign as w (ε > 0)       |
///
/// Assumptions shared by all: isothermal, incompressible, iso-viscous Newtonian film; rigid
/// aligned cylinders; Reynolds' thin-film equation (Eq. 1) with either the axial (short) or
/// the circumferential (long) flow term dropped; wedge and squeeze terms superposed.
///
/// Singularity: every law grows without bound as ε → 1 (film thickness c(1 − ε) → 0), like
/// (1 − ε²)^(−n) with n given per law. The code does not clamp, regularize or switch to a
/// contact model: it evaluates the formula, with 1 − ε² formed as (1 − ε)(1 + ε) so that it
/// stays accurate near 1, and returns a finite (possibly huge) value for every representable
/// ε < 1 and moderate ε̇, w. ε >= 1 violates the precondition (the caller must model
/// contact) and may give ±inf or NaN.
///
/// At ε = 0 the direction e is undefined; the laws return the limit of (F_r, F_t) as ε → 0⁺
/// and the caller chooses the radial direction.
///
/// ### frene_long — Frêne et al. infinitely long bearing, full (Sommerfeld) film, Eqs. (8)–(9)
///
///     F_r = −12 π C ε̇ / (1 − ε²)^(3/2)                         C = μ L R_J³ / c²   [N s]
///     F_t =  12 π C ε w / ((2 + ε²) (1 − ε²)^(1/2))
///
/// Exactly the integral over the full circle θ ∈ [0, 2π) of the pressure of Eq. (5)
/// (`pressure_long`), negative pressures included: a film that sustains tension. Valid for
/// L/D ≳ 2. Singular as (1 − ε²)^(−3/2) (radial) and (1 − ε²)^(−1/2) (tangential). Smooth at
/// ε = 0 and ε̇ = 0: no special cases. The radial force always resists ε̇ (pure damping);
/// the tangential force is the Sommerfeld wedge force, normal to e (no radial wedge part).
///
/// ### frene_short — Frêne et al. infinitely short (Ocvirk) bearing, full film, Eqs. (6)–(7)
///
///     F_r = −π C_s ε̇ (1 + 2ε²) / (1 − ε²)^(5/2)                 C_s = μ L³ R_J / c²  [N s]
///     F_t =  π C_s ε w / (2 (1 − ε²)^(3/2))
///
/// Exactly the integral of the pressure of Eq. (3) (`pressure_short`) over z ∈ [−L/2, L/2]
/// and the full circle. Valid for L/D ≲ 0.5. Singular as (1 − ε²)^(−5/2) (radial) and
/// (1 − ε²)^(−3/2) (tangential). Smooth at ε = 0 and ε̇ = 0.
///
/// ### pinkus_sternlicht — Pinkus–Sternlicht long bearing with film rupture, Eqs. (10)–(14) as printed
///
///     ε̇ >= 0:  F_r = −6 C ε̇ / ((2+ε²)(1−ε²)^(3/2)) · [4kε² + (2+ε²) π (k+3)/(k+3/2)]   (10)
///              F_t =  6 π C ε w / ((2+ε²)(1−ε²)^(3/2)) · (k+3)/(k+3/2)                 (11)
///     ε̇ <  0:  F_r = −6 C ε̇ / ((2+ε²)(1−ε²)^(3/2)) · [4kε² − (2+ε²) π k/(k+3/2)]       (12)
///              F_t =  6 π C ε w / ((2+ε²)(1−ε²)^(3/2)) · k/(k+3/2)                     (13)
///     k = +sqrt((1 − ε²) (w²/(4ε̇²) + 1/ε²)) >= sqrt(1 − ε²)/ε                           (14)
///
/// with C = μ L R_J³ / c² [N s]. Intended to integrate only the positive part of the long
/// bearing pressure, with rupture angles that move with ε̇ and w. Singular as
/// (1 − ε²)^(−3/2) in both components.
///
/// Evaluation (no 0/0): the code never forms k. It uses
///     ε̇ k ε² = sgn · ε (1 − ε²)^(1/2) · sqrt(ε² w²/4 + ε̇²),
///     1/k    = ε |ε̇| / ((1 − ε²)^(1/2) · sqrt(ε² w²/4 + ε̇²))   (taken as 0 when ε̇ = εw = 0),
/// sgn = +1 on the ε̇ >= 0 branch and −1 on the ε̇ < 0 branch, and rewrites
/// (k+3)/(k+3/2) = (1 + 3/k)/(1 + 1.5/k), k/(k+3/2) = 1/(1 + 1.5/k).
///
/// Limits, as implemented:
///  - **ε̇ = 0 exactly (also −0.0) takes the ε̇ >= 0 branch, Eqs. (10)–(11)**, so the value at
///    ε̇ = 0 is the limit ε̇ → 0⁺ (k → ∞ when w ≠ 0):
///        F_r = −12 C ε² |w| / ((2+ε²)(1−ε²)),   F_t = 6 π C ε w / ((2+ε²)(1−ε²)^(3/2)).
///    The limit ε̇ → 0⁻ has the same F_t and the opposite F_r.
///  - ε̇ = 0 and w = 0: force 0 (and ε̇ = 0, ε = 0: force 0).
///  - ε = 0 with ε̇ ≠ 0 (k → ∞): F_r = −6 π C |ε̇|, F_t = 0, on both branches.
///
/// Known defects of the printed law (see the paper notes, NOTES.md; pinned down by
/// tests/test_core_force_laws.cpp):
///  1. F_t does not reach the half-Sommerfeld (Gümbel) long-bearing limit: as ε̇ → 0⁺ it is
///     larger than the integral of the positive part of Eq. (5) by exactly 1/(1 − ε²)
///     (denominator (1−ε²)^(3/2) where the half-Sommerfeld value has (1−ε²)^(1/2)).
///     F_r does agree with the half-Sommerfeld limit.
///  2. F_r jumps in sign across ε̇ = 0 whenever w ≠ 0: F_r(0⁻) = −F_r(0⁺). An integrator sees
///     a discontinuous right-hand side; trajectories can slide on ε̇ = 0 (Filippov), and a
///     sample of this function there returns one side of the jump, not the acting force.
///  3. For ε̇ < 0 with little wedge, Eq. (12) gives F_r < 0 (towards the centre): it speeds
///     the inward motion instead of resisting it (e.g. ε = 0.3, ε̇ = −10 1/s, w = 0), where
///     the full film pushes back and the half film gives zero.
enum class ForceLaw {
  pinkus_sternlicht,  ///< Pinkus–Sternlicht long bearing as printed, Eqs. (10)–(14)
  frene_long,         ///< Frêne et al. long bearing, Sommerfeld (full film), Eqs. (8)–(9)
  frene_short,        ///< Frêne et al. short bearing, Sommerfeld (full film), Eqs. (6)–(7)
};

/// Scene name of a law ("pinkus_sternlicht", ...).
std::string_view to_string(ForceLaw law);
/// Parses a scene name (exact, case-sensitive); returns false for an unknown name and
/// then leaves `law` unchanged.
bool parse_force_law(std::string_view name, ForceLaw& law);
/// All names, comma separated, for error messages.
std::string force_law_names();

/// Film force of `law`. Requires 0 <= eps < 1, finite eps_dot and wedge, positive
/// geometry and viscosity (the caller validates; see each law for its limits:
/// ε = 0 and ε̇ = 0 are evaluated by their limits, never NaN).
FilmForce film_force(ForceLaw law, const BearingGeometry& g, double viscosity_Pa_s,
                     const BearingState& s);

/// The laws one by one (what `film_force` dispatches to); same preconditions.
FilmForce film_force_pinkus_sternlicht(const BearingGeometry& g, double viscosity_Pa_s,
                                       const BearingState& s);
FilmForce film_force_frene_long(const BearingGeometry& g, double viscosity_Pa_s,
                                const BearingState& s);
FilmForce film_force_frene_short(const BearingGeometry& g, double viscosity_Pa_s,
                                 const BearingState& s);

/// Force scale of the long-bearing laws, C = μ L R_J³ / c² [N s].
double long_bearing_coefficient(const BearingGeometry& g, double viscosity_Pa_s);
/// Force scale of the short-bearing law, C_s = μ L³ R_J / c² [N s].
double short_bearing_coefficient(const BearingGeometry& g, double viscosity_Pa_s);

// --- Pressure fields, for verification and plotting ---------------------------------

/// Short-bearing (Ocvirk) pressure of Eq. (3) at angle θ and axial position z ∈ [−L/2, L/2]
/// [Pa], full (Sommerfeld) field, may be negative. With h = c(1 + ε cos θ):
///     p = −3 μ (L²/4 − z²) (2 ε̇ cos θ − ε w sin θ) / (c² (1 + ε cos θ)³).
double pressure_short(const BearingGeometry& g, double viscosity_Pa_s, const BearingState& s,
                      double theta, double z);

/// Long-bearing (Sommerfeld) pressure of Eq. (5) at angle θ [Pa], full field.
///     p = 6 μ (R_J/c)² { w (2 + ε cos θ) ε sin θ / ((2 + ε²)(1 + ε cos θ)²)
///                        + (ε̇/ε) [1/(1 + ε cos θ)² − 1/(1 + ε)²] }.
/// The squeeze term is evaluated in the algebraically equal form
/// ε̇ (1 − cos θ)(2 + ε(1 + cos θ)) / ((1 + ε cos θ)²(1 + ε)²), so at ε = 0 it is its limit
/// 2 ε̇ (1 − cos θ), never 0/0.
double pressure_long(const BearingGeometry& g, double viscosity_Pa_s, const BearingState& s,
                     double theta);

}  // namespace lub
