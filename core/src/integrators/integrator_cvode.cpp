// CVODES adapter: Adams–Moulton with fixed-point iteration (the paper's variable step and
// order predictor–corrector) and BDF with Newton and a dense direct linear solver.
#include <cvodes/cvodes.h>
#include <cvodes/cvodes_proj.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <cfloat>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrators/integrator_common.hpp"
#include "integrators/small_kernels.hpp"
#include "lub/integrators/integrator.hpp"

namespace lub {

namespace detail {

/// Forward sensitivities' state (Integrator::start_sensitivities): their vectors and the
/// states' scales of their difference steps.
struct SensitivityData {
  int ns = 0;
  N_Vector* yS = nullptr;
  std::vector<double> scale;
  std::vector<double> pbar;  ///< each column's scale (CVodeSetSensParams)
  N_Vector* atol = nullptr;  ///< their absolute tolerances
  bool off = false;          ///< stopped (Integrator::stop_sensitivities)
  void allocate(int n_sens, N_Vector like) {
    yS = N_VCloneVectorArray(n_sens, like);
    if (!yS) throw std::runtime_error("N_VCloneVectorArray failed");
    ns = n_sens;
  }
  SensitivityData() = default;
  SensitivityData(const SensitivityData&) = delete;
  SensitivityData& operator=(const SensitivityData&) = delete;
  ~SensitivityData() {
    if (yS) N_VDestroyVectorArray(yS, ns);
    if (atol) N_VDestroyVectorArray(atol, ns);
  }
};

}  // namespace detail

namespace {

/// The sensitivities' relative difference step: u^(1/3).
const double kSensitivityStep = std::cbrt(DBL_EPSILON);
/// The sensitivities' relative tolerance at the finest (their corrector's convergence test):
/// their right-hand side, a difference quotient, carries round-off of ~1e-10 of itself,
/// which a tighter test chases (at rtol 1e-10 the corrector failed hundreds of times a
/// period, each failure a smaller step).
constexpr double kSensitivityRtol = 1e-6;

using detail::CallbackData;
using detail::SensitivityData;
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
    // The sensitivities at t, likewise, to restart them there.
    const bool sens = sens_.ns > 0 && !sens_.off;
    if (sens) check(CVodeGetSensDky(mem_, t, 0, sens_.yS), "CVodeGetSensDky");
    check(CVodeReInit(mem_, t, y_), "CVodeReInit");
    if (q_) check(CVodeQuadReInit(mem_, q_), "CVodeQuadReInit");
    if (sens) check(CVodeSensReInit(mem_, CV_STAGGERED, sens_.yS), "CVodeSensReInit");
    check(CVodeSetStopTime(mem_, t_stop_), "CVodeSetStopTime");
  }

  void set_stop_time(double t_stop) override {
    t_stop_ = t_stop;
    check(CVodeSetStopTime(mem_, t_stop_), "CVodeSetStopTime");
  }

  void set_abs_tolerances(const std::vector<double>& atol) override {
    for (sunindextype i = 0; i < N_VGetLength(atol_); ++i) NV_Ith_S(atol_, i) = atol[static_cast<size_t>(i)];
    check(CVodeSVtolerances(mem_, rtol_, atol_), "CVodeSVtolerances");
    if (sens_.ns > 0) set_sensitivity_scales();
  }

  bool start_sensitivities(int ns, const double* S0) override {
    if (method_ != Method::cvode_bdf || ns < 1 || sens_.ns > 0) return false;
    const sunindextype n = N_VGetLength(y_);
    sens_.allocate(ns, y_);
    data_.sens = &sens_;
    for (int k = 0; k < ns; ++k)
      for (sunindextype i = 0; i < n; ++i) NV_Ith_S(sens_.yS[k], i) = S0[static_cast<size_t>(k * n + i)];
    set_sensitivity_scales();
    check(CVodeSensInit(mem_, ns, CV_STAGGERED, sensitivity_rhs, sens_.yS), "CVodeSensInit");
    // Each column's scale, for the tolerances CVODES derives from the state's (atol / pbar_k,
    // which its corrector's convergence test uses): S_ik is ∂y_i/∂y0_k, of order the ratio of
    // the two states' scales when the seed is the identity; a seed column's size in its state's
    // scales otherwise.
    sens_.pbar.assign(static_cast<size_t>(ns), 1.0);
    for (int k = 0; k < ns; ++k) {
      double size = 0.0;
      for (sunindextype i = 0; i < n; ++i)
        size = std::max(size, std::abs(S0[static_cast<size_t>(k * n + i)]) / sens_.scale[static_cast<size_t>(i)]);
      if (size > 0.0) sens_.pbar[static_cast<size_t>(k)] = 1.0 / size;
    }
    check(CVodeSetSensParams(mem_, nullptr, sens_.pbar.data(), nullptr), "CVodeSetSensParams");
    const double rtol_s = std::max(rtol_, kSensitivityRtol);
    sens_.atol = N_VCloneVectorArray(ns, y_);
    for (int k = 0; k < ns; ++k)
      for (sunindextype i = 0; i < n; ++i)
        NV_Ith_S(sens_.atol[k], i) = rtol_s * sens_.scale[static_cast<size_t>(i)] / sens_.pbar[static_cast<size_t>(k)];
    check(CVodeSensSVtolerances(mem_, rtol_s, sens_.atol), "CVodeSensSVtolerances");
    check(CVodeSetSensErrCon(mem_, SUNFALSE), "CVodeSetSensErrCon");
    return true;
  }

