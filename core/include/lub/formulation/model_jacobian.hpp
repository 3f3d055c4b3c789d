// The model's derivatives for the structured Jacobians (defined in the formulation stage,
// model_jacobian.cpp): the film elements' force derivatives, the sliding rows' curvature
// and ∂γ/∂v, each on a Model and its Workspace.
#pragma once

#include <Eigen/Core>

#include "lub/mechanism/model.hpp"

namespace lub {

/// How add_film_force_jacobian treats a sliding film's radial force (the sliding row's
/// multiplier −λ_s).
enum class SlidingRadial {
  /// Part of g, held at ws.lambda of an evaluate() at the same state: its derivative is
  /// the row's geometric stiffness, which the baumgarte ODE's a = M⁻¹(g − Φ_qᵀλ) needs.
  held_multiplier,
  /// Not part of g (zero): it enters elsewhere as Φ_qᵀλ with the DAE's own multiplier
  /// (the GGL residual, whose g is evaluate()'s before the solve).
  in_constraint,
};

/// Structured Jacobian, force part: adds ∂g/∂q and ∂g/∂v (nq × nq each) of every film
/// element at (q, v) to Gq and Gv, with each switching film held in its current mode
/// (ws.film_mode; a sliding film's radial force as `sliding` says), contact hand-over
/// included: exactly what evaluate() adds to g. Central difference quotients of the film element alone (≤ 2
/// bodies: ≤ 12 columns, 24 calls of film_element_force; steps scaled with the distance
/// to the wall). q and v are scratch copies (perturbed and restored in place). Gravity is
/// constant and contributes nothing. No allocation. Returns 0, or 1 if a perturbed state
/// leaves the model's domain (ε >= 1 without contact).
int add_film_force_jacobian(const Model& m, Workspace& ws, double* q, double* v, Eigen::Ref<Eigen::MatrixXd> Gq,
                            Eigen::Ref<Eigen::MatrixXd> Gv,
                            SlidingRadial sliding = SlidingRadial::held_multiplier);

/// Directional form of add_film_force_jacobian: adds (∂g/∂q) dq_d + (∂g/∂v) dv_d of every
/// film element at (q, v) to column d of `out` (nq × n_dir, column-major), for n_dir
/// directions (dq_d, dv_d) of the state space (columns of dq, dv, nq × n_dir; nullptr: zero),
/// from two evaluations of each film element a direction moves (central differences along
/// it, the step scaled with the distance to the wall as there). The partitioned
/// formulation's Jacobian needs the force derivatives only along its degrees of freedom: 4
/// directions for the slider-crank (8 film-law calls) against the 24 of the full blocks.
/// q and v are scratch copies (perturbed and restored in place). Films held in their
/// current modes (not for sliding films: their radial force is a multiplier). No
/// allocation. Returns 0, or 1 if a perturbed state leaves the model's domain.
int add_film_force_directional(const Model& m, Workspace& ws, double* q, double* v, int n_dir, const double* dq,
                               const double* dv, double* out);

/// Rows of the sliding films' constraints: ∂(Φ̈ + 2αΦ̇ + β²Φ)/∂q at fixed (v, q̈ = a)
/// into the sliding rows of D (ws.slide_row; other rows untouched): the curvature of a
/// sliding row has the clearance as its length scale, so unlike that of the ideal joints it
/// is not negligible in a Newton matrix. Central differences; q is perturbed and restored.
void sliding_rows_position_jacobian(const Model& m, const Workspace& ws, const Stabilisation& stab, double* q,
                                    const double* v, const double* a, Eigen::Ref<Eigen::MatrixXd> D);

/// ∂γ/∂v (ws.nc_active × nq) of the constraint rows at (q, v), the sliding rows of sliding
/// films included (their row numbers from ws.slide_row: call constraint_residual() at the
/// same state first). γ is quadratic in v, so this is exact (analytic). No allocation.
void constraint_gamma_velocity_jacobian(const Model& m, const Workspace& ws, const double* q, const double* v,
                                        Eigen::Ref<Eigen::MatrixXd> Gamma_v);

}  // namespace lub
