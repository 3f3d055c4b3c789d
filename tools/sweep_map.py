#!/usr/bin/python3
"""Sweep maps: a metric of a lubsweep study over two of its axes, as a colour map with
the value printed in each cell.

    /usr/bin/python3 tools/sweep_map.py out/ff.h5 -x clearance_m -y viscosity_Pa_s \\
        --fix speed_rpm=5000 --fix force_law=pinkus_sternlicht -m max_eps -o out/maps
    /usr/bin/python3 tools/sweep_map.py out/ff.h5 -x speed_rpm -y clearance_m -m all ...

Every other axis that varies among the rows must be fixed with --fix AXIS=VALUE (the
message lists their values). `-m all` draws one map per metric column. Cases that are
not ok are hatched and labelled with their status. Writes <outdir>/map_<metric>_<x>_<y>.png.
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

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_io  # noqa: E402


def parse_fix(study, items):
    fixed = {}
    for it in items:
        if "=" not in it:
            raise SystemExit(f"sweep_map: --fix {it}: must be AXIS=VALUE")
        k, v = it.split("=", 1)
        if k not in study.axes:
            raise SystemExit(f"sweep_map: --fix {it}: {k} is not an axis of the study ({', '.join(study.axes)})")
        col = study.cases[k]
        fixed[k] = v if col.dtype.kind == "O" else float(v)
    return fixed


def select(study, x, y, fixed):
    rows = np.ones(study.n, dtype=bool)
    for k, v in fixed.items():
        col = study.cases[k]
        rows &= (col == v) if col.dtype.kind == "O" else np.isclose(col.astype(float), v, rtol=1e-12, atol=0)
    free = []
    for a in study.axes:
        if a in (x, y) or a in fixed:
            continue
        vals = ordered(study.cases[a][rows].tolist())
        if len(vals) > 1:
            free.append(f"{a} ({', '.join(map(str, vals))})")
    if free:
        raise SystemExit("sweep_map: fix the other axes that vary with --fix AXIS=VALUE: " + "; ".join(free))
    if not rows.any():
        raise SystemExit("sweep_map: no case matches the --fix values")
    return rows


def ordered(values):
    """Axis values in the order of the study's grids (as listed), else sorted."""
    try:
        return sorted(set(values), key=float)
    except (TypeError, ValueError):
        seen = []
        for v in values:
            if v not in seen:
                seen.append(v)
        return seen


def label(study, name):
    u = study.units.get(name, "")
    return f"{name} [{u}]" if u and u not in ("1",) and not name.endswith(u.replace(" ", "_")) else name


def draw(study, metric, x, y, rows, fixed, outdir):
    xs, ys = ordered(study.cases[x][rows].tolist()), ordered(study.cases[y][rows].tolist())
    z = np.full((len(ys), len(xs)), np.nan)
    status = np.empty((len(ys), len(xs)), dtype=object)
    for r in np.nonzero(rows)[0]:
        i, j = ys.index(study.cases[y][r]), xs.index(study.cases[x][r])
        z[i, j] = float(study.cases[metric][r])
        status[i, j] = study.cases["status"][r]
    finite = z[np.isfinite(z)]
    norm = None
    if finite.size and finite.min() > 0 and finite.max() / finite.min() > 100:
        norm = LogNorm(vmin=finite.min(), vmax=finite.max())
    fig, ax = plt.subplots(figsize=(1.4 * len(xs) + 2.6, 0.9 * len(ys) + 1.9))
    im = ax.imshow(np.ma.masked_invalid(z), origin="lower", cmap="viridis", norm=norm, aspect="auto")
    for i in range(len(ys)):
        for j in range(len(xs)):
            txt = "" if not math.isfinite(z[i, j]) else f"{z[i, j]:.3g}"
            if status[i, j] not in (None, "ok"):
                ax.add_patch(plt.Rectangle((j - 0.5, i - 0.5), 1, 1, fill=False, hatch="///", color="firebrick", lw=0))
                txt = f"{txt}\n{status[i, j]}"
            colour = "firebrick"
            if math.isfinite(z[i, j]):
                r, g, b, _ = im.cmap(im.norm(z[i, j]))
                colour = "black" if 0.299 * r + 0.587 * g + 0.114 * b > 0.5 else "white"
            ax.text(j, i, txt, ha="center", va="center", fontsize=7, color=colour,
                    bbox=None if status[i, j] in (None, "ok") else dict(fc="white", ec="none", alpha=0.7, pad=1))
    ax.set_xticks(range(len(xs)), [f"{v:g}" if isinstance(v, float) else str(v) for v in xs], fontsize=8)
    ax.set_yticks(range(len(ys)), [f"{v:g}" if isinstance(v, float) else str(v) for v in ys], fontsize=8)
    ax.set_xlabel(label(study, x))
    ax.set_ylabel(label(study, y))
    fig.colorbar(im, ax=ax, label=label(study, metric))
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
    s = study_io.Study(args.study)
    for a in (args.x, args.y):
        if a not in s.axes:
            raise SystemExit(f"sweep_map: {a} is not an axis of the study ({', '.join(s.axes)})")
    metrics = args.metric or ["max_eps"]
    if "all" in metrics:
        metrics = [m for m in s.metrics if s.cases[m].dtype.kind in "fiu"]
    for m in metrics:
        if m not in s.columns:
            raise SystemExit(f"sweep_map: {m} is not a column of /cases")
    fixed = parse_fix(s, args.fix)
    rows = select(s, args.x, args.y, fixed)
    os.makedirs(args.outdir, exist_ok=True)
    for m in metrics:
        print(draw(s, m, args.x, args.y, rows, fixed, args.outdir))
    return 0


if __name__ == "__main__":
    sys.exit(main())
