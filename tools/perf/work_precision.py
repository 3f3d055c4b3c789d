#!/usr/bin/python3
"""Work-precision study: what accuracy costs in time.

Reads a lubsweep study file made from an accuracy grid (configs/grids/accuracy_*.json:
integrator x formulation x relative tolerance, plus one reference case at a much tighter
tolerance), measures every case's error against the reference and plots error against
wall time and against right-hand-side evaluations, one line per method (log-log).

Errors, all dimensionless:
  orbit      max |e - e_ref| / c over the last recorded cycle (the journal orbit)
  min_film   |h_min - h_min,ref| / h_min,ref over the last cycle (last_cycle_min_film_m:
             a study file reports steady metrics of steady cycles only, and these cases
             are four-cycle transients)
  reaction   |R_peak - R_peak,ref| / R_peak,ref, the largest of the recorded
             reaction_force channel's samples over the last recorded cycle (at the same
             crank angles in every case)

    PYTHONPATH=build/python /usr/bin/python3 tools/perf/work_precision.py out/accuracy_reference.h5 \
        --png out/work_precision.png --table out/work_precision.md

Exit status 0, or 2 for a file that is not an accuracy study.
"""
import argparse
import math
import sys

import numpy as np

from lubjoint import study as study_reader  # PYTHONPATH=build/python: docs/guide/post-processing.md


def label(cases, i):
    method = cases["method"][i] or "cvode_bdf"
    form = cases["formulation"][i] if "formulation" in cases else ""
    proj = cases["projection"][i] if "projection" in cases else ""
    name = method
    if method == "ida" or form == "ggl":
        name += " ggl"
    elif form in ("partitioned", "joint"):
        name += " " + form
    elif proj in ("true", True, 1):
        name += " projection"
    else:
        name += " baumgarte"
    return name


THRESHOLDS = (1e-3, 1e-5, 1e-7)  # orbit error / c


def summary(rows):
    """Per method and formulation (and case, where the grid has other axes): the loosest rtol
    from which every tighter one reaches each orbit-error threshold, with its error, its
    right-hand-side evaluations and wall time; and the loosest from which every tighter one
    ends ok, with its error. A Markdown table under "## Summary"."""
    out = ["", "## Summary", "",
           "The loosest rtol from which every tighter one has an orbit error within the threshold "
           "(its error, RHS evaluations, wall); the loosest from which every tighter one ends ok "
           "(its orbit error / c).", "",
           "| case | method | " + " | ".join(f"≤ {t:.0e} c" for t in THRESHOLDS) + " | every tighter ok |",
           "|---|---|" + "---|" * (len(THRESHOLDS) + 1)]
    groups = {}
    for r in rows:
        groups.setdefault(r["label"], []).append(r)
    for lab, rs in sorted(groups.items()):
        rs = sorted(rs, key=lambda r: -r["rtol"])  # loose to tight
        ok = lambda r: r["status"] == "ok" and not math.isnan(r["orbit"])
        cells = []
        for t in THRESHOLDS:
            k = len(rs)
            while k > 0 and ok(rs[k - 1]) and rs[k - 1]["orbit"] <= t:
                k -= 1
            if k < len(rs):
                r = rs[k]
                cells.append(f"{r['rtol']:.0e} ({r['orbit']:.1e}), {r['rhs']}, {r['wall']:.2f} s")
            else:
                last = rs[-1]
                cells.append(f"not reached: {last['rtol']:.0e} gives "
                             + (f"{last['orbit']:.1e}" if ok(last) else last["status"]))
        k = len(rs)
        while k > 0 and rs[k - 1]["status"] == "ok":
            k -= 1
        tail = f"{rs[k]['rtol']:.0e} ({rs[k]['orbit']:.2g} c)" if k < len(rs) else "none"
        case, _, name = lab.rpartition(": ")
        out.append(f"| {case or '–'} | {name} | " + " | ".join(cells) + f" | {tail} |")
    return out


