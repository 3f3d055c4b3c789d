"""compare.py nightly: the nightly reproduction of the paper's study against the committed baseline.

    PYTHONPATH=build/python /usr/bin/python3 tools/compare.py nightly STUDY.h5 [--baseline tests/baselines/paper.csv]
                                      [--report DIR] [--accepted-study OLD.h5]
    PYTHONPATH=build/python /usr/bin/python3 tools/compare.py nightly --accept STUDY.h5 [--baseline tests/baselines/paper.csv]

`tools/check/nightly.sh` runs the paper grid and calls these; see docs/validation/nightly.md.

The baseline is a CSV file, one row per case of configs/grids/paper.json, keyed by the
case's axis values (clearance_m, viscosity_Pa_s, speed_rpm, force_law: every case has a
value on every axis, read back from its scene), not by its hash, so a change of the scene
format or the build does not orphan it. The hash is kept as a column for reference.

The comparison exits 1 on a regression and names the case (its axis values and its name) and
the metric: a baseline case missing from the study, a case not in the baseline, a changed
status, or a metric outside its tolerance (lubjoint.baseline.TOLERANCES:
|now - baseline| > atol + rtol |baseline|); changes of NOTES are reported only. It writes DIR/report.md (what changed, by how
much) and, for each changed case, DIR/<case>.png: the case's film thickness and orbit
(the accepted study's series beside them if --accepted-study is given) and its metrics
against the baseline's. --accept writes the baseline from STUDY instead. Exit 2: bad input.
"""
import csv
import math
import os

from lubjoint import study as study_reader  # (PYTHONPATH=build/python: docs/guide/post-processing.md)
# The comparison itself (keys, tolerances, baseline reader) is lubjoint.baseline's, shared with
# the HTML report (lubjoint.report --baseline).
from lubjoint import baseline as nightly
from lubjoint.baseline import INFO, KEY, TOLERANCES, fmt, key_text


def study_rows(path):
    """The study's cases as {key: row dict} (lubjoint.baseline.study_rows), or exit with the message."""
    try:
        return nightly.study_rows(path)
    except (nightly.BaselineError, study_reader.StudyFormatError, OSError) as e:
        raise SystemExit(f"nightly: {e}") from None


def read_baseline(path):
    """The baseline CSV (lubjoint.baseline.read_baseline), or exit with the message."""
    try:
        return nightly.read_baseline(path)
    except nightly.BaselineError as e:
        raise SystemExit(f"nightly: {e}") from None


def accept(study, baseline):
    rows = study_rows(study)
    cols = KEY + ["case", "hash", "status", "classification"] + list(TOLERANCES) + INFO
    tmp = baseline + ".partial"
    with open(tmp, "w", newline="") as f:
        f.write("# Baseline of the nightly reproduction (tools/check/nightly.sh): the metrics of every case of\n"
                "# configs/grids/paper.json, keyed by the axis columns clearance_m [m], viscosity_Pa_s [Pa s],\n"
                "# speed_rpm [min-1], force_law. Units in the column names (metrics as in /cases); steps and\n"
                "# wall_time_s are recorded, not compared. Tolerances: TOLERANCES in core/python/lubjoint/baseline.py.\n"
                "# Regenerate with: tools/check/nightly.sh --accept (then review the diff and commit it).\n")
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore", lineterminator="\n")
        w.writeheader()
        for k in sorted(rows, key=lambda k: rows[k]["case"]):
            w.writerow({c: fmt(c, v) for c, v in rows[k].items()})
    os.replace(tmp, baseline)
    print(f"nightly: wrote {baseline}: {len(rows)} cases from {study}")
    return 0


