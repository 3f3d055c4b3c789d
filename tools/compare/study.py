"""compare.py study: a lubsweep study file against a baseline study file.

    PYTHONPATH=build/python /usr/bin/python3 tools/compare.py study out/study.h5 baseline/study.h5 \\
        [--rtol 1e-3] [--tol peak_reaction_N=0.05] [--tol periodicity=0:1e-3] [--steps-rtol 0.5]

Cases are matched by the hash of their scene. A regression, and exit status 1, is:
  - a baseline case missing from the study, or a case whose status changed;
  - for a case that is ok in both, a metric outside its tolerance:
    |value − baseline| > atol + rtol·|baseline|.
Default tolerance of every metric: --rtol (1e-3), atol 0; flags and counts (steady,
below_safe_film, ...) must be equal unless given a tolerance. --tol METRIC=RTOL or
METRIC=RTOL:ATOL sets one metric's; --tol METRIC=skip ignores it. --steps-rtol R also
flags a solver cost (steps) grown by more than the fraction R.
Cases only in the study are reported, not regressions. Exit 0: no regression; 1: a
regression; 2: bad input. Reads through xarray/pandas (lubjoint.study).
"""
import math

from lubjoint import study as study_reader  # (PYTHONPATH=build/python: docs/guide/post-processing.md)


def tolerances(base, rtol, items):
    tol = {m: ((0.0, 0.0) if base[m].dtype.kind in "iu" else (rtol, 0.0)) for m in base.attrs["metrics"]}
    for it in items:
        if "=" not in it:
            raise SystemExit(f"compare study: --tol {it}: must be METRIC=RTOL[:ATOL] or METRIC=skip")
        m, v = it.split("=", 1)
        if m not in base.columns:
            raise SystemExit(f"compare study: --tol {it}: {m} is not a column of /cases")
        r, _, a = v.partition(":")
        tol[m] = None if v == "skip" else (float(r), float(a or 0.0))
    return tol


def add_arguments(ap):
    ap.add_argument("study")
    ap.add_argument("baseline")
    ap.add_argument("--rtol", type=float, default=1e-3, help="default relative tolerance of the metrics")
    ap.add_argument("--tol", action="append", default=[], help="METRIC=RTOL[:ATOL] or METRIC=skip")
    ap.add_argument("--steps-rtol", type=float, default=None, help="flag solver steps grown by more than this fraction")
    ap.add_argument("-q", "--quiet", action="store_true", help="print regressions only")


def run(args):
    for p in (args.study, args.baseline):
        study_reader.check_or_exit(p)
    new = study_reader.cases(args.study).set_index("hash")
    base = study_reader.cases(args.baseline).set_index("hash")
    tol = tolerances(base, args.rtol, args.tol)
    regressions, worst = [], {}  # worst: metric -> (relative deviation, case)
    for h, b in base.iterrows():
        if h not in new.index:
            regressions.append(f"{b['name']}: missing from the study")
            continue
        n = new.loc[h]
        if b["status"] != n["status"]:
            regressions.append(f"{b['name']}: status {n['status']!r}, baseline {b['status']!r}")
            continue
        if b["status"] != "ok":
            continue
        for m, t in tol.items():
            if t is None:
                continue
            if m not in n:
                regressions.append(f"{b['name']}: column {m} missing from the study")
                continue
            vb, v = float(b[m]), float(n[m])
            if math.isnan(vb) and math.isnan(v):
                continue
            dev, lim = abs(v - vb), t[1] + t[0] * abs(vb)
            rel = dev / abs(vb) if vb != 0 else (0.0 if dev == 0 else math.inf)
            if rel > worst.get(m, (-1, ""))[0]:
                worst[m] = (rel, b["name"])
            if not dev <= lim:
                regressions.append(f"{b['name']}: {m} = {v:.9g}, baseline {vb:.9g} (|diff| {dev:.3g} > {lim:.3g})")
        if args.steps_rtol is not None and n["steps"] > b["steps"] * (1 + args.steps_rtol):
            regressions.append(f"{b['name']}: steps = {n['steps']:.0f}, baseline {b['steps']:.0f} (> +{args.steps_rtol:.0%})")
    extra = list(new.loc[~new.index.isin(base.index), "name"])

    if not args.quiet:
        print(f"compare study: {args.study} against {args.baseline}: {len(base)} baseline cases")
        if worst:
            print(f"  {'metric':34s} {'largest rel. deviation':>22s}  case")
            for m, (r, c) in worst.items():
                print(f"  {m:34s} {r:22.3g}  {c}")
        if extra:
            print(f"  note: {len(extra)} cases not in the baseline: {', '.join(extra[:10])}{' ...' if len(extra) > 10 else ''}")
    for r in regressions:
        print("REGRESSION " + r)
    if not args.quiet or regressions:
        print(f"compare study: {len(regressions)} regression{'s' if len(regressions) != 1 else ''}")
    return 1 if regressions else 0
