// The model: an immutable description assembled from a Scene, holding only the terms the
// scene names (gravity only if the scene has it, a film force only for each lubricated
// joint), and a Workspace preallocated once and reused for every evaluation.
//
// ## Equations of motion (absolute coordinates, paper Eq. 30)
// q = (x, y, φ) per moving body (the ground is not in q). With the diagonal mass matrix M,
// the constraint Jacobian Φ_q, generalised forces g (gravity, film forces and their
// moments about the centres of mass) and γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt,
//     M q̈ + Φ_qᵀ λ = g,    Φ_q q̈ = γ − 2α Φ̇ − β² Φ      (Baumgarte's α, β: a Stabilisation).
// Because M is diagonal the multipliers come from the small SPD system
//     (Φ_q M⁻¹ Φ_qᵀ) λ = Φ_q M⁻¹ g − γ̂,    q̈ = M⁻¹ (g − Φ_qᵀ λ).
// A lubricated revolute joint is a force element: no constraint rows, the film force F on
// the journal at the journal centre P_j, −F on the bearing at the bearing centre P_i.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "lub/bearing/asperity.hpp"
#include "lub/bearing/contact.hpp"
#include "lub/bearing/film_force.hpp"
#include "lub/common/name_table.hpp"
#include "lub/mechanism/driver.hpp"
#include "lub/mechanism/planar.hpp"

