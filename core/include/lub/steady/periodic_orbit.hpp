// Periodic orbits of a periodically forced system as fixed points of its cycle map
// (the steady stage: pure numerics on an abstract map, Eigen and SUNDIALS' KINSOL only).
//
//   P: z ↦ z(T)   the state after one forcing period T, started at z at phase 0;
//   a periodic orbit is z* = P(z*), found by Newton on r(z) = P(z) − z (shooting);
//   its stability by the Floquet multipliers μ_i = eig(M), M = ∂P/∂z at z* (the
//   monodromy matrix): |μ|max < 1 a stable cycle, a disturbance shrinking by |μ|max
//   per period; > 1 an unstable one.
//
// Every state has its own unit s_i (docs/theory/steady-cycles.md: lengths in the clearance c,
// angles in c over the body's size, rates in those times the driver's speed): residuals,
// tolerances and difference steps are measured in them, max_i |r_i| / s_i.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace lub::steady {

/// One period of the system, z ↦ P(z) on dim() states.
class CycleMap {
 public:
  virtual ~CycleMap() = default;
  virtual int dim() const = 0;
  /// Writes P(z) into Pz. Returns 0, > 0 if the map cannot be evaluated at z (the orbit
  /// from z leaves the domain: a film collapses, the integrator fails), or < 0 if it
  /// refuses to go on at all (a budget of periods is spent): the solvers stop there.
  virtual int apply(const double* z, double* Pz) = 0;
  /// P(z) and its derivative M = ∂P/∂z (dim × dim, column-major) from the variational
  /// equation integrated with the period on the period's own steps: the derivative of the
  /// computed map itself, smooth where the flow is. Returns as apply(), or kNoDerivative
  /// where the map has no such derivative at z (then Pz holds P(z) if it could be
  /// evaluated, and a caller differences instead).
  virtual int apply_with_derivative(const double* /*z*/, double* /*Pz*/, double* /*M*/) { return kNoDerivative; }
  static constexpr int kNoDerivative = 1000;
};

/// Monodromy M = ∂P/∂z by differences of the flow map. Differences of the map itself
/// (rather than variational equations) carry the saltation of every switching event and
/// the rank drop of sliding motion, which forward sensitivities integrated through
/// events would not (docs/theory/steady-cycles.md, monodromy).
struct MonodromyOptions {
  std::vector<double> scales;  ///< s_i
  double step = 1e-4;          ///< difference step h_i = step × s_i
  bool central = true;         ///< central (2 n maps, error O(h²)) or forward (n maps, O(h))
  /// A column whose perturbed period fails is tried again with the step ÷ 10, this many times.
  int retries = 0;
  /// monodromy(): the map's own derivative first (CycleMap::apply_with_derivative, one map),
  /// differences only where it has none.
  bool derivative = false;
};
struct Monodromy {
  Eigen::MatrixXd M;
  long long maps = 0;  ///< map evaluations spent
  int failed = 0;      ///< > 0: a perturbed map could not be evaluated (M not set)
  bool refused = false;  ///< the map refused to go on (CycleMap::apply < 0; failed > 0 too)
};
/// `Pz` = P(z) (used by forward differences).
Monodromy monodromy_by_differences(CycleMap& P, const Eigen::VectorXd& z, const Eigen::VectorXd& Pz,
                                   const MonodromyOptions& opt);
/// M at z: with opt.derivative the map's own derivative where it has one (forward
/// sensitivities on the period's steps: smooth in z, no difference step to choose), else
/// monodromy_by_differences.
Monodromy monodromy(CycleMap& P, const Eigen::VectorXd& z, const Eigen::VectorXd& Pz, const MonodromyOptions& opt);

/// Eigenvalues of M, largest modulus first (ties: larger angle first).
std::vector<std::complex<double>> floquet_multipliers(const Eigen::MatrixXd& M);