def peak_reaction(ser):
    """The largest sample of the reaction_force channel [N]; NaN if not recorded."""
    if ser is None or "reaction_force" not in ser:
        return math.nan
    return float(np.max(np.abs(ser["reaction_force"])))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("study", help="study file from an accuracy grid")
    ap.add_argument("--png", help="write the plot here")
    ap.add_argument("--table", help="write the table (Markdown) here; default: stdout")
    ap.add_argument("--clearance-m", type=float, default=None,
                    help="radial clearance for the orbit error [m] (default: from the reference scene)")
    args = ap.parse_args()

    study_reader.check_or_exit(args.study)
    c = study_reader.cases(args.study)  # pandas, index: case id
    series = lambda cid: {k: v.values for k, v in study_reader.series(args.study, c["name"][cid]).variables.items()}
    if "rtol" not in c or "reference" not in study_reader.grid_names(args.study):
        print(f"{args.study}: not an accuracy study (needs an rtol axis and a 'reference' grid)", file=sys.stderr)
        return 2
    # One reference per setting of the other axes (e.g. per force law): a case is measured
    # against the reference whose values of the other axes equal its own.
    numerics = {"method", "rtol", "formulation", "projection"}
    others = [a for a in c.attrs.get("axes", []) if a not in numerics]
    key = lambda i: tuple(str(c[a][i]) for a in others)
    refs = {}
    for rid in study_reader.grid(args.study, "reference").case_id.values.ravel():
        r = int(rid)
        if c["status"][r] != "ok":
            print(f"{args.study}: the reference case {int(rid)} did not complete: {c['message'][r]}", file=sys.stderr)
            return 2
        refs[key(r)] = r
    scene = study_reader.scene(args.study, next(iter(refs.values())))
    clearance = args.clearance_m
    if clearance is None:
        j = next(j for j in scene["joints"] if j["type"] == "lubricated_revolute")
        clearance = j["bearing_radius_m"] - j["journal_radius_m"]

    rows = []
    for i in c.index:
        ref = refs.get(key(i))
        if ref is None or i in refs.values():
            continue
        ref_series = series(ref)
        h_ref = c["last_cycle_min_film_m"][ref]
        r_ref = peak_reaction(ref_series)
        cost_rhs = int(c["rhs_evals"][i]) + int(c["rhs_evals_jacobian"][i])
        row = {"label": label(c, i), "other": " ".join(key(i)), "rtol": float(c["rtol"][i]), "status": c["status"][i],
               "steps": int(c["steps"][i]), "rhs": cost_rhs, "wall": float(c["wall_time_s"][i]),
               "orbit": math.nan, "min_film": math.nan, "reaction": math.nan}
        if row["status"] == "ok":
            ser = series(i)
            if ser is not None and ref_series is not None:
                ex = np.interp(ref_series["t"], ser["t"], ser["e_x"])
                ey = np.interp(ref_series["t"], ser["t"], ser["e_y"])
                row["orbit"] = float(np.max(np.hypot(ex - ref_series["e_x"], ey - ref_series["e_y"])) / clearance)
            # In contact the reference film is zero: then the error relative to the clearance.
            row["min_film"] = abs(c["last_cycle_min_film_m"][i] - h_ref) / (h_ref if h_ref > 0 else clearance)
            row["reaction"] = abs(peak_reaction(ser) - r_ref) / r_ref
        rows.append(row)
    rows.sort(key=lambda r: (r["other"], r["label"], -r["rtol"]))
    for r in rows:
        if r["other"]:
            r["label"] = r["other"] + ": " + r["label"]

    lines = ["| case | method | formulation | rtol | status | steps | RHS evals | wall [s] | orbit err / c | min-film err | peak-reaction err |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        m, f = r["label"].split(": ")[-1].split(" ", 1)
        fmt = lambda x: "–" if math.isnan(x) else f"{x:.1e}"
        lines.append(f"| {r['other'] or '–'} | {m} | {f} | {r['rtol']:.0e} | {r['status']} | {r['steps']} | {r['rhs']} | "
                     f"{r['wall']:.3f} | {fmt(r['orbit'])} | {fmt(r['min_film'])} | {fmt(r['reaction'])} |")
    lines.append("")
    for k, ref in refs.items():
        lines.append(f"Reference{' (' + ' '.join(k) + ')' if k else ''}: case {ref} "
                     f"({label(c, ref)}, rtol {c['rtol'][ref]:.0e}): "
                     f"h_min = {c['last_cycle_min_film_m'][ref] * 1e6:.4f} µm, "
                     f"peak reaction = {peak_reaction(series(ref)):.2f} N (sampled), "
                     f"{int(c['steps'][ref])} steps, {float(c['wall_time_s'][ref]):.3f} s.  ")
    lines += summary(rows)
    text = "\n".join(lines) + "\n"
    if args.table:
        with open(args.table, "w") as fh:
            fh.write(text)
    else:
        sys.stdout.write(text)

    if args.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axs = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
        labels = sorted({r["label"] for r in rows})
        markers = "osD^v<>ph*"
        for k, lab in enumerate(labels):
            pts = [r for r in rows if r["label"] == lab and r["status"] == "ok" and r["orbit"] > 0]
            if not pts:
                continue
            err = [r["orbit"] for r in pts]
            axs[0].loglog([r["wall"] for r in pts], err, marker=markers[k % len(markers)], label=lab)
            axs[1].loglog([r["rhs"] for r in pts], err, marker=markers[k % len(markers)], label=lab)
        axs[0].set_xlabel("wall time per run [s]")
        axs[1].set_xlabel("right-hand-side evaluations (incl. Jacobian)")
        axs[0].set_ylabel("orbit error  max |e - e_ref| / c")
        for ax in axs:
            ax.grid(True, which="both", alpha=0.3)
        axs[1].legend(fontsize=8)
        fig.suptitle("Work-precision, " + (scene.get("description", "")[:60] + "…"), fontsize=9)
        fig.tight_layout()
        fig.savefig(args.png, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
