#!/usr/bin/python3
"""Compare a lubsweep study file against a baseline (the nightly reproduction).

    /usr/bin/python3 tools/compare_study.py out/study.h5 baseline/study.h5 \\
        [--rtol 1e-3] [--tol peak_reaction_N=0.05] [--tol periodicity=0:1e-3] [--steps-rtol 0.5]

Cases are matched by the hash of their scene. A regression, and exit status 1, is:
  - a baseline case missing from the study, or a case whose status changed;
  - for a case that is ok in both, a metric outside its tolerance:
    |value − baseline| > atol + rtol·|baseline|.
Default tolerance of every metric: --rtol (1e-3), atol 0; flags and counts (steady,
below_safe_film, ...) must be equal unless given a tolerance. --tol METRIC=RTOL or
METRIC=RTOL:ATOL sets one metric's; --tol METRIC=skip ignores it. --steps-rtol R also
flags a solver cost (steps) grown by more than the fraction R.
Cases only in the study are reported, not regressions. Exit 0: no regression; 2: bad
input.
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_io  # noqa: E402


def tolerances(study, rtol, items):
    tol = {}
    for m in study.metrics:
        integer = study.cases[m].dtype.kind in "iu"
        tol[m] = (0.0, 0.0) if integer else (rtol, 0.0)
    for it in items:
        if "=" not in it:
            raise SystemExit(f"compare_study: --tol {it}: must be METRIC=RTOL[:ATOL] or METRIC=skip")
        m, v = it.split("=", 1)
        if m not in study.columns:
            raise SystemExit(f"compare_study: --tol {it}: {m} is not a column of /cases")
        if v == "skip":
            tol[m] = None
            continue
        r, _, a = v.partition(":")
        tol[m] = (float(r), float(a or 0.0))
    return tol


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study")
    ap.add_argument("baseline")
    ap.add_argument("--rtol", type=float, default=1e-3, help="default relative tolerance of the metrics")
    ap.add_argument("--tol", action="append", default=[], help="METRIC=RTOL[:ATOL] or METRIC=skip")
    ap.add_argument("--steps-rtol", type=float, default=None, help="flag solver steps grown by more than this fraction")
    ap.add_argument("-q", "--quiet", action="store_true", help="print regressions only")
    args = ap.parse_args()
    try:
        new, base = study_io.Study(args.study), study_io.Study(args.baseline)
    except (OSError, KeyError) as e:
        print(f"compare_study: {e}", file=sys.stderr)
        return 2
    tol = tolerances(base, args.rtol, args.tol)
    row_new = {h: i for i, h in enumerate(new.cases["hash"])}
    row_base = {h: i for i, h in enumerate(base.cases["hash"])}
    regressions, notes = [], []
    worst = {}  # metric -> (relative deviation, case)
    for h, rb in row_base.items():
        name = base.cases["case"][rb]
        if h not in row_new:
            regressions.append(f"{name}: missing from the study")
            continue
        rn = row_new[h]
        sb, sn = base.cases["status"][rb], new.cases["status"][rn]
        if sb != sn:
            regressions.append(f"{name}: status {sn!r}, baseline {sb!r}")
            continue
        if sb != "ok":
            continue
        for m, t in tol.items():
            if t is None or m not in new.columns:
                if t is not None:
                    regressions.append(f"{name}: column {m} missing from the study")
                continue
            b, v = float(base.cases[m][rb]), float(new.cases[m][rn])
            if math.isnan(b) and math.isnan(v):
                continue
            dev = abs(v - b)
            lim = t[1] + t[0] * abs(b)
            rel = dev / abs(b) if b != 0 else (0.0 if dev == 0 else math.inf)
            if rel > worst.get(m, (-1, ""))[0]:
                worst[m] = (rel, name)
            if not dev <= lim:
                regressions.append(f"{name}: {m} = {v:.9g}, baseline {b:.9g} (|diff| {dev:.3g} > {lim:.3g})")
        if args.steps_rtol is not None and "steps" in new.columns:
            b, v = float(base.cases["steps"][rb]), float(new.cases["steps"][rn])
            if v > b * (1 + args.steps_rtol):
                regressions.append(f"{name}: steps = {v:.0f}, baseline {b:.0f} (> +{args.steps_rtol:.0%})")
    extra = [new.cases["case"][i] for h, i in row_new.items() if h not in row_base]
    if extra:
        notes.append(f"{len(extra)} cases not in the baseline: {', '.join(extra[:10])}{' ...' if len(extra) > 10 else ''}")

    if not args.quiet:
        print(f"compare_study: {args.study} against {args.baseline}: {len(row_base)} baseline cases")
        if worst:
            print(f"  {'metric':34s} {'largest rel. deviation':>22s}  case")
            for m in base.metrics:
                if m in worst:
                    r, c = worst[m]
                    print(f"  {m:34s} {r:22.3g}  {c}")
        for n in notes:
            print("  note: " + n)
    for r in regressions:
        print("REGRESSION " + r)
    if not args.quiet or regressions:
        print(f"compare_study: {len(regressions)} regression{'s' if len(regressions) != 1 else ''}")
    return 1 if regressions else 0


if __name__ == "__main__":
    sys.exit(main())
