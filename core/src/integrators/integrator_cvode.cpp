// CVODES adapter: Adams–Moulton with fixed-point iteration (the paper's variable step and
// order predictor–corrector) and BDF with Newton and a dense direct linear solver.
#include <cvodes/cvodes.h>
#include <cvodes/cvodes_proj.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrators/integrator_common.hpp"
#include "integrators/small_kernels.hpp"
#include "lub/integrators/integrator.hpp"

namespace lub {

namespace {

using detail::CallbackData;
using detail::err_cb;
using detail::quad_cb;
using detail::rhs_cb;
using detail::root_cb;
using detail::small_dense_matrix;
using detail::small_dense_solver;

struct FreeCvode {
  void operator()(void* mem) const { CVodeFree(&mem); }
};

class CvodeIntegrator final : public Integrator {
 public:
  CvodeIntegrator(const IntegratorSettings& s, OdeSystem& sys, double t0, const std::vector<double>& y0)
      : method_(s.method) {
    data_.sys = &sys;
    data_.n = sys.size();
    ctx_ = detail::new_context();
    const sunindextype n = sys.size();
    y_ = N_VNew_Serial(n, ctx_);
    for (sunindextype i = 0; i < n; ++i) NV_Ith_S(y_, i) = y0[i];
    // Fused vector operations (one call for CVODE's sums of several vectors): on 4 states a
    // call costs more than its arithmetic. Same results, ~1 % fewer instructions a step.
    N_VEnableFusedOps_Serial(y_, SUNTRUE);
    // And the per-step linear sum, scaling, constant fill and norm, written for short
    // vectors: CVODE's working vectors are clones of y_ and take its operations
    // (small_kernels.hpp).
    detail::use_small_vector_ops(y_);
    atol_ = N_VNew_Serial(n, ctx_);
    for (sunindextype i = 0; i < n; ++i) NV_Ith_S(atol_, i) = s.atol[i];
    mem_ = CVodeCreate(s.method == Method::cvode_adams ? CV_ADAMS : CV_BDF, ctx_);
    if (!mem_) throw std::runtime_error("CVodeCreate failed");
    check(CVodeSetErrHandlerFn(mem_, err_cb, &data_), "CVodeSetErrHandlerFn");
    check(CVodeInit(mem_, rhs_cb, t0, y_), "CVodeInit");
    check(CVodeSetUserData(mem_, &data_), "CVodeSetUserData");
    check(CVodeSVtolerances(mem_, s.rtol, atol_), "CVodeSVtolerances");
    check(CVodeSetMaxNumSteps(mem_, -1), "CVodeSetMaxNumSteps");  // the run loop budgets steps
    if (s.max_step > 0) check(CVodeSetMaxStep(mem_, s.max_step), "CVodeSetMaxStep");
    if (s.initial_step > 0) check(CVodeSetInitStep(mem_, s.initial_step), "CVodeSetInitStep");
    if (s.max_order > 0) check(CVodeSetMaxOrd(mem_, s.max_order), "CVodeSetMaxOrd");
    t_stop_ = s.t_stop;
    rtol_ = s.rtol;
    check(CVodeSetStopTime(mem_, s.t_stop), "CVodeSetStopTime");
    if (s.method == Method::cvode_adams) {
      nls_ = SUNNonlinSol_FixedPoint(y_, 0, ctx_);
      check(CVodeSetNonlinearSolver(mem_, nls_), "CVodeSetNonlinearSolver");
    } else {
      // SUNDIALS' dense matrix and LU, their per-step operations written out for these
      // small matrices: the same numbers at fewer instructions (small_kernels.hpp).
      A_ = small_dense_matrix(static_cast<int>(n), ctx_);
      ls_ = small_dense_solver(static_cast<int>(n), ctx_);
      check(CVodeSetLinearSolver(mem_, ls_, A_), "CVodeSetLinearSolver");
      if (s.user_jacobian) check(CVodeSetJacFn(mem_, detail::jac_cb), "CVodeSetJacFn");
      if (s.jacobian_steps > 0) {
        check(CVodeSetJacEvalFrequency(mem_, s.jacobian_steps), "CVodeSetJacEvalFrequency");
        check(CVodeSetLSetupFrequency(mem_, 1), "CVodeSetLSetupFrequency");
      }
      if (s.projection) {
        check(CVodeSetProjFn(mem_, detail::proj_cb), "CVodeSetProjFn");
        // The error test on the whole local error, normal components included. With the
        // projected estimate (CVODE's default) it ignores how far each step leaves Φ = 0,
        // Φ̇ = 0, so the projections' corrections are not bounded by the tolerance; they
        // also move the journal in its bearing (the film is no constraint), and the stiff
        // squeeze film answers with a transient that fails the error test where a velocity
        // crosses zero (StiffNewton.ProjectionSlowCrankPassesCycleBoundaries: 2 of the 4
        // full-factorial failures remain without this, 1 without the Jacobian refresh, 0 with both).
        check(CVodeSetProjErrEst(mem_, SUNFALSE), "CVodeSetProjErrEst");
      }
    }
    if (sys.num_roots() > 0) {
      check(CVodeRootInit(mem_, sys.num_roots(), root_cb), "CVodeRootInit");
      CVodeSetNoInactiveRootWarn(mem_);
    }
    if (sys.num_quadratures() > 0) {
      q_ = N_VNew_Serial(sys.num_quadratures(), ctx_);
      N_VConst(0.0, q_);
      check(CVodeQuadInit(mem_, quad_cb, q_), "CVodeQuadInit");
    }
  }

