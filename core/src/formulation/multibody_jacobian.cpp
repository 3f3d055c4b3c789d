// Structured Jacobian of the baumgarte formulation, for the Newton iterations of the
// implicit methods (CVODE BDF, ARKODE SDIRK) in place of SUNDIALS' dense difference
// quotients (2 nq = 18 full evaluations per Jacobian for the slider-crank).
//
// y = (q, v), f = (v, a(q, v)) with
//     a = P g(q, v) + M⁻¹Φ_qᵀ S⁻¹ γ̂(q, v),   P = M⁻¹ − M⁻¹Φ_qᵀ S⁻¹ Φ_q M⁻¹,
//     S = Φ_q M⁻¹ Φ_qᵀ,   γ̂ = γ − 2α Φ̇ − β² Φ   (model.hpp),
// so J = [[0, I], [J_q, J_v]] with
//     J_q ≈ P ∂g/∂q − β² M⁻¹Φ_qᵀ S⁻¹ Φ_q
//     J_v =  P ∂g/∂v + M⁻¹Φ_qᵀ S⁻¹ (∂γ/∂v − 2α Φ_q).
// ∂g/∂q, ∂g/∂v: the film elements (the stiff part), exactly up to difference-quotient
// round-off (add_film_force_jacobian: the film element alone, contact hand-over and the
// switching modes included; gravity is constant). ∂γ/∂v: analytic (γ is quadratic in v:
// the φ̇² a terms of the revolute rows, the Coriolis term of the translational rows, the
// |ė⊥|²/|e| of a sliding row); it is not small: 2ω|a| ≈ 1000 1/s at 5000 rpm against
// 2α = 10 1/s. The sliding rows of sliding films are in Φ_q (constraint_residual), and
// because their curvature radius is |e| ~ c (not a link length) their second derivatives
// are kept: the geometric stiffness λ_s ∂r/∂q (in ∂g/∂q, the multiplier held) and the
// full ∂(Φ̈ + 2αΦ̇ + β²Φ)/∂q of the row (sliding_rows_position_jacobian). Without them the
// position block is 5 % off at a sliding state (tests/test_core_jacobian.cpp).
//
// Neglected (J_v is exact up to ∂Φ_t/∂v = 0; J_q is not): the derivatives with respect to
// q of P and of M⁻¹Φ_qᵀS⁻¹ (through Φ_q(q)), of γ and of −2αΦ̇ = −2α(Φ_q v + Φ_t). Each is
// a constraint-geometry term of order |constraint force|/(m L) or ω² |s|/L ~ ω² (links of
// L ~ 0.05–0.12 m, crank at ω = 524 rad/s: ~3e5 1/s²). In the Newton matrix
// I − γ_h J the J_q block enters, after eliminating the position block, multiplied by
// γ_h² (γ_h = h β₀ ≤ h): at the reference case's ~400 steps per crank cycle (rtol 1e-6,
// h ≈ 3e-5 s) that is γ_h² ω² ≈ (0.016)² ≈ 3e-4 relative to the identity, whereas the
// film block it sits next to is γ_h ∂a/∂v ≈ 3e-5 s × 3e5 1/s ≈ 10 at ε ≈ 0.95 (damping
// ~C/c (1 − ε²)^(-3/2) ≈ 7e4 N s/m on 0.14–0.21 kg). An error of 3e-4 in the Newton
// matrix only slows the (modified) Newton iteration's contraction to ~3e-4 per iteration:
// invisible against the convergence test. At rtol 1e-8 the steps are smaller and the
// neglected terms smaller still.
//
// The CVODE/ARKODE Newton iteration keeps a Jacobian for many steps anyway, so exactness
// buys little; the gain is the cost: ~24 film-law calls per film plus one small Cholesky
// factorisation instead of 18 full evaluations.
#include <Eigen/Cholesky>

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "common/central_difference.hpp"
#include "common/small_dense.hpp"
#include "lub/formulation/model_jacobian.hpp"
#include "lub/formulation/multibody_system.hpp"

