// Hydrodynamic force laws of a lubricated revolute joint (journal bearing).
//
// A force law is a pure function of the bearing state: geometry, viscosity, the
// eccentricity ratio ε, its rate ε̇ and the wedge speed w. It knows nothing of any
// mechanism, and is tested on its own against quadrature of its own pressure field.
//
// ## Conventions (shared by every law here; see docs/theory/force-laws.md)
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

#include <array>
#include <string>
#include <string_view>
#include <utility>

#include "lub/common/name_table.hpp"

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
/// The first three are closed forms of the paper (Eqs. 6–14); the others are documented below
/// them. Common symbols, SI units:
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
/// aligned cylinders; Reynolds' thin-film equation (Eq. 1). The closed forms drop either the
/// axial (short) or the circumferential (long) flow term; `finite_reynolds` keeps both.
/// Where the film is cut to its positive part (the Gümbel and π-film laws), squeeze and wedge
/// act together (one pressure field, one rupture), not superposed.
///
/// Singularity: every law grows without bound as ε → 1 (film thickness c(1 − ε) → 0), like
/// (1 − ε²)^(−n) with n given per law. The code does not clamp, regularize or switch to a
/// contact model: it evaluates the formula, with 1 − ε² formed as (1 − ε)(1 + ε) so that it
/// stays accurate near 1, and returns a finite (possibly huge) value for every representable
/// ε < 1 and moderate ε̇, w. ε >= 1 violates the precondition and may give ±inf or NaN: the
/// caller must not evaluate a film law there (the model's contact effect, lub/bearing/contact.hpp,
/// hands over to a dry-contact force below ε = 1 and then stops calling the film law).
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
/// Known defects of the printed law (docs/theory/force-laws.md; pinned down by
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
///
/// ## Laws beyond the paper (issue 3)
///
/// They share one tool, the eccentric anomaly ψ (Sommerfeld substitution), s = (1 − ε²)^(1/2):
///     1 + ε cos θ = s²/(1 − ε cos ψ),  cos ψ = (cos θ + ε)/(1 + ε cos θ),  sin ψ = s sin θ/(1 + ε cos θ),
///     ψ(θ) = θ − 2 atan(β sin θ/(1 + β cos θ)),  β = ε/(1 + s)    (continuous, increasing, ψ = θ at ε = 0).
/// Under it every film integral needed below is a trigonometric polynomial in ψ, so each law is
/// a closed form with no division by ε (exact at ε = 0) and at most one cubic to solve. The
/// antiderivatives used (all in ψ):
///     A = sin²ψ − ε cos ψ        B = ψ/2 − sin 2ψ/4          G = s² ψ + sin 2ψ/2 − ε sin ψ
///     E = sin²ψ/2 + ε cos ψ      Q = (1/2 + ε²) ψ + sin 2ψ/4 − 2ε sin ψ
/// and, for a long bearing with C = μ L R_J³/c² [N s],
///     α = ε w/((2+ε²) s²),  β_s = 2ε̇/s³,  γ = ε w/((2+ε²) s³),  δ = 2ε̇/s⁴.
///
/// ### gumbel_long — Gümbel (half-Sommerfeld) long bearing: the positive part of Eq. (5)
///
///     F_r = R_J L ∫ p⁺ cos θ dθ,   F_t = R_J L ∫ p⁺ sin θ dθ,   p⁺ = max(p, 0),  p of Eq. (5),
///
/// squeeze and wedge together: the film (where p > 0) moves with the ratio ε̇/w. Derivation: in ψ,
///     p = 6 μ (R_J/c)² g(ψ)/s⁴,   g = a sin ψ (2 − ε² − ε cos ψ) + ε̇ (1 − cos ψ)(2 − ε − ε cos ψ),
///     a = ε w s/(2+ε²).
/// Its zeros are ψ = 0 (always: Eq. (5) is gauged to p = 0 at the thickest film), ψ = 2 atan t for
/// the real roots t of  2ε̇ t³ + a(1+ε)(2−ε) t² + 2ε̇(1−ε) t + a(1−ε)(2+ε) = 0  (found on the two
/// charts |t| <= 1 and |1/t| <= 1 by bracketed Newton, so roots near ψ = π are as accurate as
/// the others), and ψ = π when ε̇ = 0. On each arc [ψ_a, ψ_b] where g > 0, integrating by parts
/// (p = 0 at both ends) with the long-bearing Reynolds equation
/// p' = 6μ(R_J/c)²[w(1/H² − h_m/H³) + 2ε̇ sin θ/H³], h_m = 2s²/(2+ε²), leaves
///     F_r = −6C Σ [α A + β_s B]_{ψ_a}^{ψ_b},     F_t = 6C Σ [γ G + δ E]_{ψ_a}^{ψ_b}
/// (over the whole circle this is Eqs. (8)–(9) again). The code also adds the boundary terms
/// [p sin θ], [−p cos θ] at the computed zeros (zero up to rounding), so an error δ in a zero
/// costs O(δ²), not O(δ).
/// Limits: ε̇ = 0, w ≠ 0: F_r = −12 C ε² |w|/((2+ε²)(1−ε²)), F_t = 6π C ε w/((2+ε²)(1−ε²)^(1/2)),
/// the classical half-Sommerfeld bearing (tan φ = π(1−ε²)^(1/2)/(2ε)). ε = 0: F_r = −12π C ε̇⁺,
/// F_t = 0 (the Eq. (5) squeeze field at ε = 0 is 12μ(R/c)² ε̇ (1 − cos θ), of one sign).
/// Caveat of the field it integrates: Eq. (5)'s squeeze term is <= 0 everywhere for ε̇ < 0, so a
/// journal moving towards the centre with little wedge feels (almost) no force; the long limit
/// of a finite bearing with ambient pressure at its ends has another gauge (see finite_reynolds).
/// Continuous in (ε, ε̇, w) everywhere, ε̇ = 0 and ε = 0 included (the integral of the positive
/// part of a continuous field); piecewise smooth (the derivative jumps where two zeros of g
/// merge); positively homogeneous of degree 1 in (ε̇, w). Singular at most as (1 − ε²)^(−2).
///
/// ### gumbel_short — Gümbel (half-Sommerfeld) short bearing: the positive part of Eq. (3)
///
/// Eq. (3) is p ∝ (L²/4 − z²) ρ sin(θ − θ₀)/H³ with ρ = hypot(ε w, 2ε̇), θ₀ = atan2(2ε̇, ε w): at every
/// z it is positive exactly on the half circle θ ∈ (θ₀, θ₀ + π), whose position moves with ε̇/w.
/// Integrating over the length (L³/6) and that half circle, in ψ (no integration by parts):
///     F_r = (C_s/2) [ε w E/s⁴ − 2ε̇ Q/s⁵]_{ψ₀}^{ψ₁},    F_t = (C_s/2) [ε w B/s³ − 2ε̇ E/s⁴]_{ψ₀}^{ψ₁},
///     ψ₀ = ψ(θ₀),  ψ₁ = ψ₀ + π + 2 atan(ε sin θ₀/s),   C_s = μ L³ R_J/c².
/// Limits: ε̇ = 0, w > 0: F_r = −C_s ε² w/(1−ε²)², F_t = π C_s ε w/(4 (1−ε²)^(3/2)) (Ocvirk, π film:
/// tan φ = π(1−ε²)^(1/2)/(4ε)). ε = 0: F_r = −(π/2) C_s ε̇ (resists either sign), F_t = 0.
/// ε̇ = ε w = 0: force 0 (θ₀ is then undefined but multiplied by zero). Continuous everywhere,
/// positively homogeneous in (ε̇, w); singular at most as (1 − ε²)^(−5/2).
///
/// ### pinkus_sternlicht_continuous — the Pinkus–Sternlicht π film, integrated exactly
///
/// The model Eqs. (10)–(14) stand for: a long bearing whose film spans half the circle,
/// θ ∈ [θ₁, θ₁ + π], from a rupture angle θ₁ that moves with ε̇/w, carrying the pressure of Eq. (5)
/// shifted by the constant that makes it vanish at both film ends. Those two end conditions fix
/// both unknowns: p(θ₁) = p(θ₁ + π) for the Sommerfeld field reduces (exactly) to
///     ε w sin θ₁/(2+ε²) = ε̇ cos θ₁    ⇒    θ₁ = atan2((2+ε²) ε̇, ε w)
/// (the branch on which the film pressure is positive), and the constant to p_Eq5(θ₁). Integrating
/// by parts (p = 0 at both ends, so the constant drops out) gives the gumbel_long antiderivatives
/// on the single arc
///     F_r = −6C [α A + β_s B]_{ψ₁}^{ψ₂},   F_t = 6C [γ G + δ E]_{ψ₁}^{ψ₂},
///     ψ₁ = ψ(θ₁),  ψ₂ = ψ₁ + π + 2 atan(ε sin θ₁/s).
/// In Pinkus–Sternlicht's notation ε |sin θ₁|/s = 1/k* with k*² = (1−ε²)[(w/((2+ε²)ε̇))² + 1/ε²]:
/// Eq. (14) with its 2 replaced by 2 + ε². Where the exact integral has the atan of ψ₂ − ψ₁ and
/// the trigonometric end values, the printed law has the rational factors (k+3)/(k+3/2) and
/// k/(k+3/2): an approximation, measured below.
/// Properties (tests/test_core_gumbel.cpp): continuous in (ε, ε̇, w) everywhere (θ₁ jumps only
/// where ε̇ = ε w = 0, where every coefficient vanishes); at ε̇ = 0 it is exactly the
/// half-Sommerfeld long bearing (θ₁ = 0 or π), i.e. gumbel_long; at ε = 0: F_r = −6π C ε̇,
/// F_t = 0, resisting either sign of ε̇; for w = 0 F_r always opposes ε̇.
/// Where it differs from the printed law (pinkus_sternlicht):
///  - ε̇ → 0⁺: same F_r; the printed F_t is larger by 1/(1−ε²) (denominator (1−ε²)^(3/2) where
///    the π film gives (1−ε²)^(1/2)).
///  - ε̇ → 0⁻: the printed F_r is −F_r(0⁺) (a jump); here F_r(0⁻) = F_r(0⁺).
///  - ε̇ < 0: the printed Eq. (12) has the opposite sign wherever the wedge is weak (it pulls an
///    inward-moving journal further in); here F_r > 0 for w = 0, resisting the motion.
///  - ε̇ > 0 away from the limits, Eqs. (10)–(11) approximate the exact π film: F_r within
///    9 %, F_t·(1−ε²) within 11 % (ε = 0.1…0.95, ε̇ = 0.01…100 1/s, |w| <= 300 rad/s,
///    tests/test_core_gumbel.cpp); the printed F_t carries the 1/(1−ε²) error on top.
/// Singular as (1 − ε²)^(−2) at most.
///
/// ### finite_reynolds — finite-length bearing, Eq. (1) solved numerically
///
/// The two-dimensional Reynolds equation on the unwrapped film (θ, z), ambient pressure at both
/// ends z = ±L/2, for the given ε, ε̇, w and L/D = L/(2 R_J), with a cavitation condition
/// (`Cavitation`): `gumbel` (the full-film solution, then only its positive part integrated),
/// `reynolds` (Swift–Stieber: p >= 0 with ∂p/∂n = 0 at the film rupture, solved as a linear
/// complementarity problem), or `sommerfeld` (full film, negative pressures kept: the
/// reference for the Frêne laws). Finite volumes, second order; see lub/bearing/reynolds.hpp for the
/// discretization, the solvers, the cost per evaluation and the measured convergence order.
/// It is the reference the closed forms are measured against (docs/theory/force-laws.md, printed by build/tests/test_core_law_deviation), and a law for
/// 0.25 <~ L/D <~ 2, where neither closed form holds.
enum class ForceLaw {
  pinkus_sternlicht,             ///< Pinkus–Sternlicht long bearing as printed, Eqs. (10)–(14)
  frene_long,                    ///< Frêne et al. long bearing, Sommerfeld (full film), Eqs. (8)–(9)
  frene_short,                   ///< Frêne et al. short bearing, Sommerfeld (full film), Eqs. (6)–(7)
  gumbel_long,                   ///< positive part of Eq. (5), squeeze and wedge together
  gumbel_short,                  ///< positive part of Eq. (3), squeeze and wedge together
  pinkus_sternlicht_continuous,  ///< exact Pinkus–Sternlicht π film (continuous, corrected)
  finite_reynolds,               ///< 2-D Reynolds equation, numerically (lub/bearing/reynolds.hpp)
};

