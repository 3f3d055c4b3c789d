#include "lub/mechanism/model.hpp"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/small_dense.hpp"
#include "lub/common/check.hpp"
#include "lub/mechanism/film_element.hpp"
#include "mechanism/constraints.hpp"

namespace lub {

using detail::fill_constraints;

namespace {

using Eigen::Vector2d;

}  // namespace

Workspace::Workspace(const Model& m)
    : Phi_q(Eigen::MatrixXd::Zero(m.nc + m.n_switching, m.nq)),
      Phi(Eigen::VectorXd::Zero(m.nc + m.n_switching)),
      Phi_dot(Eigen::VectorXd::Zero(m.nc + m.n_switching)),
      gamma(Eigen::VectorXd::Zero(m.nc + m.n_switching)),
      g(Eigen::VectorXd::Zero(m.nq)),
      rhs(Eigen::VectorXd::Zero(m.nc + m.n_switching)),
      lambda(Eigen::VectorXd::Zero(m.nc + m.n_switching)),
      qdd(Eigen::VectorXd::Zero(m.nq)),
      S(Eigen::MatrixXd::Zero(m.nc + m.n_switching, m.nc + m.n_switching)),
      row_bodies(static_cast<size_t>(m.nc + m.n_switching), {kGround, kGround}),
      cos_phi(static_cast<size_t>(m.nb), 1.0),
      sin_phi(static_cast<size_t>(m.nb), 0.0),
      trig_phi(static_cast<size_t>(m.nb), std::numeric_limits<double>::quiet_NaN()),
      films(m.films.size()),
      film_mode(m.films.size(), FilmMode::natural),
      slide_radius(m.films.size(), 0.0),
      slide_row(m.films.size(), -1),
      nc_active(m.nc),
      film_solvers(m.films.size()),
      contact_N(m.films.size(), 0.0) {
  for (size_t k = 0; k < m.films.size(); ++k) {
    if (m.films[k].switching) film_mode[k] = FilmMode::outward;  // ε̇ >= 0 at a centred start
    if (m.films[k].law == ForceLaw::finite_reynolds) film_solvers[k].emplace(m.films[k].finite);
  }
  for (const Constraint& c : m.constraints)
    for (int r = c.row; r < c.row + c.rows; ++r)
      row_bodies[r] = {c.body_i, c.body_j == c.body_i ? kGround : c.body_j};
  for (int r = 0; r < m.nc; ++r)
    for (int s = 0; s <= r; ++s)
      for (const int b : row_bodies[r])
        if (b != kGround && (b == row_bodies[s][0] || b == row_bodies[s][1])) schur_pairs.push_back({r, s, b});
}

void Workspace::reset(const Model& m) {
  check_workspace(m, *this);
  for (Eigen::VectorXd* x : {&Phi, &Phi_dot, &gamma, &g, &rhs, &lambda, &qdd}) x->setZero();
  Phi_q.setZero();
  S.setZero();
  std::fill(cos_phi.begin(), cos_phi.end(), 1.0);
  std::fill(sin_phi.begin(), sin_phi.end(), 0.0);
  std::fill(trig_phi.begin(), trig_phi.end(), std::numeric_limits<double>::quiet_NaN());
  std::fill(films.begin(), films.end(), FilmKinematics{});
  counters = EvalCounters{};
  std::fill(slide_radius.begin(), slide_radius.end(), 0.0);
  std::fill(slide_row.begin(), slide_row.end(), -1);
  nc_active = m.nc;
  std::fill(contact_N.begin(), contact_N.end(), 0.0);
  for (size_t k = 0; k < m.films.size(); ++k) {
    film_mode[k] = m.films[k].switching ? FilmMode::outward : FilmMode::natural;
    if (m.films[k].law == ForceLaw::finite_reynolds) film_solvers[k].emplace(m.films[k].finite);
  }
}

namespace {
// Adds a body's share of a film element's generalised force (x, y, φ) to g.
inline void add_body_load(Eigen::VectorXd& g, int b, const double* load) {
  if (b == kGround) return;
  g(3 * b) += load[0];
  g(3 * b + 1) += load[1];
  g(3 * b + 2) += load[2];
}
}  // namespace

namespace {
// Sliding on ε̇ = 0 (ws.cos_phi, sin_phi at q): the row Φ = |e| − e_s (e_s the |e| held since the switch), with
// Φ̇ = r·ė and γ = r·(φ̇_j² a_j − φ̇_i² a_i) − |ė⊥|²/|e|.
void fill_sliding_rows(const Model& m, Workspace& ws, const double* q, const double* v) {
  for (size_t k = 0; k < m.films.size(); ++k) {
    const FilmKinematics& fk = ws.films[k];
    if (!fk.sliding) continue;
    const FilmElement& f = m.films[k];
    const int row = ws.slide_row[k];
    const BodyState bi = body_state(f.bearing, q, v, ws.cos_phi.data(), ws.sin_phi.data());
    const BodyState bj = body_state(f.journal, q, v, ws.cos_phi.data(), ws.sin_phi.data());
    const Vector2d ai = bi.rot(f.s_bearing), aj = bj.rot(f.s_journal);
    const double e = fk.e.norm();
    const double erd = fk.r.dot(fk.e_dot);
    const Vector2d ed_perp = fk.e_dot - erd * fk.r;
    ws.Phi(row) = e - ws.slide_radius[k];
    ws.Phi_dot(row) = erd;
    ws.gamma(row) = fk.r.dot(bj.phid * bj.phid * aj - bi.phid * bi.phid * ai) - ed_perp.squaredNorm() / e;
    if (f.journal != kGround) {
      const int o = 3 * f.journal;
      ws.Phi_q(row, o) = fk.r.x();
      ws.Phi_q(row, o + 1) = fk.r.y();
      ws.Phi_q(row, o + 2) = fk.r.dot(perp(aj));
    }
    if (f.bearing != kGround) {
      const int o = 3 * f.bearing;
      ws.Phi_q(row, o) = -fk.r.x();
      ws.Phi_q(row, o + 1) = -fk.r.y();
      ws.Phi_q(row, o + 2) = -fk.r.dot(perp(ai));
    }
  }
}
}  // namespace

namespace {
// The rows of Φ_q are sparse (a constraint block touches at most two bodies, see
// Workspace::row_bodies): the products below visit those columns only. Raw column-major
// access (leading dimension ld): these loops are most of an evaluation's arithmetic.

// Φ_q,r · x.
inline double row_dot(const Workspace& ws, int r, const double* x) {
  const double* J = ws.Phi_q.data();
  const long ld = ws.Phi_q.rows();
  double s = 0.0;
  for (const int b : ws.row_bodies[r]) {
    if (b == kGround) continue;
    for (int i = 3 * b; i < 3 * b + 3; ++i) s += J[i * ld + r] * x[i];
  }
  return s;
}

// x −= Φ_qᵀ λ over the first nc rows.
inline void subtract_transpose(const Workspace& ws, int nc, const double* lambda, double* x) {
  const double* J = ws.Phi_q.data();
  const long ld = ws.Phi_q.rows();
  for (int r = 0; r < nc; ++r) {
    const double l = lambda[r];
    for (const int b : ws.row_bodies[r]) {
      if (b == kGround) continue;
      const double* Jr = J + 3 * b * ld + r;
      double* xb = x + 3 * b;
      xb[0] -= Jr[0] * l;
      xb[1] -= Jr[ld] * l;
      xb[2] -= Jr[2 * ld] * l;
    }
  }
}

// S = Φ_q M⁻¹ Φ_qᵀ over the first nc rows into ws.S (lower triangle), factored in place
// (Cholesky). Rows r and s couple only through a body both touch. False if S is not
// positive definite (redundant or singular constraints).
bool factor_schur(const Model& m, Workspace& ws, int nc) {
  const double* w = m.inv_mass_diag.data();
  const double* J = ws.Phi_q.data();
  const long ld = ws.Phi_q.rows();
  const std::array<int, 2>* rb = ws.row_bodies.data();
  double* S = ws.S.data();
  const long lds = ws.S.rows();
  std::fill(S, S + lds * nc, 0.0);
  for (const auto& [r, s, b] : ws.schur_pairs) {
    const double* Jr = J + 3 * b * ld + r;
    const double* Js = J + 3 * b * ld + s;
    const double* wb = w + 3 * b;
    double sum = Jr[0] * wb[0] * Js[0];
    sum += Jr[ld] * wb[1] * Js[ld];
    sum += Jr[2 * ld] * wb[2] * Js[2 * ld];
    S[s * lds + r] += sum;
  }
  // The sliding rows change with the films' modes: found on the fly.
  for (int r = m.nc; r < nc; ++r) {
    for (int s = 0; s <= r; ++s) {
      double sum = 0.0;
      for (const int b : rb[r]) {
        if (b == kGround || (b != rb[s][0] && b != rb[s][1])) continue;
        for (int i = 3 * b; i < 3 * b + 3; ++i) sum += J[i * ld + r] * w[i] * J[i * ld + s];
      }
      S[s * lds + r] = sum;
    }
  }
  return dense::cholesky(S, static_cast<int>(lds), nc);
}
}  // namespace

void check_workspace(const Model& m, const Workspace& ws) {
  const long rows = m.nc + m.n_switching;
  LUB_ASSERT(ws.g.size() == m.nq && ws.qdd.size() == m.nq, "workspace built for a model of another size");
  LUB_ASSERT(ws.Phi_q.rows() == rows && ws.Phi_q.cols() == m.nq && ws.Phi.size() == rows,
             "workspace built for a model with other constraints");
  LUB_ASSERT(ws.films.size() == m.films.size() && ws.film_mode.size() == m.films.size(),
             "workspace built for a model with other film elements");
}

EvalStatus evaluate_forces(const Model& m, Workspace& ws, double t, const double* q, const double* v,
                           bool constraint_rows) {
  check_workspace(m, ws);
  ++ws.counters.rhs;
  const double* cphi = ws.cos_phi.data();
  const double* sphi = ws.sin_phi.data();
  body_trig(m.nb, q, ws.cos_phi.data(), ws.sin_phi.data(), ws.trig_phi.data());
  ws.g.setZero();
  if (m.gravity) {
    ++ws.counters.gravity;
    for (int b = 0; b < m.nb; ++b) {
      ws.g(3 * b) += m.mass_diag(3 * b) * m.gravity->x();
      ws.g(3 * b + 1) += m.mass_diag(3 * b) * m.gravity->y();
    }
  }
  int n_sliding = 0;
  for (size_t k = 0; k < m.films.size(); ++k) {
    const FilmElement& f = m.films[k];
    FilmKinematics& fk = ws.films[k];
    // A sliding film's radial force is the sliding constraint's multiplier, after the solve.
    double load[6];
    if (!film_element_load(m, ws, static_cast<int>(k), body_state(f.bearing, q, v, cphi, sphi),
                           body_state(f.journal, q, v, cphi, sphi), 0.0, &ws.counters.film, fk, load))
      return EvalStatus::outside_domain;
    fk.sliding = ws.film_mode[k] == FilmMode::sliding;
    if (fk.sliding) {
      ws.slide_row[k] = m.nc + n_sliding++;
      ws.row_bodies[ws.slide_row[k]] = {f.bearing, f.journal};
    }
    add_body_load(ws.g, f.journal, load + 3);
    add_body_load(ws.g, f.bearing, load);
  }
  ws.nc_active = m.nc + n_sliding;
  if (ws.nc_active == 0) return EvalStatus::ok;
  if (constraint_rows)
    fill_constraints(m.constraints, t, q, v, cphi, sphi, ws.Phi_q, ws.Phi, ws.Phi_dot, &ws.gamma);
  else if (n_sliding > 0)
    ws.Phi_q.middleRows(m.nc, n_sliding).setZero();
  if (n_sliding > 0) fill_sliding_rows(m, ws, q, v);
  return EvalStatus::ok;
}

EvalStatus evaluate(const Model& m, Workspace& ws, const Stabilisation& stab, double t, const double* q,
                    const double* v, double* qdd) {
  if (const EvalStatus s = evaluate_forces(m, ws, t, q, v); s != EvalStatus::ok) return s;
  const double* w = m.inv_mass_diag.data();
  const int nc = ws.nc_active;
  if (nc == 0) {
    for (int i = 0; i < m.nq; ++i) qdd[i] = w[i] * ws.g(i);
    return EvalStatus::ok;
  }
  const bool any_sliding = nc > m.nc;
  // (Φ_q M⁻¹ Φ_qᵀ) λ = Φ_q M⁻¹ g − γ̂,  γ̂ = γ − 2α Φ̇ − β² Φ  (qdd holds M⁻¹ g meanwhile)
  for (int i = 0; i < m.nq; ++i) qdd[i] = w[i] * ws.g(i);
  for (int r = 0; r < nc; ++r)
    ws.rhs(r) = row_dot(ws, r, qdd) - stab.stabilised_gamma(ws.gamma(r), ws.Phi_dot(r), ws.Phi(r));
  if (!factor_schur(m, ws, nc)) return EvalStatus::singular;
  ws.lambda.head(nc) = ws.rhs.head(nc);
  dense::cholesky_solve(ws.S.data(), static_cast<int>(ws.S.rows()), nc, ws.lambda.data());
  // q̈ = M⁻¹ (g − Φ_qᵀ λ)
  ws.qdd = ws.g;
  subtract_transpose(ws, nc, ws.lambda.data(), ws.qdd.data());
  for (int i = 0; i < m.nq; ++i) qdd[i] = w[i] * ws.qdd(i);
  if (any_sliding) {
    for (size_t k = 0; k < m.films.size(); ++k) {
      FilmKinematics& fk = ws.films[k];
      if (!fk.sliding) continue;
      // The constraint's force on the journal is −λ r: that is the radial film force.
      fk.force.radial_N = -ws.lambda(ws.slide_row[k]);
      fk.F = fk.force.radial_N * fk.r + fk.force.tangential_N * perp(fk.r);
    }
  }
  return EvalStatus::ok;
}

void constraint_residual(const Model& m, Workspace& ws, double t, const double* q, const double* v) {
  const double* cphi = ws.cos_phi.data();
  const double* sphi = ws.sin_phi.data();
  body_trig(m.nb, q, ws.cos_phi.data(), ws.sin_phi.data(), ws.trig_phi.data());
  fill_constraints(m.constraints, t, q, v, cphi, sphi, ws.Phi_q, ws.Phi, ws.Phi_dot, nullptr);
  int n_sliding = 0;
  for (size_t k = 0; k < m.films.size(); ++k) {
    FilmKinematics& fk = ws.films[k];
    fk.sliding = ws.film_mode[k] == FilmMode::sliding;
    if (!fk.sliding) continue;
    const FilmElement& f = m.films[k];
    Vector2d ai, aj;
    const FilmKinematics kin =
        film_kinematics(f, body_state(f.bearing, q, v, cphi, sphi), body_state(f.journal, q, v, cphi, sphi), ai, aj);
    fk.e = kin.e;
    fk.e_dot = kin.e_dot;
    fk.r = kin.r;
    ws.slide_row[k] = m.nc + n_sliding++;
    ws.row_bodies[ws.slide_row[k]] = {f.bearing, f.journal};
  }
  if (n_sliding > 0) fill_sliding_rows(m, ws, q, v);
  ws.nc_active = m.nc + n_sliding;
}

int project_state(const Model& m, Workspace& ws, double t, double* q, double* v, double* dq, double* dv,
                  double tol, double* err) {
  // M-weighted least corrections: Δ = −M⁻¹ Jᵀ (J M⁻¹ Jᵀ)⁻¹ r, for r = Φ (Newton on the
  // positions) and then r = Φ̇ (one linear step on the velocities). Scratch: ws.rhs (r),
  // ws.qdd (Δ).
  Eigen::Map<Eigen::VectorXd> Q(q, m.nq), V(v, m.nq), DQ(dq, m.nq), DV(dv, m.nq);
  DQ.setZero();
  DV.setZero();
  // ws.qdd = Δ for r = ws.rhs; false if J M⁻¹ Jᵀ is singular.
  auto solve = [&](int nc) {
    if (!factor_schur(m, ws, nc)) return false;
    dense::cholesky_solve(ws.S.data(), static_cast<int>(ws.S.rows()), nc, ws.rhs.data());
    ws.qdd.setZero();
    subtract_transpose(ws, nc, ws.rhs.data(), ws.qdd.data());
    ws.qdd.array() *= m.inv_mass_diag.array();
    return true;
  };
  for (int it = 0; it < 8; ++it) {
    constraint_residual(m, ws, t, q, v);
    const int nc = ws.nc_active;
    if (nc == 0) return 0;
    if (ws.Phi.head(nc).lpNorm<Eigen::Infinity>() <= tol) break;
    ws.rhs.head(nc) = ws.Phi.head(nc);
    if (!solve(nc)) return -1;
    Q += ws.qdd;
    DQ += ws.qdd;
    if (it == 7) return 1;  // did not converge: let the integrator retry smaller
  }
  constraint_residual(m, ws, t, q, v);
  const int nc = ws.nc_active;
  ws.rhs.head(nc) = ws.Phi_dot.head(nc);
  if (!solve(nc)) return -1;
  V += ws.qdd;
  DV = ws.qdd;
  if (err) {
    // The error estimate loses its components normal to the constraint manifold.
    for (double* e : {err, err + m.nq}) {
      for (int r = 0; r < nc; ++r) ws.rhs(r) = row_dot(ws, r, e);
      if (!solve(nc)) return -1;
      Eigen::Map<Eigen::VectorXd>(e, m.nq) += ws.qdd;
    }
  }
  return 0;
}

Eigen::Vector2d joint_force(const Model& m, const Workspace& ws, int joint) {
  if (const int f = m.joint_film[joint]; f >= 0) return ws.films[f].F;
  const int ci = m.joint_constraint[joint];
  if (ci < 0) return {0, 0};
  const Constraint& c = m.constraints[ci];
  // Generalised constraint force on a body: −Φ_qᵀ λ restricted to its (x, y) columns.
  const bool on_j = c.body_j != kGround;
  const int b = on_j ? c.body_j : c.body_i;
  Vector2d F = -ws.Phi_q.block(c.row, 3 * b, c.rows, 2).transpose() * ws.lambda.segment(c.row, c.rows);
  return on_j ? F : Vector2d(-F);
}

Eigen::VectorXd state_scales(const Model& m, double length_m, double rate_rad_s) {
  std::vector<double> size(static_cast<size_t>(m.nb), 0.0);
  auto reach = [&](int body, const Vector2d& s) {
    if (body != kGround) size[static_cast<size_t>(body)] = std::max(size[static_cast<size_t>(body)], s.norm());
  };
  for (const Constraint& c : m.constraints) {
    if (c.kind != Constraint::Kind::revolute && c.kind != Constraint::Kind::translational) continue;
    reach(c.body_i, c.s_i);
    reach(c.body_j, c.s_j);
  }
  for (const FilmElement& f : m.films) {
    reach(f.bearing, f.s_bearing);
    reach(f.journal, f.s_journal);
  }
  Eigen::VectorXd s(2 * m.nq);
  for (int b = 0; b < m.nb; ++b) {
    const double gyration = std::sqrt(m.mass_diag(3 * b + 2) / m.mass_diag(3 * b));
    const double r = std::max(size[static_cast<size_t>(b)], gyration);
    const double angle = r > 0.0 ? length_m / r : length_m;  // a point mass: 1 m
    s.segment<3>(3 * b) << length_m, length_m, angle;
    s.segment<3>(m.nq + 3 * b) = rate_rad_s * s.segment<3>(3 * b);
  }
  return s;
}

double mechanical_energy(const Model& m, const double* q, const double* v) {
  double E = 0.0;
  for (int i = 0; i < m.nq; ++i) E += 0.5 * m.mass_diag(i) * v[i] * v[i];
  if (m.gravity)
    for (int b = 0; b < m.nb; ++b)
      E -= m.mass_diag(3 * b) * (m.gravity->x() * q[3 * b] + m.gravity->y() * q[3 * b + 1]);
  return E;
}

double driver_power(const Model& m, const Workspace& ws, const double* v) {
  double P = 0.0;
  for (const Constraint& c : m.constraints)
    if (c.kind == Constraint::Kind::driver) P += -ws.lambda(c.row) * v[3 * c.body_j + 2];
  return P;
}

double film_power(const Workspace& ws) {
  double P = 0.0;
  for (const FilmKinematics& fk : ws.films) P += fk.F.dot(fk.e_dot) + fk.torque_power_W;
  return P;
}

}  // namespace lub
