#include <stdexcept>

#include "integrators/integrator_common.hpp"

namespace lub {

std::unique_ptr<Integrator> make_integrator(const IntegratorSettings& settings, OdeSystem& sys, double t0,
                                            const std::vector<double>& y0) {
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
  throw std::logic_error("make_integrator: unknown method");
}

}  // namespace lub
