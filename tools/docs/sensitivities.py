#!/usr/bin/python3
"""Sensitivities of the paper's reference case (configs/scenes/slider_crank.json, steady auto)
by the implicit-function route (lubsim --sensitivity) against central differences of orbits
located separately at the parameter ± 1 % (the bearing radius ± 1 % of the clearance, 5 µm: 1 % of
the radius would change the clearance by 20 %) (docs/validation/sensitivities.md). Prints a
Markdown table.

    PYTHONPATH=build/python /usr/bin/python3 tools/docs/sensitivities.py      (~5 s)
"""
import os
import subprocess
import sys
import tempfile

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LUBSIM = os.path.join(ROOT, "build", "core", "lubsim")
SCENE = os.path.join(ROOT, "configs", "scenes", "slider_crank.json")
# pointer, value, unit, the central differences' relative step
PARAMETERS = [("/joints/3/viscosity_Pa_s", 0.4, "Pa s", 0.01), ("/drivers/0/speed_rpm", 5000.0, "rpm", 0.01),
              ("/joints/3/bearing_radius_m", 0.010, "m", 0.0005)]
METRICS = ["min_film_thickness_m", "max_eps", "peak_reaction_N", "peak_acceleration_m_s2", "film_power_loss_W"]


def lubsim(out, *args):
    cmd = [LUBSIM, SCENE, "-o", out, "--quiet", "--set", "/simulation/steady=auto", *args]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"sensitivities: {' '.join(cmd)}: {p.stderr}")


def main():
    print("| parameter | metric | implicit function ± bar | central differences ± bar | difference / bound |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for pointer, value, unit, step in PARAMETERS:
            sens = os.path.join(tmp, "sens.h5")
            lubsim(sens, "--sensitivity", pointer)
            ends = []
            for f in (1.0 + step, 1.0 - step):
                out = os.path.join(tmp, f"end{f}.h5")
                lubsim(out, "--set", f"{pointer}={value * f!r}")
                with h5py.File(out) as h:
                    ends.append({k: (h["metrics"].attrs[k], h["metrics"].attrs[k + "_error"]) for k in METRICS})
            with h5py.File(sens) as h:
                g = h["sensitivities/0"]
                for k in METRICS:
                    d, e = g[k][0], g[k + "_error"][0]
                    cd = (ends[0][k][0] - ends[1][k][0]) / (2.0 * step * value)
                    ce = (ends[0][k][1] + ends[1][k][1]) / (2.0 * step * value)
                    bound = e + ce + 0.02 * abs(cd)
                    units = g[k].attrs["units"]
                    units = units.decode() if isinstance(units, bytes) else units
                    print(f"| {pointer} | d {k} [{units}] | {d:.5g} ± {e:.2g} | {cd:.5g} ± {ce:.2g} | "
                          f"{abs(d - cd) / bound:.2f} |")


if __name__ == "__main__":
    main()