  StepOutcome step(double& t) override {
    sunrealtype tret = 0;
    // tout = the stop time: CVODE's initial-step estimate after a (re)start uses it.
    const int flag = CVode(mem_, t_stop_, y_, &tret, CV_ONE_STEP);
    t = tret;
    if (flag == CV_ROOT_RETURN) return StepOutcome::root;
    if (flag < 0) {
      if (data_.error.empty()) {
        char* name = CVodeGetReturnFlagName(flag);
        data_.error = std::string("CVode returned ") + (name ? name : "an error");
        free(name);
      }
      return StepOutcome::failure;
    }
    return StepOutcome::step;
  }

  bool dense(double t, int k, double* out) override {
    detail::OwnedVector v;
    v = N_VMake_Serial(N_VGetLength(y_), out, ctx_);
    return CVodeGetDky(mem_, t, k, v) == CV_SUCCESS;
  }

  void quadratures(double* out) override {
    if (!q_) return;
    sunrealtype tret;
    CVodeGetQuad(mem_, &tret, q_);
    for (sunindextype i = 0; i < N_VGetLength(q_); ++i) out[i] = NV_Ith_S(q_, i);
  }

  const double* y() const override { return N_VGetArrayPointer(y_); }

  void statistics(IntegratorStats& s) const override {
    current(s);
    s += base_;
  }

  long long steps() const override {
    long v = 0;
    CVodeGetNumSteps(mem_, &v);
    return v + base_.steps;
  }

  // Counters since the last (re)initialisation: CVodeReInit resets them.
  void current(IntegratorStats& s) const {
    long v = 0;
    CVodeGetNumSteps(mem_, &v); s.steps = v;
    CVodeGetNumRhsEvals(mem_, &v); s.rhs_evals = v;
    CVodeGetNumErrTestFails(mem_, &v); s.error_test_fails = v;
    CVodeGetNumNonlinSolvIters(mem_, &v); s.nonlinear_iters = v;
    CVodeGetNumNonlinSolvConvFails(mem_, &v); s.nonlinear_conv_fails = v;
    CVodeGetNumGEvals(mem_, &v); s.root_evals = v;
    if (method_ == Method::cvode_bdf) {
      CVodeGetNumJacEvals(mem_, &v); s.jacobian_evals = v;
      CVodeGetNumLinRhsEvals(mem_, &v); s.rhs_evals_jacobian = v;
      CVodeGetNumLinSolvSetups(mem_, &v); s.linear_setups = v;
    }
  }

  std::string error_message() const override { return data_.error; }
  void clear_error() override { data_.error.clear(); }

  void root_flags(std::vector<int>& flags) override {
    flags.assign(static_cast<size_t>(data_.sys->num_roots()), 0);
    if (!flags.empty()) CVodeGetRootInfo(mem_, flags.data());
  }

  void set_root_directions(const std::vector<int>& dirs) override {
    if (dirs.empty()) return;
    std::vector<int> d(dirs);
    check(CVodeSetRootDirection(mem_, d.data()), "CVodeSetRootDirection");
  }

  void reinit(double t, const double* y) override {
    IntegratorStats total;
    statistics(total);
    base_ = total;
    // The quadratures at t (a root inside the last step): before CVodeReInit forgets
    // the step's history.
    if (q_) check(CVodeGetQuadDky(mem_, t, 0, q_), "CVodeGetQuadDky");
    for (sunindextype i = 0; i < N_VGetLength(y_); ++i) NV_Ith_S(y_, i) = y[i];
    check(CVodeReInit(mem_, t, y_), "CVodeReInit");
    if (q_) check(CVodeQuadReInit(mem_, q_), "CVodeQuadReInit");
    check(CVodeSetStopTime(mem_, t_stop_), "CVodeSetStopTime");
  }

  void set_stop_time(double t_stop) override {
    t_stop_ = t_stop;
    check(CVodeSetStopTime(mem_, t_stop_), "CVodeSetStopTime");
  }

  void set_abs_tolerances(const std::vector<double>& atol) override {
    for (sunindextype i = 0; i < N_VGetLength(atol_); ++i) NV_Ith_S(atol_, i) = atol[static_cast<size_t>(i)];
    check(CVodeSVtolerances(mem_, rtol_, atol_), "CVodeSVtolerances");
  }

 private:
  void check(int flag, const char* what) {
    if (flag != 0) throw std::runtime_error(std::string(what) + " failed: " + data_.error);
  }

  Method method_;
  double t_stop_ = 0.0;
  double rtol_ = 0.0;
  IntegratorStats base_;  // counters accumulated before the last reinit
  CallbackData data_;
  // Owned handles, in the order they must outlive each other (destroyed bottom-up).
  detail::OwnedContext ctx_;
  detail::OwnedVector y_, atol_, q_;
  detail::OwnedNonlinearSolver nls_;
  detail::OwnedMatrix A_;
  detail::OwnedLinearSolver ls_;
  detail::Owned<void*, FreeCvode> mem_;
};

}  // namespace

std::unique_ptr<Integrator> make_cvode_integrator(const IntegratorSettings& settings, OdeSystem& sys,
                                                  double t0, const std::vector<double>& y0) {
  return std::make_unique<CvodeIntegrator>(settings, sys, t0, y0);
}

}  // namespace lub
