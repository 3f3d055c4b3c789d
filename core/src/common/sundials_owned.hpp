// Ownership of SUNDIALS handles, shared by the stages that call SUNDIALS (integrators:
// CVODES, ARKODE, IDAS; steady: KINSOL). Header-only; each stage links the SUNDIALS
// libraries it uses.
#pragma once

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_nonlinearsolver.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <memory>
#include <stdexcept>
#include <type_traits>

namespace lub::detail {

// --- Ownership of SUNDIALS handles ------------------------------------------------------
// Each handle an adapter creates is held by an Owned<> member from the moment it exists,
// so it is freed whether the adapter's constructor completes or throws half-way (a failed
// Set call, an inconsistent initial state). Members are destroyed in reverse declaration
// order: declare the context first and the integrator memory last (the memory refers to
// the solvers and vectors, everything to the context).

/// A unique_ptr to a SUNDIALS handle type H (a pointer type), freed by `Free`, that reads
/// as the raw handle where SUNDIALS' C API wants one.
template <class H, class Free>
class Owned {
 public:
  Owned() = default;
  Owned& operator=(H raw) {
    p_.reset(raw);
    return *this;
  }
  operator H() const { return p_.get(); }  // NOLINT: passes as the handle to the C API
  H operator->() const { return p_.get(); }
  H get() const { return p_.get(); }

 private:
  std::unique_ptr<std::remove_pointer_t<H>, Free> p_;
};

struct FreeContext {
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};
struct FreeVector {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct FreeMatrix {
  void operator()(SUNMatrix a) const { SUNMatDestroy(a); }
};
struct FreeLinearSolver {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
struct FreeNonlinearSolver {
  void operator()(SUNNonlinearSolver s) const { SUNNonlinSolFree(s); }
};
using OwnedContext = Owned<SUNContext, FreeContext>;
using OwnedVector = Owned<N_Vector, FreeVector>;
using OwnedMatrix = Owned<SUNMatrix, FreeMatrix>;
using OwnedLinearSolver = Owned<SUNLinearSolver, FreeLinearSolver>;
using OwnedNonlinearSolver = Owned<SUNNonlinearSolver, FreeNonlinearSolver>;

/// A new SUNDIALS context (throws if it cannot be created).
inline SUNContext new_context() {
  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0) throw std::runtime_error("SUNContext_Create failed");
  return ctx;
}

}  // namespace lub::detail
