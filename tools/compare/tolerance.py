"""compare.py tolerance: do a study's labels and metrics hold when its grid is integrated more tightly?

    PYTHONPATH=build/python /usr/bin/python3 tools/compare.py tolerance default.h5 tight.h5 [--markdown]

The two files are the same grid run twice, the second with a tighter tolerance in its
`set` (e.g. "/solver/rtol": 1e-9 against the scene's 1e-8: docs/validation/steady-cycles.md,
"Against the same grid at rtol/10"), or by another route (the same grid as long
transients, "/simulation/steady": "transient"). Cases are matched by their axes' values (the
/cases attribute `axes`), not by hash (the hash includes the tolerance). It prints:

  - the label transitions, default → tight;
  - for the cases that are orbits (periodic, periodic_unstable) in both, each metric with
    an error bar: how many agree within the summed error bars |a − b| <= e_a + e_b, how
    many within twice them, and the largest ratio |a − b| / (e_a + e_b) (angles on the
    circle); a case whose bars are NaN counts as outside, and how many there are is said
    (a study of transients has none: its orbits are confirmed stops, not located ones);
    then how far apart the two are whatever the bars, |a − b| / |a| (in rad for an angle),
    median and largest;
  - for the cases drifting by the slow flow in both (slow_flow_cycles > 0): the tight
    run's film where its flow got to over the default's (quartiles), and its cycles over
    the default's;
  - the default's cases the tight file lacks (a run stopped early).

Exit 0; 2: bad input (not a study file, files of different axes).
"""
import math
import sys

import numpy as np

from lubjoint import study as study_reader  # (PYTHONPATH=build/python: docs/guide/post-processing.md)

# The metrics with error bars (<metric>_error in /cases); those in rad are angles.
BARRED = ("min_film_thickness_m", "max_eps", "peak_reaction_N", "peak_acceleration_m_s2",
          "crank_angle_at_min_film_rad", "crank_angle_at_peak_reaction_rad")


def keyed(df):
    """The cases indexed by their axes' values (a tuple per case)."""
    axes = [str(a) for a in df.attrs["axes"]]
    out = df.copy()
    out.index = [tuple(r) for r in df[axes].itertuples(index=False)]
    return out, axes


def difference(a, b, angle):
    """|a − b| (on the circle for an angle), 0 within rounding: an angle of 0 and one of
    2π − 1 ulp, each with no error bar, agree."""
    d = abs(a - b)
    if angle:
        d = min(d, 2 * math.pi - d % (2 * math.pi))
    rounding = 4 * sys.float_info.epsilon * max(abs(a), abs(b), 2 * math.pi if angle else 0.0)
    return 0.0 if d <= rounding else d


def agreement(default, tight):
    """The comparison as a dict (see the module's docstring); `default`, `tight`: /cases
    DataFrames as lubjoint.study.cases returns them."""
    a, axes = keyed(default)
    b, axes_b = keyed(tight)
    if axes != axes_b:
        raise ValueError(f"the two studies have different axes: {axes} and {axes_b}")
    both = [k for k in a.index if k in b.index]
    # The classifications with an orbit, as each file says (/cases orbit_classifications).
    orbit_a, orbit_b = study_reader.orbit_classifications(default), study_reader.orbit_classifications(tight)
    labels = {}
    for k in both:
        t = (str(a.at[k, "classification"]), str(b.at[k, "classification"]))
        labels[t] = labels.get(t, 0) + 1
    orbits = [k for k in both
              if str(a.at[k, "classification"]) in orbit_a and str(b.at[k, "classification"]) in orbit_b]
    metrics = {}
    for m in BARRED:
        if m not in a.columns or m + "_error" not in a.columns:
            continue
        angle = m.endswith("_rad")
        ratios, apart, unbarred = [], [], 0
        for k in orbits:
            bars = float(a.at[k, m + "_error"]) + float(b.at[k, m + "_error"])
            d = difference(float(a.at[k, m]), float(b.at[k, m]), angle)
            ratios.append(d / bars if bars > 0 else (0.0 if d == 0 else math.inf))
            unbarred += not math.isfinite(bars)
            # How far apart, whatever the bars: in rad for an angle, else relative to the
            # default's value.
            scale = 1.0 if angle else abs(float(a.at[k, m]))
            apart.append(d / scale if scale > 0 else (0.0 if d == 0 else math.inf))
        r = np.array(ratios, dtype=float)
        x = np.array(apart, dtype=float)
        metrics[m] = {"within_1": int(np.sum(r <= 1)), "within_2": int(np.sum(r <= 2)),
                      "worst": float(np.nanmax(r)) if np.isfinite(r).any() else math.nan,
                      "cases": len(r), "unbarred": unbarred,
                      "apart_median": float(np.median(x)) if len(x) else math.nan,
                      "apart_max": float(np.max(x)) if len(x) else math.nan,
                      "apart_unit": "rad" if angle else "relative"}
    flows = [k for k in both if str(a.at[k, "classification"]) == "drifting"
             and str(b.at[k, "classification"]) == "drifting"
             and float(a.at[k, "slow_flow_cycles"]) > 0 and float(b.at[k, "slow_flow_cycles"]) > 0]
    film = np.array([float(b.at[k, "last_cycle_min_film_m"]) / float(a.at[k, "last_cycle_min_film_m"]) for k in flows])
    cycles = np.array([float(b.at[k, "slow_flow_cycles"]) / float(a.at[k, "slow_flow_cycles"]) for k in flows])
    quart = (lambda x: list(np.percentile(x, [0, 25, 50, 75, 100])) if len(x) else [])
    return {"axes": axes, "cases": len(a), "matched": len(both),
            "missing": [k for k in a.index if k not in b.index],
            "labels": labels, "same_label": sum(v for (x, y), v in labels.items() if x == y),
            "orbits": len(orbits), "metrics": metrics,
            "flows": len(flows), "film_ratio": quart(film), "cycle_ratio": quart(cycles)}