namespace lub {

/// One ideal constraint (a block of rows of Φ).
struct Constraint {
  enum class Kind { revolute, translational, ground, driver };
  Kind kind = Kind::revolute;
  int joint = -1;  ///< scene joint index (or driver index for Kind::driver)
  int body_i = kGround, body_j = kGround;
  Eigen::Vector2d s_i{0, 0}, s_j{0, 0};  ///< points in body frames
  Eigen::Vector2d n_i{0, 1};             ///< translational: normal to the axis, body i frame
  double phi0 = 0.0;                     ///< translational: φ_j − φ_i; driver: φ0
  Eigen::Vector3d q0{0, 0, 0};           ///< ground: the fixed pose
  Eigen::Vector2d offset{0, 0};          ///< revolute: P_i − P_j target (0 for a joint)
  DriverType driver_type = DriverType::constant_speed;
  double omega = 0.0, Omega = 0.0;       ///< driver speed, reversal frequency
  int row = 0;                           ///< first row in Φ
  int rows = 0;
};

/// A lubricated revolute joint as a force element.
struct FilmElement {
  int joint = -1;  ///< scene joint index
  int bearing = kGround, journal = kGround;
  Eigen::Vector2d s_bearing{0, 0}, s_journal{0, 0};
  BearingGeometry geometry;
  double clearance = 0.0;
  double viscosity = 0.0;
  ForceLaw law = ForceLaw::pinkus_sternlicht;
  FiniteBearingOptions finite;        ///< finite_reynolds: cavitation, grid
  /// The scene's contact effect covers this joint: the film hands over to dry contact in
  /// [ε_a, ε_b] and is never evaluated above ε_b (lub/bearing/contact.hpp). Absent: no contact code.
  std::optional<ContactLaw> contact;
  /// The scene's mixed-lubrication effect covers this joint: the asperity load is added to
  /// the film force (lub/bearing/asperity.hpp). Absent: no asperity code.
  std::optional<AsperityLaw> asperity;
  /// The scene's film-friction effect covers this joint: the film's shear torques (and the
  /// asperities' friction) act on journal and bearing (film_element_friction).
  bool friction = false;
  /// The law jumps across ε̇ = 0 (the printed Pinkus–Sternlicht law) and the scene asks
  /// for event-driven switching: the run tracks a FilmMode for this film.
  bool switching = false;
};

/// How a switching film's law is evaluated (see docs/theory/switching.md).
enum class FilmMode : int {
  natural = 0,   ///< the law at the actual ε̇ (continuous laws, or switching off)
  outward = 1,   ///< the ε̇ > 0 branch, continued at ε̇ = 0⁺ for ε̇ < 0
  inward = -1,   ///< the ε̇ < 0 branch, continued at ε̇ = 0⁻ for ε̇ > 0
  sliding = 2,   ///< Filippov sliding on ε̇ = 0: |e| held by a constraint whose
                 ///< multiplier is the radial film force; F_t at ε̇ = 0
};

struct Model {
  int nb = 0;    ///< moving bodies
  int nq = 0;    ///< 3 nb
  int nc = 0;    ///< constraint rows
  Eigen::VectorXd mass_diag;      ///< (m, m, J) per body
  Eigen::VectorXd inv_mass_diag;
  std::vector<Constraint> constraints;
  std::vector<FilmElement> films;
  int n_switching = 0;  ///< films with switching (each may add one sliding row)
  std::optional<Eigen::Vector2d> gravity;
  /// constraint block of each scene joint (ideal joints, and lubricated ones with law
  /// "ideal"), or -1; film element of each scene joint, or -1
  std::vector<int> joint_constraint, joint_film;
};

/// Baumgarte's stabilisation of the constraints, Φ̈ + 2α Φ̇ + β² Φ = 0 (α, β [1/s]): the
/// formulation's choice (solver.baumgarte_alpha, solver.baumgarte_beta), not part of the
/// mechanism, so the Model does not hold it; evaluate() is told.
struct Stabilisation {
  double alpha = 5.0;
  double beta = 5.0;
  /// γ̂ = γ − 2αΦ̇ − β²Φ: a constraint row's acceleration right-hand side with Baumgarte's
  /// terms (Φ in m or rad, Φ̇ per s, γ per s²).
  double stabilised_gamma(double gamma, double Phi_dot, double Phi) const {
    return gamma - 2.0 * alpha * Phi_dot - (beta * beta) * Phi;
  }
};

/// What an evaluation of the model found.
enum class EvalStatus {
  ok,              ///< accelerations (and forces) evaluated
  outside_domain,  ///< ε >= 1 without contact: a recoverable failure for an integrator
  singular,        ///< the constraint system is singular: fatal
};
/// The integrators' convention (OdeSystem, as SUNDIALS'): 0 ok, 1 recoverable, −1 fatal.
constexpr int ode_flag(EvalStatus s) {
  return s == EvalStatus::ok ? 0 : s == EvalStatus::outside_domain ? 1 : -1;
}

/// Bearing kinematics of one film element at one state.
struct FilmKinematics {
  bool sliding = false;         ///< the radial force is the sliding constraint's multiplier
  Eigen::Vector2d e{0, 0};      ///< journal centre − bearing centre [m]
  Eigen::Vector2d e_dot{0, 0};  ///< [m/s]
  Eigen::Vector2d r{1, 0};      ///< unit radial direction (along e; along ė or x at e = 0)
  double gamma_dot = 0.0;
  BearingState state;           ///< ε, ε̇, wedge
  FilmForce force;              ///< on the journal, radial/tangential
  Eigen::Vector2d F{0, 0};      ///< on the journal, global [N]
  /// Power of the friction torques applied to the two bodies, −T_J ω_J + T_B ω_B [W]
  /// (0 unless the film-friction effect covers the film).
  double torque_power_W = 0.0;
  /// Angle of the line of centres [rad]; on demand, as only observers need it.
  double gamma() const { return std::atan2(r.y(), r.x()); }
};

/// Counters of what the right-hand side evaluated (for the effect-counting tests).
struct EvalCounters {
  long long rhs = 0;
  long long gravity = 0;
  long long film = 0;
  long long film_jacobian = 0;  ///< force-law calls spent on structured Jacobians
  /// Right-hand sides spent on the system's own difference Jacobians (joint coordinates; a
  /// sliding film's partitioned Jacobian): SUNDIALS counts only its own difference quotients.
  long long rhs_jacobian = 0;
};

/// Preallocated buffers; one per thread of work, reused for every case of the same model.
struct Workspace {
  explicit Workspace(const Model& m);
  /// Back to the state the constructor leaves, without allocating (a finite-Reynolds
  /// film's solver aside: it is built anew, the one way to drop its warm start exactly):
  /// what one evaluation leaves for the next (film modes, counters, warm starts) must not
  /// reach the next run segment that reuses this workspace.
  void reset(const Model& m);
  Eigen::MatrixXd Phi_q;   ///< nc × nq
  Eigen::VectorXd Phi, Phi_dot, gamma, g, rhs, lambda, qdd;
  Eigen::MatrixXd S;       ///< nc × nc; after evaluate() its Cholesky factor (lower triangle)
  /// The moving bodies (at most two; kGround: none) each row of Phi_q touches: the rows
  /// are sparse, and S = Φ_q M⁻¹ Φ_qᵀ is formed from these columns only.
  std::vector<std::array<int, 2>> row_bodies;
  /// (r, s, b): constraint rows r >= s that share moving body b, the nonzero terms of S.
  std::vector<std::array<int, 3>> schur_pairs;
  std::vector<double> cos_phi, sin_phi;  ///< of each body's angle, at the last evaluation
  /// The angles cos_phi and sin_phi were computed at (NaN: none yet): an evaluation at the
  /// same angles (the recovery's last check, then evaluate(); the Jacobian) reuses them.
  std::vector<double> trig_phi;
  std::vector<FilmKinematics> films;
  EvalCounters counters;
  // Switching films: mode, and in sliding mode the held |e| [m] and the constraint row.
  std::vector<FilmMode> film_mode;
  std::vector<double> slide_radius;
  std::vector<int> slide_row;
  int nc_active = 0;  ///< constraint rows in use: nc + films sliding
  /// finite_reynolds films: the solver with its preallocated scratch (empty for other laws).
  std::vector<std::optional<FiniteBearingSolver>> film_solvers;
  /// Films with the contact effect: normal contact force of the last evaluation [N].
  std::vector<double> contact_N;
};

/// Always-on check (LUB_ASSERT: lub::InternalError) that `ws` was built for `m`: the sizes
/// every evaluation relies on. Cheap (a few integer comparisons), called at the
/// model/workspace boundary (each evaluation, each system built over the pair).
void check_workspace(const Model& m, const Workspace& ws);

/// The first half of evaluate(): generalised forces ws.g (gravity and film elements; a
/// sliding film's radial force left out: it is its row's multiplier), film kinematics
/// and forces, and — when there are constraint rows — Φ, Φ_q, Φ̇, γ of the ws.nc_active
/// rows, without solving for λ and q̈ (the GGL residual needs no more): ok, or
/// outside_domain. With `constraint_rows` false the ideal joints' and drivers' rows are
/// left out (the joint-coordinate formulation satisfies them by construction); the sliding
/// rows are filled all the same.
EvalStatus evaluate_forces(const Model& m, Workspace& ws, double t, const double* q, const double* v,
                           bool constraint_rows = true);

/// Evaluates accelerations q̈ (and λ, film kinematics and forces in `ws`) at (t, q, v), the
/// constraints stabilised by `stab`: ok, outside_domain (ε >= 1 without contact) or singular.
EvalStatus evaluate(const Model& m, Workspace& ws, const Stabilisation& stab, double t, const double* q,
                    const double* v, double* qdd);

/// Constraint violation Φ and Φ̇ at (t, q, v) into ws.Phi, ws.Phi_dot (and ws.Phi_q).
/// Also the sliding rows of sliding films (ws.nc_active rows in all).
void constraint_residual(const Model& m, Workspace& ws, double t, const double* q, const double* v);

/// Projects (q, v) onto Φ = 0 (Newton, to `tol`) and Φ̇ = 0 with M-weighted least
/// corrections, in place; the corrections go to dq, dv; `err` (2 nq, or nullptr) is
/// projected onto the manifold's tangent space. Returns 0, 1 (no convergence), −1.
int project_state(const Model& m, Workspace& ws, double t, double* q, double* v, double* dq, double* dv,
                  double tol, double* err);

/// Force on body j of scene joint `joint` from body i, global [N], after evaluate():
/// the film force on the journal for a lubricated joint, the constraint reaction otherwise.
Eigen::Vector2d joint_force(const Model& m, const Workspace& ws, int joint);

/// Characteristic size of each state component (q, v), 2 nq entries, each in the
/// component's own unit, for the integrators' absolute tolerances (atol_i = rtol × scale_i):
///   x, y of every body:   ℓ                    [m]      (`length_m`: the smallest clearance)
///   φ of body b:          ℓ / r_b              [rad]    (r_b: the body's size, below)
///   ẋ, ẏ:                 ℓ Ω                  [m/s]    (`rate_rad_s` Ω: the driver's speed)
///   φ̇ of body b:          ℓ Ω / r_b            [rad/s]
/// r_b = max(the farthest joint or bearing point from the centre of mass, the radius of
/// gyration √(J/m)): an angle error δφ moves the body's farthest point by r_b δφ, so ℓ/r_b
/// is the angle whose effect equals a length error ℓ; the radius of gyration covers
/// bodies whose points sit at the centre of mass (a slider).
Eigen::VectorXd state_scales(const Model& m, double length_m, double rate_rad_s);

/// Kinetic energy + gravity potential [J].
double mechanical_energy(const Model& m, const double* q, const double* v);
/// Power of the drivers on the system [W] (after evaluate()).
double driver_power(const Model& m, const Workspace& ws, const double* v);
/// Power of the film forces on the system, F·ė plus the applied friction torques' power,
/// summed over films [W] (after evaluate()).
double film_power(const Workspace& ws);

}  // namespace lub