/// Cavitation condition of `finite_reynolds`.
enum class Cavitation {
  gumbel,      ///< half-Sommerfeld: full-film pressure, only its positive part integrated
  reynolds,    ///< Swift–Stieber: p >= 0 and the film ruptures with zero pressure gradient
  sommerfeld,  ///< full film, negative pressures kept (verification against the Frêne laws)
};

/// Options of `finite_reynolds` (a scene sets them on the lubricated joint).
struct FiniteBearingOptions {
  Cavitation cavitation = Cavitation::reynolds;
  int n_theta = 48;  ///< cells around the circumference, uniform in ψ (>= 8)
  int n_z = 8;       ///< axial nodes over half the length (mid-plane symmetry), >= 1
  /// Ambient pressure along the line of maximum film thickness θ = 0 (an axial supply groove
  /// that follows the line of centres): Raimondi & Boyd's convention for the full bearing
  /// under steady load. Off (default): the film is periodic, for dynamic loads.
  bool groove_at_max_film = false;
};

/// Scene names of the laws (lub/common/name_table.hpp: name_of, parse_name, names_list).
template <>
struct NameTable<ForceLaw> {
  static constexpr std::array<std::pair<ForceLaw, std::string_view>, 7> entries{{
      {ForceLaw::pinkus_sternlicht, "pinkus_sternlicht"},
      {ForceLaw::frene_long, "frene_long"},
      {ForceLaw::frene_short, "frene_short"},
      {ForceLaw::gumbel_long, "gumbel_long"},
      {ForceLaw::gumbel_short, "gumbel_short"},
      {ForceLaw::pinkus_sternlicht_continuous, "pinkus_sternlicht_continuous"},
      {ForceLaw::finite_reynolds, "finite_reynolds"},
  }};
};

