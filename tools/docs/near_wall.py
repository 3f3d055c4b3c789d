#!/usr/bin/python3
"""Tight transients near the wall (docs/theory/long-runs.md, the crank's turns): Frene short
and long on the paper's slider-crank at rtol 1e-10 for thousands of cycles; prints the
Markdown table of the minimum film at chosen cycles and draws the figure.

    PYTHONPATH=build/python /usr/bin/python3 tools/docs/near_wall.py \\
        [-o docs/figures/near_wall_transients.png] [--runs DIR]      (~6 min on 2 cores)

The figure's two panels, against the cycle: the cycle's minimum film thickness [um]; how far
the Poincare point (e_x, e_y)/c at crank angle 0 moves from one cycle to the next [1], a
running median over 101 cycles (a smooth descent moves it by its drift, integration noise by
its own size whatever the drift). docs/figures/near_wall_before.csv, the reference case run
by the version before the driver's phase was reduced, is drawn beside them.
"""
import argparse
import concurrent.futures
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import lubjoint  # noqa: E402  PYTHONPATH=build/python

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "configs", "scenes", "slider_crank.json")
BEFORE = os.path.join(ROOT, "docs", "figures", "near_wall_before.csv")
MARKS = (1000, 2000, 3000, 5000, 10000, 20000, 30000, 40000)
# name, label, law, clearance [m], speed [rpm], cycles
CASES = (
    ("frene_short_0.5mm_5000rpm", "Frêne short, 0.5 mm, 5000 rpm", "frene_short", 0.5e-3, 5000, 40000),
    ("frene_short_0.2mm_5000rpm", "Frêne short, 0.2 mm, 5000 rpm", "frene_short", 0.2e-3, 5000, 10000),
    ("frene_long_0.2mm_500rpm", "Frêne long, 0.2 mm, 500 rpm", "frene_long", 0.2e-3, 500, 10000),
)


def run(case, runs_dir):
    name, _, law, clearance, rpm, cycles = case
    overrides = {
        "/joints/3/force_law": law,
        "/joints/3/journal_radius_m": 0.0100 - clearance,
        "/drivers/0/speed_rpm": rpm,
        "/solver/rtol": 1e-10,
        "/solver/max_steps": 1_000_000_000,
        "/solver/max_wall_time_s": 3600,
        "/simulation/steady": "transient",
        "/simulation/stop_when_steady": False,
        "/simulation/max_cycles": cycles,
        "/outputs/channels": [],
    }
    output = os.path.join(runs_dir, name + ".h5") if runs_dir else None
    return lubjoint.simulate(SCENE, overrides, output)


def running_median(x, width=101):
    if len(x) < width:
        return x
    half = width // 2
    windows = np.lib.stride_tricks.sliding_window_view(np.pad(x, half, mode="edge"), width)
    return np.median(windows, axis=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", default=os.path.join(ROOT, "docs", "figures", "near_wall_transients.png"))
    ap.add_argument("--runs", metavar="DIR", help="also write each case's run file there")
    args = ap.parse_args()
    if args.runs:
        os.makedirs(args.runs, exist_ok=True)
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:  # the GIL is released in a run
        results = list(pool.map(lambda c: run(c, args.runs), CASES))

    print("| case: h_min [µm] at | " + " | ".join(f"cycle {m}" for m in MARKS) + " | how it ended |")
    print("|---|" + "---|" * (len(MARKS) + 1))
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    for case, ds in zip(CASES, results):
        cycle = ds["cycle"].values
        h = ds["cycle_min_film_thickness_m"].values * 1e6
        cells = [f"{h[m - 1]:.3f}" if m <= len(h) else "" for m in MARKS]
        print(f"| {case[0]} | " + " | ".join(cells) + f" | {ds.attrs['status']} at cycle {len(h)} |")
        end = "" if ds.attrs["status"] == "ok" else f" ({ds.attrs['status']} at cycle {cycle[-1]})"
        (line,) = top.semilogy(cycle, h, lw=1.0, label=case[1] + end)
        move = np.hypot(np.diff(ds["cycle_end_eccentricity_x"].values), np.diff(ds["cycle_end_eccentricity_y"].values))
        bottom.semilogy(cycle[1:], running_median(move), lw=1.0, color=line.get_color())
    with open(BEFORE) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    cycle = np.array([int(r["cycle"]) for r in rows])
    (line,) = top.semilogy(cycle, [float(r["min_film_thickness_um"]) for r in rows], lw=1.0,
                           label="before the phase fix: Frêne short, 0.5 mm, 5000 rpm")
    bottom.semilogy(cycle, [float(r["poincare_move_running_median_c"]) for r in rows], lw=1.0,
                    color=line.get_color())
    top.set_ylabel("minimum film thickness [µm]")
    top.legend(fontsize=8)
    top.grid(alpha=0.3, which="both")
    bottom.set_ylabel("Poincaré point's move a cycle [c]\n(running median, 101 cycles)")
    bottom.set_xlabel("crank cycle")
    bottom.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)


if __name__ == "__main__":
    main()