struct ShootingOptions {
  std::vector<double> scales;     ///< s_i: the unknowns' units (steps, difference steps)
  /// The residual's units r_i (empty: s_i), where a coordinate stretches what the
  /// tolerance should measure (the wall coordinates near the wall).
  std::vector<double> residual_scales;
  /// The units the residual is measured in: residual_scales, or scales where it is empty.
  const std::vector<double>& residual_units() const { return residual_scales.empty() ? scales : residual_scales; }
  double tolerance = 1e-9;        ///< converged when max_i |P(z)_i − z_i| / r_i <= tolerance
  double step = 1e-4;             ///< difference step of the Newton Jacobians, × s_i
  int max_iterations = 25;        ///< Newton iterations
  /// The shortest Newton step, scaled (units s_i), its line search's included: shorter, Newton
  /// stops (KIN_STEP_LT_STPTOL). ≤ 0: 1e-3 × tolerance. A step below the map's own noise
  /// cannot change its residual measurably: a line search that backtracks below it spends a
  /// period a trial for nothing.
  double step_tolerance = 0.0;
  /// Newton stops where its best residual has not halved over this many of its trial points
  /// (periods of its line search; its Jacobians' differences not counted), while that
  /// residual is above `stagnation_floor`; 0: never. A residual form of Deuflhard's
  /// monotonicity test: inside Newton's region of convergence each iteration at least
  /// halves the residual, so one that does not for this long is not converging to an orbit
  /// (from a transient's end: walking along the slow manifold, or into the wall).
  int stagnation_maps = 0;
  double stagnation_floor = 0.0;
  double max_newton_step = 0.3;   ///< largest Newton step, scaled 2-norm (units s_i)
  /// A Newton that stalls (no decrease along its direction) within this factor of the
  /// tolerance has reached the map's own noise: converged, with its residual reported.
  /// The printed law's maps near the wall (Filippov sliding entered and left within a
  /// period) stall at 1e-7–1e-6 clearances: still 1000 times inside a transient's 1e-3.
  double noise_factor = 1000.0;
  /// Central differences for the Newton Jacobians (2 n maps instead of n; error O(h²)
  /// instead of O(h): a slowly contracting cycle's M − I is nearly singular, and an O(h)
  /// error swamps its smallest singular value).
  bool central_jacobian = true;
  /// The map the Jacobians difference (nullptr: P itself), e.g. P integrated at a tighter
  /// tolerance: less noise over the difference step.
  CycleMap* jacobian_map = nullptr;
  /// A first Jacobian M₀ − I to start from (continuation: a neighbouring orbit's
  /// monodromy; nullptr: differences from the start). With it Newton runs chord
  /// iterations, reusing a Jacobian for up to `chord_iterations` iterations, and takes a
  /// fresh difference Jacobian only when the line search fails with a stale one (KINSOL's
  /// own rule) or the reuse count runs out: one period an iteration instead of 2 n + 1.
  const Eigen::MatrixXd* initial_jacobian = nullptr;
  int chord_iterations = 2;
  /// MonodromyOptions::retries of the Newton Jacobians' differences.
  int difference_retries = 0;
  /// MonodromyOptions::derivative of the Newton Jacobians (simulation.monodromy).
  bool map_derivative = false;
  /// The options of a monodromy at this Newton's scales and step (central or not).
  MonodromyOptions monodromy_options(bool central) const {
    return MonodromyOptions{scales, step, central, difference_retries, map_derivative};
  }
};

enum class ShootingOutcome {
  converged,      ///< residual below the tolerance
  left_domain,    ///< the map failed along Newton's path (the iterates walked out of the domain)
  not_converged,  ///< no convergence (line search stalled, iteration limit)
  refused,        ///< the map refused to go on (CycleMap::apply < 0: a budget spent)
};

struct ShootingResult {
  ShootingOutcome outcome = ShootingOutcome::not_converged;
  Eigen::VectorXd z;        ///< the last iterate (z* if converged)
  Eigen::VectorXd Pz;       ///< P(z)
  double residual = -1.0;   ///< max_i |P(z)_i − z_i| / r_i at z (−1: not evaluated)
  long iterations = 0;      ///< Newton iterations
  long long maps = 0;       ///< map evaluations (including the Jacobians' differences)
  int jacobians = 0;        ///< difference Jacobians computed (not counting an initial one)
  std::string message;      ///< KINSOL's verdict when not converged
  bool at_noise_floor = false;  ///< converged by stalling within noise_factor of the tolerance
  bool skipped = false;         ///< Newton not run (the caller's estimate: `message` says why)
  double first_residual = -1.0; ///< newton_picard: the residual at z0 (−1: not evaluated)
};

