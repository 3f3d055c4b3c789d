// A hand-written minimal-coordinate model of the paper's slider-crank with a lubricated
// rod–slider joint: two degrees of freedom (rod angle β, slider position x), crank driven
// at θ = ωt, derived by Lagrange's equations on paper. It shares nothing with the engine
// but the force law, so it is both an independent check of the engine's absolute-
// coordinate formulation and the speed floor no general engine can beat.
//
// Crank pin A = a(cos θ, sin θ); rod direction u = (cos β, sin β), u⊥ = (−sin β, cos β);
// rod centre G = A + (l/2) u; journal B = A + l u; bearing centre (slider) P = (x, 0).
// With F the film force on the journal (the slider gets −F):
//   (J_r + m_r l²/4) β̈ = l u⊥·F + (l/2) m_r u⊥·(g − Ä)          (Ä = −aω² (cos θ, sin θ))
//   m_s ẍ = −F_x                                                  (guide frictionless)
// The mass matrix is diagonal because the only coupling is the film force.
//
// The printed Pinkus–Sternlicht law (pinkus_sternlicht) jumps at ε̇ = 0: its radial force
// changes sign. The floor then integrates it as a Filippov system, the engine's model
// (README "Discontinuous force laws") written again here on its own: a mode per branch
// (outward: the ε̇ >= 0 formula, inward: the ε̇ < 0 one), CVODE's root finder on ε̇ = 0,
// and a restart there on the branch the state moves to, or on a sliding motion along
// ε̇ = 0 when the radial force that keeps |e| constant lies within the jump. Sliding: the
// radial force is that multiplier λ, from the second derivative of |e| (Baumgarte-
// stabilised, α below), the tangential force the law's at ε̇ = 0; it ends where λ leaves
// [F_r(0⁺), F_r(0⁻)]. Across ε̇ = 0 inside a step (a Newton iterate, or the step that
// overshoots the root) the branch is continued to first order from ε̇ = 0±, as the engine
// does, so that the corrector sees no kink; the restart at the root discards that side.
#pragma once

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "lub/bearing/film_force.hpp"

