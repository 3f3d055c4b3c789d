// Friction torques of a film: see lub/bearing/film_outputs.hpp.
#include "lub/bearing/film_outputs.hpp"

#include <cmath>

#include "lub/common/constants.hpp"

namespace lub {

double petroff_torque_Nm(double viscosity_Pa_s, double sliding_rad_s, double radius_m, double length_m,
                         double clearance_m) {
  return kTwoPi * viscosity_Pa_s * sliding_rad_s * radius_m * radius_m * radius_m * length_m / clearance_m;
}

FrictionTorques film_friction_torques(const BearingGeometry& g, double viscosity_Pa_s, double eps,
                                      double sliding_rad_s, double tangential_N) {
  const double c = g.clearance_m();
  // Couette over the whole clearance: Petroff / (1 − ε²)^(1/2), 1 − ε² formed as (1 − ε)(1 + ε).
  const double couette = petroff_torque_Nm(viscosity_Pa_s, sliding_rad_s, g.journal_radius_m, g.length_m, c) /
                         std::sqrt((1.0 - eps) * (1.0 + eps));
  const double pressure = 0.5 * c * eps * tangential_N;
  return {couette + pressure, couette - pressure};
}

}  // namespace lub
