// Callback plumbing shared by the SUNDIALS adapters (internal to lubcore): no C++
// exception crosses into SUNDIALS; callbacks catch, record the message and return −1.
#pragma once

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_nonlinearsolver.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "common/sundials_owned.hpp"
#include "lub/integrators/integrator.hpp"

namespace lub::detail {

struct SensitivityData;  // integrator_cvode.cpp: forward sensitivities, where started

struct CallbackData {
  OdeSystem* sys = nullptr;
  SensitivityData* sens = nullptr;
  int n = 0;         ///< ODE size (quadratures appended after it by ARKODE)
  int nquad = 0;     ///< quadratures integrated as extra states (ARKODE)
  std::string error; ///< SUNDIALS' first error text, or an exception's
  std::vector<double> jac;  ///< n × n scratch for the system's Jacobian when nquad > 0
};

template <class F>
int guarded(CallbackData* d, const char* where, F&& f) {
  try {
    return f();
  } catch (const std::exception& e) {
    d->error = std::string(where) + ": " + e.what();
  } catch (...) {
    d->error = std::string(where) + ": unknown exception";
  }
  return -1;
}

inline int rhs_cb(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto* d = static_cast<CallbackData*>(user);
  return guarded(d, "right-hand side", [&] {
    double* yy = N_VGetArrayPointer(y);
    double* yd = N_VGetArrayPointer(ydot);
    const int rc = d->sys->rhs(t, yy, yd);
    if (rc != 0 || d->nquad == 0) return rc;
    return d->sys->quadrature_rhs(t, yy, yd + d->n);
  });
}

inline int root_cb(sunrealtype t, N_Vector y, sunrealtype* g, void* user) {
  auto* d = static_cast<CallbackData*>(user);
  return guarded(d, "root function", [&] { return d->sys->roots(t, N_VGetArrayPointer(y), g); });
}

inline int quad_cb(sunrealtype t, N_Vector y, N_Vector qdot, void* user) {
  auto* d = static_cast<CallbackData*>(user);
  return guarded(d, "quadrature", [&] {
    return d->sys->quadrature_rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(qdot));
  });
}

inline int proj_cb(sunrealtype t, N_Vector y, N_Vector corr, sunrealtype /*eps*/, N_Vector err, void* user) {
  auto* d = static_cast<CallbackData*>(user);
  return guarded(d, "projection", [&] {
    return d->sys->project(t, N_VGetArrayPointer(y), N_VGetArrayPointer(corr),
                           err ? N_VGetArrayPointer(err) : nullptr);
  });
}

// The system's Jacobian into SUNDIALS' dense matrix (column-major, leading dimension
// n + nquad). Quadratures integrated as states (ARKODE) feed back into nothing: their
// columns are zero, and so are their rows (∂q̇/∂y is left out: the Newton iteration then
// converges the quadratures one iteration behind the states they depend on).
inline int jac_cb(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void* user, N_Vector, N_Vector,
                  N_Vector) {
  auto* d = static_cast<CallbackData*>(user);
  return guarded(d, "Jacobian", [&] {
    double* out = SUNDenseMatrix_Data(J);
    const int n = d->n;
    int rc = 0;
    if (d->nquad == 0) {
      rc = d->sys->jacobian(t, N_VGetArrayPointer(y), N_VGetArrayPointer(fy), out);
    } else {
      rc = d->sys->jacobian(t, N_VGetArrayPointer(y), N_VGetArrayPointer(fy), d->jac.data());
      if (rc == 0) {
        const int ld = n + d->nquad;
        std::fill(out, out + static_cast<size_t>(ld) * ld, 0.0);
        for (int c = 0; c < n; ++c)
          std::copy(d->jac.data() + static_cast<size_t>(c) * n, d->jac.data() + static_cast<size_t>(c + 1) * n,
                    out + static_cast<size_t>(c) * ld);
      }
    }
    if (rc == -1 && d->error.empty()) d->error = "Jacobian: the system provides none (use difference quotients)";
    return rc;
  });
}

inline void err_cb(int /*code*/, const char* module, const char* function, char* msg, void* user) {
  auto* d = static_cast<CallbackData*>(user);
  if (!d->error.empty()) return;  // keep the first (root-cause) message
  d->error = std::string(module ? module : "") + "/" + (function ? function : "") + ": " + (msg ? msg : "");
}


}  // namespace lub::detail

namespace lub {
std::unique_ptr<Integrator> make_cvode_integrator(const IntegratorSettings&, OdeSystem&, double t0,
                                                  const std::vector<double>& y0);
std::unique_ptr<Integrator> make_arkode_integrator(const IntegratorSettings&, OdeSystem&, double t0,
                                                   const std::vector<double>& y0);
std::unique_ptr<Integrator> make_ida_integrator(const IntegratorSettings&, OdeSystem&, double t0,
                                                const std::vector<double>& y0);
}  // namespace lub
