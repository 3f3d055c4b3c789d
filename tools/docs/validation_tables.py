#!/usr/bin/python3
"""Prints the tables of docs/validation/reference-case.md and docs/validation/hard-cases.md
as Markdown, from runs of this build (a few seconds on 2 cores):

    PYTHONPATH=build/python /usr/bin/python3 tools/docs/validation_tables.py reference-case
    PYTHONPATH=build/python /usr/bin/python3 tools/docs/validation_tables.py hard-cases

reference-case: the paper's slider-crank (configs/scenes/slider_crank.json) with each of
the paper's three force laws; hard-cases: every scene of configs/scenes/hard/ as it is.
Each scene runs through lubjoint.simulate, the same code as `lubsim SCENE -o run.h5`
(equal bit for bit: tests/python/test_lubjoint.py). Wall times are this machine's of the
moment (shared: indicative only); everything else is deterministic for a given build.
"""
import argparse
import glob
import os
import sys

import lubjoint  # PYTHONPATH=build/python

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PAPER_LAWS = ("pinkus_sternlicht", "frene_long", "frene_short")


class Run:
    """A run's status, metrics and solver statistics, by their run-file names."""

    def __init__(self, ds):
        self.status = ds.attrs["status"]
        self.values = {k: v.item() for k, v in ds.data_vars.items() if v.ndim == 0}
        self.values["rtol"] = ds.attrs["solver_rtol"]

    def __getitem__(self, name):
        return self.values[name]


def run(scene, overrides=None):
    """One run (an incomplete run, film collapse or budget, is a result too)."""
    return Run(lubjoint.simulate(scene, overrides))


def wall(seconds):
    return "<0.01" if seconds < 0.01 else f"{seconds:.2f}"


def reference_case():
    scene = os.path.join(ROOT, "configs", "scenes", "slider_crank.json")
    print("| law | min film [µm] | max ε | peak reaction [N] | periodicity | steps | ε̇ = 0 switches | wall [s] |")
    print("|---|---|---|---|---|---|---|---|")
    for law in PAPER_LAWS:
        m = s = run(scene, {"/joints/3/force_law": law})
        if m.status != "ok":
            sys.exit(f"validation_tables: the reference case with {law} ended {m.status}")
        print(f"| {law} | {m['min_film_thickness_m'] * 1e6:.2f} | {m['max_eps']:.4f} | "
              f"{m['peak_reaction_N']:.0f} | {m['periodicity']:.2g} | {s['steps']} | "
              f"{s['mode_switches']} | {wall(s['wall_time_s'])} |")


def hard_cases():
    print("| case | rtol | status | end time [s] | steps | wall [s] | min film [µm] |")
    print("|---|---|---|---|---|---|---|")
    for scene in sorted(glob.glob(os.path.join(ROOT, "configs", "scenes", "hard", "*.json"))):
        name = os.path.splitext(os.path.basename(scene))[0]
        m = s = run(scene)
        status = m.status
        print(f"| `{name}` | {s['rtol']:.0e} | {status} | {s['final_time_s']:.6g} | {s['steps']} | "
              f"{wall(s['wall_time_s'])} | {m['min_film_thickness_m'] * 1e6:.4g} |".replace("e-0", "e-"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("table", choices=("reference-case", "hard-cases"))
    args = parser.parse_args()
    {"reference-case": reference_case, "hard-cases": hard_cases}[args.table]()


if __name__ == "__main__":
    main()
