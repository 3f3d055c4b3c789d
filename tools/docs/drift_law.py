#!/usr/bin/python3
"""The drift law against tight transients (docs/validation/steady-cycles.md, the drift law):
every drifting case of a study whose drift law gives the cycle at which its film crosses
the safe film (safe_film_cycle), integrated cycle by cycle from rest at rtol 1e-10 to past
that cycle; prints the Markdown tables of the predicted and the integrated crossing, of the
drift exponents per force law, and of the law's reach on the paper's Frene short case.
Run from the repository root.

    mpirun -np 2 build/sweep/lubsweep configs/grids/full_factorial.json -o ff.h5
    PYTHONPATH=build/python /usr/bin/python3 tools/docs/drift_law.py ff.h5   (~10 min on 2 cores: the rtol 1e-11 transient)
"""
import argparse
import concurrent.futures
import math

import numpy as np

import lubjoint  # noqa: E402  PYTHONPATH=build/python
from lubjoint import study as lstudy

RTOL = 1e-10


def crossing(path, case_id, until, safe):
    """The first cycle (from the run's start) whose minimum film is below `safe`, integrated
    cycle by cycle at RTOL to `until` cycles (NaN: not crossed, or the run failed)."""
    overrides = {
        "/solver/rtol": RTOL,
        "/solver/max_steps": 1_000_000_000,
        "/simulation/steady": "transient",
        "/simulation/stop_when_steady": False,
        "/simulation/max_cycles": int(until),
        "/outputs/channels": [],
    }
    ds = lubjoint.simulate(lstudy.scene(path, case_id), overrides)
    h = ds["cycle_min_film_thickness_m"].values
    below = np.nonzero(h < safe)[0]
    return float(below[0]) if below.size else math.nan


def reach_table():
    """The paper's Frene short case (0.5 mm, 400 cP, 5000 rpm), whose safe film lies beyond
    its law's checked reach: the law's cycle for films from its own fitted range toward the
    wall (from the flow's end, its drift and exponent) against transients from rest at rtol
    1e-10 and 1e-11 (the tighter reaches each film earlier near the wall: the looser one's
    map error is a growing share of the drift there)."""
    scene = "configs/scenes/slider_crank.json"
    study = {"/joints/3/force_law": "frene_short", "/simulation/steady": "auto", "/simulation/max_cycles": 40,
             "/simulation/stop_when_steady": True, "/simulation/steady_tolerance": 1e-3, "/outputs/channels": []}
    a = lubjoint.simulate(scene, study)
    p, h0 = float(a["drift_exponent"]), float(a["last_cycle_min_film_m"])
    s0 = -float(a["min_film_drift_m_per_cycle"])
    n0 = float(a["cycle_min_film_thickness_m"].size) + float(a["slow_flow_cycles"])
    targets = [t for t in (10e-6, 8e-6, 6.5e-6, 5e-6, 4e-6, 3e-6) if t < h0]
    runs = {1e-10: 10000, 1e-11: 5300}
    transient = {**study, "/simulation/steady": "transient"}
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        tr = dict(zip(runs, pool.map(lambda r: crossing_series(scene, transient, runs[r], r), runs)))
    print(f"The paper's Frene short case: law p = {p:.2f}, fitted down to {h0 * 1e6:.1f} µm at cycle {n0:.0f}; "
          "the cycle each film is reached, by the law and by transients from rest:\n")
    print("| film [µm] | below the fitted films | law's cycle | rtol 1e-10 | rtol 1e-11 |")
    print("|---|---|---|---|---|")
    for t in targets:
        law = n0 + h0 * ((t / h0) ** (1 - p) - 1) / (s0 * (p - 1))
        seen = []
        for r in runs:
            k = np.nonzero(tr[r] < t)[0]
            seen.append(f"{k[0]}" if k.size else f"> {runs[r]}")
        print(f"| {t * 1e6:g} | {h0 / t:.2f} × | {law:.0f} | {seen[0]} | {seen[1]} |")
    print()


def crossing_series(scene, overrides, cycles, rtol=RTOL):
    """Each cycle's minimum film of a transient from rest at `rtol`."""
    o = {**overrides, "/solver/rtol": rtol, "/solver/max_steps": 1_000_000_000, "/solver/max_wall_time_s": 7200,
         "/simulation/stop_when_steady": False, "/simulation/max_cycles": cycles}
    return lubjoint.simulate(scene, o)["cycle_min_film_thickness_m"].values


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("study", help="a study file (lubsweep -o)")
    args = ap.parse_args()
    reach_table()
    cases = lubjoint.load_study(args.study).cases.to_dataframe()
    drifting = cases[cases.classification == "drifting"]
    law = drifting[np.isfinite(drifting.drift_exponent)]
    print("Drift exponents p of dh/dN = -a h^p, by force law (median, range; cases):\n")
    print("| force law | median p | range | cases with a law | of drifting |")
    print("|---|---|---|---|---|")
    for name, g in drifting.groupby("force_law"):
        p = g.drift_exponent[np.isfinite(g.drift_exponent)]
        if len(p):
            print(f"| {name} | {p.median():.2f} | {p.min():.2f}–{p.max():.2f} | {len(p)} | {len(g)} |")
    print()
    due = law[np.isfinite(law.safe_film_cycle)]
    jobs = {cid: (row.safe_film_cycle + row.safe_film_cycle_error + 100, row.safe_film_thickness_m)
            for cid, row in due.iterrows()}
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:  # the GIL is released in a run
        found = dict(zip(jobs, pool.map(lambda c: crossing(args.study, c, *jobs[c]), jobs)))
    print(f"Cycle at which the film crosses the safe film: the drift law's (safe_film_cycle ± its error bar) "
          f"against a transient from rest at rtol {RTOL:g}:\n")
    print("| case | force law | c [mm] | μ [Pa s] | n [rpm] | film at the flow's end [µm] | p | law's cycle | transient's | within the bar |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    inside = 0
    for cid, row in due.iterrows():
        t = found[cid]
        ok = abs(t - row.safe_film_cycle) <= row.safe_film_cycle_error
        inside += bool(ok)
        print(f"| {cid} | {row.force_law} | {row.clearance_m * 1e3:g} | {row.viscosity_Pa_s:g} | {row.speed_rpm:g} "
              f"| {row.last_cycle_min_film_m * 1e6:.2f} | {row.drift_exponent:.2f} ± {row.drift_exponent_error:.2f} "
              f"| {row.safe_film_cycle:.0f} ± {row.safe_film_cycle_error:.0f} | {t:.0f} | {'yes' if ok else 'no'} |")
    print(f"\n{inside} of {len(due)} within the law's error bar.")


if __name__ == "__main__":
    main()
