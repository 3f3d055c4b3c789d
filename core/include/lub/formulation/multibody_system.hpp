// The multibody equations as an ODE for the integrators (internal to lubcore).
//
// Two formulations of the same equations:
//  - baumgarte: y = (q, v), all 3 nb coordinates; the constraints enter at acceleration
//    level with Baumgarte's terms (the paper's choice); optional projection (CVODE BDF).
//  - partitioned: generalised coordinate partitioning (Wehage & Haug): y = (z, ż), the
//    nq − nc independent coordinates only; the dependent ones are recovered from Φ = 0
//    by Newton and their velocities from Φ̇ = 0 at every evaluation. No drift, and the
//    integrator works on the mechanism's degrees of freedom, like a hand-written
//    minimal-coordinate model. The partition is chosen by full-pivoting LU of Φ_q and
//    renewed when the dependent block becomes ill-conditioned.
//  - ggl: the stabilised index-2 DAE of Gear, Gupta & Leimkuhler (1985) for IDA,
//        q' = v − Φ_qᵀ μ,   M v' = g − Φ_qᵀ λ,   Φ = 0,   Φ_q v + Φ_t = 0,
//    in Y = (q, v, λ, μ): the constraints hold at position and velocity level without
//    Baumgarte's terms (μ = 0 on the exact solution; it absorbs the drift).
//  - joint: y = (θ, θ̇), the coordinates of the spanning tree of the ideal joints
//    (lub/formulation/joint_tree.hpp), where the lubricated joints cut every loop. Forward
//    kinematics gives q = q(θ, t), q̇ = J θ̇ + q̇_t, q̈ = J θ̈ + c; the equations of motion
//        (Jᵀ M J) θ̈ = Jᵀ (g − M c)
//    have no constraint equation (a sliding film's row aside, Baumgarte-stabilised as in
//    evaluate()); g is evaluate_forces()'s, the film element's force in one place.
// All expose roots (ε limit, switching of discontinuous laws) and quadratures (work).
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "lub/formulation/joint_tree.hpp"
#include "lub/formulation/options.hpp"
#include "lub/integrators/integrator.hpp"
#include "lub/mechanism/model.hpp"

namespace lub {

/// Preallocated scratch of the structured Jacobian (MultibodySystem::jacobian).
struct JacobianScratch {
  explicit JacobianScratch(const Model& m);
  std::vector<double> q, v, a;   ///< perturbed copies of the state; accelerations
  Eigen::MatrixXd Gq, Gv;        ///< ∂g/∂q, ∂g/∂v (nq × nq)
  Eigen::MatrixXd B, R, Gamma_v; ///< Φ_q M⁻¹, right-hand sides, ∂γ/∂v (rows: nc + switching films)
  Eigen::MatrixXd S;             ///< Φ_q M⁻¹ Φ_qᵀ, factorised in place
  // ggl (dae_jacobian): multipliers by row of ws.Phi, each row's slot in (λ, μ), and the
  // q-derivatives of Φ_qᵀλ, Φ_qᵀμ (nq × nq) and of Φ̇ (rows × nq).
  Eigen::VectorXd lam_rows, mu_rows;
  std::vector<int> slot_of_row;
  std::vector<char> slot_active;
  Eigen::MatrixXd Lq, Uq, Dq;
  // partitioned (partitioned_jacobian), nz = nq − nc degrees of freedom: the null-space
  // basis T = ∂q/∂z and W = ∂v/∂z (nq × nz), the film forces' derivatives along them
  // (nq × nz each), Φ_dep⁻¹ ∂γ/∂v T (nc × nz), TᵀMT (nz × nz).
  Eigen::MatrixXd T, W, Fz, Fzd, U, N;
  std::vector<int> piv_n;
};

class MultibodySystem final : public OdeSystem {
 public:
  MultibodySystem(const Model& m, Workspace& ws, const Stabilisation& stab, double eps_limit, bool energy,
                  Formulation f);