def figure(path, key, now, base, study, accepted, outdir):
    """Side by side: film thickness and orbit now (and accepted), and the metrics' changes."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, axs = plt.subplots(1, 3, figsize=(15, 4.2))
    sources = [("now", study, now["case"], "C0")]
    if accepted and os.path.exists(accepted):
        try:
            acc = study_rows(accepted).get(key)
            if acc is not None:
                sources.insert(0, ("accepted", accepted, acc["case"], "k"))
        except SystemExit:
            pass
    for label, f, case, colour in sources:
        s = study_reader.series(f, case)
        if s is None or "h_min" not in s:
            continue
        a = s["crank_angle"].values if "crank_angle" in s else s["t"].values
        deg = np.degrees(a - 2 * math.pi * math.floor(a[0] / (2 * math.pi) + 1e-6))
        axs[0].plot(deg, s["h_min"].values * 1e6, color=colour, lw=0.8, label=f"{label} ({case})")
        if "e_x" in s:
            axs[1].plot(s["e_x"].values * 1e3, s["e_y"].values * 1e3, color=colour, lw=0.8, label=label)
    axs[0].axhline(base["min_film_thickness_m"] * 1e6, color="firebrick", ls="--", lw=0.8, label="baseline h_min")
    axs[0].set_xlabel("crank angle [deg]")
    axs[0].set_ylabel("minimum film thickness [µm]")
    axs[0].legend(fontsize=7)
    axs[1].set_aspect("equal")
    axs[1].set_xlabel("e_x [mm]")
    axs[1].set_ylabel("e_y [mm]")
    axs[1].set_title("journal orbit", fontsize=9)
    names = [m for m in TOLERANCES if isinstance(base[m], float) and base[m] != 0 and math.isfinite(base[m])]
    rel = [(now[m] - base[m]) / abs(base[m]) * 100 if math.isfinite(now[m]) else float("nan") for m in names]
    axs[2].barh(names, rel, color=["firebrick" if abs(r) > 0 else "gray" for r in rel])
    axs[2].set_xscale("symlog", linthresh=1.0)
    axs[2].set_xlabel("change against the baseline [%] (symlog)")
    axs[2].tick_params(labelsize=7)
    fig.suptitle(f"{now['case']}: {key_text(key)}", fontsize=10)
    fig.tight_layout()
    out = os.path.join(outdir, f"{now['case']}.png")
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out


def compare(study, baseline, report_dir, accepted):
    now, base = study_rows(study), read_baseline(baseline)
    if report_dir:
        os.makedirs(report_dir, exist_ok=True)
        for old in os.listdir(report_dir):  # figures of an earlier comparison
            if old.startswith("case_") and old.endswith(".png"):
                os.remove(os.path.join(report_dir, old))
    c = nightly.compare(now, base)
    regressions, notes, changed, worst = c["regressions"], c["notes"], c["changed"], c["worst"]

    lines = [f"# Nightly reproduction: {'REGRESSION' if regressions else 'ok'}", "",
             f"Study `{study}` against baseline `{baseline}`: {len(base)} baseline cases, {len(now)} in the study, "
             f"{len(regressions)} regression{'s' if len(regressions) != 1 else ''}.", ""]
    if regressions:
        lines += ["## Regressions", ""] + [f"- {r}" for r in regressions] + [""]
    if notes:
        lines += ["## Notes", ""] + [f"- {n}" for n in notes] + [""]
    if changed:
        lines += ["## Changed cases", ""]
        for k, items in changed.items():
            c = now[k]["case"]
            lines += [f"### {c}: {key_text(k)}", "", "| metric | baseline | now | relative | tolerance |",
                      "|---|---|---|---|---|"] + [f"| {' | '.join(map(str, it))} |" for it in items] + [""]
            if report_dir:
                try:
                    png = figure(study, k, now[k], base[k], study, accepted, report_dir)
                    lines += [f"![{c}]({os.path.basename(png)})", ""]
                except Exception as e:  # a figure is a help, not the verdict
                    lines += [f"(no figure: {e})", ""]
    lines += ["## Largest deviation per metric (against its tolerance)", "",
              "| metric | deviation / tolerance | abs. deviation | relative (max_eps: of 1 - eps) | tolerance | case |",
              "|---|---|---|---|---|---|"]
    for m, (ratio, dev, rel, lim, c) in worst.items():
        lines.append(f"| {m} | {ratio:.3g} | {dev:.3g} | {rel:.3g} | {lim:.3g} | {c} |")
    steps_now = sum(n["steps"] for n in now.values() if math.isfinite(n["steps"]))
    steps_base = sum(b["steps"] for b in base.values() if math.isfinite(b["steps"]))
    lines += ["", f"Cost (not compared): {steps_now:.0f} integrator steps in all, baseline {steps_base:.0f}."]
    text = "\n".join(lines) + "\n"
    if report_dir:
        with open(os.path.join(report_dir, "report.md"), "w") as f:
            f.write(text)
    for r in regressions:
        print("REGRESSION " + r)
    print(f"nightly: {len(regressions)} regression{'s' if len(regressions) != 1 else ''} "
          f"({len(base)} baseline cases)" + (f"; report {os.path.join(report_dir, 'report.md')}" if report_dir else ""))
    return 1 if regressions else 0


def add_arguments(ap):
    ap.add_argument("study")
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--baseline", default=os.path.join(here, "..", "..", "tests", "baselines", "paper.csv"))
    ap.add_argument("--report", default=None, help="directory of report.md and the figures")
    ap.add_argument("--accepted-study", default=None, help="the study the baseline was accepted from, if kept")
    ap.add_argument("--accept", action="store_true", help="write the baseline from the study instead of comparing")


def run(args):
    if args.accept:
        return accept(args.study, args.baseline)
    return compare(args.study, args.baseline, args.report, args.accepted_study)
