#!/usr/bin/python3
"""Prints the tables of docs/validation/reference-case.md and docs/validation/hard-cases.md
as Markdown, from lubsim runs of this build (a few seconds on 2 cores):

    /usr/bin/python3 tools/validation_tables.py reference-case [--build-dir build]
    /usr/bin/python3 tools/validation_tables.py hard-cases [--build-dir build]

reference-case: the paper's slider-crank (configs/scenes/slider_crank.json) with each of
the paper's three force laws; hard-cases: every scene of configs/scenes/hard/ as it is.
Each run's metrics and solver statistics are read from its run file (h5py). Wall times
are this machine's of the moment (shared: indicative only); everything else is
deterministic for a given build.
"""
import argparse
import glob
import os
import subprocess
import sys
import tempfile

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PAPER_LAWS = ("pinkus_sternlicht", "frene_long", "frene_short")


def run(lubsim, scene, out, overrides=()):
    """Runs lubsim (exit 0 ok, 3 a run that could not be completed: both are results)."""
    cmd = [lubsim, scene, "-o", out, "-q"]
    for o in overrides:
        cmd += ["--set", o]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode not in (0, 3):
        sys.exit(f"validation_tables: {' '.join(cmd)} failed ({r.returncode}): {r.stderr.strip()}")
    with h5py.File(out, "r") as f:
        status = f.attrs["status"]
        status = status.decode() if isinstance(status, bytes) else str(status)
        return status, dict(f["metrics"].attrs), dict(f["solver"].attrs)


def wall(seconds):
    return "<0.01" if seconds < 0.01 else f"{seconds:.2f}"


def reference_case(lubsim, tmp):
    scene = os.path.join(ROOT, "configs", "scenes", "slider_crank.json")
    print("| law | min film [µm] | max ε | peak reaction [N] | periodicity | steps | ε̇ = 0 switches | wall [s] |")
    print("|---|---|---|---|---|---|---|---|")
    for law in PAPER_LAWS:
        status, m, s = run(lubsim, scene, os.path.join(tmp, f"{law}.h5"), [f"/joints/3/force_law={law}"])
        if status != "ok":
            sys.exit(f"validation_tables: the reference case with {law} ended {status}")
        print(f"| {law} | {m['min_film_thickness_m'] * 1e6:.2f} | {m['max_eps']:.4f} | "
              f"{m['peak_reaction_N']:.0f} | {m['periodicity']:.2g} | {s['steps']} | "
              f"{s['mode_switches']} | {wall(s['wall_time_s'])} |")


def hard_cases(lubsim, tmp):
    print("| case | rtol | status | end time [s] | steps | wall [s] | min film [µm] |")
    print("|---|---|---|---|---|---|---|")
    for scene in sorted(glob.glob(os.path.join(ROOT, "configs", "scenes", "hard", "*.json"))):
        name = os.path.splitext(os.path.basename(scene))[0]
        status, m, s = run(lubsim, scene, os.path.join(tmp, f"{name}.h5"))
        print(f"| `{name}` | {s['rtol']:.0e} | {status} | {s['final_time_s']:.6g} | {s['steps']} | "
              f"{wall(s['wall_time_s'])} | {m['min_film_thickness_m'] * 1e6:.4g} |".replace("e-0", "e-"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("table", choices=("reference-case", "hard-cases"))
    parser.add_argument("--build-dir", default=os.path.join(ROOT, "build"))
    args = parser.parse_args()
    lubsim = os.path.join(args.build_dir, "core", "lubsim")
    if not os.access(lubsim, os.X_OK):
        sys.exit(f"validation_tables: {lubsim} not found: build first (bash tools/build.sh)")
    with tempfile.TemporaryDirectory(prefix="validation_tables-") as tmp:
        {"reference-case": reference_case, "hard-cases": hard_cases}[args.table](lubsim, tmp)


if __name__ == "__main__":
    main()
