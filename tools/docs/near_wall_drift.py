#!/usr/bin/python3
"""The near-wall drift against the integration's own error (docs/validation/steady-cycles.md,
near the wall): the reference case's journal (Frene short, 0.5 mm, 400 cP, 5000 rpm) started
at rest 2 and 1 um from the wall, integrated cycle by cycle for 300 cycles at rtol 1e-9 ...
1e-12; prints the Markdown table of the minimum film's drift a cycle, a least-squares slope
over cycles 100-300 (the first cycles settle the start onto its slow manifold).

    PYTHONPATH=build/python /usr/bin/python3 tools/docs/near_wall_drift.py      (~2 min on 2 cores)
"""
import concurrent.futures
import math
import os

import numpy as np

import lubjoint  # noqa: E402  PYTHONPATH=build/python

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "configs", "scenes", "slider_crank.json")
CLEARANCE = 0.5e-3  # [m], the scene's
# The start's direction: where the reference case's transient from rest is at cycle 40 000.
ANGLE = math.atan2(-2.0726884e-5, -4.975019963e-4)
FILMS_UM = (2.0, 1.0)
RTOLS = (1e-9, 1e-10, 1e-11, 1e-12)
CYCLES, FROM = 300, 100


def run(film_um, rtol):
    e = CLEARANCE - film_um * 1e-6
    overrides = {
        "/joints/3/force_law": "frene_short",
        "/joints/3/initial_eccentricity_m": [e * math.cos(ANGLE), e * math.sin(ANGLE)],
        "/solver/rtol": rtol,
        "/solver/max_steps": 1_000_000_000,
        "/solver/max_wall_time_s": 3600,
        "/simulation/steady": "transient",
        "/simulation/stop_when_steady": False,
        "/simulation/max_cycles": CYCLES,
        "/outputs/channels": [],
    }
    ds = lubjoint.simulate(SCENE, overrides)
    h = ds["cycle_min_film_thickness_m"].values
    k = np.arange(len(h))
    if ds.attrs["status"] != "ok" or len(h) < CYCLES:
        return float("nan")
    return np.polyfit(k[FROM:], h[FROM:], 1)[0]


def main():
    cases = [(f, r) for f in FILMS_UM for r in RTOLS]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:  # the GIL is released in a run
        drift = dict(zip(cases, pool.map(lambda c: run(*c), cases)))
    print("| start: film from rest [µm] | " + " | ".join(f"rtol {r:.0e}" for r in RTOLS) + " |")
    print("|---|" + "---|" * len(RTOLS))
    for f in FILMS_UM:
        print(f"| {f} | " + " | ".join(f"{drift[(f, r)]:.3g}" for r in RTOLS) + " |")


if __name__ == "__main__":
    main()
