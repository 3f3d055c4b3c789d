#!/usr/bin/python3
"""Sweep maps: a metric of a lubsweep study over two of its axes, as a colour map with
the value printed in each cell.

    PYTHONPATH=build/python /usr/bin/python3 tools/plot/sweep_map.py out/ff.h5 -x clearance_m -y viscosity_Pa_s \\
        --fix speed_rpm=5000 --fix force_law=pinkus_sternlicht -m max_eps -o out/maps
    PYTHONPATH=build/python /usr/bin/python3 tools/plot/sweep_map.py out/ff.h5 -x speed_rpm -y clearance_m -m all ...

Every other axis that varies among the rows must be fixed with --fix AXIS=VALUE (the
message lists their values). `-m all` draws one map per metric column. Cases that are
not ok are hatched and labelled with their status (lubjoint.plot.cell_map, which draws the
module's classification maps too). Writes <outdir>/map_<metric>_<x>_<y>.png.
"""
import argparse
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402

from lubjoint import plot as lubplot  # noqa: E402  (the cells and labels lubjoint.plot draws its maps with)
from lubjoint import study as study_reader  # noqa: E402  (PYTHONPATH=build/python: docs/guide/post-processing.md)


def select(cases, axes, x, y, items):
    """The rows with the --fix values; every other axis that varies must be fixed."""
    rows, fixed = cases, {}
    for it in items:
        k, eq, v = it.partition("=")
        if not eq or k not in axes:
            raise SystemExit(f"sweep_map: --fix {it}: must be AXIS=VALUE with AXIS one of {', '.join(axes)}")
        fixed[k] = v if cases[k].dtype.kind == "O" else float(v)
        rows = rows[rows[k] == v] if cases[k].dtype.kind == "O" else rows[np.isclose(rows[k], float(v), rtol=1e-12, atol=0)]
    free = [f"{a} ({', '.join(map(str, rows[a].unique()))})" for a in axes
            if a not in (x, y) and a not in fixed and rows[a].nunique() > 1]
    if free:
        raise SystemExit("sweep_map: fix the other axes that vary with --fix AXIS=VALUE: " + "; ".join(free))
    if rows.empty:
        raise SystemExit("sweep_map: no case matches the --fix values")
    return rows, fixed


def ordered(col):
    """Axis values sorted if numeric, else in their order of appearance."""
    return sorted(col.unique()) if col.dtype.kind != "O" else list(dict.fromkeys(col))


def draw(rows, units, metric, x, y, fixed, outdir):
    xs, ys = ordered(rows[x]), ordered(rows[y])
    z = rows.pivot_table(index=y, columns=x, values=metric, aggfunc="first", dropna=False).reindex(index=ys, columns=xs)
    status = rows.pivot_table(index=y, columns=x, values="status", aggfunc="first").reindex(index=ys, columns=xs)
    z, status = z.to_numpy(dtype=float), status.to_numpy(dtype=object)
    finite = z[np.isfinite(z)]
    norm = None
    if finite.size and finite.min() > 0 and finite.max() / finite.min() > 100:
        norm = LogNorm(vmin=finite.min(), vmax=finite.max())
    fig, ax = plt.subplots(figsize=(1.4 * len(xs) + 2.6, 0.9 * len(ys) + 1.9))
    text = [["" if not math.isfinite(v) else f"{v:.3g}" for v in row] for row in z]
    im = lubplot.cell_map(ax, z, xs, ys, cmap="viridis", norm=norm, text=text, status=status)
    ax.set_xlabel(lubplot.axis_label(x, units.get(x, "")))
    ax.set_ylabel(lubplot.axis_label(y, units.get(y, "")))
    fig.colorbar(im, ax=ax, label=lubplot.axis_label(metric, units.get(metric, "")))
    title = metric + ("" if not fixed else "  (" + ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
                                                           for k, v in fixed.items()) + ")")
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    path = os.path.join(outdir, f"map_{metric}_{x}_{y}.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study")
    ap.add_argument("-x", required=True, help="axis along x")
    ap.add_argument("-y", required=True, help="axis along y")
    ap.add_argument("-m", "--metric", action="append", default=[], help="metric column (repeatable), or 'all'")
    ap.add_argument("--fix", action="append", default=[], help="AXIS=VALUE for every other varying axis")
    ap.add_argument("-o", "--outdir", default=".")
    args = ap.parse_args()
    study_reader.check_or_exit(args.study)
    cases = study_reader.cases(args.study)
    axes, units = list(cases.attrs.get("axes", [])), cases.attrs["units"]
    for a in (args.x, args.y):
        if a not in axes:
            raise SystemExit(f"sweep_map: {a} is not an axis of the study ({', '.join(axes)})")
    metrics = args.metric or ["max_eps"]
    if "all" in metrics:
        metrics = [m for m in cases.attrs["metrics"] if cases[m].dtype.kind in "fiu"]
    for m in metrics:
        if m not in cases.columns:
            raise SystemExit(f"sweep_map: {m} is not a column of /cases")
    rows, fixed = select(cases, axes, args.x, args.y, args.fix)
    os.makedirs(args.outdir, exist_ok=True)
    for m in metrics:
        print(draw(rows, units, m, args.x, args.y, fixed, args.outdir))
    return 0


if __name__ == "__main__":
    sys.exit(main())