/// Scene names of the cavitation conditions.
template <>
struct NameTable<Cavitation> {
  static constexpr std::array<std::pair<Cavitation, std::string_view>, 3> entries{{
      {Cavitation::gumbel, "gumbel"},
      {Cavitation::reynolds, "reynolds"},
      {Cavitation::sommerfeld, "sommerfeld"},
  }};
};

/// The closed-form laws one by one (what `film_force`, lub/bearing/film_force.hpp,
/// dispatches to with finite_reynolds); same preconditions.
using ClosedFormLaw = FilmForce(const BearingGeometry& g, double viscosity_Pa_s, const BearingState& s);
ClosedFormLaw film_force_pinkus_sternlicht, film_force_frene_long, film_force_frene_short, film_force_gumbel_long,
    film_force_gumbel_short, film_force_pinkus_sternlicht_continuous;

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

/// Film-start angle θ₁ = atan2((2+ε²) ε̇, ε w) of the Pinkus–Sternlicht π film [rad], in (−π, π].
double pi_film_start(const BearingState& s);

/// Pressure of the Pinkus–Sternlicht π film at θ [Pa]: Eq. (5) minus its value at θ₁ for
/// θ in [θ₁, θ₁ + π] (mod 2π), 0 elsewhere (`pinkus_sternlicht_continuous` integrates it).
double pressure_pi_film(const BearingGeometry& g, double viscosity_Pa_s, const BearingState& s,
                        double theta);

}  // namespace lub
