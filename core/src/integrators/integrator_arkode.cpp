// ARKODE adapter (ARKStep): an explicit Runge–Kutta method (Dormand–Prince 5(4)) and an
// implicit one (L-stable SDIRK 5-stage 4th order, Newton with a dense direct linear
// solver). ARKODE has no quadratures: they are integrated as extra states.
#include <arkode/arkode_arkstep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "integrators/integrator_common.hpp"

namespace lub {

namespace {

using detail::CallbackData;

struct FreeArkStep {
  void operator()(void* mem) const { ARKStepFree(&mem); }
};

class ArkodeIntegrator final : public Integrator {
 public:
  ArkodeIntegrator(const IntegratorSettings& s, OdeSystem& sys, double t0, const std::vector<double>& y0)
      : implicit_(s.method == Method::arkode_dirk) {
    data_.sys = &sys;
    data_.n = sys.size();
    data_.nquad = sys.num_quadratures();
    ctx_ = detail::new_context();
    const sunindextype n = data_.n + data_.nquad;
    y_ = N_VNew_Serial(n, ctx_);
    atol_ = N_VNew_Serial(n, ctx_);
    for (sunindextype i = 0; i < n; ++i) {
      NV_Ith_S(y_, i) = i < data_.n ? y0[i] : 0.0;
      // Quadratures (work integrals) take part in the error test like any state.
      NV_Ith_S(atol_, i) = i < data_.n ? s.atol[i] : s.atol.front();
    }
    mem_ = implicit_ ? ARKStepCreate(nullptr, detail::rhs_cb, t0, y_, ctx_)
                     : ARKStepCreate(detail::rhs_cb, nullptr, t0, y_, ctx_);
    if (!mem_) throw std::runtime_error("ARKStepCreate failed");
    check(ARKStepSetErrHandlerFn(mem_, detail::err_cb, &data_), "ARKStepSetErrHandlerFn");
    check(ARKStepSetUserData(mem_, &data_), "ARKStepSetUserData");
    check(ARKStepSVtolerances(mem_, s.rtol, atol_), "ARKStepSVtolerances");
    check(ARKStepSetMaxNumSteps(mem_, -1), "ARKStepSetMaxNumSteps");
    if (implicit_) {
      check(ARKStepSetTableNum(mem_, ARKODE_SDIRK_5_3_4, ARKODE_ERK_NONE), "ARKStepSetTableNum");
      A_ = SUNDenseMatrix(n, n, ctx_);
      ls_ = SUNLinSol_Dense(y_, A_, ctx_);
      check(ARKStepSetLinearSolver(mem_, ls_, A_), "ARKStepSetLinearSolver");
      if (s.user_jacobian) {
        if (data_.nquad > 0) data_.jac.assign(static_cast<size_t>(data_.n) * data_.n, 0.0);
        check(ARKStepSetJacFn(mem_, detail::jac_cb), "ARKStepSetJacFn");
      }
    } else {
      check(ARKStepSetTableNum(mem_, ARKODE_DIRK_NONE, ARKODE_DORMAND_PRINCE_7_4_5), "ARKStepSetTableNum");
    }
    if (s.max_step > 0) check(ARKStepSetMaxStep(mem_, s.max_step), "ARKStepSetMaxStep");
    if (s.initial_step > 0) check(ARKStepSetInitStep(mem_, s.initial_step), "ARKStepSetInitStep");
    t_stop_ = s.t_stop;
    rtol_ = s.rtol;
    check(ARKStepSetStopTime(mem_, t_stop_), "ARKStepSetStopTime");
    if (sys.num_roots() > 0) {
      check(ARKStepRootInit(mem_, sys.num_roots(), detail::root_cb), "ARKStepRootInit");
      ARKStepSetNoInactiveRootWarn(mem_);
    }
  }

  StepOutcome step(double& t) override {
    sunrealtype tret = 0;
    // tout = the stop time: ARKODE's initial-step estimate after a (re)start uses it.
    const int flag = ARKStepEvolve(mem_, t_stop_, y_, &tret, ARK_ONE_STEP);
    t = tret;
    if (flag == ARK_ROOT_RETURN) return StepOutcome::root;
    if (flag < 0) {
      if (data_.error.empty()) data_.error = "ARKStepEvolve returned " + std::to_string(flag);
      return StepOutcome::failure;
    }
    return StepOutcome::step;
  }

