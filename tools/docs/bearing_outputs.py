#!/usr/bin/python3
"""The finite bearing's friction, flow and peak pressure against Raimondi & Boyd (1958), Table 1
(full journal bearing, Swift-Stieber rupture, supply at ambient pressure along the line of
maximum film), L/D = 1, 1/2, 1/4 (docs/validation/bearing-outputs.md): each row's load from the
tabulated Sommerfeld number, solved by `lubbearing steady` (finite_reynolds, 192 x 24, groove),
and its friction variable (R/c) f, flow variable Q/(R c N L), side-flow ratio Q_s/Q and P/p_max
beside the table's. Prints a Markdown table.

With --energy instead: the paper's slider-crank (configs/scenes/slider_crank.json, 3 cycles
from the centred start, rtol 1e-9) with and without effects.film_friction, each law's energy
balance W_driver = ΔE + D_film and its mean film power loss.

    PYTHONPATH=build/python /usr/bin/python3 tools/docs/bearing_outputs.py      (~5 s)
    PYTHONPATH=build/python /usr/bin/python3 tools/docs/bearing_outputs.py --energy   (~2 s)
"""
import sys

import lubjoint.bearing  # noqa: E402  PYTHONPATH=build/python
import lubjoint.run

RADIUS, CLEARANCE, MU, RPM = 0.025, 50e-6, 0.05, 3000.0
# eps, S, (R/c) f, Q/(RcNL), Qs/Q, P/pmax: Raimondi & Boyd (1958) Table 1, as reproduced in
# Shigley's Mechanical Engineering Design, Table 12-4.
TABLE = {
    1.0: [(0.1, 1.33, 26.4, 3.37, 0.150, 0.540), (0.2, 0.631, 12.8, 3.59, 0.280, 0.529),
          (0.4, 0.264, 5.79, 3.99, 0.497, 0.484), (0.6, 0.121, 3.22, 4.33, 0.680, 0.415),
          (0.8, 0.0446, 1.70, 4.62, 0.842, 0.313), (0.9, 0.0188, 1.05, 4.74, 0.919, 0.247),
          (0.97, 0.00474, 0.514, 4.82, 0.973, 0.152)],
    0.5: [(0.1, 4.31, 85.6, 3.43, 0.173, 0.523), (0.2, 2.03, 40.9, 3.72, 0.318, 0.506),
          (0.4, 0.779, 17.0, 4.29, 0.552, 0.441), (0.6, 0.319, 8.10, 4.85, 0.730, 0.365),
          (0.8, 0.0923, 3.26, 5.41, 0.874, 0.267), (0.9, 0.0313, 1.60, 5.69, 0.939, 0.206),
          (0.97, 0.00609, 0.610, 5.88, 0.980, 0.126)],
    0.25: [(0.1, 16.2, 322.0, 3.45, 0.180, 0.515), (0.2, 7.57, 153.0, 3.76, 0.330, 0.489),
           (0.4, 2.83, 61.1, 4.37, 0.567, 0.415), (0.6, 1.07, 26.7, 4.99, 0.746, 0.334),
           (0.8, 0.261, 8.80, 5.60, 0.884, 0.240), (0.9, 0.0736, 3.50, 5.91, 0.945, 0.180),
           (0.97, 0.0101, 0.922, 6.12, 0.984, 0.108)],
}


def main():
    print("| L/D | ε table / ours | (R/c) f ours / table | Q/(RcNL) ours / table | Q_s/Q ours / table "
          "| P/p_max ours / table |")
    print("|---|---|---|---|---|---|")
    n_rev = RPM / 60.0
    for ld, rows in TABLE.items():
        length = ld * 2.0 * RADIUS
        for eps, S, f, q, qs, pr in rows:
            pressure = (RADIUS / CLEARANCE) ** 2 * MU * n_rev / S
            r = lubjoint.bearing.steady_bearing(
                "finite_reynolds", load_N=pressure * 2.0 * RADIUS * length, speed_rpm=RPM, radius_m=RADIUS,
                clearance_m=CLEARANCE, length_m=length, viscosity_Pa_s=MU, n_theta=192, n_z=24,
                groove_at_max_film=True)
            print(f"| {ld:g} | {eps:g} / {r['eps']:.3f} | {r['friction_variable']:.3g} / {f:g} | "
                  f"{r['flow_variable']:.3g} / {q:g} | {r['side_flow_ratio']:.3g} / {qs:g} | "
                  f"{r['load_over_peak_pressure']:.3g} / {pr:g} |")


def energy():
    print("| law | film_friction | W_driver [J] | ΔE [J] | D_film [J] | residual / W_driver "
          "| D_film / t [W] | mean power loss [W] |")
    print("|---|---|---|---|---|---|---|---|")
    for law in ("frene_long", "frene_short", "pinkus_sternlicht"):
        for friction in (False, True):
            over = {"/joints/3/force_law": law, "/solver/rtol": 1e-9, "/simulation/max_cycles": 3,
                    "/simulation/metric_cycles": 3, "/simulation/steady": "transient",
                    "/outputs/channels": [], "/outputs/energy_balance": True}
            if friction:
                over["/effects/film_friction"] = {}
            r = lubjoint.run.simulate("configs/scenes/slider_crank.json", over)
            w, de, d = (float(r[k]) for k in ("driver_work_J", "energy_change_J", "film_dissipation_J"))
            t = float(r["final_time_s"])
            print(f"| {law} | {'yes' if friction else 'no'} | {w:.5g} | {de:.3g} | {d:.5g} | "
                  f"{float(r['energy_residual_J']) / w:.1e} | {d / t:.5g} | {float(r['film_power_loss_W']):.5g} |")


if __name__ == "__main__":
    energy() if "--energy" in sys.argv[1:] else main()
