// The film element: see lub/mechanism/film_element.hpp.
#include "lub/mechanism/film_element.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lub {

using Eigen::Vector2d;

// Kinematics of film f between bearing body bi and journal body bj; ai, aj: the bearing
// and journal points from their bodies' centres, global.
FilmKinematics film_kinematics(const FilmElement& f, const BodyState& bi, const BodyState& bj, Vector2d& ai,
                               Vector2d& aj) {
  ai = bi.rot(f.s_bearing);
  aj = bj.rot(f.s_journal);
  FilmKinematics k_out;
  k_out.e = bj.r + aj - bi.r - ai;
  k_out.e_dot = bj.rd + bj.phid * perp(aj) - bi.rd - bi.phid * perp(ai);
  const double c = f.clearance;
  const double e = k_out.e.norm();
  if (e > 1e-12 * c) {
    k_out.r = k_out.e / e;
    k_out.state.eps = e / c;
    k_out.state.eps_dot = k_out.r.dot(k_out.e_dot) / c;
    k_out.gamma_dot = cross(k_out.e, k_out.e_dot) / (e * e);
  } else {
    // Centred journal: the line of centres is undefined. Take it along the journal's
    // relative velocity (the direction it is about to move in), so ε̇ = |ė|/c and γ̇ = 0;
    // this is the limit e → 0 along the trajectory, and the Sommerfeld laws reduce to
    // the isotropic squeeze damping −(K/c) ė whatever the choice.
    const double ed = k_out.e_dot.norm();
    k_out.r = ed > 0.0 ? Vector2d(k_out.e_dot / ed) : Vector2d(1.0, 0.0);
    k_out.state.eps = 0.0;
    k_out.state.eps_dot = ed / c;
    k_out.gamma_dot = 0.0;
  }
  k_out.state.wedge = bj.phid + bi.phid - 2.0 * k_out.gamma_dot;
  return k_out;
}

FilmKinematics film_kinematics(const Model& m, int k, const double* q, const double* v) {
  const FilmElement& f = m.films[k];
  Vector2d ai, aj;
  return film_kinematics(f, body_state(f.bearing, q, v), body_state(f.journal, q, v), ai, aj);
}

FilmForce film_element_force(const Model& m, Workspace& ws, int k, const BearingState& state, FilmMode mode,
                             long long* law_calls) {
  const FilmElement& f = m.films[k];
  FiniteBearingSolver* solver = ws.film_solvers[k] ? &*ws.film_solvers[k] : nullptr;
  const auto law = [&](const BearingState& at) {
    if (law_calls) ++*law_calls;
    return film_force(f.law, f.geometry, f.viscosity, at, solver);
  };
  // A switching film held on one branch (outward: ε̇ >= 0, inward: ε̇ < 0) while the state
  // is on the other side of ε̇ = 0: a Newton iterate, a difference quotient or the step
  // that overshoots before the root finder locates the crossing and the run switches. The
  // branch is continued to first order from ε̇ = 0±, F(ε̇) = F(0±) + ε̇ ∂F/∂ε̇(0±): C¹ across
  // ε̇ = 0, so the integrator's Newton iteration and Jacobian see no kink. (Holding F at its
  // ε̇ = 0± value instead left ∂F/∂ε̇ jumping from the squeeze film's damping, huge near
  // the wall, to zero: a slowly sinking journal, ε̇ ~ 1e-5 1/s at 50 rpm, sat on that kink
  // and the corrector failed at h ~ 1e-8 s.) The slope is a one-sided difference over
  // δ = 1e-6 of the state's own ε̇ scale, the larger of |ε w|/2 and |ε̇|.
  const auto continued = [&](const BearingState& at, double side) {
    BearingState at0 = at;
    at0.eps_dot = side > 0 ? 0.0 : -std::numeric_limits<double>::min();
    const double delta = 1e-6 * std::max({0.5 * std::abs(at.eps * at.wedge), std::abs(at.eps_dot), 1e-12});
    BearingState at1 = at;
    at1.eps_dot = side * delta;
    const FilmForce f0 = law(at0), f1 = law(at1);
    const double x = at.eps_dot / (side * delta);  // (ε̇ − 0) / (δ₁ − 0), in units of the step
    FilmForce out;
    out.radial_N = f0.radial_N + x * (f1.radial_N - f0.radial_N);
    out.tangential_N = f0.tangential_N + x * (f1.tangential_N - f0.tangential_N);
    return out;
  };
  const auto film = [&](const BearingState& at) {
    switch (mode) {
      case FilmMode::natural: return law(at);
      case FilmMode::outward: return at.eps_dot >= 0.0 ? law(at) : continued(at, +1.0);
      case FilmMode::inward: return at.eps_dot < 0.0 ? law(at) : continued(at, -1.0);
      case FilmMode::sliding: {
        BearingState at0 = at;
        at0.eps_dot = 0.0;
        return law(at0);
      }
    }
    return law(at);
  };
  // With contact: film weighted over the hand-over band (not evaluated above it) plus the
  // dry-contact force, whose damping sees the true ε̇. With mixed lubrication: plus the
  // asperity load, radial, a function of ε alone.
  FilmForce out = f.contact ? force_with_contact(*f.contact, f.clearance, state, film, &ws.contact_N[k]) : film(state);
  if (f.asperity) out.radial_N -= asperity_load_N(*f.asperity, f.geometry, state.eps);
  return out;
}