  bool dense(double t, int k, double* out) override {
    detail::OwnedVector v;
    v = N_VNew_Serial(N_VGetLength(y_), ctx_);
    const int flag = ARKStepGetDky(mem_, t, k, v);
    for (int i = 0; i < data_.n; ++i) out[i] = NV_Ith_S(v, i);
    return flag == ARK_SUCCESS;
  }

  void quadratures(double* out) override {
    for (int i = 0; i < data_.nquad; ++i) out[i] = NV_Ith_S(y_, data_.n + i);
  }

  const double* y() const override { return N_VGetArrayPointer(y_); }

  void statistics(IntegratorStats& s) const override {
    // Counters since the last (re)initialisation, plus those from before it.
    long v = 0, w = 0;
    ARKStepGetNumSteps(mem_, &v); s.steps = v;
    ARKStepGetNumRhsEvals(mem_, &v, &w); s.rhs_evals = v + w;
    ARKStepGetNumErrTestFails(mem_, &v); s.error_test_fails = v;
    ARKStepGetNumGEvals(mem_, &v); s.root_evals = v;
    if (implicit_) {
      ARKStepGetNumNonlinSolvIters(mem_, &v); s.nonlinear_iters = v;
      ARKStepGetNumNonlinSolvConvFails(mem_, &v); s.nonlinear_conv_fails = v;
      ARKStepGetNumJacEvals(mem_, &v); s.jacobian_evals = v;
      ARKStepGetNumLinRhsEvals(mem_, &v); s.rhs_evals_jacobian = v;
      ARKStepGetNumLinSolvSetups(mem_, &v); s.linear_setups = v;
    }
    s += base_;
  }

  std::string error_message() const override { return data_.error; }
  void clear_error() override { data_.error.clear(); }

  void root_flags(std::vector<int>& flags) override {
    flags.assign(static_cast<size_t>(data_.sys->num_roots()), 0);
    if (!flags.empty()) ARKStepGetRootInfo(mem_, flags.data());
  }

  void set_root_directions(const std::vector<int>& dirs) override {
    if (dirs.empty()) return;
    std::vector<int> d(dirs);
    check(ARKStepSetRootDirection(mem_, d.data()), "ARKStepSetRootDirection");
  }

  void reinit(double t, const double* y) override {
    IntegratorStats total;
    statistics(total);
    base_ = total;
    for (int i = 0; i < data_.n; ++i) NV_Ith_S(y_, i) = y[i];  // quadratures carry on
    check(implicit_ ? ARKStepReInit(mem_, nullptr, detail::rhs_cb, t, y_)
                    : ARKStepReInit(mem_, detail::rhs_cb, nullptr, t, y_),
          "ARKStepReInit");
    check(ARKStepSetStopTime(mem_, t_stop_), "ARKStepSetStopTime");
  }

  void set_stop_time(double t_stop) override {
    t_stop_ = t_stop;
    check(ARKStepSetStopTime(mem_, t_stop_), "ARKStepSetStopTime");
  }

  void set_abs_tolerances(const std::vector<double>& atol) override {
    for (int i = 0; i < data_.n; ++i) NV_Ith_S(atol_, i) = atol[static_cast<size_t>(i)];
    check(ARKStepSVtolerances(mem_, rtol_, atol_), "ARKStepSVtolerances");
  }

 private:
  void check(int flag, const char* what) {
    if (flag != 0) throw std::runtime_error(std::string(what) + " failed: " + data_.error);
  }

  bool implicit_;
  double t_stop_ = 0.0;
  double rtol_ = 0.0;
  IntegratorStats base_;
  CallbackData data_;
  // Owned handles, in the order they must outlive each other (destroyed bottom-up).
  detail::OwnedContext ctx_;
  detail::OwnedVector y_, atol_;
  detail::OwnedMatrix A_;
  detail::OwnedLinearSolver ls_;
  detail::Owned<void*, FreeArkStep> mem_;
};

}  // namespace

std::unique_ptr<Integrator> make_arkode_integrator(const IntegratorSettings& s, OdeSystem& sys, double t0,
                                                   const std::vector<double>& y0) {
  return std::make_unique<ArkodeIntegrator>(s, sys, t0, y0);
}

}  // namespace lub