/// Solves z = P(z) from z0 by KINSOL's Newton with a line search (globalised), the
/// Jacobian M − I by differences of the map (ShootingOptions::central_jacobian,
/// jacobian_map). A map failure at a trial point is
/// reported to KINSOL as recoverable (it shortens the step).
ShootingResult solve_periodic_orbit(CycleMap& P, const Eigen::VectorXd& z0, const ShootingOptions& opt);

/// Anderson-accelerated iteration of the map (Walker & Ni 2011, type II): each step
/// z_{k+1} = z_k + f_k − (ΔZ + ΔF) γ, f = P(z) − z, γ the least-squares fit of f_k by the
/// last `depth` differences ΔF of f (ΔZ those of z), in the residual's units. One period a
/// step and no Jacobian: where the orbit lies far along a slow manifold (a multiplier close
/// to 1, the transient creeping towards it by a little each cycle) it extrapolates along
/// the slow direction as a secant method would, and each iterate stays a state the flow
/// itself nearly reaches, where a Newton step from far would leave along the linearisation.
/// An extrapolated iterate whose map fails (beyond the wall), or whose residual is 10 ×
/// the best so far, is pulled back towards the plain iterate P(z_k) (a state the flow
/// reached), halving the extrapolation four times before taking P(z_k) and starting the
/// history afresh; `stall` maps without a better residual end it (at the map's noise the
/// history only cycles).
struct AndersonOptions {
  std::vector<double> residual_scales;  ///< r_i
  int depth = 4;                        ///< differences kept (m)
  int max_maps = 60;                    ///< periods at most
  double tolerance = 1e-6;              ///< stop when max_i |f_i| / r_i <= tolerance
  int stall = 12;                       ///< stop after this many maps without a better residual
};
/// The best iterate (smallest residual) and its image; `outcome` converged if it met the
/// tolerance; `maps` the periods spent; `iterations` the steps taken.
ShootingResult anderson_fixed_point(CycleMap& P, const Eigen::VectorXd& z0, const AndersonOptions& opt);

/// Newton–Picard iteration on a fixed Jacobian J ≈ M − I (chord steps), each Newton
/// point followed by one period: z_{k+1} = P(z_k − J⁻¹ (P(z_k) − z_k)). Where the period
/// map contracts some directions to nothing (the squeeze film's: multipliers ~1e-10)
/// and others hardly at all (|μ| ≈ 1), its orbits lie on a curved manifold that one
/// period projects onto. A Newton step along the manifold leaves it by the curvature ×
/// the step², so the residual at the Newton point grows and a line search refuses the
/// step: the error bars' re-solve by KINSOL stalled at its first iterate on Frêne short
/// near the wall (|μ| 0.99991 and 0.99984, a step of 7e-3 c leaving the manifold by 6e-6 c
/// against a residual of 1e-6 c). The period after the step puts the iterate back on the
/// manifold, as Newton–Picard methods treat the fast directions by Picard iteration
/// (Lust, Roose, Spence & Champneys 1998). Two periods an iteration.
struct NewtonPicardOptions {
  std::vector<double> residual_scales;  ///< r_i
  double tolerance = 1e-11;             ///< converged when max_i |P(z)_i − z_i| / r_i <= tolerance
  /// ... or when it is within this fraction of the start's residual (0: the tolerance
  /// alone). An error bar's re-solve needs its orbit only to a fraction of its distance
  /// from the start, (I − M)⁻¹ times the residual: 1e-2 locates it to 1 % of that.
  double relative_tolerance = 0.0;
  /// A stop (stall or iteration limit) within this factor of the tolerance is the map's
  /// own noise: converged, at_noise_floor (ShootingOptions::noise_factor).
  double noise_factor = 1000.0;
  int max_iterations = 6;
  int stall = 2;  ///< iterations without a smaller residual before it stops
};
/// The best iterate (smallest residual) and its image; `maps` the periods spent.
/// A Newton point whose period fails (beyond the wall) is pulled back, the step halved up
/// to four times. `outcome` left_domain if the start's period fails.
ShootingResult newton_picard(CycleMap& P, const Eigen::VectorXd& z0, const Eigen::MatrixXd& jacobian,
                             const NewtonPicardOptions& opt);

/// max_i |a_i − b_i| / s_i.
double scaled_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const std::vector<double>& scales);

}  // namespace lub::steady