FrictionTorques film_element_friction(const FilmElement& f, const FilmKinematics& fk, double omega_journal,
                                      double omega_bearing) {
  FrictionTorques tq;
  const double eps = fk.state.eps;
  if (!(eps < 1.0)) return tq;
  const double sliding = omega_journal - omega_bearing;
  const double weight = f.contact ? film_weight(*f.contact, eps) : 1.0;
  if (weight > 0.0) {
    tq = film_friction_torques(f.geometry, f.viscosity, eps, sliding, fk.force.tangential_N);
    tq.journal_Nm *= weight;
    tq.bearing_Nm *= weight;
  }
  if (f.asperity && f.asperity->boundary_friction > 0.0) {
    constexpr double kOmega0 = 1e-3;  // rad/s: below it the Coulomb sign is regularised
    const double Ta = f.asperity->boundary_friction * asperity_load_N(*f.asperity, f.geometry, eps) *
                      f.geometry.journal_radius_m * sliding / std::hypot(sliding, kOmega0);
    tq.journal_Nm += Ta;
    tq.bearing_Nm += Ta;
  }
  return tq;
}

bool film_element_load(const Model& m, Workspace& ws, int k, const BodyState& bi, const BodyState& bj,
                       double sliding_radial_N, long long* law_calls, FilmKinematics& fk, double load[6]) {
  const FilmElement& f = m.films[k];
  Vector2d ai, aj;
  fk = film_kinematics(f, bi, bj, ai, aj);
  // Journal through the wall: outside the model, unless the contact effect takes over.
  if (!f.contact && !(fk.state.eps < 1.0)) return false;
  fk.force = film_element_force(m, ws, k, fk.state, ws.film_mode[k], law_calls);
  if (ws.film_mode[k] == FilmMode::sliding) fk.force.radial_N = sliding_radial_N;
  const Vector2d t_dir = perp(fk.r);
  fk.F = fk.force.radial_N * fk.r + fk.force.tangential_N * t_dir;
  if (!std::isfinite(fk.F.x()) || !std::isfinite(fk.F.y())) return false;
  load[0] = -fk.F.x();
  load[1] = -fk.F.y();
  load[2] = -cross(ai, fk.F);
  load[3] = fk.F.x();
  load[4] = fk.F.y();
  load[5] = cross(aj, fk.F);
  fk.torque_power_W = 0.0;
  if (f.friction) {
    const FrictionTorques tq = film_element_friction(f, fk, bj.phid, bi.phid);
    if (!std::isfinite(tq.journal_Nm) || !std::isfinite(tq.bearing_Nm)) return false;
    load[2] += tq.bearing_Nm;
    load[5] -= tq.journal_Nm;
    fk.torque_power_W = tq.bearing_Nm * bi.phid - tq.journal_Nm * bj.phid;
  }
  return true;
}

}  // namespace lub
