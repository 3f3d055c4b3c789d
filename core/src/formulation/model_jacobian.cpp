// The pieces of the structured Jacobian that need the model's internals: derivatives of
// the film elements' generalised forces and of the constraints' γ with respect to the
// state (see MultibodySystem::jacobian for how they are assembled, and what is neglected).
// Kept apart from model.cpp: evaluate() is not touched.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "common/central_difference.hpp"
#include "lub/formulation/model_jacobian.hpp"
#include "lub/mechanism/film_element.hpp"
#include "lub/mechanism/model.hpp"

namespace lub {

namespace {

using Eigen::Vector2d;

// What film element k adds to g at (q, v), as evaluate() adds it: out[0..2] on the bearing
// body (x, y, φ), out[3..5] on the journal body. False outside the model's domain.
bool film_generalised_force(const Model& m, Workspace& ws, int k, const double* q, const double* v,
                            SlidingRadial sliding, double out[6]) {
  const FilmElement& f = m.films[k];
  // Sliding: the radial force is the sliding row's multiplier −λ_s, held at its value
  // at the state of the last evaluate(): differentiating F = −λ_s r(q) at fixed λ_s gives
  // the row's geometric stiffness −∂(Φ_s,qᵀ λ_s)/∂q, which is not small (λ_s/|e|, with
  // |e| ~ the clearance as radius of curvature) and which a = M⁻¹(g − Φ_qᵀλ) needs.
  // In the GGL DAE (SlidingRadial::in_constraint) the radial force is not in g but in
  // Φ_qᵀλ with the DAE's multiplier, as in evaluate() before its solve: zero here.
  const double sliding_radial_N = ws.film_mode[k] == FilmMode::sliding && sliding == SlidingRadial::held_multiplier
                                      ? -ws.lambda(ws.slide_row[k])
                                      : 0.0;
  FilmKinematics fk;
  return film_element_load(m, ws, k, body_state(f.bearing, q, v), body_state(f.journal, q, v), sliding_radial_N,
                           &ws.counters.film_jacobian, fk, out);
}

// Position step of the film elements' difference quotients [m]: u^(1/3) of the distance to
// the wall, (1 − ε) c (floored at 1e-4 c), the length over which the force changes:
// truncation ~ (h/d)² and round-off ~ u d/h balance at ~ u^(2/3) ≈ 4e-11 relative,
// uniformly up to the wall.
double film_position_step(const FilmKinematics& fk, double c) {
  return std::cbrt(DBL_EPSILON) * c * std::max(std::abs(1.0 - fk.state.eps), 1e-4);
}

// Velocity step of the film elements' difference quotients [m/s]. The force laws are
// positively homogeneous of degree 1 in the film's velocities (ε̇, ε w/2): linear for the
// smooth laws, not differentiable at zero for the printed law (q = hypot(ε w/2, ε̇), Eq. 14)
// and the cavitated ones. A derivative is therefore smooth on the scale of those velocities
// themselves, c |(ε̇, ε w/2)|, and the step is u^(1/3) of it. A step scaled with the shafts'
// speeds instead (as first written) straddles the cone where a journal creeps (50 rpm,
// ε̇ ~ 1e-5 1/s while w crosses zero): the partitioned Jacobian's Newton iteration then
// stalled on the full factorial's 50 rpm printed-law cases. The floor, 1e-3 c at the
// shafts' speeds, keeps the step clear of the round-off in ė (a difference of the bodies'
// velocities): with 1e-6 c there, IDA's GGL iteration matrix for the printed law at rtol
// 1e-12 failed (IdaGgl.PrintedLawAtTightToleranceDoesNotStall).
double film_velocity_step(const FilmKinematics& fk, double c, double shaft_rates) {
  const double film = c * std::hypot(fk.state.eps_dot, 0.5 * fk.state.eps * fk.state.wedge);
  return std::cbrt(DBL_EPSILON) * std::max(film, 1e-3 * c * (1.0 + shaft_rates));
}

// Φ̈ + 2α Φ̇ + β² Φ of the sliding row of film k at (q, v, q̈ = a): Φ = |e| − e_s,
// Φ̇ = r·ė, Φ̈ = r·ë + |ė⊥|²/|e|.
double sliding_row_residual(const Model& m, const Workspace& ws, const Stabilisation& stab, int k, const double* q,
                            const double* v, const double* a) {
  const FilmElement& f = m.films[k];
  Vector2d e(0, 0), ed(0, 0), edd(0, 0);
  const int bodies[2] = {f.bearing, f.journal};
  const Vector2d* points[2] = {&f.s_bearing, &f.s_journal};
  for (int side = 0; side < 2; ++side) {
    const int b = bodies[side];
    if (b == kGround) continue;
    const double sign = side == 0 ? -1.0 : 1.0;
    const int o = 3 * b;
    const Vector2d s = rot(q[o + 2], *points[side]);
    e += sign * (Vector2d(q[o], q[o + 1]) + s);
    ed += sign * (Vector2d(v[o], v[o + 1]) + v[o + 2] * perp(s));
    edd += sign * (Vector2d(a[o], a[o + 1]) + a[o + 2] * perp(s) - v[o + 2] * v[o + 2] * s);
  }
  const double en = e.norm();
  const Vector2d r = e / en;
  const double erd = r.dot(ed);
  const double Phidd = r.dot(edd) + (ed.squaredNorm() - erd * erd) / en;
  return Phidd + 2.0 * stab.alpha * erd + stab.beta * stab.beta * (en - ws.slide_radius[k]);
}

}  // namespace

void sliding_rows_position_jacobian(const Model& m, const Workspace& ws, const Stabilisation& stab, double* q,
                                    const double* v, const double* a, Eigen::Ref<Eigen::MatrixXd> D) {
  const double delta = std::cbrt(DBL_EPSILON);
  for (int k = 0; k < static_cast<int>(m.films.size()); ++k) {
    if (ws.film_mode[k] != FilmMode::sliding) continue;
    const FilmElement& f = m.films[k];
    const int row = ws.slide_row[k];
    D.row(row).setZero();
    const double h_pos = delta * f.clearance;
    const int bodies[2] = {f.bearing, f.journal};
    const double arms[2] = {std::max(f.s_bearing.norm(), f.clearance), std::max(f.s_journal.norm(), f.clearance)};
    for (int side = 0; side < 2; ++side) {
      const int b = bodies[side];
      if (b == kGround) continue;
      for (int dof = 0; dof < 3; ++dof) {
        const int col = 3 * b + dof;
        const double h = dof == 2 ? h_pos / arms[side] : h_pos;
        double fp = 0.0, fm = 0.0;
        const double span = detail::central_difference(q, col, h, [&](int sign) {
          (sign > 0 ? fp : fm) = sliding_row_residual(m, ws, stab, k, q, v, a);
          return true;
        });
        D(row, col) = (fp - fm) / span;
      }
    }
  }
}

int add_film_force_jacobian(const Model& m, Workspace& ws, double* q, double* v, Eigen::Ref<Eigen::MatrixXd> Gq,
                            Eigen::Ref<Eigen::MatrixXd> Gv, SlidingRadial sliding) {
  // Central differences, steps film_position_step and film_velocity_step.
  for (int k = 0; k < static_cast<int>(m.films.size()); ++k) {
    const FilmElement& f = m.films[k];
    const double contact_N = ws.contact_N[k];  // film_element_force writes it: restore
    const FilmKinematics fk = film_kinematics(m, k, q, v);
    const double c = f.clearance;
    const double h_pos = film_position_step(fk, c);
    const double h_vel = film_velocity_step(fk, c, std::abs(rate(f.bearing, v)) + std::abs(rate(f.journal, v)));
    const int bodies[2] = {f.bearing, f.journal};
    const double arms[2] = {std::max(f.s_bearing.norm(), c), std::max(f.s_journal.norm(), c)};
    double plus[6], minus[6];
    for (int side = 0; side < 2; ++side) {
      const int b = bodies[side];
      if (b == kGround) continue;
      for (int dof = 0; dof < 3; ++dof) {
        const int col = 3 * b + dof;
        for (int which = 0; which < 2; ++which) {  // 0: ∂/∂q, 1: ∂/∂v
          double* x = which == 0 ? q : v;
          double h = which == 0 ? h_pos : h_vel;
          if (dof == 2) h /= arms[side];  // a rotation moves the point by |s| δφ
          const double span = detail::central_difference(x, col, h, [&](int sign) {
            return film_generalised_force(m, ws, k, q, v, sliding, sign > 0 ? plus : minus);
          });
          if (span == 0.0) {
            ws.contact_N[k] = contact_N;
            return 1;
          }
          Eigen::Ref<Eigen::MatrixXd>& G = which == 0 ? Gq : Gv;
          for (int s2 = 0; s2 < 2; ++s2) {
            if (bodies[s2] == kGround) continue;
            for (int r = 0; r < 3; ++r) G(3 * bodies[s2] + r, col) += (plus[3 * s2 + r] - minus[3 * s2 + r]) / span;
          }
        }
      }
    }
    ws.contact_N[k] = contact_N;
  }
  return 0;
}

int add_film_force_directional(const Model& m, Workspace& ws, double* q, double* v, int n_dir, const double* dq,
                               const double* dv, double* out) {
  const int nq = m.nq;
  for (int k = 0; k < static_cast<int>(m.films.size()); ++k) {
    const FilmElement& f = m.films[k];
    const int bodies[2] = {f.bearing, f.journal};
    const Vector2d* points[2] = {&f.s_bearing, &f.s_journal};
    const FilmKinematics fk = film_kinematics(m, k, q, v);
    const double c = f.clearance;
    const double h_pos = film_position_step(fk, c);
    const double h_vel = film_velocity_step(fk, c, std::abs(rate(f.bearing, v)) + std::abs(rate(f.journal, v)));
    const double contact_N = ws.contact_N[k];
    double saved[12] = {};
    for (int side = 0; side < 2; ++side) {
      const int b = bodies[side];
      if (b == kGround) continue;
      for (int i = 0; i < 3; ++i) saved[6 * side + i] = q[3 * b + i], saved[6 * side + 3 + i] = v[3 * b + i];
    }
    for (int d = 0; d < n_dir; ++d) {
      const double* dqd = dq ? dq + static_cast<size_t>(d) * nq : nullptr;
      const double* dvd = dv ? dv + static_cast<size_t>(d) * nq : nullptr;
      // How far the direction moves the journal in its bearing per unit step: δe from δq
      // (translations and the points' rotations), δė from δv (its leading part).
      Vector2d de(0, 0), ded(0, 0);
      for (int side = 0; side < 2; ++side) {
        const int b = bodies[side];
        if (b == kGround) continue;
        const double sign = side == 0 ? -1.0 : 1.0;
        const Vector2d s = perp(rot(angle(b, q), *points[side]));
        const int o = 3 * b;
        if (dqd) de += sign * (Vector2d(dqd[o], dqd[o + 1]) + dqd[o + 2] * s);
        if (dvd) ded += sign * (Vector2d(dvd[o], dvd[o + 1]) + dvd[o + 2] * s);
      }
      const double nde = de.norm(), nded = ded.norm();
      if (nde == 0.0 && nded == 0.0) continue;  // the direction does not move this film
      double h = std::numeric_limits<double>::infinity();
      if (nde > 0.0) h = h_pos / nde;
      if (nded > 0.0) h = std::min(h, h_vel / nded);
      // Perturb the film's bodies only (film_element_load reads nothing else); restore exactly.
      double plus[6], minus[6];
      bool ok = true;
      for (int pass = 0; pass < 2 && ok; ++pass) {
        const double step = pass == 0 ? h : -h;
        for (int side = 0; side < 2; ++side) {
          const int b = bodies[side];
          if (b == kGround) continue;
          for (int i = 0; i < 3; ++i) {
            const int o = 3 * b + i;
            if (dqd) q[o] = saved[6 * side + i] + step * dqd[o];
            if (dvd) v[o] = saved[6 * side + 3 + i] + step * dvd[o];
          }
        }
        ok = film_generalised_force(m, ws, k, q, v, SlidingRadial::held_multiplier, pass == 0 ? plus : minus);
      }
      for (int side = 0; side < 2; ++side) {
        const int b = bodies[side];
        if (b == kGround) continue;
        for (int i = 0; i < 3; ++i) q[3 * b + i] = saved[6 * side + i], v[3 * b + i] = saved[6 * side + 3 + i];
      }
      if (!ok) {
        ws.contact_N[k] = contact_N;
        return 1;
      }
      double* o = out + static_cast<size_t>(d) * nq;
      for (int side = 0; side < 2; ++side) {
        if (bodies[side] == kGround) continue;
        for (int r = 0; r < 3; ++r) o[3 * bodies[side] + r] += (plus[3 * side + r] - minus[3 * side + r]) / (2.0 * h);
      }
    }
    ws.contact_N[k] = contact_N;
  }
  return 0;
}

void constraint_gamma_velocity_jacobian(const Model& m, const Workspace& ws, const double* q, const double* v,
                                        Eigen::Ref<Eigen::MatrixXd> G) {
  G.setZero();
  for (const Constraint& c : m.constraints) {
    const int row = c.row;
    const int bi = c.body_i, bj = c.body_j;
    switch (c.kind) {
      case Constraint::Kind::revolute: {
        // γ = φ̇_i² a_i − φ̇_j² a_j
        if (bi != kGround) G.block<2, 1>(row, 3 * bi + 2) = 2.0 * rate(bi, v) * rot(angle(bi, q), c.s_i);
        if (bj != kGround) G.block<2, 1>(row, 3 * bj + 2) = -2.0 * rate(bj, v) * rot(angle(bj, q), c.s_j);
        break;
      }
      case Constraint::Kind::translational: {
        // γ(row + 1) = φ̇_i² n·d − 2 φ̇_i n⊥·ḋ + φ̇_j² n·a_j − φ̇_i² n·a_i,
        // ḋ = ṙ_j + φ̇_j a_j⊥ − ṙ_i − φ̇_i a_i⊥ (row: γ = 0)
        const double pi = angle(bi, q), pj = angle(bj, q), wi = rate(bi, v), wj = rate(bj, v);
        const Vector2d ai = rot(pi, c.s_i), aj = rot(pj, c.s_j);
        const Vector2d n = rot(pi, c.n_i), pn = perp(n);
        const Vector2d ri = bi == kGround ? Vector2d(0, 0) : Vector2d(q[3 * bi], q[3 * bi + 1]);
        const Vector2d rj = bj == kGround ? Vector2d(0, 0) : Vector2d(q[3 * bj], q[3 * bj + 1]);
        const Vector2d rdi = bi == kGround ? Vector2d(0, 0) : Vector2d(v[3 * bi], v[3 * bi + 1]);
        const Vector2d rdj = bj == kGround ? Vector2d(0, 0) : Vector2d(v[3 * bj], v[3 * bj + 1]);
        const Vector2d d = rj + aj - ri - ai;
        const Vector2d dd = rdj + wj * perp(aj) - rdi - wi * perp(ai);
        const int r1 = row + 1;
        if (bj != kGround) {
          G(r1, 3 * bj) = -2.0 * wi * pn.x();
          G(r1, 3 * bj + 1) = -2.0 * wi * pn.y();
          G(r1, 3 * bj + 2) = -2.0 * wi * pn.dot(perp(aj)) + 2.0 * wj * n.dot(aj);
        }
        if (bi != kGround) {
          G(r1, 3 * bi) = 2.0 * wi * pn.x();
          G(r1, 3 * bi + 1) = 2.0 * wi * pn.y();
          G(r1, 3 * bi + 2) =
              2.0 * wi * n.dot(d) - 2.0 * pn.dot(dd) + 2.0 * wi * pn.dot(perp(ai)) - 2.0 * wi * n.dot(ai);
        }
        break;
      }
      case Constraint::Kind::ground:
      case Constraint::Kind::driver:
        break;  // γ does not depend on v
    }
  }
  // Sliding rows: γ = r·(φ̇_j² a_j − φ̇_i² a_i) − |ė⊥|²/|e|, ė⊥ = ė − (r·ė) r.
  for (size_t k = 0; k < m.films.size(); ++k) {
    if (ws.film_mode[k] != FilmMode::sliding) continue;
    const FilmElement& f = m.films[k];
    const int row = ws.slide_row[k];
    const FilmKinematics fk = film_kinematics(m, static_cast<int>(k), q, v);
    const double e = fk.e.norm();
    const Vector2d ed_perp = fk.e_dot - fk.r.dot(fk.e_dot) * fk.r;
    const Vector2d dgde = -2.0 * ed_perp / e;  // ∂γ/∂ė
    const Vector2d ai = rot(angle(f.bearing, q), f.s_bearing), aj = rot(angle(f.journal, q), f.s_journal);
    if (f.journal != kGround) {
      const int o = 3 * f.journal;
      G(row, o) = dgde.x();
      G(row, o + 1) = dgde.y();
      G(row, o + 2) = 2.0 * rate(f.journal, v) * fk.r.dot(aj) + dgde.dot(perp(aj));
    }
    if (f.bearing != kGround) {
      const int o = 3 * f.bearing;
      G(row, o) = -dgde.x();
      G(row, o + 1) = -dgde.y();
      G(row, o + 2) = -2.0 * rate(f.bearing, v) * fk.r.dot(ai) - dgde.dot(perp(ai));
    }
  }
}

}  // namespace lub
