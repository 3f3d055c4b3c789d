#!/usr/bin/python3
"""The paper's figures from a lubsweep study file (configs/grids/paper.json or one of the
paper_*.json grids).

    PYTHONPATH=build/python /usr/bin/python3 tools/plot/paper.py out/study.h5 [-o out/figures]

Writes PNGs (Agg backend, no display needed):
  fig05_reference.png           the reference case (0.5 mm, 400 cP, 5000 rpm, Pinkus-Sternlicht):
                                slider velocity and acceleration, joint reaction, journal orbit,
                                minimum film thickness, phase portrait
  fig05_reference_pressure.png  the reference case's film pressure over its steady cycle: the
                                mid-plane pressure over crank angle and bearing angle, its profile
                                at four crank angles, and the peak pressure (the case re-run from
                                its scene with the channels the field needs; needs the compiled
                                lubjoint)
  figNN_<study>_reaction.png    joint reaction force against crank angle, one panel per case,
                                with the ideal-joint mechanism at the same crank speed (dashed)
  figNN_<study>_orbit.png       journal centre orbit inside the clearance circle
  figNN_<study>_film.png        minimum film thickness against crank angle (safe film dotted)
  figNN_<study>_phase.png       phase portrait: eps_dot against eps
for each one-axis sub-grid of the study (clearance, viscosity, speed, force_law: the
paper's Figs. 6-21). Series are what the study stored for each case: a periodic case's
periodic orbit (the metric cycles; docs/reference/study-file.md), otherwise the run's last
cycles, marked in the panel as a transient with its classification; a case that did not
complete shows its status instead.
"""
import argparse
import math
import os
import sys
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from lubjoint import study as study_reader  # noqa: E402  (PYTHONPATH=build/python: docs/guide/post-processing.md)

# Paper figure numbers of the four studies (reaction, orbit, film, phase).
FIRST_FIGURE = {"clearance": 6, "viscosity": 10, "speed": 14, "force_law": 18}
# Channels each panel needs (configs/grids/paper.json stores them all).
NEEDS = {"reaction": ["reaction_force"], "orbit": ["e_x", "e_y"], "film": ["h_min"], "phase": ["eps", "eps_dot"]}
AXIS_WORDS = {"clearance_m": "clearance sizes", "viscosity_Pa_s": "lubricant viscosities",
              "speed_rpm": "crank speeds", "force_law": "hydrodynamic force models"}
LAW_NAMES = {"pinkus_sternlicht": "Pinkus-Sternlicht", "frene_long": "Frêne long",
             "frene_short": "Frêne short", "ideal": "ideal"}


def crank_deg(s):
    """Crank angle in degrees from the start of the stored cycles (0 .. 360 k)."""
    a = s["crank_angle"]
    return np.degrees(a - 2 * math.pi * math.floor(a[0] / (2 * math.pi) + 1e-6))


def case_title(cases, cid, axis):
    v = cases.at[cid, axis]
    if axis == "clearance_m":
        return f"c = {v * 1e3:g} mm"
    if axis == "viscosity_Pa_s":
        return f"μ = {v * 1e3:g} cP"
    if axis == "speed_rpm":
        return f"n = {v:g} rpm"
    if axis == "force_law":
        return LAW_NAMES.get(v, str(v))
    return f"{axis} = {v}"


def clearance_m(path, cases, cid):
    if "clearance_m" in cases.columns:
        return float(cases.at[cid, "clearance_m"])
    scene = study_reader.scene(path, cid)
    name = scene.get("metrics", {}).get("joint")
    for j in scene["joints"]:
        if j.get("name") == name and "bearing_radius_m" in j:
            return j["bearing_radius_m"] - j["journal_radius_m"]
    return float("nan")


