#include "lub/formulation/multibody_system.hpp"
#include "lub/mechanism/film_element.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/small_dense.hpp"

namespace lub {

MultibodySystem::MultibodySystem(const Model& m, Workspace& ws, const Stabilisation& stab, double eps_limit,
                                 bool energy, Formulation f)
    : m_(m), ws_(ws), stab_(stab), eps_limit_(eps_limit), energy_(energy), form_(f),
      nz_(f == Formulation::partitioned ? m.nq - m.nc : m.nq) {
  check_workspace(m, ws);
  acc_.assign(m.nq, 0.0);
  switch_acc_.assign(m.nq, 0.0);
  scratch_.assign(2 * m.nq, 0.0);
  int next_slot = m.nc;
  for (const FilmElement& film : m.films) slot_of_switching_.push_back(film.switching ? next_slot++ : -1);
  for (Recovery* rc : {&integ_rec_, &obs_rec_}) {
    rc->qv.assign(2 * m.nq, 0.0);
    if (f != Formulation::partitioned) continue;
    rc->lu.assign(static_cast<size_t>(m.nc) * m.nc, 0.0);
    rc->block = rc->lu;
    rc->piv.assign(static_cast<size_t>(m.nc), 0);
    rc->last_y.assign(static_cast<size_t>(2 * nz_), 0.0);
  }
  if (f == Formulation::joint) {
    std::string why;
    tree_ = build_joint_tree(m, &why);
    if (!tree_) throw std::runtime_error("solver.formulation = joint does not apply: " + why);
    nz_ = tree_->ndof;
    kin_.emplace(m, *tree_);
    dense_kin_.emplace(m, *tree_);
    const int rows = m.n_switching;
    Mt_ = Eigen::MatrixXd::Zero(nz_, nz_);
    Qt_ = Eigen::VectorXd::Zero(nz_);
    At_ = Eigen::MatrixXd::Zero(std::max(rows, 1), nz_);
    Xt_ = Eigen::MatrixXd::Zero(nz_, std::max(rows, 1));
    St_ = Eigen::MatrixXd::Zero(std::max(rows, 1), std::max(rows, 1));
    bt_ = Eigen::VectorXd::Zero(std::max(rows, 1));
  }
  if (f == Formulation::partitioned || f == Formulation::joint) {
    r_.assign(static_cast<size_t>(m.nc), 0.0);
    dq_y_.assign(static_cast<size_t>(2 * nz_), 0.0);
    dq_f_ = dq_y_;
  }
}

void MultibodySystem::partition(double t, const double* qv) {
  for (Recovery* rc : {&integ_rec_, &obs_rec_}) {
    std::copy(qv, qv + 2 * m_.nq, rc->qv.begin());
    rc->have_last = false;
    rc->lu_valid = false;
  }
  if (form_ != Formulation::partitioned) return;
  ind_.clear();
  dep_.clear();
  if (m_.nc == 0) {
    for (int i = 0; i < m_.nq; ++i) ind_.push_back(i);
    return;
  }
  constraint_residual(m_, ws_, t, qv, nullptr);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(ws_.Phi_q.topRows(m_.nc));
  if (lu.rank() < m_.nc)
    throw std::runtime_error("coordinate partitioning: the constraint Jacobian is rank deficient");
  const auto& perm = lu.permutationQ().indices();
  for (int i = 0; i < m_.nq; ++i) (i < m_.nc ? dep_ : ind_).push_back(perm(i));
  std::sort(dep_.begin(), dep_.end());
  std::sort(ind_.begin(), ind_.end());
  degraded_ = false;
}

void MultibodySystem::factor_dependent_block(Recovery& rc) {
  // The block already factored (e.g. the integrator's difference quotients that perturb
  // only velocities): nothing to do, the factors are exact for it.
  const int nc = m_.nc;
  bool same = rc.lu_valid;
  for (int j = 0; j < nc; ++j)
    for (int i = 0; i < nc; ++i) {
      const double a = ws_.Phi_q(i, dep_[j]);
      double& b = rc.block[static_cast<size_t>(j) * nc + i];
      if (a != b) same = false, b = a;
    }
  if (same) return;
  std::copy(rc.block.begin(), rc.block.end(), rc.lu.begin());
  dense::lu(rc.lu.data(), nc, nc, rc.piv.data());
}

void MultibodySystem::joint_expand(double t, const double* y, double* qv, Context who) {
  const int nq = m_.nq;
  // With J and c: the observation that follows at this state (a step end, a phase point)
  // finds its kinematics done, and so does a second expansion of the same state (the root
  // function's at a step end, then the run loop's): forward_kinematics keeps the last
  // state of each JointKinematics. The integrator's states in kin_, an observer's inside a
  // step in dense_kin_.
  JointKinematics& k = who == Context::observer ? *dense_kin_ : *kin_;
  forward_kinematics(m_, *tree_, t, y, y + nz_, k, true);
  std::copy(k.q.data(), k.q.data() + nq, qv);
  std::copy(k.v.data(), k.v.data() + nq, qv + nq);
}

int MultibodySystem::expand(double t, const double* y, double* qv, Context who) {
  const int nq = m_.nq;
  if (form_ == Formulation::joint) {
    joint_expand(t, y, qv, who);
    return 0;
  }
  if (form_ != Formulation::partitioned) {
    std::copy(y, y + 2 * nq, qv);
    return 0;
  }
  Recovery& rc = who == Context::integrator ? integ_rec_ : obs_rec_;
  const int nd = static_cast<int>(ind_.size());
  if (who == Context::observer) {
    // Start from the integrator's last recovered state with fresh factors, every time:
    // an observation then depends on (t, y) and the integration alone, not on which
    // other observations were made before it.
    std::copy(integ_rec_.qv.begin(), integ_rec_.qv.end(), rc.qv.begin());
    rc.lu_valid = false;
    rc.have_last = false;
  }
  // The integrator often asks again for the state it just had (roots, quadratures,
  // observers at a step end): reuse it.
  if (rc.have_last && t == rc.last_t && std::equal(y, y + 2 * nd, rc.last_y.begin())) {
    std::copy(rc.qv.begin(), rc.qv.end(), qv);
    return 0;
  }
  rc.have_last = false;
  // Warm start from the last recovered state; the independent coordinates from y.
  double* q = rc.qv.data();
  double* v = rc.qv.data() + nq;
  for (int i = 0; i < nd; ++i) q[ind_[i]] = y[i];
  if (m_.nc > 0) {
    const double tol = 1e-13;  // m or rad: far below any clearance and DQ perturbation
    // Chord Newton: the LU of the dependent block from the last evaluation serves as
    // long as it converges fast (the configuration moved little); it is refreshed at
    // the solution for the velocities, and whenever the iteration stalls.
    const int nc = m_.nc;
    const double* Phi = ws_.Phi.data();
    bool converged = false;
    double last = std::numeric_limits<double>::infinity();
    for (int it = 0; it < 30; ++it) {
      constraint_residual(m_, ws_, t, q, nullptr);
      double res = 0.0;
      for (int i = 0; i < nc; ++i) {
        if (!std::isfinite(Phi[i])) return 1;
        res = std::max(res, std::abs(Phi[i]));
      }
      if (res <= tol) {
        converged = true;
        break;
      }
      if (!rc.lu_valid || res > 0.25 * last) {
        factor_dependent_block(rc);
        rc.lu_valid = true;
      }
      last = res;
      std::copy(Phi, Phi + nc, r_.begin());
      dense::lu_solve(rc.lu.data(), nc, nc, rc.piv.data(), r_.data());
      for (int i = 0; i < nc; ++i) q[dep_[i]] -= r_[i];
    }
    if (!converged) {
      rc.lu_valid = false;
      return 1;
    }
    // Velocities: Φ_q,dep v_dep = −(Φ_q,ind ż + Φ_t), with Φ_t = Φ̇ at v = 0. Exact only
    // with the dependent block at the solution: factor it (this is also the next chord).
    factor_dependent_block(rc);
    rc.lu_valid = true;
    if (who == Context::integrator) {
      double dmin = std::numeric_limits<double>::infinity(), dmax = 0.0;
      for (int i = 0; i < nc; ++i) {
        const double d = std::abs(rc.lu[static_cast<size_t>(i) * nc + i]);
        dmin = std::min(dmin, d);
        dmax = std::max(dmax, d);
      }
      degraded_ = dmin < 1e-4 * dmax;
    }
    std::copy(ws_.Phi_dot.data(), ws_.Phi_dot.data() + nc, r_.begin());
    for (int i = 0; i < nd; ++i) {
      v[ind_[i]] = y[nd + i];
      for (int r = 0; r < nc; ++r) r_[r] += ws_.Phi_q(r, ind_[i]) * y[nd + i];
    }
    dense::lu_solve(rc.lu.data(), nc, nc, rc.piv.data(), r_.data());
    for (int i = 0; i < nc; ++i) v[dep_[i]] = -r_[i];
  } else {
    for (int i = 0; i < nd; ++i) v[ind_[i]] = y[nd + i];
  }
  std::copy(rc.qv.begin(), rc.qv.end(), qv);
  rc.last_t = t;
  std::copy(y, y + 2 * nd, rc.last_y.begin());
  rc.have_last = true;
  return 0;
}

void MultibodySystem::reduce(const double* qv, double* y) const {
  if (form_ == Formulation::joint) {
    joint_coordinates(m_, *tree_, qv, y, y + nz_);
    return;
  }
  if (form_ != Formulation::partitioned) {
    std::copy(qv, qv + 2 * m_.nq, y);
    return;
  }
  const int nd = static_cast<int>(ind_.size());
  for (int i = 0; i < nd; ++i) {
    y[i] = qv[ind_[i]];
    y[nd + i] = qv[m_.nq + ind_[i]];
  }
}

void MultibodySystem::reduce_units(const double* full, double* out) const {
  if (form_ == Formulation::joint) {
    joint_units(m_, *tree_, full, out);
    return;
  }
  reduce(full, out);
}

// M_θ θ̈ = Q with M_θ = JᵀMJ, Q = Jᵀ(g − Mc) (in Mt_, Qt_); with sliding films, the rows
// A θ̈ = b (At_, bt_) by their Schur complement, λ = (A M_θ⁻¹ Aᵀ)⁻¹ (A M_θ⁻¹ Q − b) into
// ws.lambda, θ̈ = M_θ⁻¹ (Q − Aᵀλ). False if M_θ or the complement is singular.
bool MultibodySystem::joint_accelerations(Workspace& ws, double* thdd) {
  const int nd = nz_, ns = ws.nc_active - m_.nc;
  const int ld = static_cast<int>(Mt_.rows());
  if (!dense::cholesky(Mt_.data(), ld, nd)) return false;
  for (int i = 0; i < nd; ++i) thdd[i] = Qt_(i);
  dense::cholesky_solve(Mt_.data(), ld, nd, thdd);
  if (ns == 0) return true;
  const int lx = static_cast<int>(Xt_.rows()), ls = static_cast<int>(St_.rows());
  for (int r = 0; r < ns; ++r) {
    for (int j = 0; j < nd; ++j) Xt_(j, r) = At_(r, j);
    dense::cholesky_solve(Mt_.data(), ld, nd, Xt_.data() + static_cast<long>(r) * lx);
  }
  for (int r = 0; r < ns; ++r) {
    double rhs = -bt_(r);
    for (int j = 0; j < nd; ++j) rhs += At_(r, j) * thdd[j];
    ws.lambda(m_.nc + r) = rhs;
    for (int s = 0; s <= r; ++s) {
      double x = 0.0;
      for (int j = 0; j < nd; ++j) x += At_(r, j) * Xt_(j, s);
      St_(r, s) = x;
    }
  }
  if (!dense::cholesky(St_.data(), ls, ns)) return false;
  double* lam = ws.lambda.data() + m_.nc;
  dense::cholesky_solve(St_.data(), ls, ns, lam);
  for (int r = 0; r < ns; ++r)
    for (int j = 0; j < nd; ++j) thdd[j] -= Xt_(j, r) * lam[r];
  return true;
}

EvalStatus MultibodySystem::joint_evaluate(Workspace& ws, double t, const double* y, double* thdd,
                                           JointKinematics& k) {
  const int nq = m_.nq, nd = nz_;
  forward_kinematics(m_, *tree_, t, y, y + nd, k, true);
  // The bodies' cos φ and sin φ are the forward kinematics': evaluate_forces' table
  // (body_trig) keeps them, the same values for the same angles.
  for (int b = 0; b < m_.nb; ++b) {
    ws.cos_phi[static_cast<size_t>(b)] = k.cphi[static_cast<size_t>(b)];
    ws.sin_phi[static_cast<size_t>(b)] = k.sphi[static_cast<size_t>(b)];
    ws.trig_phi[static_cast<size_t>(b)] = k.q(3 * b + 2);
  }
  if (const EvalStatus s = evaluate_forces(m_, ws, t, k.q.data(), k.v.data(), false); s != EvalStatus::ok)
    return s;
  const double* M = m_.mass_diag.data();
  // g − M c into ws.qdd (scratch), then M_θ and Q.
  for (int i = 0; i < nq; ++i) ws.qdd(i) = ws.g(i) - M[i] * k.c(i);
  // The sums run over J's nonzero rows only (JointTree::dof_rows, pair_rows): the same
  // terms in the same order, without J's structural zeros.
  const JointTree& tree = *tree_;
  for (int a = 0; a < nd; ++a) {
    const double* Ja = k.J.data() + static_cast<long>(a) * nq;
    double qa = 0.0;
    for (const int i : tree.dof_rows[static_cast<size_t>(a)]) qa += Ja[i] * ws.qdd(i);
    Qt_(a) = qa;
    for (int b = 0; b <= a; ++b) {
      const double* Jb = k.J.data() + static_cast<long>(b) * nq;
      double x = 0.0;
      for (const int i : tree.pair_rows[static_cast<size_t>(a * nd + b)]) x += Ja[i] * M[i] * Jb[i];
      Mt_(a, b) = x;
    }
  }
  // Sliding rows: Φ_q,r (J θ̈ + c) = γ̂_r, γ̂ = γ − 2αΦ̇ − β²Φ (as evaluate()).
  const int ns = ws.nc_active - m_.nc;
  for (int r = 0; r < ns; ++r) {
    const int row = m_.nc + r;
    double b = stab_.stabilised_gamma(ws.gamma(row), ws.Phi_dot(row), ws.Phi(row));
    for (int i = 0; i < nq; ++i) b -= ws.Phi_q(row, i) * k.c(i);
    bt_(r) = b;
    for (int j = 0; j < nd; ++j) {
      double x = 0.0;
      for (const int i : tree.dof_rows[static_cast<size_t>(j)]) x += ws.Phi_q(row, i) * k.J(i, j);
      At_(r, j) = x;
    }
  }
  if (!joint_accelerations(ws, thdd)) return EvalStatus::singular;
  for (size_t f = 0; f < m_.films.size() && ns > 0; ++f) {
    FilmKinematics& fk = ws.films[f];
    if (!fk.sliding) continue;
    // The constraint's force on the journal is −λ r: that is the radial film force.
    fk.force.radial_N = -ws.lambda(ws.slide_row[f]);
    fk.F = fk.force.radial_N * fk.r + fk.force.tangential_N * perp(fk.r);
  }
  return EvalStatus::ok;
}

int MultibodySystem::joint_rhs(double t, const double* y, double* ydot) {
  const int nd = nz_;
  std::copy(y + nd, y + 2 * nd, ydot);
  const EvalStatus s = joint_evaluate(ws_, t, y, ydot + nd, *kin_);
  if (s == EvalStatus::singular) throw std::runtime_error("the joint-coordinate mass matrix is singular");
  return ode_flag(s);
}

EvalStatus MultibodySystem::joint_observation(double t, const double* y, Workspace& ws, double* qdd) {
  const int nq = m_.nq, nd = nz_;
  // A step end's state is the integrator's (kin_, from its root function or expansion);
  // any other is an observer's inside a step (dense_kin_, from its expansion).
  JointKinematics& k = kin_->holds(t, y, y + nd, true) ? *kin_ : *dense_kin_;
  const EvalStatus s = joint_evaluate(ws, t, y, acc_.data(), k);
  if (s != EvalStatus::ok) return s;
  // q̈ = J θ̈ + c
  for (int i = 0; i < nq; ++i) qdd[i] = k.c(i);
  for (int j = 0; j < nd; ++j) {
    const double* Jj = k.J.data() + static_cast<long>(j) * nq;
    for (const int i : tree_->dof_rows[static_cast<size_t>(j)]) qdd[i] += Jj[i] * acc_[static_cast<size_t>(j)];
  }
  return EvalStatus::ok;
}

int MultibodySystem::rhs(double t, const double* y, double* ydot) {
  const int nq = m_.nq;
  if (form_ == Formulation::joint) return joint_rhs(t, y, ydot);
  if (form_ != Formulation::partitioned) {
    std::copy(y + nq, y + 2 * nq, ydot);
    const EvalStatus s = evaluate(m_, ws_, stab_, t, y, y + nq, ydot + nq);
    if (s == EvalStatus::singular) throw std::runtime_error("the constraint matrix Phi_q M^-1 Phi_q^T is singular");
    return ode_flag(s);
  }
  if (expand(t, y, scratch_.data()) != 0) return 1;
  const EvalStatus s = evaluate(m_, ws_, stab_, t, scratch_.data(), scratch_.data() + nq, acc_.data());
  if (s == EvalStatus::singular) throw std::runtime_error("the constraint matrix Phi_q M^-1 Phi_q^T is singular");
  if (s != EvalStatus::ok) return ode_flag(s);
  const int nd = static_cast<int>(ind_.size());
  for (int i = 0; i < nd; ++i) {
    ydot[i] = y[nd + i];
    ydot[nd + i] = acc_[ind_[i]];
  }
  return 0;
}

int MultibodySystem::quadrature_rhs(double t, const double* y, double* qdot) {
  const int nq = m_.nq;
  if (expand(t, y, scratch_.data()) != 0) return 1;
  if (const EvalStatus s = evaluate(m_, ws_, stab_, t, scratch_.data(), scratch_.data() + nq, acc_.data());
      s != EvalStatus::ok)
    return ode_flag(s);
  qdot[0] = driver_power(m_, ws_, scratch_.data() + nq);
  qdot[1] = film_power(ws_);
  return 0;
}

int MultibodySystem::project(double t, const double* y, double* corr, double* err) {
  if (form_ != Formulation::baumgarte) return -1;
  std::copy(y, y + 2 * m_.nq, scratch_.begin());
  return project_state(m_, ws_, t, scratch_.data(), scratch_.data() + m_.nq, corr, corr + m_.nq,
                       projection_tol_, err);
}

int MultibodySystem::num_algebraic() const {
  return form_ == Formulation::ggl ? 2 * (m_.nc + m_.n_switching) : 0;
}

int MultibodySystem::residual(double t, const double* Y, const double* Yp, double* F) {
  const int nq = m_.nq, na = m_.nc + m_.n_switching;
  const double* q = Y;
  const double* v = Y + nq;
  const double* lam = Y + 2 * nq;
  const double* mu = lam + na;
  // g, Φ, Φ_q and Φ̇ at (q, v), with the sliding rows of sliding films: no solve.
  if (const EvalStatus s = evaluate_forces(m_, ws_, t, q, v); s != EvalStatus::ok) return ode_flag(s);
  for (int i = 0; i < nq; ++i) {
    F[i] = Yp[i] - v[i];
    F[nq + i] = m_.mass_diag(i) * Yp[nq + i] - ws_.g(i);
  }
  double* F_lam = F + 2 * nq;
  double* F_mu = F_lam + na;
  // A slot without an active row (a switching film not sliding): λ = μ = 0.
  std::copy(lam, lam + na, F_lam);
  std::copy(mu, mu + na, F_mu);
  auto add_row = [&](int row, int s) {
    for (int i = 0; i < nq; ++i) {
      const double a = ws_.Phi_q(row, i);
      F[i] += a * mu[s];
      F[nq + i] += a * lam[s];
    }
    F_lam[s] = ws_.Phi(row);
    F_mu[s] = ws_.Phi_dot(row);
  };
  for (int row = 0; row < m_.nc; ++row) add_row(row, row);
  for (size_t k = 0; k < m_.films.size(); ++k)
    if (ws_.film_mode[k] == FilmMode::sliding) add_row(ws_.slide_row[k], slot_of_switching_[k]);
  return 0;
}

int MultibodySystem::consistent_state(double t, const double* y, double* Y, double* Yp) {
  const int nq = m_.nq, na = m_.nc + m_.n_switching;
  std::copy(y, y + 2 * nq, Y);
  const EvalStatus s = evaluate(m_, ws_, stab_, t, y, y + nq, acc_.data());
  if (s == EvalStatus::singular) throw std::runtime_error("the constraint matrix Phi_q M^-1 Phi_q^T is singular");
  if (s != EvalStatus::ok) return ode_flag(s);
  // On the constraint manifold the index-1 multipliers are the DAE's; μ = 0.
  std::fill(Y + 2 * nq, Y + 2 * nq + 2 * na, 0.0);
  for (int row = 0; row < m_.nc; ++row) Y[2 * nq + row] = ws_.lambda(row);
  for (size_t k = 0; k < m_.films.size(); ++k)
    if (ws_.film_mode[k] == FilmMode::sliding) Y[2 * nq + slot_of_switching_[k]] = ws_.lambda(ws_.slide_row[k]);
  std::copy(y + nq, y + 2 * nq, Yp);
  std::copy(acc_.begin(), acc_.end(), Yp + nq);
  std::fill(Yp + 2 * nq, Yp + 2 * nq + 2 * na, 0.0);
  return 0;
}

void MultibodySystem::algebraic_tolerances(double /*rtol*/, double /*atol*/, double* out) const {
  const int na = m_.nc + m_.n_switching;
  // The multipliers carry round-off amplified by 1/h (index 2: λ ~ M Φ̇/h, μ ~ Φ/h), so a
  // Newton test on them fails at small steps although (q, v) have converged. Their
  // accuracy shows in (q, v) — M v' = g − Φ_qᵀλ, q' = v − Φ_qᵀμ — which IDA tests; the
  // multipliers themselves are left out of the test by a weight of 1e-20.
  std::fill(out, out + 2 * na, 1e20);
}

}  // namespace lub
