// A steadily loaded journal bearing: the equilibrium of a journal turning at constant speed
// under a constant load, for any force law — the `lubbearing steady` computation.
//
// Journal speed ω (bearing at rest), load W [N] fixed in direction. At equilibrium the journal
// centre is at rest (ε̇ = 0, γ̇ = 0, so the wedge speed is w = ω) and the film force balances
// the load: |F(ε)| = W, solved for ε ∈ (0, 1) by bracketed secant/bisection on log |F| (|F|
// grows monotonically from 0 at ε = 0 to ∞ as ε → 1 for every law here). Then:
//   attitude angle φ = atan2(F_t, −F_r): the angle between the load line and the line of centres
//     (90° for the full-film laws, tan φ = π(1−ε²)^(1/2)/(4ε) for Ocvirk's π film, ...);
//   minimum film thickness h_min = c (1 − ε);
//   Sommerfeld number S = (R_J/c)² μ N/P, N = ω/(2π) [rev/s], P = W/(L D), D = 2R_J
//     (Raimondi & Boyd's definition);
//   friction (lub/bearing/film_outputs.hpp): the torque on the journal T_J, the friction
//     coefficient f = T_J/(R_J W), Raimondi & Boyd's friction variable (R_J/c) f and the power
//     loss T_J ω; the peak pressure of the law's field, its angle θ and P/p_max; for
//     finite_reynolds also the inflow Q, the side flow Q_s, the flow variable Q/(R_J c N L), Q_s/Q.
#pragma once

#include <cmath>
#include <string>

#include "lub/bearing/film_outputs.hpp"
#include "lub/bearing/force_laws.hpp"
#include "lub/common/constants.hpp"

namespace lub {

struct SteadyBearingInput {
  ForceLaw law = ForceLaw::gumbel_short;
  FiniteBearingOptions finite;  ///< for finite_reynolds
  BearingGeometry geometry;
  double viscosity_Pa_s = 0.0;
  double load_N = 0.0;        ///< W > 0
  double speed_rad_s = 0.0;   ///< ω ≠ 0 (journal, relative to the bearing)
};

struct SteadyBearingResult {
  bool converged = false;
  std::string message;       ///< why not, if not converged
  double eps = 0.0;
  double attitude_rad = 0.0;
  double min_film_thickness_m = 0.0;
  double sommerfeld = 0.0;
  FilmForce force;           ///< film force at the equilibrium (|F| = W)
  FilmOutputs outputs;       ///< friction, peak pressure (every law); flows (has_flows)
  bool has_field = false;    ///< finite_reynolds
  bool has_flows = false;    ///< the outputs' flows are set (finite_reynolds, the short-bearing laws)
  int evaluations = 0;       ///< force-law evaluations
};

/// Equilibrium of the steadily loaded bearing. Requires positive geometry, viscosity and
/// load and a non-zero speed (the caller validates).
SteadyBearingResult solve_steady_bearing(const SteadyBearingInput& in);

/// Sommerfeld number S = (R_J/c)² μ N/P of a bearing (N = ω/(2π), P = W/(2 R_J L)).
double sommerfeld_number(const BearingGeometry& g, double viscosity_Pa_s, double load_N,
                         double speed_rad_s);

/// The report of one steady bearing, written into any map-like `out` (out["key"] = value:
/// `lubbearing steady`'s JSON, the Python module's dict): the load and speed, the
/// Sommerfeld number, whether it converged, then either the message or ε, the attitude
/// angle [deg], h_min [m], the film force [N] and the force-law evaluations. One list of
/// keys, so the program and the module report the same thing.
template <class Out>
void report_steady_bearing(Out& out, const SteadyBearingInput& in, double speed_rpm, const SteadyBearingResult& r) {
  out["load_N"] = in.load_N;
  out["speed_rpm"] = speed_rpm;
  out["sommerfeld_number"] = sommerfeld_number(in.geometry, in.viscosity_Pa_s, in.load_N, in.speed_rad_s);
  out["converged"] = r.converged;
  if (!r.converged) {
    out["message"] = r.message;
    return;
  }
  out["eps"] = r.eps;
  out["attitude_angle_deg"] = r.attitude_rad * 180.0 / kPi;
  out["min_film_thickness_m"] = r.min_film_thickness_m;
  out["radial_N"] = r.force.radial_N;
  out["tangential_N"] = r.force.tangential_N;
  const double R = in.geometry.journal_radius_m, c = in.geometry.clearance_m(), L = in.geometry.length_m;
  const FilmOutputs& o = r.outputs;
  out["friction_torque_Nm"] = o.journal_friction_torque_Nm;
  out["friction_coefficient"] = o.journal_friction_torque_Nm / (R * in.load_N);
  out["friction_variable"] = (R / c) * o.journal_friction_torque_Nm / (R * in.load_N);
  out["power_loss_W"] = o.journal_friction_torque_Nm * in.speed_rad_s;
  out["peak_pressure_Pa"] = o.peak_pressure_Pa;
  out["peak_pressure_angle_deg"] = o.peak_pressure_angle_rad * 180.0 / kPi;
  out["load_over_peak_pressure"] = in.load_N / (L * 2.0 * R) / o.peak_pressure_Pa;
  if (r.has_flows) {
    const double n_rev = std::fabs(in.speed_rad_s) / kTwoPi;
    out["inflow_m3_s"] = o.inflow_m3_s;
    out["side_flow_m3_s"] = o.side_flow_m3_s;
    out["flow_variable"] = o.inflow_m3_s / (R * c * n_rev * L);
    out["side_flow_ratio"] = o.side_flow_m3_s / o.inflow_m3_s;
  }
  out["force_law_evaluations"] = r.evaluations;
}

}  // namespace lub