class Figures:
    def __init__(self, path, outdir):
        self.path, self.out, self.written = path, outdir, []
        self.c = study_reader.cases(path)
        # Classifications whose stored channels are a steady cycle (the periodic orbit shooting
        # found, or a transient the period map confirmed), as the file says; the others' are a
        # transient's last cycles.
        self.steady = study_reader.orbit_classifications(self.c)
        self.ideal_by_speed = {}
        if "force_law" in self.c.columns:
            ideal = self.c[(self.c["force_law"] == "ideal") & (self.c["status"] == "ok")]
            for cid, row in ideal.iterrows():
                self.ideal_by_speed.setdefault(row.get("speed_rpm"), cid)

    def value(self, column, cid):
        return self.c.at[cid, column]

    def series(self, cid):
        """A case's channels as numpy arrays, or None."""
        ds = study_reader.series(self.path, self.value("name", cid))
        return None if ds is None else {k: v.values for k, v in ds.variables.items()}

    def ideal_for(self, cid):
        speed = self.value("speed_rpm", cid) if "speed_rpm" in self.c.columns else None
        ic = self.ideal_by_speed.get(speed)
        return None if ic is None else (ic, self.series(ic))

    def save(self, fig, name):
        path = os.path.join(self.out, name)
        fig.savefig(path, dpi=110)
        plt.close(fig)
        self.written.append(path)

    def status_panel(self, ax, cid):
        st, msg = self.value("status", cid), self.value("message", cid)
        ax.text(0.5, 0.5, f"{st}\n{msg[:60]}", ha="center", va="center", transform=ax.transAxes, fontsize=8,
                wrap=True, color="firebrick")

    # --- one quantity in one panel -------------------------------------------------------
    def reaction(self, ax, cid, s):
        ideal = self.ideal_for(cid)
        if ideal and ideal[1] is not None and ideal[0] != cid and "reaction_force" in ideal[1]:
            ax.plot(crank_deg(ideal[1]), ideal[1]["reaction_force"], "k--", lw=0.9, label="ideal joint")
        ax.plot(crank_deg(s), s["reaction_force"], lw=0.8, label="lubricated joint")
        ax.set_xlabel("crank angle [deg]")
        ax.set_ylabel("joint reaction [N]")

    def orbit(self, ax, cid, s):
        c = clearance_m(self.path, self.c, cid)
        th = np.linspace(0, 2 * math.pi, 361)
        ax.plot(c * 1e3 * np.cos(th), c * 1e3 * np.sin(th), "k-", lw=0.8)
        ax.plot(s["e_x"] * 1e3, s["e_y"] * 1e3, lw=0.8)
        ax.set_aspect("equal")
        ax.set_xlabel("e_x [mm]")
        ax.set_ylabel("e_y [mm]")

    def film(self, ax, cid, s):
        ax.plot(crank_deg(s), s["h_min"] * 1e6, lw=0.8)
        safe = self.value("safe_film_thickness_m", cid)
        if safe is not None and np.isfinite(safe) and safe > 0:
            ax.axhline(safe * 1e6, color="firebrick", ls=":", lw=0.8, label="safe film")
        ax.set_xlabel("crank angle [deg]")
        ax.set_ylabel("min. film thickness [μm]")

    def phase(self, ax, cid, s):
        ax.plot(s["eps"], s["eps_dot"], lw=0.6)
        ax.set_xlabel("ε")
        ax.set_ylabel("dε/dt [1/s]")

    def panel(self, ax, what, cid, title):
        s = self.series(cid)
        ax.set_title(title, fontsize=9)
        ax.tick_params(labelsize=7)
        ax.xaxis.label.set_size(8)
        ax.yaxis.label.set_size(8)
        if s is None or "crank_angle" not in s or len(s["crank_angle"]) < 2:
            self.status_panel(ax, cid)
            return
        missing = [c for c in NEEDS[what] if c not in s]
        if missing:
            ax.text(0.5, 0.5, "not stored: " + ", ".join(missing), ha="center", va="center",
                    transform=ax.transAxes, fontsize=8, color="gray")
            return
        getattr(self, what)(ax, cid, s)
        if self.value("status", cid) != "ok":
            ax.text(0.02, 0.02, self.value("status", cid), transform=ax.transAxes, fontsize=7, color="firebrick")
        elif "classification" in self.c.columns and self.value("classification", cid) not in self.steady:
            # No steady cycle: the stored channels are the run's last cycles, a transient, or
            # where its slow flow got to (docs/theory/steady-cycles.md, slow flow).
            flow = self.value("slow_flow_cycles", cid) if "slow_flow_cycles" in self.c.columns else 0.0
            where = (f"where its slow flow got to\n(~{flow:.0f} cycles on), no steady cycle"
                     if flow == flow and flow > 0 else "last cycles of a transient, no steady cycle")
            ax.text(0.02, 0.02, f"{self.value('classification', cid)}: {where}",
                    transform=ax.transAxes, fontsize=7, color="firebrick")
        ax.grid(True, lw=0.3, alpha=0.5)

    # --- figures -------------------------------------------------------------------------
    def study_figures(self, grid, g):
        axis = g.case_id.dims[0]
        ids = [int(i) for i in g.case_id.values.ravel()]
        first = FIRST_FIGURE.get(grid)
        labels = {"reaction": "joint reaction force", "orbit": "journal centre orbit",
                  "film": "minimum film thickness", "phase": "phase portrait"}
        for k, what in enumerate(["reaction", "orbit", "film", "phase"]):
            n = len(ids)
            cols = 2 if n == 4 else min(n, 3)
            rows = math.ceil(n / cols)
            fig, axs = plt.subplots(rows, cols, figsize=(4.6 * cols, 3.4 * rows), squeeze=False)
            for i, cid in enumerate(ids):
                self.panel(axs[i // cols][i % cols], what, cid, f"({chr(ord('a') + i)}) " + case_title(self.c, cid, axis))
            for j in range(n, rows * cols):
                axs[j // cols][j % cols].set_visible(False)
            if what == "reaction":
                axs[0][0].legend(fontsize=7, loc="best")
            fig.suptitle(f"{labels[what]} for different {AXIS_WORDS.get(axis, axis + ' values')}", fontsize=10)
            fig.tight_layout()
            num = f"fig{first + k:02d}_" if first else "fig_"
            self.save(fig, f"{num}{grid}_{what}.png")

    def reference(self, cid):
        s = self.series(cid)
        if s is None:
            return
        fig, axs = plt.subplots(2, 3, figsize=(12, 6.6))
        ideal = self.ideal_for(cid)
        x = crank_deg(s)
        for ax, key, label, scale in [(axs[0][0], "slider_v", "slider velocity [m/s]", 1.0),
                                      (axs[0][1], "slider_a", "slider acceleration [m/s²]", 1.0)]:
            if key not in s:
                ax.text(0.5, 0.5, "not stored: " + key, ha="center", va="center", transform=ax.transAxes,
                        fontsize=8, color="gray")
                continue
            if ideal and ideal[1] is not None and key in ideal[1]:
                ax.plot(crank_deg(ideal[1]), ideal[1][key] * scale, "k--", lw=0.9, label="ideal joint")
            ax.plot(x, s[key] * scale, lw=0.8, label="lubricated joint")
            ax.set_xlabel("crank angle [deg]", fontsize=8)
            ax.set_ylabel(label, fontsize=8)
            ax.tick_params(labelsize=7)
            ax.grid(True, lw=0.3, alpha=0.5)
        axs[0][0].legend(fontsize=7)
        self.panel(axs[0][2], "reaction", cid, "joint reaction")
        self.panel(axs[1][0], "orbit", cid, "journal centre orbit")
        self.panel(axs[1][1], "film", cid, "minimum film thickness")
        self.panel(axs[1][2], "phase", cid, "phase portrait")
        for ax, t in zip([axs[0][0], axs[0][1]], ["slider velocity", "slider acceleration"]):
            ax.set_title(t, fontsize=9)
        fig.suptitle("reference case: " + ", ".join(
            case_title(self.c, cid, a) for a in ["clearance_m", "viscosity_Pa_s", "speed_rpm", "force_law"]
            if a in self.c.columns), fontsize=10)
        fig.tight_layout()
        self.save(fig, "fig05_reference.png")


def pressure_figure(figs, cid):
    """fig05_reference_pressure.png: the film pressure of case `cid` over its steady cycle, from the
    law's own field (lubjoint.pressure) at the state of each sample. The study stores no wedge
    speed, so the case is run again from its scene with ε, ε̇ and w recorded."""
    try:
        import lubjoint
    except ImportError as e:  # the pure-Python reader works without the extension; this does not
        print(f"plot_paper: no pressure figure: {e}", file=sys.stderr)
        return
    scene = study_reader.scene(figs.path, cid)
    name = scene.get("metrics", {}).get("joint")
    joint = next((j for j in scene["joints"] if j.get("name") == name and "bearing_radius_m" in j), None)
    if joint is None or joint.get("force_law", "pinkus_sternlicht") == "ideal":
        return
    crank = [c for c in scene.get("outputs", {}).get("channels", []) if c.get("name") == "crank_angle"]
    channels = crank + [{"name": q, "joint": name, "quantity": q} for q in ("eps", "eps_dot", "wedge")]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", lubjoint.ValidityNote)  # the study's summary notes them
        ds = lubjoint.simulate(scene, {"/outputs/channels": channels, "/outputs/last_cycles": 1})
    pre = "orbit_" if "orbit_eps" in ds else ""
    if pre + "eps" not in ds:
        return
    s = {q: ds[pre + q].values for q in ("eps", "eps_dot", "wedge")}
    s["crank_angle"] = ds[pre + "crank_angle"].values if crank else ds[pre + "t"].values if pre else ds["t"].values
    law = joint.get("force_law", "pinkus_sternlicht")
    c = joint["bearing_radius_m"] - joint["journal_radius_m"]
    geometry = dict(radius_m=joint["journal_radius_m"], clearance_m=c, length_m=joint["length_m"],
                    viscosity_Pa_s=joint["viscosity_Pa_s"])
    theta = np.linspace(0.0, 2.0 * math.pi, 181)
    p = np.array([lubjoint.pressure(law, theta, e, ed, w, **geometry)
                  for e, ed, w in zip(s["eps"], s["eps_dot"], s["wedge"])]) / 1e6
    x = crank_deg(s) if crank else (s["crank_angle"] - s["crank_angle"][0]) / (s["crank_angle"][-1] - s["crank_angle"][0]) * 360
    fig, axs = plt.subplots(1, 3, figsize=(13, 4.0))
    lim = np.nanmax(np.abs(p))
    m = axs[0].pcolormesh(x, np.degrees(theta), p.T, shading="auto", cmap="RdBu_r", vmin=-lim, vmax=lim)
    fig.colorbar(m, ax=axs[0], label="pressure [MPa]")
    axs[0].set_xlabel("crank angle [deg]", fontsize=8)
    axs[0].set_ylabel("θ from the line of maximum film [deg]", fontsize=8)
    axs[0].set_title("mid-plane film pressure", fontsize=9)
    for k in np.linspace(0, len(x) - 1, 5)[:-1].astype(int):
        axs[1].plot(np.degrees(theta), p[k], lw=0.9, label=f"crank {x[k]:.0f}°")
    top = int(np.nanargmax(p.max(axis=1)))
    axs[1].plot(np.degrees(theta), p[top], "k", lw=1.2, label=f"peak, crank {x[top]:.0f}°")
    axs[1].set_xlabel("θ [deg]", fontsize=8)
    axs[1].set_ylabel("pressure [MPa]", fontsize=8)
    axs[1].set_title("pressure profiles", fontsize=9)
    axs[1].legend(fontsize=7)
    axs[2].plot(x, p.max(axis=1), lw=0.9)
    axs[2].set_xlabel("crank angle [deg]", fontsize=8)
    axs[2].set_ylabel("peak film pressure [MPa]", fontsize=8)
    axs[2].set_title("peak pressure over the cycle", fontsize=9)
    for ax in axs:
        ax.tick_params(labelsize=7)
        ax.grid(True, lw=0.3, alpha=0.5)
    what = "its periodic orbit" if pre else "its last cycle (no orbit located)"
    fig.suptitle(f"film pressure of the reference case ({LAW_NAMES.get(law, law)}), over {what}", fontsize=10)
    fig.tight_layout()
    figs.save(fig, "fig05_reference_pressure.png")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study", help="study file written by lubsweep")
    ap.add_argument("-o", "--outdir", default=None, help="directory of the PNGs (default: <study>_figures)")
    args = ap.parse_args()
    study_reader.check_or_exit(args.study)
    out = args.outdir or os.path.splitext(args.study)[0] + "_figures"
    os.makedirs(out, exist_ok=True)
    figs = Figures(args.study, out)

    grids = {n: study_reader.grid(args.study, n) for n in study_reader.grid_names(args.study)}
    studies = [(n, g) for n, g in grids.items() if g.attrs.get("kind") == "factorial" and g.case_id.ndim == 1
               and g.case_id.size > 1]
    # The paper's order first.
    studies.sort(key=lambda ng: FIRST_FIGURE.get(ng[0], 99))
    for name, g in studies:
        figs.study_figures(name, g)
    # Reference: the first case of the clearance study, else the first lubricated case.
    ref = None
    if "clearance" in grids:
        ref = int(grids["clearance"].case_id.values.ravel()[0])
    elif len(figs.c):
        ref = int(figs.c.index[0])
    if ref is not None:
        figs.reference(ref)
        pressure_figure(figs, ref)
    if not figs.written:
        print(f"plot_paper: {args.study}: no series to plot (does the grid store channels?)", file=sys.stderr)
        return 1
    for p in figs.written:
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main())
