// What a bearing engineer reads besides the film force: the film's friction torque, the oil
// flow and the peak film pressure (docs/theory/bearing-outputs.md).
//
// ## Friction
// The shear stress of the film on the journal surface, resisting its rotation relative to the
// bearing, is τ_J = μ U/h + (h/2) ∂p/∂x (Couette and pressure-gradient parts), U = R_J ω_s
// the sliding speed, ω_s = ω_J − ω_B [rad/s], x = R_J θ. Over the film, with h = c(1 + ε cos θ)
// and integrating the second part by parts (p periodic, or zero where the film ruptures):
//     T_J = μ ω_s R_J³ L/c · I_c + (c ε/2) F_t,      T_B = μ ω_s R_J³ L/c · I_c − (c ε/2) F_t,
//     I_c = (1/L) ∫∫_film dθ dz / (1 + ε cos θ)      (2π/(1 − ε²)^(1/2) over a full film),
// T_J [N m] the torque on the journal against ω_s, T_B the torque on the bearing along it
// (T_J − T_B = e F_t: the film's moment balance), F_t the tangential film force. At ε = 0:
// Petroff's T = 2π μ ω_s R_J³ L/c. The Couette part is taken over the whole clearance for every
// law, ruptured films included, as Raimondi & Boyd (1958) do (their friction variable is
// reproduced to 1 % by the finite bearing so), so the torque needs only ε, ω_s and F_t.
//
// ## Flow
// Per unit width, q_x = R_J w h/2 − h³/(12μ) ∂p/∂x circumferentially (w the wedge speed,
// relative to the line of centres) and q_z = −h³/(12μ) ∂p/∂z axially [m²/s]:
//     inflow  Q   = ∫ q_x dz across the line of maximum film θ = 0 (the supply groove),
//     side flow Q_s = ∫ q_z R_J dθ out of both ends.
// At ε = 0: Q = π R_J c N L (N = w/(2π)), Q_s = 0.
// The short-bearing laws have no circumferential pressure flow: the Couette flow alone carries
// the film round, Q = R_J |w| c (1 + ε) L/2 at θ = 0, and what enters the pressurised half
// (θ from 0 to π) and does not leave it at θ = π leaves through the ends, Q_s = ε c R_J |w| L
// (short_bearing_flows; a steady load, ε̇ = 0).
//
// ## Peak pressure
// The largest pressure of the law's own field and its angle θ from the line of maximum film:
// Eq. (3) at the mid-plane for the short laws, Eq. (5) for the long ones, the π film (Eq. (5)
// less its value at the film start) for the Pinkus–Sternlicht laws; for finite_reynolds the
// solver's grid (FiniteBearingSolver::outputs). Located by sampling 64 points uniform in the
// eccentric anomaly ψ (they crowd where the film is thin) and golden-section search in ψ
// between the neighbours of the largest sample, to 1e-9 rad.
#pragma once

#include "lub/bearing/force_laws.hpp"

namespace lub {

struct FilmOutputs {
  double journal_friction_torque_Nm = 0.0;  ///< T_J, against the sliding ω_J − ω_B
  double bearing_friction_torque_Nm = 0.0;  ///< T_B, along it
  double peak_pressure_Pa = 0.0;            ///< largest film pressure (0 for no pressure)
  double peak_pressure_angle_rad = 0.0;     ///< θ there, from the line of maximum film, [0, 2π)
  double inflow_m3_s = 0.0;                 ///< Q across θ = 0
  double side_flow_m3_s = 0.0;              ///< Q_s out of both ends
};

/// Petroff's torque 2π μ ω_s R³ L/c [N m] of a centred journal.
double petroff_torque_Nm(double viscosity_Pa_s, double sliding_rad_s, double radius_m, double length_m,
                         double clearance_m);

struct PeakPressure {
  double pressure_Pa = 0.0;  ///< 0 where the field has no positive pressure
  double angle_rad = 0.0;    ///< θ, in [0, 2π)
};

/// The film pressure [Pa] of the closed-form law `law` (not finite_reynolds) at state `s`, at
/// angle θ [rad] from the line of maximum film, in the mid-plane: the field its force integrates
/// (Eq. (3), (5) or the π film, negative values included for the full-film laws; 0 where a
/// cavitated film has ruptured).
double film_pressure_Pa(ForceLaw law, const BearingGeometry& g, double viscosity_Pa_s, const BearingState& s,
                        double theta);

/// The peak of the closed-form law `law`'s pressure field at state `s` (not finite_reynolds:
/// its field is the solver's).
PeakPressure peak_film_pressure(ForceLaw law, const BearingGeometry& g, double viscosity_Pa_s, const BearingState& s);

struct FrictionTorques {
  double journal_Nm = 0.0, bearing_Nm = 0.0;  ///< T_J, T_B (above)
};

/// Inflow Q and side flow Q_s [m³/s] of a short-bearing law's film at ε with wedge speed w
/// [rad/s] under a steady load (above): into FilmOutputs' inflow_m3_s and side_flow_m3_s.
void short_bearing_flows(const BearingGeometry& g, double eps, double wedge_rad_s, FilmOutputs& out);

/// T_J and T_B of a film at eccentricity ratio ε (0 <= ε < 1), sliding speed ω_s = ω_J − ω_B
/// [rad/s] and tangential film force F_t [N] (the law's own).
FrictionTorques film_friction_torques(const BearingGeometry& g, double viscosity_Pa_s, double eps,
                                      double sliding_rad_s, double tangential_N);

}  // namespace lub