namespace floor_model {

struct Params {
  double a = 0.05, l = 0.12, mr = 0.21, Jr = 2.5e-4, ms = 0.14, g = 9.81;
  double omega = 5000.0 * 2 * M_PI / 60;
  lub::BearingGeometry geom{0.0095, 0.0100, 0.040};
  double mu = 0.4;
  lub::ForceLaw law = lub::ForceLaw::frene_long;
  /// Absolute tolerances: false, rtol × c for every state (as first written); true, each
  /// state in its own unit, as the engine does: x in c, β in c/l, ẋ in c ω, β̇ in c ω/l.
  bool atol_per_state = false;
};

/// The branch the printed law is held on (switching), or the law as it is (natural).
enum class Mode { natural, outward, inward, sliding };

/// In: the mode, and while sliding the |e| it holds, `radius` [m]. Out (rhs): the film's
/// state, |e| [m] and the radial force [N] (sliding: the multiplier λ that holds |e|).
struct Switching {
  Mode mode = Mode::natural;
  double radius = 0.0;
  lub::BearingState state;
  double e_norm = 0.0, radial_N = 0.0;
};

/// The printed law's jump at ε̇ = 0 in the state `s`: its ends F_r(0⁺) <= F_r(0⁻) [N].
/// Sliding holds while the multiplier lies between them.
inline std::pair<double, double> jump_limits(const Params& p, lub::BearingState s) {
  s.eps_dot = 0.0;
  const double f_out = lub::film_force(p.law, p.geom, p.mu, s).radial_N;
  s.eps_dot = -std::numeric_limits<double>::min();
  return {f_out, lub::film_force(p.law, p.geom, p.mu, s).radial_N};
}

/// Baumgarte rate of the sliding constraint |e| = radius [1/s]: critically damped at the
/// crank speed's scale, so a drift of |e| (the local error, ~rtol c) decays within a
/// fraction of a cycle and the constraint adds no stiffness the film does not have.
inline double sliding_alpha(const Params& p) { return 4.0 * p.omega; }

// y = (β, x, β̇, ẋ)
inline int rhs(double t, const double* y, double* yd, const Params& p, double* film_out = nullptr,
               Switching* sw = nullptr) {
  const double th = p.omega * t;
  const double c = p.geom.clearance_m();
  const double beta = y[0], x = y[1], bd = y[2], xd = y[3];
  const double ub[2] = {std::cos(beta), std::sin(beta)};
  const double up[2] = {-ub[1], ub[0]};
  const double A[2] = {p.a * std::cos(th), p.a * std::sin(th)};
  const double Ad[2] = {-p.a * p.omega * std::sin(th), p.a * p.omega * std::cos(th)};
  const double Add[2] = {-p.omega * p.omega * A[0], -p.omega * p.omega * A[1]};
  const double e[2] = {A[0] + p.l * ub[0] - x, A[1] + p.l * ub[1]};
  const double ed[2] = {Ad[0] + p.l * bd * up[0] - xd, Ad[1] + p.l * bd * up[1]};
  const double en = std::hypot(e[0], e[1]);
  double r[2] = {1, 0};
  lub::BearingState s;
  double gamma_dot = 0;
  if (en > 1e-12 * c) {
    r[0] = e[0] / en;
    r[1] = e[1] / en;
    s.eps = en / c;
    s.eps_dot = (r[0] * ed[0] + r[1] * ed[1]) / c;
    gamma_dot = (e[0] * ed[1] - e[1] * ed[0]) / (en * en);
  } else {
    const double edn = std::hypot(ed[0], ed[1]);
    if (edn > 0) r[0] = ed[0] / edn, r[1] = ed[1] / edn;
    s.eps_dot = edn / c;
  }
  if (!(s.eps < 1.0)) return 1;
  s.wedge = bd - 2 * gamma_dot;  // ω_J = β̇, the slider does not rotate
  const auto law = [&](const lub::BearingState& at) { return lub::film_force(p.law, p.geom, p.mu, at); };
  // The branch continued to first order from ε̇ = 0 (side +1: 0⁺, −1: 0⁻), slope over a
  // step of 1e-6 of the state's ε̇ scale (max of |ε w|/2 and |ε̇|).
  const auto continued = [&](lub::BearingState at, double side) {
    lub::BearingState a0 = at, a1 = at;
    a0.eps_dot = side > 0 ? 0.0 : -std::numeric_limits<double>::min();
    const double d = 1e-6 * std::max({0.5 * std::abs(at.eps * at.wedge), std::abs(at.eps_dot), 1e-12});
    a1.eps_dot = side * d;
    const lub::FilmForce f0 = law(a0), f1 = law(a1);
    const double w = at.eps_dot / (side * d);
    return lub::FilmForce{f0.radial_N + w * (f1.radial_N - f0.radial_N),
                          f0.tangential_N + w * (f1.tangential_N - f0.tangential_N)};
  };
  const Mode mode = sw ? sw->mode : Mode::natural;
  lub::FilmForce f;
  switch (mode) {
    case Mode::natural: f = law(s); break;
    case Mode::outward: f = s.eps_dot >= 0.0 ? law(s) : continued(s, +1.0); break;
    case Mode::inward: f = s.eps_dot < 0.0 ? law(s) : continued(s, -1.0); break;
    case Mode::sliding: {
      lub::BearingState s0 = s;
      s0.eps_dot = 0.0;
      f = law(s0);
      break;
    }
  }
  const double Ieff = p.Jr + p.mr * p.l * p.l / 4;
  const double gv[2] = {0.0, -p.g};
  const double tdir[2] = {-r[1], r[0]};
  const double Gb = 0.5 * p.l * p.mr * (up[0] * (gv[0] - Add[0]) + up[1] * (gv[1] - Add[1]));
  if (sw && mode == Mode::sliding) {
    // λ from  d²|e|/dt² = r·ë + (|ė|² − (r·ė)²)/|e| = −2α (r·ė) − α² (|e| − radius),
    // with ë = Ä + l β̈ u⊥ − l β̇² u − (ẍ, 0), β̈ = (l u⊥·F + G_β)/I, ẍ = −F_x/m_s and
    // F = λ r + F_t t: r·ë is affine in λ, with slope l² (u⊥·r)²/I + r_x²/m_s > 0.
    const double a = sliding_alpha(p);
    const double Ft[2] = {f.tangential_N * tdir[0], f.tangential_N * tdir[1]};
    const double bdd_t = (p.l * (up[0] * Ft[0] + up[1] * Ft[1]) + Gb) / Ieff;
    const double xdd_t = -Ft[0] / p.ms;
    const double edd_t[2] = {Add[0] + p.l * (bdd_t * up[0] - bd * bd * ub[0]) - xdd_t,
                             Add[1] + p.l * (bdd_t * up[1] - bd * bd * ub[1])};
    const double er = r[0] * ed[0] + r[1] * ed[1];
    const double curv = (ed[0] * ed[0] + ed[1] * ed[1] - er * er) / std::max(en, 1e-300);
    const double upr = up[0] * r[0] + up[1] * r[1];
    const double slope = p.l * p.l * upr * upr / Ieff + r[0] * r[0] / p.ms;
    const double target = -2 * a * er - a * a * (en - sw->radius);
    f.radial_N = (target - (r[0] * edd_t[0] + r[1] * edd_t[1]) - curv) / slope;
  }
  if (sw) {
    sw->state = s;
    sw->e_norm = en;
    sw->radial_N = f.radial_N;
  }
  const double F[2] = {f.radial_N * r[0] + f.tangential_N * tdir[0], f.radial_N * r[1] + f.tangential_N * tdir[1]};
  if (film_out) film_out[0] = F[0], film_out[1] = F[1];
  yd[0] = bd;
  yd[1] = xd;
  yd[2] = (p.l * (up[0] * F[0] + up[1] * F[1]) + Gb) / Ieff;
  yd[3] = -F[0] / p.ms;
  return 0;
}

/// Integrates from the paper's initial state (crank and rod aligned, journal centred,
/// ideal-joint velocities) for `cycles` crank cycles with CVODE; returns the state at
/// every multiple of `dt_out` and counts steps. The printed law runs with its events
/// (Switching above): restarts at every mode switch, counted in `switches`.
struct Result {
  std::vector<double> t, beta, x, e_x, e_y;
  long steps = 0, rhs_evals = 0, switches = 0;
  bool ok = true;
};

namespace detail {
struct UserData {
  const Params* p;
  Switching sw;
};

/// Root functions: free modes g0 = ε̇ (the other constant); sliding the two exits,
/// λ − F_r(0⁺) and F_r(0⁻) − λ, each falling through 0.
inline void set_root_directions(void* mem, Mode mode) {
  int dir[2] = {0, 0};
  if (mode == Mode::outward) dir[0] = -1;
  if (mode == Mode::inward) dir[0] = +1;
  if (mode == Mode::sliding) dir[0] = dir[1] = -1;
  CVodeSetRootDirection(mem, dir);
}

/// The mode after a root at state y (t), by the Filippov conditions: from a free branch at
/// ε̇ = 0, sliding if the multiplier that holds |e| lies within the jump, else the other
/// branch; from sliding, the branch on the side the multiplier left by.
inline Mode next_mode(double t, const double* y, UserData& ud, const int* fired) {
  const Params& p = *ud.p;
  const Mode from = ud.sw.mode;
  if (from == Mode::sliding) return fired[0] != 0 ? Mode::outward : Mode::inward;
  const Mode other = from == Mode::outward ? Mode::inward : Mode::outward;
  double yd[4];
  Switching trial = ud.sw;
  if (rhs(t, y, yd, p, nullptr, &trial) != 0) return other;  // |e| here
  if (trial.e_norm <= 1e-9 * p.geom.clearance_m()) return other;
  trial.mode = Mode::sliding;
  trial.radius = trial.e_norm;
  if (rhs(t, y, yd, p, nullptr, &trial) != 0) return other;  // λ that holds it
  const auto [f_out, f_in] = jump_limits(p, trial.state);
  const bool slide = from == Mode::outward ? trial.radial_N <= f_in : trial.radial_N >= f_out;
  if (!slide) return other;
  ud.sw.radius = trial.radius;
  return Mode::sliding;
}
}  // namespace detail

inline Result integrate(const Params& p, double cycles, double rtol, bool bdf, double dt_out) {
  SUNContext ctx;
  SUNContext_Create(nullptr, &ctx);
  N_Vector y = N_VNew_Serial(4, ctx);
  NV_Ith_S(y, 0) = 0.0;
  NV_Ith_S(y, 1) = p.a + p.l;
  NV_Ith_S(y, 2) = -p.a * p.omega / p.l;
  NV_Ith_S(y, 3) = 0.0;
  const bool switching = p.law == lub::ForceLaw::pinkus_sternlicht;
  detail::UserData ud{&p, {}};
  if (switching) ud.sw.mode = Mode::outward;  // ε̇ >= 0 at the centred start
  void* mem = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, ctx);
  auto f = [](sunrealtype t, N_Vector yv, N_Vector ydv, void* u) {
    auto* d = static_cast<detail::UserData*>(u);
    return rhs(t, N_VGetArrayPointer(yv), N_VGetArrayPointer(ydv), *d->p, nullptr,
               d->p->law == lub::ForceLaw::pinkus_sternlicht ? &d->sw : nullptr);
  };
  auto g = [](sunrealtype t, N_Vector yv, sunrealtype* gout, void* u) {
    auto* d = static_cast<detail::UserData*>(u);
    double yd[4];
    if (rhs(t, N_VGetArrayPointer(yv), yd, *d->p, nullptr, &d->sw) != 0) return 1;
    if (d->sw.mode == Mode::sliding) {
      const auto [f_out, f_in] = jump_limits(*d->p, d->sw.state);
      gout[0] = d->sw.radial_N - f_out;
      gout[1] = f_in - d->sw.radial_N;
    } else {
      gout[0] = d->sw.state.eps_dot;
      gout[1] = 1.0;
    }
    return 0;
  };
  CVodeInit(mem, f, 0.0, y);
  CVodeSetUserData(mem, &ud);
  if (switching) {
    CVodeRootInit(mem, 2, g);
    CVodeSetNoInactiveRootWarn(mem);
    detail::set_root_directions(mem, ud.sw.mode);
  }
  N_Vector atol = N_VNew_Serial(4, ctx);
  const double c = p.geom.clearance_m();
  const double units[4] = {c / p.l, c, c * p.omega / p.l, c * p.omega};
  for (int i = 0; i < 4; ++i) NV_Ith_S(atol, i) = rtol * (p.atol_per_state ? units[i] : c);
  CVodeSVtolerances(mem, rtol, atol);
  CVodeSetMaxNumSteps(mem, -1);
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  SUNNonlinearSolver NLS = nullptr;
  if (bdf) {
    A = SUNDenseMatrix(4, 4, ctx);
    LS = SUNLinSol_Dense(y, A, ctx);
    CVodeSetLinearSolver(mem, LS, A);
  } else {
    NLS = SUNNonlinSol_FixedPoint(y, 0, ctx);
    CVodeSetNonlinearSolver(mem, NLS);
  }
  const double t_end = cycles * 2 * M_PI / p.omega;
  CVodeSetStopTime(mem, t_end);
  Result res;
  long steps_before = 0, rhs_before = 0;  // the counters of the runs before each restart
  const auto count = [&](long& steps, long& evals) {
    long s = 0, e = 0, je = 0;
    CVodeGetNumSteps(mem, &s);
    CVodeGetNumRhsEvals(mem, &e);
    if (bdf) CVodeGetNumLinRhsEvals(mem, &je);  // the difference-quotient Jacobian's, as the engine counts them
    steps = s;
    evals = e + je;
  };
  const int n_out = static_cast<int>(std::floor(t_end / dt_out + 1e-9));
  for (int k = 1; k <= n_out && res.ok; ++k) {
    double tret = 0;
    int flag = 0;
    while ((flag = CVode(mem, k * dt_out, y, &tret, CV_NORMAL)) == CV_ROOT_RETURN) {
      int fired[2] = {0, 0};
      CVodeGetRootInfo(mem, fired);
      ud.sw.mode = detail::next_mode(tret, N_VGetArrayPointer(y), ud, fired);
      ++res.switches;
      long s = 0, e = 0;
      count(s, e);
      steps_before += s;
      rhs_before += e;
      CVodeReInit(mem, tret, y);
      detail::set_root_directions(mem, ud.sw.mode);
    }
    if (flag < 0) {
      res.ok = false;
      break;
    }
    res.t.push_back(tret);
    res.beta.push_back(NV_Ith_S(y, 0));
    res.x.push_back(NV_Ith_S(y, 1));
    const double th = p.omega * tret;
    res.e_x.push_back(p.a * std::cos(th) + p.l * std::cos(NV_Ith_S(y, 0)) - NV_Ith_S(y, 1));
    res.e_y.push_back(p.a * std::sin(th) + p.l * std::sin(NV_Ith_S(y, 0)));
  }
  count(res.steps, res.rhs_evals);
  res.steps += steps_before;
  res.rhs_evals += rhs_before;
  CVodeFree(&mem);
  if (LS) SUNLinSolFree(LS);
  if (A) SUNMatDestroy(A);
  if (NLS) SUNNonlinSolFree(NLS);
  N_VDestroy(y);
  N_VDestroy(atol);
  SUNContext_Free(&ctx);
  return res;
}

}  // namespace floor_model
