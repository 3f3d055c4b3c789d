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
#pragma once

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
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

// y = (β, x, β̇, ẋ)
inline int rhs(double t, const double* y, double* yd, const Params& p, double* film_out = nullptr) {
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
  const lub::FilmForce f = lub::film_force(p.law, p.geom, p.mu, s);
  const double F[2] = {f.radial_N * r[0] - f.tangential_N * r[1], f.radial_N * r[1] + f.tangential_N * r[0]};
  if (film_out) film_out[0] = F[0], film_out[1] = F[1];
  const double Ieff = p.Jr + p.mr * p.l * p.l / 4;
  const double gv[2] = {0.0, -p.g};
  yd[0] = bd;
  yd[1] = xd;
  yd[2] = (p.l * (up[0] * F[0] + up[1] * F[1]) +
           0.5 * p.l * p.mr * (up[0] * (gv[0] - Add[0]) + up[1] * (gv[1] - Add[1]))) / Ieff;
  yd[3] = -F[0] / p.ms;
  return 0;
}

/// Integrates from the paper's initial state (crank and rod aligned, journal centred,
/// ideal-joint velocities) for `cycles` crank cycles with CVODE; returns the state at
/// every multiple of `dt_out` and counts steps.
struct Result {
  std::vector<double> t, beta, x, e_x, e_y;
  long steps = 0, rhs_evals = 0;
};

inline Result integrate(const Params& p, double cycles, double rtol, bool bdf, double dt_out) {
  SUNContext ctx;
  SUNContext_Create(nullptr, &ctx);
  N_Vector y = N_VNew_Serial(4, ctx);
  NV_Ith_S(y, 0) = 0.0;
  NV_Ith_S(y, 1) = p.a + p.l;
  NV_Ith_S(y, 2) = -p.a * p.omega / p.l;
  NV_Ith_S(y, 3) = 0.0;
  void* mem = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, ctx);
  auto f = [](sunrealtype t, N_Vector yv, N_Vector ydv, void* ud) {
    return rhs(t, N_VGetArrayPointer(yv), N_VGetArrayPointer(ydv), *static_cast<const Params*>(ud));
  };
  CVodeInit(mem, f, 0.0, y);
  CVodeSetUserData(mem, const_cast<Params*>(&p));
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
  const int n_out = static_cast<int>(std::floor(t_end / dt_out + 1e-9));
  for (int k = 1; k <= n_out; ++k) {
    double tret;
    const int flag = CVode(mem, k * dt_out, y, &tret, CV_NORMAL);
    if (flag < 0) break;
    res.t.push_back(tret);
    res.beta.push_back(NV_Ith_S(y, 0));
    res.x.push_back(NV_Ith_S(y, 1));
    const double th = p.omega * tret;
    res.e_x.push_back(p.a * std::cos(th) + p.l * std::cos(NV_Ith_S(y, 0)) - NV_Ith_S(y, 1));
    res.e_y.push_back(p.a * std::sin(th) + p.l * std::sin(NV_Ith_S(y, 0)));
  }
  CVodeGetNumSteps(mem, &res.steps);
  CVodeGetNumRhsEvals(mem, &res.rhs_evals);
  if (bdf) {  // with the difference-quotient Jacobian's, as the engine counts them
    long jac_rhs = 0;
    CVodeGetNumLinRhsEvals(mem, &jac_rhs);
    res.rhs_evals += jac_rhs;
  }
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
