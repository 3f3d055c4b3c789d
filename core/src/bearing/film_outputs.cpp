// Friction torques of a film: see lub/bearing/film_outputs.hpp.
#include "lub/bearing/film_outputs.hpp"

#include <algorithm>
#include <cmath>

#include "bearing/film_math.hpp"
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

void short_bearing_flows(const BearingGeometry& g, double eps, double wedge_rad_s, FilmOutputs& out) {
  const double c = g.clearance_m(), U = g.journal_radius_m * std::abs(wedge_rad_s) * g.length_m;
  out.inflow_m3_s = 0.5 * U * c * (1.0 + eps);
  out.side_flow_m3_s = U * c * eps;
}

double film_pressure_Pa(ForceLaw law, const BearingGeometry& g, double viscosity_Pa_s, const BearingState& s,
                        double theta) {
  switch (law) {
    case ForceLaw::frene_short: return pressure_short(g, viscosity_Pa_s, s, theta, 0.0);
    case ForceLaw::gumbel_short: return std::max(0.0, pressure_short(g, viscosity_Pa_s, s, theta, 0.0));
    case ForceLaw::pinkus_sternlicht:
    case ForceLaw::pinkus_sternlicht_continuous: return pressure_pi_film(g, viscosity_Pa_s, s, theta);
    case ForceLaw::gumbel_long: return std::max(0.0, pressure_long(g, viscosity_Pa_s, s, theta));
    default: return pressure_long(g, viscosity_Pa_s, s, theta);
  }
}

PeakPressure peak_film_pressure(ForceLaw law, const BearingGeometry& g, double viscosity_Pa_s,
                                const BearingState& s) {
  const auto field = [&](double theta) { return film_pressure_Pa(law, g, viscosity_Pa_s, s, theta); };
  const double beta = detail::kepler_beta(s.eps, std::sqrt((1.0 - s.eps) * (1.0 + s.eps)));
  const auto at = [&](double psi) { return field(detail::theta_of_psi(psi, beta)); };
  constexpr int kSamples = 64;
  const double dpsi = kTwoPi / kSamples;
  int best = 0;
  double pbest = at(0.0);
  for (int i = 1; i < kSamples; ++i)
    if (const double p = at(i * dpsi); p > pbest) pbest = p, best = i;
  PeakPressure out;
  if (!(pbest > 0.0)) return out;
  // Golden section on [ψ_best − Δψ, ψ_best + Δψ] (the maximum of a smooth field lies there).
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = (best - 1) * dpsi, b = (best + 1) * dpsi;
  double x1 = b - r * (b - a), x2 = a + r * (b - a), f1 = at(x1), f2 = at(x2);
  while (b - a > 1e-9) {
    if (f1 > f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - r * (b - a), f1 = at(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + r * (b - a), f2 = at(x2);
    }
  }
  const double psi = f1 > f2 ? x1 : x2;
  out.pressure_Pa = std::max(pbest, std::max(f1, f2));
  const double th = out.pressure_Pa == pbest ? detail::theta_of_psi(best * dpsi, beta) : detail::theta_of_psi(psi, beta);
  out.angle_rad = th - kTwoPi * std::floor(th / kTwoPi);
  return out;
}

}  // namespace lub