  int size() const override { return 2 * nz_; }
  int rhs(double t, const double* y, double* ydot) override;
  int num_roots() const override { return static_cast<int>(m_.films.size()) + 2 * m_.n_switching; }
  int roots(double t, const double* y, double* g) override;
  int num_quadratures() const override { return energy_ ? 2 : 0; }
  int quadrature_rhs(double t, const double* y, double* qdot) override;
  int project(double t, const double* y, double* corr, double* err) override;
  int num_algebraic() const override;
  int residual(double t, const double* Y, const double* Yp, double* F) override;
  int consistent_state(double t, const double* y, double* Y, double* Yp) override;
  void algebraic_tolerances(double rtol, double atol, double* out) const override;
  /// Structured Jacobian (multibody_jacobian.cpp) of the baumgarte formulation, or of the
  /// partitioned one (its degrees of freedom; forward differences of rhs() while a film
  /// slides); −1 (not provided) for ggl.
  int jacobian(double t, const double* y, const double* fy, double* J) override;
  /// Structured iteration matrix of the GGL DAE (ida; multibody_jacobian.cpp); −1 for the
  /// ODE formulations.
  int dae_jacobian(double t, double cj, const double* Y, const double* Yp, double* J) override;

  /// Who asks for an expansion. The partitioned recovery is a Newton iteration warm-started
  /// from the last state its context recovered: its result depends on that history at
  /// round-off level. The integrator's callbacks and the run loop's step ends use one
  /// context; the observers' samples and phase points use another, started afresh from the
  /// integrator's last state each time, so how often a run samples changes neither its
  /// trajectory nor any other observation.
  enum class Context { integrator, observer };
  /// Integrator state → full (q, v) (2 nq). Returns 0, or 1 if the dependent
  /// coordinates cannot be recovered (partitioned).
  int expand(double t, const double* y, double* qv, Context who = Context::integrator);
  /// Full (q, v) → integrator state.
  void reduce(const double* qv, double* y) const;
  /// Each integrated state's unit size from the full state's (2 nq): the tolerances.
  void reduce_units(const double* full, double* out) const;
  /// Chooses the independent coordinates at the consistent state (q, v).
  void partition(double t, const double* qv);
  /// Whether the dependent block has become ill-conditioned (partitioned): re-partition.
  bool partition_degraded() const { return degraded_; }
  Formulation formulation() const { return form_; }
  /// The independent coordinates chosen by partition() (indices into q; all of q for the
  /// formulations that integrate every coordinate).
  const std::vector<int>& independent() const { return ind_; }

  /// The radial force of switching film k at ε̇ = 0⁺ and at ε̇ = 0⁻ (F_out <= F_in for
  /// the printed law: the jump pushes back towards ε̇ = 0); a sliding motion holds while
  /// the force that keeps ε̇ = 0 lies between them.
  std::pair<double, double> sliding_limits(int k, BearingState st);
  /// Sliding film k after an evaluate(): (F − F_out, F_in − F), both >= 0 while its force
  /// lies within the jump; the first < 0: the load pulls the journal outwards off ε̇ = 0,
  /// the second < 0: it pushes it inwards. The root functions of a sliding film, and the
  /// step-end check for an exit they missed.
  std::pair<double, double> sliding_exit_functions(int k) { return sliding_exit_functions(k, ws_); }
  /// The same from the films of `ws`, a workspace evaluated at the state in question.
  std::pair<double, double> sliding_exit_functions(int k, const Workspace& ws);
  std::vector<int> root_directions() const;
  /// At a root return: switches each switching film whose roots fired (`flags`, as the
  /// integrator reports them) at the consistent state y = (q, v): at ε̇ = 0 into sliding
  /// if the force that holds ε̇ = 0 lies within the jump, else across; out of sliding by
  /// the side the load points to. Returns the number of switches.
  int switch_modes(const std::vector<int>& flags, double t, const double* y);
  /// Modes that no longer match the state (a crossing or a sliding exit the root finder
  /// could not see), switched to the branch that applies: y the integrated state, qv its
  /// consistent (q, v). `evaluated`: a workspace already evaluated at this state with these
  /// modes (the step end's observation), whose films the check reads instead of evaluating
  /// the model again; or null. Returns the number of switches (0: none; the integrator
  /// must be restarted otherwise).
  int resync_modes(double t, const double* y, const double* qv, const Workspace* evaluated = nullptr);
  /// The observers' evaluation in joint coordinates (joint formulation only): at the
  /// integrated state y = (θ, θ̇), the forces and films (a sliding film's force included)
  /// into `ws` and the absolute accelerations q̈ = J θ̈ + c (nq) into qdd — the equations
  /// the right-hand side solves, not the absolute model's: the ideal joints' and drivers'
  /// rows (Φ, Φ_q, their multipliers λ) in `ws` are left unset. `ws` carries the film modes
  /// to evaluate in; it may be the integrator's or another workspace.
  EvalStatus joint_observation(double t, const double* y, Workspace& ws, double* qdd);
  void set_projection_tolerance(double tol) { projection_tol_ = tol; }
  /// Size of each integrated state in its own unit (atol / rtol: 2 nz entries, in the
  /// current partition's order): the increments of the partitioned Jacobian's forward
  /// differences while a film slides.
  void set_difference_scales(const std::vector<double>& scales) { dq_scale_ = scales; }

