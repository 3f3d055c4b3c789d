// IDAS adapter: variable-order BDF on the DAE F(t, Y, Y') = 0 that the system provides
// (MultibodySystem's GGL form), Newton with a dense direct linear solver and either the
// system's structured iteration matrix (dae_jacobian, IntegratorSettings::user_jacobian)
// or SUNDIALS' dense difference quotients. The run loop sees only the state y (the first size()
// components of Y); the multipliers stay inside. They are excluded from the local error
// test (IDASetSuppressAlg): an index-2 DAE's multipliers are not controlled to the
// accuracy of the state, and need not be — the forces that matter are recomputed from
// (q, v) by the observers.
#include <idas/idas.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrators/integrator_common.hpp"
#include "lub/integrators/integrator.hpp"

namespace lub {

namespace {

using detail::CallbackData;
using detail::err_cb;
using detail::guarded;

struct FreeIda {
  void operator()(void* mem) const { IDAFree(&mem); }
};

int res_cb(sunrealtype t, N_Vector Y, N_Vector Yp, N_Vector F, void* user) {
  auto* d = static_cast<CallbackData*>(user);
  return guarded(d, "DAE residual", [&] {
    return d->sys->residual(t, N_VGetArrayPointer(Y), N_VGetArrayPointer(Yp), N_VGetArrayPointer(F));
  });
}

// The system's iteration matrix ∂F/∂Y + cj ∂F/∂Y' into SUNDIALS' dense matrix
// (column-major, leading dimension n: IDA's quadratures are not part of the system).
int ida_jac_cb(sunrealtype t, sunrealtype cj, N_Vector Y, N_Vector Yp, N_Vector /*rr*/, SUNMatrix J, void* user,
               N_Vector, N_Vector, N_Vector) {
  auto* d = static_cast<CallbackData*>(user);
  return guarded(d, "DAE Jacobian", [&] {
    const int rc = d->sys->dae_jacobian(t, cj, N_VGetArrayPointer(Y), N_VGetArrayPointer(Yp), SUNDenseMatrix_Data(J));
    if (rc == -1 && d->error.empty()) d->error = "DAE Jacobian: the system provides none (use difference quotients)";
    return rc;
  });
}

int ida_root_cb(sunrealtype t, N_Vector Y, N_Vector /*Yp*/, sunrealtype* g, void* user) {
  auto* d = static_cast<CallbackData*>(user);
  return guarded(d, "root function", [&] { return d->sys->roots(t, N_VGetArrayPointer(Y), g); });
}

int ida_quad_cb(sunrealtype t, N_Vector Y, N_Vector /*Yp*/, N_Vector qdot, void* user) {
  auto* d = static_cast<CallbackData*>(user);
  return guarded(d, "quadrature", [&] {
    return d->sys->quadrature_rhs(t, N_VGetArrayPointer(Y), N_VGetArrayPointer(qdot));
  });
}

class IdaIntegrator final : public Integrator {
 public:
  IdaIntegrator(const IntegratorSettings& s, OdeSystem& sys, double t0, const std::vector<double>& y0) {
    data_.sys = &sys;
    data_.n = sys.size();
    if (sys.num_algebraic() <= 0) throw std::runtime_error("ida: the system has no DAE form");
    ctx_ = detail::new_context();
    const sunindextype n = sys.size() + sys.num_algebraic();
    Y_ = N_VNew_Serial(n, ctx_);
    Yp_ = N_VNew_Serial(n, ctx_);
    dky_ = N_VNew_Serial(n, ctx_);
    consistent(t0, y0.data());
    atol_ = N_VNew_Serial(n, ctx_);
    for (int i = 0; i < data_.n; ++i) NV_Ith_S(atol_, i) = s.atol[static_cast<size_t>(i)];
    sys.algebraic_tolerances(s.rtol, *std::min_element(s.atol.begin(), s.atol.end()),
                             N_VGetArrayPointer(atol_) + data_.n);
    id_ = N_VNew_Serial(n, ctx_);
    for (sunindextype i = 0; i < n; ++i) NV_Ith_S(id_, i) = i < data_.n ? 1.0 : 0.0;
    mem_ = IDACreate(ctx_);
    if (!mem_) throw std::runtime_error("IDACreate failed");
    check(IDASetErrHandlerFn(mem_, err_cb, &data_), "IDASetErrHandlerFn");
    check(IDAInit(mem_, res_cb, t0, Y_, Yp_), "IDAInit");
    check(IDASetUserData(mem_, &data_), "IDASetUserData");
    check(IDASVtolerances(mem_, s.rtol, atol_), "IDASVtolerances");
    check(IDASetId(mem_, id_), "IDASetId");
    check(IDASetSuppressAlg(mem_, SUNTRUE), "IDASetSuppressAlg");
    if (s.max_step > 0) check(IDASetMaxStep(mem_, s.max_step), "IDASetMaxStep");
    if (s.initial_step > 0) check(IDASetInitStep(mem_, s.initial_step), "IDASetInitStep");
    if (s.max_order > 0) check(IDASetMaxOrd(mem_, s.max_order), "IDASetMaxOrd");
    t_stop_ = s.t_stop;
    rtol_ = s.rtol;
    check(IDASetStopTime(mem_, s.t_stop), "IDASetStopTime");
    A_ = SUNDenseMatrix(n, n, ctx_);
    ls_ = SUNLinSol_Dense(Y_, A_, ctx_);
    check(IDASetLinearSolver(mem_, ls_, A_), "IDASetLinearSolver");
    if (s.user_jacobian) check(IDASetJacFn(mem_, ida_jac_cb), "IDASetJacFn");
    if (sys.num_roots() > 0) {
      check(IDARootInit(mem_, sys.num_roots(), ida_root_cb), "IDARootInit");
      IDASetNoInactiveRootWarn(mem_);
    }
    if (sys.num_quadratures() > 0) {
      q_ = N_VNew_Serial(sys.num_quadratures(), ctx_);
      N_VConst(0.0, q_);
      check(IDAQuadInit(mem_, ida_quad_cb, q_), "IDAQuadInit");
    }
  }

