#!/usr/bin/python3
"""Sensitivities of the paper's reference case (configs/scenes/slider_crank.json, steady auto)
by the implicit-function route (lubjoint.simulate(..., sensitivity=...), as lubsim
--sensitivity) against central differences of orbits located separately at the parameter
± 1 % (the bearing radius ± 1 % of the clearance, 5 µm: 1 % of the radius would change the
clearance by 20 %) (docs/validation/sensitivities.md). Prints a Markdown table.

    PYTHONPATH=build/python /usr/bin/python3 tools/docs/sensitivities.py      (~5 s)
"""
import os
import warnings

import lubjoint  # PYTHONPATH=build/python

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "configs", "scenes", "slider_crank.json")
BASE = {"/simulation/steady": "auto", "/outputs/channels": []}
# pointer, value, the central differences' relative step
PARAMETERS = [("/joints/3/viscosity_Pa_s", 0.4, 0.01), ("/drivers/0/speed_rpm", 5000.0, 0.01),
              ("/joints/3/bearing_radius_m", 0.010, 0.0005)]
METRICS = ["min_film_thickness_m", "max_eps", "peak_reaction_N", "peak_acceleration_m_s2", "film_power_loss_W"]


def main():
    warnings.simplefilter("ignore", lubjoint.ValidityNote)
    print("| parameter | metric | implicit function ± bar | central differences ± bar | difference / bound |")
    print("|---|---|---|---|---|")
    for pointer, value, step in PARAMETERS:
        key = pointer.lstrip("/").replace("/", "_")
        s = lubjoint.simulate(SCENE, BASE, sensitivity=[pointer])
        ends = [lubjoint.simulate(SCENE, {**BASE, pointer: value * f}) for f in (1.0 + step, 1.0 - step)]
        for k in METRICS:
            d, e = float(s[f"d_{k}_per_{key}"]), float(s[f"d_{k}_per_{key}_error"])
            cd = (float(ends[0][k]) - float(ends[1][k])) / (2.0 * step * value)
            ce = (float(ends[0][k + "_error"]) + float(ends[1][k + "_error"])) / (2.0 * step * value)
            bound = e + ce + 0.02 * abs(cd)
            units = s[f"d_{k}_per_{key}"].attrs["units"]
            print(f"| {pointer} | d {k} [{units}] | {d:.5g} ± {e:.2g} | {cd:.5g} ± {ce:.2g} | {abs(d - cd) / bound:.2f} |")


if __name__ == "__main__":
    main()
