#include "integrators/integrator_common.hpp"
#include "lub/common/check.hpp"

namespace lub {

std::unique_ptr<Integrator> make_integrator(const IntegratorSettings& settings, OdeSystem& sys, double t0,
                                            const std::vector<double>& y0) {
  LUB_ASSERT(static_cast<int>(y0.size()) == sys.size(), "initial state of another size than the system");
  LUB_ASSERT(static_cast<int>(settings.atol.size()) == sys.size(), "absolute tolerances of another size than the system");
  switch (settings.method) {
    case Method::cvode_adams:
    case Method::cvode_bdf:
      return make_cvode_integrator(settings, sys, t0, y0);
    case Method::arkode_erk:
    case Method::arkode_dirk:
      return make_arkode_integrator(settings, sys, t0, y0);
    case Method::ida:
      return make_ida_integrator(settings, sys, t0, y0);
  }
  throw InternalError("make_integrator: unknown method");
}

}  // namespace lub