 private:
  const Model& m_;
  Workspace& ws_;
  Stabilisation stab_;
  double eps_limit_;
  bool energy_;
  Formulation form_;
  int nz_;  // integrated coordinates
  double projection_tol_ = 1e-12;
  std::vector<double> scratch_, acc_;
  std::vector<double> switch_acc_;  // accelerations of the mode decisions' evaluations (discarded)
  // partitioned
  std::vector<int> ind_, dep_;
  /// One context of the partitioned recovery (see Context).
  struct Recovery {
    std::vector<double> qv;  // the last recovered (q, v): the next warm start
    // Φ_q restricted to the dependent columns when last factored, its LU factors
    // (dense::lu) and pivots
    std::vector<double> block, lu;
    std::vector<int> piv;
    bool lu_valid = false;   // lu holds a factorisation of a recent dependent block
    bool have_last = false;  // cache of the last expansion
    double last_t = 0.0;
    std::vector<double> last_y;
  };
  Recovery integ_rec_, obs_rec_;
  std::vector<double> r_;
  bool degraded_ = false;  // set by the integrator context's expansions only
  // ggl: multiplier slot of each row of ws_.Phi (constraints, then the sliding rows in
  // film order) — a switching film's sliding row keeps one slot whether active or not.
  std::vector<int> slot_of_switching_;  // per film: nc + its index among switching films, or −1
  JacobianScratch jac_{m_};
  std::vector<double> dq_scale_, dq_y_, dq_f_;  // partitioned: the forward differences' scales and scratch

  // joint: the tree, its kinematics, and the reduced system's scratch: M_θ = JᵀMJ (nd × nd),
  // Q (nd), the sliding rows' Jacobian A (rows × nd), M_θ⁻¹Aᵀ, their Schur complement.
  std::optional<JointTree> tree_;
  // kin_: the integrator's states (right-hand sides, roots, step ends); dense_kin_: the
  // observers' states inside a step (phase points, output samples), so that those do not
  // displace the step end's kinematics, which the root function computed and the step
  // end's observation then finds (forward_kinematics keeps the last state of each).
  std::optional<JointKinematics> kin_, dense_kin_;
  Eigen::MatrixXd Mt_, At_, Xt_, St_;
  Eigen::VectorXd Qt_, bt_;
  int joint_rhs(double t, const double* y, double* ydot);
  /// expand() of the joint formulation: forward kinematics (kept for the last state of
  /// kin_ and of dense_kin_, an observer's state inside a step).
  void joint_expand(double t, const double* y, double* qv, Context who);
  /// θ̈ at y into thdd, the forces, films and sliding rows' λ into ws (k at y).
  EvalStatus joint_evaluate(Workspace& ws, double t, const double* y, double* thdd, JointKinematics& k);
  bool joint_accelerations(Workspace& ws, double* thdd);

  int partitioned_jacobian(double t, const double* y, const double* fy, double* J);
  int forward_difference_jacobian(double t, const double* y, const double* fy, double* J);

  void factor_dependent_block(Recovery& rc);
};

}  // namespace lub