  void stop_sensitivities() override {
    if (sens_.ns == 0 || sens_.off) return;
    check(CVodeSensToggleOff(mem_), "CVodeSensToggleOff");
    sens_.off = true;
  }

  bool sensitivities(double t, double* S) override {
    if (sens_.ns == 0 || sens_.off) return false;
    if (CVodeGetSensDky(mem_, t, 0, sens_.yS) != CV_SUCCESS) return false;
    const sunindextype n = N_VGetLength(y_);
    for (int k = 0; k < sens_.ns; ++k)
      for (sunindextype i = 0; i < n; ++i) S[static_cast<size_t>(k * n + i)] = NV_Ith_S(sens_.yS[k], i);
    return true;
  }

 private:
  void check(int flag, const char* what) {
    if (flag != 0) throw std::runtime_error(std::string(what) + " failed: " + data_.error);
  }

  /// Each state's scale for the sensitivities' difference steps: atol/rtol, the size at
  /// which its absolute and relative tolerances meet (its own unit: a clearance for a
  /// journal's position).
  void set_sensitivity_scales() {
    const sunindextype n = N_VGetLength(atol_);
    sens_.scale.resize(static_cast<size_t>(n));
    for (sunindextype i = 0; i < n; ++i) sens_.scale[static_cast<size_t>(i)] = NV_Ith_S(atol_, i) / rtol_;
  }

  /// S_k' = ∂f/∂y S_k by a central difference of f along S_k: a step of u^(1/3) in the
  /// states' scales (truncation and round-off balanced, ~1e-10 of the product). A forward
  /// difference (half the evaluations) is ~1e-8 off: near the wall its error failed the
  /// sensitivities' corrector often enough to take ten times the steps.
  static int sensitivity_rhs(int ns, sunrealtype t, N_Vector y, N_Vector, N_Vector* yS, N_Vector* ySdot,
                             void* user, N_Vector tmp1, N_Vector tmp2) {
    auto* self = static_cast<CallbackData*>(user);
    return detail::guarded(self, "sensitivity right-hand side", [&] {
      const SensitivityData& sd = *self->sens;
      const sunindextype n = N_VGetLength(y);
      const double* yy = N_VGetArrayPointer(y);
      double* yp = N_VGetArrayPointer(tmp1);
      double* fp = N_VGetArrayPointer(tmp2);
      for (int k = 0; k < ns; ++k) {
        const double* s = N_VGetArrayPointer(yS[k]);
        double* out = N_VGetArrayPointer(ySdot[k]);
        double size = 0.0;  // |S_k| in the states' scales
        for (sunindextype i = 0; i < n; ++i) size = std::max(size, std::abs(s[i]) / sd.scale[static_cast<size_t>(i)]);
        if (size == 0.0) {
          for (sunindextype i = 0; i < n; ++i) out[i] = 0.0;
          continue;
        }
        const double sigma = kSensitivityStep / size;
        for (sunindextype i = 0; i < n; ++i) yp[i] = yy[i] + sigma * s[i];
        int rc = self->sys->rhs(t, yp, fp);
        if (rc != 0) return rc;
        for (sunindextype i = 0; i < n; ++i) out[i] = fp[i];
        for (sunindextype i = 0; i < n; ++i) yp[i] = yy[i] - sigma * s[i];
        rc = self->sys->rhs(t, yp, fp);
        if (rc != 0) return rc;
        for (sunindextype i = 0; i < n; ++i) out[i] = (out[i] - fp[i]) / (2.0 * sigma);
      }
      return 0;
    });
  }

  Method method_;
  double t_stop_ = 0.0;
  double rtol_ = 0.0;
  IntegratorStats base_;  // counters accumulated before the last reinit
  CallbackData data_;
  // Owned handles, in the order they must outlive each other (destroyed bottom-up).
  detail::OwnedContext ctx_;
  detail::OwnedVector y_, atol_, q_;
  SensitivityData sens_;  // forward sensitivities' vectors, where started
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