def report(r, markdown=False):
    lines = [f"cases: {r['cases']} in the default study, {r['matched']} in both"
             + (f" ({len(r['missing'])} missing from the tight one)" if r["missing"] else ""),
             f"same label: {r['same_label']} of {r['matched']}"]
    if markdown:
        lines += ["", "| default → tight | cases |", "|---|---|"]
        lines += [f"| {x} → {y} | {n} |" for (x, y), n in sorted(r["labels"].items())]
        lines += ["", f"Orbits in both: {r['orbits']}", "",
                  "| metric | within the summed error bars | within twice them | largest ratio | without bars "
                  "| apart (median, largest) |", "|---|---|---|---|---|---|"]
        lines += [f"| `{m}` | {v['within_1']} | {v['within_2']} | {v['worst']:.3g} | {v['unbarred']} "
                  f"| {v['apart_median']:.2g}, {v['apart_max']:.2g} ({v['apart_unit']}) |" for m, v in r["metrics"].items()]
    else:
        lines += [f"  {x} -> {y}: {n}" for (x, y), n in sorted(r["labels"].items())]
        lines.append(f"orbits in both: {r['orbits']}")
        lines += [f"  {m}: within 1x {v['within_1']}, within 2x {v['within_2']}, largest ratio {v['worst']:.3g}"
                  + (f" ({v['unbarred']} without error bars: outside)" if v["unbarred"] else "")
                  + f"; apart {v['apart_median']:.2g} median, {v['apart_max']:.2g} largest ({v['apart_unit']})"
                  for m, v in r["metrics"].items()]
    q = lambda x: ", ".join(f"{v:.2f}" for v in x) if x else "-"
    lines.append(f"{'' if not markdown else chr(10)}drifting by the slow flow in both: {r['flows']}; tight/default film "
                 f"where each got to (min, quartiles, max): {q(r['film_ratio'])}; cycles: {q(r['cycle_ratio'])}")
    return "\n".join(lines)


def add_arguments(ap):
    ap.add_argument("default", help="the study at the grid's own tolerance")
    ap.add_argument("tight", help="the same grid with a tighter tolerance in its set")
    ap.add_argument("--markdown", action="store_true", help="tables in Markdown (for the docs)")


def run(args):
    for p in (args.default, args.tight):
        try:
            study_reader.check(p)
        except (study_reader.StudyFormatError, OSError) as e:
            print(f"compare tolerance: {p}: {e}", file=sys.stderr)
            return 2
    try:
        r = agreement(study_reader.cases(args.default), study_reader.cases(args.tight))
    except ValueError as e:
        print(f"compare tolerance: {e}", file=sys.stderr)
        return 2
    print(report(r, args.markdown))
    return 0
