#!/usr/bin/python3
"""Figures of steady cycles (docs/theory/steady-cycles.md).

    PYTHONPATH=build/python /usr/bin/python3 tools/plot/steady.py STUDY.h5 -o DIR [--orbit]

From a study over clearance x viscosity x crank speed x force law (configs/grids/
full_factorial.json):
  steady_classification.png   each case's classification, one panel per law and speed; the grid
                              edges where the orbit changes (lubjoint.study.bifurcation_edges):
                              F fold, PD period doubling, NS Neimark-Sacker (a bar where
                              |mu|max crosses 1, interpolated between the cells), X orbit lost
                              (a dashed bar midway), ? unclassified; an edge along the crank
                              speed is a letter at the cell's side, its arrow toward the panel
                              of the other end
  steady_edges.csv            those edges (the columns of bifurcation_edges), when there are any
  steady_multiplier.png       the dominant Floquet multiplier's modulus |mu|max there
With --orbit (needs the compiled lubjoint module): Frene long at the reference case,
  steady_frene_long_orbit.png  the journal's orbit over a 40-cycle transient, its Poincare
                               points at crank angle 0, and the periodic orbit shooting finds.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
from lubjoint import plot as lubplot  # noqa: E402  (the classification colours of lubjoint.plot's maps)
from lubjoint import study as study_reader  # noqa: E402  (PYTHONPATH=build/python: docs/guide/post-processing.md)

# One colour per classification, the same in lubjoint.plot.classification_map.
CLASSES = list(lubplot.CLASSIFICATION_COLOURS)
COLOURS = list(lubplot.CLASSIFICATION_COLOURS.values())
# The edges' marks (lubjoint.bifurcations.KINDS gives the letters).
EDGE_COLOURS = {"fold": "#d62828", "period_doubling": "#1d3557", "neimark_sacker": "#7b2cbf",
                "unclassified": "#555555", "orbit_lost": "#000000"}
EDGE_NAMES = {"fold": "F fold", "period_doubling": "PD period doubling", "neimark_sacker": "NS Neimark-Sacker",
              "unclassified": "? unclassified", "orbit_lost": "X orbit lost"}


def edge_fraction(e):
    """Where |mu|max crosses 1 on an edge, as the fraction of the way from its case a to its case b
    (the cells are one step apart; the crossing was interpolated in the log of the axis value); 0.5
    where there is no crossing value (orbit lost)."""
    x, va, vb = e.crossing_value, e.value_a, e.value_b
    if not np.isfinite(x):
        return 0.5
    if va > 0 and vb > 0:
        return float(np.log(x / va) / np.log(vb / va))
    return float((x - va) / (vb - va))


def draw_edges(axs, layout, cases, edges):
    """The edges on the panels: a bar across the link at the crossing with the kind's letter; along
    the crank speed (between panels) a letter at the cell's side, its arrow toward the other panel.
    Returns the kinds drawn."""
    laws, speeds, clearances, viscosities = layout
    drawn = set()
    for e in edges.itertuples():
        ends = [cases.loc[e.case_a], cases.loc[e.case_b]]
        colour, letter = EDGE_COLOURS[e.kind], study_reader.BIFURCATION_LETTERS[e.kind]
        style = dict(color=colour, lw=2.2, ls="--" if e.kind == "orbit_lost" else "-", solid_capstyle="butt")
        box = dict(fc="white", ec=colour, lw=0.6, pad=0.6, alpha=0.9)
        try:
            cells = [(laws.index(r["force_law"]), speeds.index(r["speed_rpm"]), clearances.index(r["clearance_m"]),
                      viscosities.index(r["viscosity_Pa_s"])) for r in ends]
        except ValueError:  # a cell off the panels (an axis unset, NaN)
            continue
        if e.axis in ("clearance_m", "viscosity_Pa_s"):
            (i, j, ya, xa), (_, _, yb, xb) = cells
            t = edge_fraction(e)
            x, y = xa + t * (xb - xa), ya + t * (yb - ya)
            bar = ([x - 0.4, x + 0.4], [y, y]) if e.axis == "clearance_m" else ([x, x], [y - 0.4, y + 0.4])
            axs[i][j].plot(*bar, **style)
            axs[i][j].text(x, y, letter, ha="center", va="center", fontsize=6, color=colour, bbox=box)
        elif e.axis == "speed_rpm":
            for (i, j, y, x), (_, jo, _, _) in ((cells[0], cells[1]), (cells[1], cells[0])):
                left = jo < j
                axs[i][j].text(x - 0.48 if left else x + 0.48, y, f"\u2190{letter}" if left else f"{letter}\u2192",
                               ha="left" if left else "right", va="center", fontsize=6, color=colour, bbox=box)
        else:
            continue
        drawn.add(e.kind)
    return drawn


def grid_panels(cases, value, title, out, cmap=None, norm=None, categorical=False, edges=None, label=None,
                annotate=None):
    """One panel per force law and crank speed, clearance x viscosity in each; `value(row)` the
    cell's number (NaN: blank), on one colour scale (`norm`) for all panels; `annotate(v, row)`
    the text written in a cell with a value."""
    laws = list(dict.fromkeys(cases["force_law"]))
    speeds = sorted(set(cases["speed_rpm"]), reverse=True)
    clearances = sorted(set(cases["clearance_m"]), reverse=True)
    viscosities = sorted(set(cases["viscosity_Pa_s"]), reverse=True)
    fig, axs = plt.subplots(len(laws), len(speeds), figsize=(3.0 * len(speeds), 2.6 * len(laws)), squeeze=False)
    for i, law in enumerate(laws):
        for j, speed in enumerate(speeds):
            ax = axs[i][j]
            img = np.full((len(clearances), len(viscosities)), np.nan)
            rows = {}
            sel = cases[(cases["force_law"] == law) & (cases["speed_rpm"] == speed)]
            for _, r in sel.iterrows():
                at = (clearances.index(r["clearance_m"]), viscosities.index(r["viscosity_Pa_s"]))
                img[at], rows[at] = value(r), r
            im = ax.imshow(img, cmap=cmap, norm=norm, aspect="auto")
            if annotate is not None:
                for (y, x), v in np.ndenumerate(img):
                    if np.isfinite(v):
                        # below the middle in a classification map, whose edges' labels sit there
                        ax.text(x, y + (0.3 if categorical else 0.0), annotate(v, rows[y, x]), ha="center",
                                va="center", fontsize=6,
                                color="black" if norm is None or norm(v) > 0.5 else "white")
            ax.set_xticks(range(len(viscosities)), [f"{v * 1e3:g}" for v in viscosities], fontsize=7)
            ax.set_yticks(range(len(clearances)), [f"{c * 1e3:g}" for c in clearances], fontsize=7)
            if i == len(laws) - 1:
                ax.set_xlabel("viscosity [cP]", fontsize=8)
            if j == 0:
                ax.set_ylabel(f"{law}\nclearance [mm]", fontsize=8)
            if i == 0:
                ax.set_title(f"{speed:g} rpm", fontsize=9)
    drawn = set()
    if edges is not None and len(edges):
        drawn = draw_edges(axs, (laws, speeds, clearances, viscosities), cases, edges)
    if categorical:
        handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in COLOURS]
        labels = list(CLASSES)
        for kind in (k for k in EDGE_NAMES if k in drawn):
            handles.append(plt.Line2D([0], [0], color=EDGE_COLOURS[kind], lw=2.2,
                                      ls="--" if kind == "orbit_lost" else "-"))
            labels.append(EDGE_NAMES[kind])
        fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8)
        fig.subplots_adjust(bottom=0.12 if not drawn else 0.16)
    else:
        fig.colorbar(im, ax=axs, shrink=0.6, label=label, extend="max")
    fig.suptitle(title, fontsize=10)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print(out)


def orbit_figure(out):
    import lubjoint
    scene = os.path.join(here, "..", "configs", "scenes", "slider_crank.json")
    base = {"/joints/3/force_law": "frene_long", "/outputs/last_cycles": 0}
    tr = lubjoint.simulate(scene, {**base, "/simulation/max_cycles": 40})
    sh = lubjoint.simulate(scene, {**base, "/simulation/steady": "shooting", "/simulation/max_cycles": 40})
    c = 0.5e-3
    fig, ax = plt.subplots(1, 2, figsize=(11, 5))
    ax[0].plot(tr["e_x"] / c, tr["e_y"] / c, lw=0.3, color="0.6", label="transient, 40 cycles from the centre")
    ax[0].plot(tr["cycle_end_eccentricity_x"], tr["cycle_end_eccentricity_y"], "o", ms=3, color="C0",
               label="its Poincare points (crank angle 0)")
    ax[0].add_patch(plt.Circle((0, 0), 1.0, fill=False, color="k", lw=0.8))
    ax[0].set_aspect("equal")
    ax[0].set_xlabel("e_x / c")
    ax[0].set_ylabel("e_y / c")
    ax[0].plot(sh["orbit_e_x"] / c, sh["orbit_e_y"] / c, lw=1.5, color="C3", label="periodic orbit (shooting)")
    mu = sh["multiplier_modulus"].values
    ang = sh["multiplier_angle_rad"].values
    ax[0].set_title(f"Frene long, reference case: {sh.attrs['classification']}, |mu|max = {mu[0]:.4f}", fontsize=9)
    ax[0].legend(fontsize=7, loc="lower left")
    k = np.arange(1, tr.sizes["cycle"] + 1)
    ax[1].semilogy(k, tr["cycle_periodicity"], "o-", ms=3, label="orbit change per cycle / c (transient)")
    ax[1].semilogy(k, np.abs(tr["cycle_min_film_thickness_m"] - sh["min_film_thickness_m"].item()) /
                   sh["min_film_thickness_m"].item(), "s-", ms=3,
                   label=f"|h_min(cycle) - h_min(orbit)| / h_min(orbit); h_min(orbit) = "
                         f"{sh['min_film_thickness_m'].item() * 1e6:.3f} um")
    kk = np.linspace(1, 40, 100)
    ax[1].semilogy(kk, tr["cycle_periodicity"].values[1] * mu[0] ** (kk - 2), "k--", lw=0.8,
                   label=f"|mu|max^k: the decay shooting predicts ({mu[0]:.4f}, angle {abs(ang[0]):.3f} rad)")
    ax[1].set_xlabel("cycle")
    ax[1].legend(fontsize=7)
    ax[1].set_title(f"shooting: {int(sh['periods_integrated'].item())} periods, "
                    f"{int(sh['newton_iterations'].item())} Newton iterations", fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study")
    ap.add_argument("-o", "--outdir", default="out/figures")
    ap.add_argument("--orbit", action="store_true")
    a = ap.parse_args()
    study_reader.check_or_exit(a.study)
    cases = study_reader.cases(a.study)
    os.makedirs(a.outdir, exist_ok=True)
    from matplotlib.colors import BoundaryNorm, ListedColormap
    cmap = ListedColormap(COLOURS)
    norm = BoundaryNorm(np.arange(len(CLASSES) + 1) - 0.5, len(CLASSES))
    orbit = study_reader.orbit_classifications(cases)  # as the file says
    edges = study_reader.bifurcation_edges(cases)
    if len(edges):
        edges.to_csv(os.path.join(a.outdir, "steady_edges.csv"), index=False)
        print(os.path.join(a.outdir, "steady_edges.csv"))
    continued = "continued_from" in cases and (cases["continued_from"] >= 0).any()
    grid_panels(cases, lambda r: CLASSES.index(r["classification"]) if r["classification"] in CLASSES else np.nan,
                f"steady-cycle classification (simulation.steady = {'continuation' if continued else 'auto'})",
                os.path.join(a.outdir, "steady_classification.png"), cmap=cmap, norm=norm, categorical=True,
                edges=edges, annotate=lambda v, r: lubplot.posedness_note(
                    r["classification"], r.get("orbit_conditioning", np.nan), r.get("drift_exponent", np.nan), orbit))
    # One scale for every panel: |mu|max in [0, 1] (a stable orbit), above 1 red (unstable);
    # only where an orbit was found and located (a not-located fixed point has multipliers too).
    from matplotlib.colors import Normalize
    grid_panels(cases, lambda r: r["multiplier_1_modulus"] if r["classification"] in orbit else np.nan,
                "dominant Floquet multiplier |mu|max of the periodic orbits (blank: no orbit)",
                os.path.join(a.outdir, "steady_multiplier.png"),
                cmap=plt.get_cmap("viridis").with_extremes(over="#d62828"), norm=Normalize(0.0, 1.0),
                label="|mu|max (red: > 1, unstable)", annotate=lambda v, r: f"{v:.4f}" if v > 0.99 else f"{v:.3f}")
    if a.orbit:
        orbit_figure(os.path.join(a.outdir, "steady_frene_long_orbit.png"))


if __name__ == "__main__":
    main()
