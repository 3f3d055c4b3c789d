// Steadily loaded bearing: see lub/bearing/steady_bearing.hpp.
#include "lub/bearing/steady_bearing.hpp"

#include <cmath>
#include <sstream>

#include "bearing/film_math.hpp"
#include "lub/bearing/film_force.hpp"
#include "lub/bearing/law_validity.hpp"

namespace lub {

double sommerfeld_number(const BearingGeometry& g, double viscosity_Pa_s, double load_N,
                         double speed_rad_s) {
  const double rc = g.journal_radius_m / g.clearance_m();
  const double n_rev = std::fabs(speed_rad_s) / kTwoPi;
  const double p = load_N / (2.0 * g.journal_radius_m * g.length_m);
  return rc * rc * viscosity_Pa_s * n_rev / p;
}

SteadyBearingResult solve_steady_bearing(const SteadyBearingInput& in) {
  SteadyBearingResult res;
  FiniteBearingSolver solver(in.finite);
  const auto force = [&](double eps) {
    ++res.evaluations;
    BearingState s;
    s.eps = eps;
    s.eps_dot = 0.0;
    s.wedge = in.speed_rad_s;
    return film_force(in.law, in.geometry, in.viscosity_Pa_s, s, &solver);
  };
  // f(ε) = log|F(ε)| − log W, increasing; bracket in (0, 1).
  const double logw = std::log(in.load_N);
  const auto f = [&](double eps) {
    const FilmForce F = force(eps);
    return std::log(std::hypot(F.radial_N, F.tangential_N)) - logw;
  };
  // Upper bracket: walk 1 − ε down by decades from 0.9 (the finite solver's grid does not
  // resolve films thinner than about c(1 − ε) ~ 1e-6 c, so do not start at the wall).
  double lo = 1e-6, hi = 0.9;
  double flo = f(lo), fhi = f(hi);
  while (!(fhi > 0.0) && hi < 1.0 - 2e-9) {
    if (fhi < 0.0) {
      lo = hi;
      flo = fhi;
    }
    hi = 1.0 - 0.1 * (1.0 - hi);
    fhi = f(hi);
  }
  if (!(flo < 0.0)) {
    std::ostringstream msg;
    msg << "the load " << in.load_N << " N is carried at eps <= " << lo
        << ": the bearing is practically centred (load too small for this speed)";
    res.message = msg.str();
    return res;
  }
  if (!(fhi > 0.0)) {
    std::ostringstream msg;
    msg << "the film cannot carry " << in.load_N << " N at this speed (eps -> 1)";
    res.message = msg.str();
    return res;
  }
  // Illinois (modified regula falsi) in ε with bisection safeguard.
  double x = 0.5 * (lo + hi);
  int side = 0;
  for (int it = 0; it < 200; ++it) {
    x = (lo * fhi - hi * flo) / (fhi - flo);
    if (!(x > lo && x < hi) || it % 8 == 7) x = 0.5 * (lo + hi);
    const double fx = f(x);
    if (fx == 0.0) {
      lo = hi = x;
      break;
    }
    if ((fx < 0.0) == (flo < 0.0)) {
      lo = x;
      flo = fx;
      if (side == -1) fhi *= 0.5;
      side = -1;
    } else {
      hi = x;
      fhi = fx;
      if (side == 1) flo *= 0.5;
      side = 1;
    }
    if (hi - lo <= 1e-14 * hi) break;
  }
  res.eps = 0.5 * (lo + hi);
  res.force = force(res.eps);
  res.converged = true;
  res.attitude_rad = std::atan2(res.force.tangential_N * (in.speed_rad_s < 0.0 ? -1.0 : 1.0),
                                -res.force.radial_N);
  res.min_film_thickness_m = in.geometry.clearance_m() * (1.0 - res.eps);
  res.sommerfeld = sommerfeld_number(in.geometry, in.viscosity_Pa_s, in.load_N, in.speed_rad_s);
  // Friction and peak pressure for every law (its F_t, its field); flows from the finite
  // bearing's field and the short-bearing laws' own.
  res.has_field = in.law == ForceLaw::finite_reynolds;
  res.has_flows = res.has_field || is_short_bearing_law(in.law);
  if (res.has_field) {
    res.outputs = solver.outputs(in.speed_rad_s);
  } else {
    const FrictionTorques t = film_friction_torques(in.geometry, in.viscosity_Pa_s, res.eps, in.speed_rad_s,
                                                    res.force.tangential_N);
    res.outputs.journal_friction_torque_Nm = t.journal_Nm;
    res.outputs.bearing_friction_torque_Nm = t.bearing_Nm;
    BearingState s;
    s.eps = res.eps;
    s.wedge = in.speed_rad_s;
    const PeakPressure peak = peak_film_pressure(in.law, in.geometry, in.viscosity_Pa_s, s);
    res.outputs.peak_pressure_Pa = peak.pressure_Pa;
    res.outputs.peak_pressure_angle_rad = peak.angle_rad;
    if (res.has_flows) short_bearing_flows(in.geometry, res.eps, in.speed_rad_s, res.outputs);
  }
  return res;
}

}  // namespace lub