namespace lub {

JacobianScratch::JacobianScratch(const Model& m)
    : q(static_cast<size_t>(m.nq), 0.0),
      v(static_cast<size_t>(m.nq), 0.0),
      a(static_cast<size_t>(m.nq), 0.0),
      Gq(Eigen::MatrixXd::Zero(m.nq, m.nq)),
      Gv(Eigen::MatrixXd::Zero(m.nq, m.nq)),
      B(Eigen::MatrixXd::Zero(m.nc + m.n_switching, m.nq)),
      R(Eigen::MatrixXd::Zero(m.nc + m.n_switching, m.nq)),
      Gamma_v(Eigen::MatrixXd::Zero(m.nc + m.n_switching, m.nq)),
      S(Eigen::MatrixXd::Zero(m.nc + m.n_switching, m.nc + m.n_switching)),
      lam_rows(Eigen::VectorXd::Zero(m.nc + m.n_switching)),
      mu_rows(Eigen::VectorXd::Zero(m.nc + m.n_switching)),
      slot_of_row(static_cast<size_t>(m.nc + m.n_switching), 0),
      slot_active(static_cast<size_t>(m.nc + m.n_switching), 0),
      Lq(Eigen::MatrixXd::Zero(m.nq, m.nq)),
      Uq(Eigen::MatrixXd::Zero(m.nq, m.nq)),
      Dq(Eigen::MatrixXd::Zero(m.nc + m.n_switching, m.nq)),
      T(Eigen::MatrixXd::Zero(m.nq, std::max(m.nq - m.nc, 0))),
      W(Eigen::MatrixXd::Zero(m.nq, std::max(m.nq - m.nc, 0))),
      Fz(Eigen::MatrixXd::Zero(m.nq, std::max(m.nq - m.nc, 0))),
      Fzd(Eigen::MatrixXd::Zero(m.nq, std::max(m.nq - m.nc, 0))),
      U(Eigen::MatrixXd::Zero(m.nc, std::max(m.nq - m.nc, 0))),
      N(Eigen::MatrixXd::Zero(std::max(m.nq - m.nc, 0), std::max(m.nq - m.nc, 0))),
      piv_n(static_cast<size_t>(std::max(m.nq - m.nc, 0)), 0) {}

int MultibodySystem::jacobian(double t, const double* y, const double* fy, double* Jout) {
  if (form_ == Formulation::partitioned) return partitioned_jacobian(t, y, fy, Jout);
  // joint: 2 nd states (4 for the slider-crank): forward differences of rhs() cost 2 nd
  // evaluations of a cheap right-hand side (no recovery, no constraint solve).
  if (form_ == Formulation::joint) {
    // These evaluations are the Jacobian's: their force-law calls count as
    // film_law_evals_jacobian, as the structured Jacobians' do, and not as model evaluations.
    const EvalCounters before = ws_.counters;
    const int rc = forward_difference_jacobian(t, y, fy, Jout);
    ws_.counters.film_jacobian += ws_.counters.film - before.film;
    ws_.counters.film = before.film;
    ws_.counters.rhs = before.rhs;
    ws_.counters.gravity = before.gravity;
    return rc;
  }
  if (form_ != Formulation::baumgarte) return -1;
  const int nq = m_.nq;
  JacobianScratch& s = jac_;
  std::copy(y, y + nq, s.q.begin());
  std::copy(y + nq, y + 2 * nq, s.v.begin());
  s.Gq.setZero();
  s.Gv.setZero();
  // A sliding film's radial force is a multiplier: its value at this state (and q̈ for the
  // sliding row's curvature) from one evaluation, only while some film slides.
  bool sliding = false;
  for (size_t k = 0; k < m_.films.size(); ++k) sliding = sliding || ws_.film_mode[k] == FilmMode::sliding;
  if (sliding && evaluate(m_, ws_, stab_, t, s.q.data(), s.v.data(), s.a.data()) != EvalStatus::ok) return 1;
  if (add_film_force_jacobian(m_, ws_, s.q.data(), s.v.data(), s.Gq, s.Gv) != 0) return 1;

  // Φ_q at this state, with the sliding rows of the films sliding now.
  constraint_residual(m_, ws_, t, s.q.data(), s.v.data());
  const int nc = ws_.nc_active;
  const auto& Minv = m_.inv_mass_diag;
  if (nc > 0) {
    const auto Phq = ws_.Phi_q.topRows(nc);
    auto B = s.B.topRows(nc);
    B.noalias() = Phq * Minv.asDiagonal();
    auto S = s.S.topLeftCorner(nc, nc);
    S.noalias() = B.lazyProduct(Phq.transpose());
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(S);  // in place: no allocation
    if (llt.info() != Eigen::Success) return 1;
    auto R = s.R.topRows(nc);
    const double beta2 = stab_.beta * stab_.beta, two_alpha = 2.0 * stab_.alpha;
    // J_q M = ∂g/∂q − Φ_qᵀ S⁻¹ (Φ_q M⁻¹ ∂g/∂q + β² Φ_q)
    R.noalias() = B.lazyProduct(s.Gq);
    R += beta2 * Phq;
    // Sliding rows: their full ∂(Φ̈ + 2αΦ̇ + β²Φ)/∂q (curvature radius |e| ~ c).
    if (sliding) {
      auto D = s.Gamma_v.topRows(nc);  // free until ∂γ/∂v below
      sliding_rows_position_jacobian(m_, ws_, stab_, s.q.data(), s.v.data(), s.a.data(), D);
      for (size_t k = 0; k < m_.films.size(); ++k)
        if (ws_.film_mode[k] == FilmMode::sliding) R.row(ws_.slide_row[k]) += D.row(ws_.slide_row[k]) - beta2 * Phq.row(ws_.slide_row[k]);
    }
    llt.solveInPlace(R);
    s.Gq.noalias() -= Phq.transpose().lazyProduct(R);
    auto Gam = s.Gamma_v.topRows(nc);
    constraint_gamma_velocity_jacobian(m_, ws_, s.q.data(), s.v.data(), Gam);
    // J_v M = ∂g/∂v − Φ_qᵀ S⁻¹ (Φ_q M⁻¹ ∂g/∂v − ∂γ/∂v + 2α Φ_q)
    R.noalias() = B.lazyProduct(s.Gv);
    R += two_alpha * Phq - Gam;
    llt.solveInPlace(R);
    s.Gv.noalias() -= Phq.transpose().lazyProduct(R);
  }
  const int n = 2 * nq;
  Eigen::Map<Eigen::MatrixXd> J(Jout, n, n);
  J.topLeftCorner(nq, nq).setZero();
  J.topRightCorner(nq, nq).setIdentity();
  J.bottomLeftCorner(nq, nq).noalias() = Minv.asDiagonal() * s.Gq;
  J.bottomRightCorner(nq, nq).noalias() = Minv.asDiagonal() * s.Gv;
  return 0;
}

// Jacobian of the partitioned formulation, y = (z, ż), f = (ż, a_z). On Φ = 0, Φ̇ = 0
// (where the recovery puts every state) evaluate()'s solve is, in reduced form,
//     a_z = N⁻¹ Tᵀ (g(q, v) − M q̈_p),   N = TᵀMT,
//     T = ∂q/∂z: rows ind = I, rows dep = −Φ_dep⁻¹ Φ_ind   (Φ_q T = 0),
//     q̈_p: rows ind = 0, rows dep = Φ_dep⁻¹ γ(q, v)       (Φ_q q̈_p = γ),
// because its q̈ = T a_z + q̈_p is the one with Tᵀ(M q̈ − g) = 0 (the multipliers' forces
// do no work along T). The velocities are v = T ż + v_p(q), so ∂v/∂ż = T exactly, and
// ∂v/∂z = W with W_ind = 0 and
//     Φ_dep W_dep = −(∂Φ̇/∂q) T = ½ (∂γ/∂v) T:
// γ = −(Φ_q v)_q v − 2 Φ_qt v − Φ_tt is quadratic in v, so ∂γ/∂v = −2 (Φ_q v)_q − 2 Φ_qt,
// while ∂Φ̇/∂q = (Φ_q v)_q + Φ_tq (Φ̇ = Φ_q v + Φ_t). Then
//     ∂a_z/∂ż = N⁻¹ Tᵀ (∂g/∂v T − M ∂q̈_p/∂v T)                   (exact)
//     ∂a_z/∂z ≈ N⁻¹ Tᵀ (∂g/∂q T + ∂g/∂v W)
// with ∂q̈_p/∂v = [0; Φ_dep⁻¹ ∂γ/∂v] (analytic: the Coriolis terms, 2ω ≈ 1000 1/s, which
// enter the Newton matrix as γ_h × 1000 ≈ 0.04). The film terms are derivatives along the
// 2 nz directions (T_j, W_j) and (0, T_j) of the state space (add_film_force_directional:
// 8 film-law calls for the slider-crank, whose 2 degrees of freedom are all the Newton
// matrix needs); ∂g/∂v W, the film's damping times the velocities a change of
// configuration brings, is of the order of its stiffness. Neglected in ∂a_z/∂z, as in the
// baumgarte Jacobian: M ∂q̈_p/∂v W and ∂q̈_p/∂q (the constraint geometry's curvature times
// the velocities squared, ω² ≈ 3e5 1/s² at 5000 rpm) and the derivatives of N⁻¹Tᵀ (the
// curvature times the forces, |F|/(m L) ≈ 1e4 N / (0.2 kg × 0.12 m) ≈ 4e5 1/s²), against
// the film's stiffness per unit mass of 1e7–1e10 1/s²; in the Newton matrix they would
// enter as γ_h² × 4e5 ≈ 1e-3 at the ~300 steps a cycle of rtol 1e-8.
// tests/test_core_jacobian.cpp compares the result with central differences of rhs().
//
// A sliding film adds a constraint row that the reduced form above does not carry: while
// one slides, forward differences of rhs() (forward_difference_jacobian), as SUNDIALS'.
int MultibodySystem::partitioned_jacobian(double t, const double* y, const double* fy, double* Jout) {
  for (size_t k = 0; k < m_.films.size(); ++k)
    if (ws_.film_mode[k] == FilmMode::sliding) return forward_difference_jacobian(t, y, fy, Jout);
  const int nq = m_.nq, nc = m_.nc, nd = nz_;
  JacobianScratch& s = jac_;
  if (expand(t, y, scratch_.data()) != 0) return 1;
  double* q = s.q.data();
  double* v = s.v.data();
  std::copy(scratch_.begin(), scratch_.begin() + nq, q);
  std::copy(scratch_.begin() + nq, scratch_.begin() + 2 * nq, v);
  Eigen::MatrixXd& T = s.T;
  Eigen::MatrixXd& W = s.W;
  T.setZero();
  W.setZero();
  for (int j = 0; j < nd; ++j) T(ind_[j], j) = 1.0;
  if (nc > 0) {
    // The recovery has just factored the dependent block at this q (expand); Φ_q at q.
    const Recovery& rc = integ_rec_;
    constraint_residual(m_, ws_, t, q, v);
    for (int j = 0; j < nd; ++j) {
      for (int i = 0; i < nc; ++i) r_[i] = ws_.Phi_q(i, ind_[j]);
      dense::lu_solve(rc.lu.data(), nc, nc, rc.piv.data(), r_.data());
      for (int i = 0; i < nc; ++i) T(dep_[i], j) = -r_[i];
    }
    auto Gam = s.Gamma_v.topRows(nc);
    constraint_gamma_velocity_jacobian(m_, ws_, q, v, Gam);
    // U = Φ_dep⁻¹ (∂γ/∂v) T = ∂q̈_p/∂v T (dependent rows), and W_dep = U / 2.
    for (int j = 0; j < nd; ++j) {
      for (int i = 0; i < nc; ++i) s.U(i, j) = Gam.row(i).dot(T.col(j));
      dense::lu_solve(rc.lu.data(), nc, nc, rc.piv.data(), s.U.col(j).data());
      for (int i = 0; i < nc; ++i) W(dep_[i], j) = 0.5 * s.U(i, j);
    }
  }
  // Film forces along (T_j, W_j) (position columns) and (0, T_j) (velocity columns); then
  // − M ∂q̈_p/∂v T in the velocity columns.
  s.Fz.setZero();
  s.Fzd.setZero();
  if (add_film_force_directional(m_, ws_, q, v, nd, T.data(), W.data(), s.Fz.data()) != 0) return 1;
  if (add_film_force_directional(m_, ws_, q, v, nd, nullptr, T.data(), s.Fzd.data()) != 0) return 1;
  for (int j = 0; j < nd; ++j)
    for (int i = 0; i < nc; ++i) s.Fzd(dep_[i], j) -= m_.mass_diag(dep_[i]) * s.U(i, j);
  // N = TᵀMT (M diagonal), factored; the acceleration rows N⁻¹ Tᵀ F.
  for (int j = 0; j < nd; ++j)
    for (int i = 0; i < nd; ++i) {
      double sum = 0.0;
      for (int k = 0; k < nq; ++k) sum += T(k, i) * m_.mass_diag(k) * T(k, j);
      s.N(i, j) = sum;
    }
  dense::lu(s.N.data(), nd, nd, s.piv_n.data());
  const int n = 2 * nd;
  Eigen::Map<Eigen::MatrixXd> J(Jout, n, n);
  J.setZero();
  J.topRightCorner(nd, nd).setIdentity();
  for (int j = 0; j < nd; ++j) {
    double* col_z = &J(nd, j);        // ∂a_z/∂z_j: rows nd … 2nd − 1, contiguous
    double* col_zd = &J(nd, nd + j);  // ∂a_z/∂ż_j
    for (int i = 0; i < nd; ++i) {
      col_z[i] = T.col(i).dot(s.Fz.col(j));
      col_zd[i] = T.col(i).dot(s.Fzd.col(j));
    }
    dense::lu_solve(s.N.data(), nd, nd, s.piv_n.data(), col_z);
    dense::lu_solve(s.N.data(), nd, nd, s.piv_n.data(), col_zd);
  }
  return 0;
}

// Forward differences of rhs(), column by column, increments √u max(|y_j|, scale_j) with
// scale_j the state's size in its own unit (set_difference_scales; 1 if not set). Joint
// coordinates: √u scale_j alone. A slide of ~0.4 m would move the journal by √u |y| ~ 6e-9
// m, a tenth of the film at ε = 0.9999 in a 0.5 mm clearance, where the law is far from
// linear: Newton then failed near the wall (the full factorial's 50 rpm printed-law cases,
// h → 1e-8 s); scale_j (the clearance for a length) moves it by ~1e-11 m.
int MultibodySystem::forward_difference_jacobian(double t, const double* y, const double* fy, double* Jout) {
  const int n = 2 * nz_;
  const double srur = std::sqrt(DBL_EPSILON);
  const bool absolute = form_ == Formulation::joint;
  std::copy(y, y + n, dq_y_.begin());
  for (int j = 0; j < n; ++j) {
    const double scale = static_cast<size_t>(j) < dq_scale_.size() ? dq_scale_[j] : 1.0;
    const double yj = dq_y_[j];
    dq_y_[j] = yj + srur * (absolute ? scale : std::max(std::abs(yj), scale));
    const double inc = dq_y_[j] - yj;
    const int rc = rhs(t, dq_y_.data(), dq_f_.data());
    ++ws_.counters.rhs_jacobian;
    dq_y_[j] = yj;
    if (rc != 0) return rc;
    for (int i = 0; i < n; ++i) Jout[static_cast<size_t>(j) * n + i] = (dq_f_[i] - fy[i]) / inc;
  }
  return 0;
}

// Iteration matrix of the GGL DAE (IDA), Y = (q, v, λ, μ), na slots each for λ and μ:
//     F_q = q' − v + Φ_qᵀμ,  F_v = M v' − g + Φ_qᵀλ,  F_λ = Φ,  F_μ = Φ_q v + Φ_t,
// J = ∂F/∂Y + cj ∂F/∂Y' (rows and columns in that order):
//     q cols: [cj I + ∂(Φ_qᵀμ)/∂q ; −∂g/∂q + ∂(Φ_qᵀλ)/∂q ; Φ_q ; ∂(Φ_q v + Φ_t)/∂q]
//     v cols: [−I ; cj M − ∂g/∂v ; 0 ; Φ_q]
//     λ cols: [0 ; Φ_qᵀ ; 0 ; 0],   μ cols: [Φ_qᵀ ; 0 ; 0 ; 0]
// on the active rows; an inactive slot (a switching film not sliding) has F = λ_s, F = μ_s:
// identity on its own equations. Nothing is neglected:
//  - ∂g/∂q, ∂g/∂v: the film elements (add_film_force_jacobian), with a sliding film's
//    radial force left out (SlidingRadial::in_constraint): the residual's g is
//    evaluate()'s before the solve, where that force is zero; it acts through the sliding
//    row's Φ_qᵀλ with the DAE's own multiplier, whose curvature term (λ_s/|e|, not small)
//    is in ∂(Φ_qᵀλ)/∂q below. Gravity is constant.
//  - ∂(Φ_qᵀλ)/∂q, ∂(Φ_qᵀμ)/∂q, ∂Φ̇/∂q: central differences of constraint_residual alone
//    (geometry only: no film law, no solve), 2 nq calls, step u^(1/3) of the smallest
//    clearance (the sliding rows' radius of curvature is |e| ~ c; the ideal joints' is a
//    link length, so their truncation error is smaller still). Φ_q (∂Φ/∂q, ∂Φ̇/∂v): exact.
// Cost: ~24 film-law calls per film and 2 nq = 18 constraint evaluations, against
// 2 nq + 2 na = 32 full residuals for SUNDIALS' dense difference quotients.
int MultibodySystem::dae_jacobian(double t, double cj, const double* Y, const double* /*Yp*/, double* Jout) {
  if (form_ != Formulation::ggl) return -1;
  const int nq = m_.nq, na = m_.nc + m_.n_switching, n = 2 * nq + 2 * na;
  const int iv = nq, il = 2 * nq, imu = 2 * nq + na;  // first row/column of each block
  JacobianScratch& s = jac_;
  double* q = s.q.data();
  double* v = s.v.data();
  std::copy(Y, Y + nq, q);
  std::copy(Y + nq, Y + 2 * nq, v);
  s.Gq.setZero();
  s.Gv.setZero();
  if (add_film_force_jacobian(m_, ws_, q, v, s.Gq, s.Gv, SlidingRadial::in_constraint) != 0) return 1;

  // Rows of Φ at this state (the constraints, then the sliding rows) and their slots.
  constraint_residual(m_, ws_, t, q, v);
  const int nr = ws_.nc_active;
  std::fill(s.slot_active.begin(), s.slot_active.end(), 0);
  for (int row = 0; row < m_.nc; ++row) s.slot_of_row[row] = row;
  for (size_t k = 0; k < m_.films.size(); ++k)
    if (ws_.film_mode[k] == FilmMode::sliding) s.slot_of_row[ws_.slide_row[k]] = slot_of_switching_[k];
  for (int row = 0; row < nr; ++row) {
    const int sl = s.slot_of_row[row];
    s.slot_active[sl] = 1;
    s.lam_rows(row) = Y[il + sl];
    s.mu_rows(row) = Y[imu + sl];
  }

  Eigen::Map<Eigen::MatrixXd> J(Jout, n, n);
  J.setZero();
  for (int row = 0; row < nr; ++row) {
    const int sl = s.slot_of_row[row];
    const auto a = ws_.Phi_q.row(row);
    J.block(0, imu + sl, nq, 1) = a.transpose();   // ∂F_q/∂μ
    J.block(iv, il + sl, nq, 1) = a.transpose();   // ∂F_v/∂λ
    J.block(il + sl, 0, 1, nq) = a;                // ∂Φ/∂q
    J.block(imu + sl, iv, 1, nq) = a;              // ∂Φ̇/∂v
  }
  for (int sl = 0; sl < na; ++sl)
    if (!s.slot_active[sl]) {
      J(il + sl, il + sl) = 1.0;
      J(imu + sl, imu + sl) = 1.0;
    }

  // q-derivatives of the constraint terms.
  double length = 1.0;
  for (const FilmElement& f : m_.films) length = std::min(length, f.clearance);
  const double h = std::cbrt(DBL_EPSILON) * length;  // [m], and [rad]: arms <= 1 m
  const auto Phq = ws_.Phi_q.topRows(nr);
  const auto lam = s.lam_rows.head(nr), mu = s.mu_rows.head(nr);
  auto Dq = s.Dq.topRows(nr);
  for (int j = 0; j < nq; ++j) {
    // f(±1) adds ± the terms at q ± h e_j: the columns hold the difference.
    s.Lq.col(j).setZero();
    s.Uq.col(j).setZero();
    Dq.col(j).setZero();
    const double span = detail::central_difference(q, j, h, [&](int sign) {
      constraint_residual(m_, ws_, t, q, v);
      s.Lq.col(j).noalias() += double(sign) * Phq.transpose().lazyProduct(lam);
      s.Uq.col(j).noalias() += double(sign) * Phq.transpose().lazyProduct(mu);
      Dq.col(j) += double(sign) * ws_.Phi_dot.head(nr);
      return true;
    });
    const double inv = 1.0 / span;
    s.Lq.col(j) *= inv;
    s.Uq.col(j) *= inv;
    Dq.col(j) *= inv;
  }
  constraint_residual(m_, ws_, t, q, v);  // leave ws at this state

  J.block(0, 0, nq, nq) = s.Uq;
  J.block(0, 0, nq, nq).diagonal().array() += cj;
  J.block(0, iv, nq, nq).diagonal().setConstant(-1.0);
  J.block(iv, 0, nq, nq) = s.Lq - s.Gq;
  J.block(iv, iv, nq, nq) = -s.Gv;
  J.block(iv, iv, nq, nq).diagonal() += cj * m_.mass_diag;
  for (int row = 0; row < nr; ++row) J.block(imu + s.slot_of_row[row], 0, 1, nq) = Dq.row(row);
  return 0;
}

}  // namespace lub