  StepOutcome step(double& t) override {
    sunrealtype tret = 0;
    const int flag = IDASolve(mem_, t_stop_, &tret, Y_, Yp_, IDA_ONE_STEP);
    t = tret;
    if (flag == IDA_ROOT_RETURN) return StepOutcome::root;
    if (flag < 0) {
      if (data_.error.empty()) {
        char* name = IDAGetReturnFlagName(flag);
        data_.error = std::string("IDASolve returned ") + (name ? name : "an error");
        free(name);
      }
      return StepOutcome::failure;
    }
    return StepOutcome::step;
  }

  bool dense(double t, int k, double* out) override {
    if (IDAGetDky(mem_, t, k, dky_) != IDA_SUCCESS) return false;
    std::copy(N_VGetArrayPointer(dky_), N_VGetArrayPointer(dky_) + data_.n, out);
    return true;
  }

  void quadratures(double* out) override {
    if (!q_) return;
    sunrealtype tret;
    IDAGetQuad(mem_, &tret, q_);
    for (sunindextype i = 0; i < N_VGetLength(q_); ++i) out[i] = NV_Ith_S(q_, i);
  }

  const double* y() const override { return N_VGetArrayPointer(Y_); }

  void statistics(IntegratorStats& s) const override {
    long v = 0;
    IDAGetNumSteps(mem_, &v); s.steps = v;
    IDAGetNumResEvals(mem_, &v); s.rhs_evals = v;
    IDAGetNumErrTestFails(mem_, &v); s.error_test_fails = v;
    IDAGetNumNonlinSolvIters(mem_, &v); s.nonlinear_iters = v;
    IDAGetNumNonlinSolvConvFails(mem_, &v); s.nonlinear_conv_fails = v;
    IDAGetNumGEvals(mem_, &v); s.root_evals = v;
    IDAGetNumJacEvals(mem_, &v); s.jacobian_evals = v;
    IDAGetNumLinResEvals(mem_, &v); s.rhs_evals_jacobian = v;
    IDAGetNumLinSolvSetups(mem_, &v); s.linear_setups = v;
    s += base_;
  }

  std::string error_message() const override { return data_.error; }
  void clear_error() override { data_.error.clear(); }

  void root_flags(std::vector<int>& flags) override {
    flags.assign(static_cast<size_t>(data_.sys->num_roots()), 0);
    if (!flags.empty()) IDAGetRootInfo(mem_, flags.data());
  }

  void set_root_directions(const std::vector<int>& dirs) override {
    if (dirs.empty()) return;
    std::vector<int> d(dirs);
    check(IDASetRootDirection(mem_, d.data()), "IDASetRootDirection");
  }

  void reinit(double t, const double* y) override {
    IntegratorStats total;
    statistics(total);
    base_ = total;
    if (q_) check(IDAGetQuadDky(mem_, t, 0, q_), "IDAGetQuadDky");
    // y may alias Y_ (the run loop passes y()): copy it before Y_ is rewritten.
    std::vector<double> state(y, y + data_.n);
    consistent(t, state.data());
    check(IDAReInit(mem_, t, Y_, Yp_), "IDAReInit");
    if (q_) check(IDAQuadReInit(mem_, q_), "IDAQuadReInit");
    check(IDASetStopTime(mem_, t_stop_), "IDASetStopTime");
  }

  void set_stop_time(double t_stop) override {
    t_stop_ = t_stop;
    check(IDASetStopTime(mem_, t_stop_), "IDASetStopTime");
  }

  void set_abs_tolerances(const std::vector<double>& atol) override {
    for (int i = 0; i < data_.n; ++i) NV_Ith_S(atol_, i) = atol[static_cast<size_t>(i)];
    check(IDASVtolerances(mem_, rtol_, atol_), "IDASVtolerances");
  }

 private:
  // (Y, Y') from the state: the multipliers and derivatives that go with it (after a
  // mode switch the set of active constraints has changed).
  void consistent(double t, const double* y) {
    const int rc = data_.sys->consistent_state(t, y, N_VGetArrayPointer(Y_), N_VGetArrayPointer(Yp_));
    if (rc != 0)
      throw std::runtime_error("ida: no consistent initial state at t = " + std::to_string(t) +
                               " s (the model cannot be evaluated there)");
  }

  void check(int flag, const char* what) {
    if (flag != 0) throw std::runtime_error(std::string(what) + " failed: " + data_.error);
  }

  double t_stop_ = 0.0;
  double rtol_ = 0.0;
  IntegratorStats base_;  // counters accumulated before the last reinit
  CallbackData data_;
  // Owned handles, in the order they must outlive each other (destroyed bottom-up).
  detail::OwnedContext ctx_;
  detail::OwnedVector Y_, Yp_, dky_, atol_, id_, q_;
  detail::OwnedMatrix A_;
  detail::OwnedLinearSolver ls_;
  detail::Owned<void*, FreeIda> mem_;
};

}  // namespace

std::unique_ptr<Integrator> make_ida_integrator(const IntegratorSettings& settings, OdeSystem& sys, double t0,
                                                const std::vector<double>& y0) {
  return std::make_unique<IdaIntegrator>(settings, sys, t0, y0);
}

}  // namespace lub
