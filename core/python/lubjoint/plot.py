"""lubjoint.plot: figures of a run and of a study, each returned as a ``matplotlib.figure.Figure``.

Pure Python (NumPy, matplotlib, xarray; h5py for a run file): it does not load the compiled
extension, and it leaves pyplot alone (no window, no global figure list): save a figure with
``fig.savefig("orbit.png")``; in Jupyter it shows as a cell's value.

    from lubjoint import load_study, plot, simulate
    s = load_study("out/study.h5")
    plot.orbit(s.series(0))                      # the journal centre's path in the clearance circle
    plot.film(simulate("configs/scenes/slider_crank.json"))  # h_min and eps over crank angle
    plot.classification_map(s, "speed")          # each cell's classification
    plot.envelope(s, grid="clearance")           # min film thickness over clearance, per force law

A *run* is what ``lubjoint.simulate`` returns, the path of a run file (``lubsim -o``), or a
study case's stored channels (``Study.series``). Its steady cycle is the periodic orbit where
the run located one (``orbit_*``), else its last ``simulation.metric_cycles`` cycles; a study
stores a case's channels as that already. Channels are found by the names the scenes and
grids of configs/ give them: ``crank_angle``, ``e_x``, ``e_y``, ``eps``, ``h_min``.

A *study* is a ``Study`` (``load_study``) or the path of a study file; its figures are drawn
from one sub-grid (``study[grid]``): labelled variables over the grid's axes.

Axes are labelled with their units: lengths in µm, pressures in MPa, speeds in rpm
(``DISPLAY_UNITS``). ``cell_map``, ``axis_label`` and ``CLASSIFICATION_COLOURS`` are shared
with ``tools/plot/sweep_map.py`` and ``tools/plot/steady.py``.
"""

import itertools
import json
import math
import os

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle
from matplotlib.ticker import FuncFormatter, NullLocator
from matplotlib.transforms import blended_transform_factory

from .study import _text

#: How values in a unit are shown on an axis: (unit shown, factor from the stored value).
DISPLAY_UNITS = {"m": ("µm", 1e6), "Pa": ("MPa", 1e-6), "min-1": ("rpm", 1.0), "1": ("–", 1.0)}

#: One colour per steady-cycle classification (docs/theory/steady-cycles.md), in the maps of
#: this module and of tools/plot/steady.py; any other (``invalid_scene``, ``not_run``, ...) is grey.
CLASSIFICATION_COLOURS = {"periodic": "#2a9d8f", "periodic_unstable": "#e9c46a", "drifting": "#e76f51",
                          "not_converged": "#8d99ae", "film_collapse": "#6d597a", "solver_failure": "#000000",
                          "budget_exceeded": "#444444"}

#: The channels each figure of a run reads.
FILM_CHANNELS = ("h_min", "eps")


# --- shared by the figures and tools/plot --------------------------------------------------


def display(unit):
    """``(unit shown, factor)`` for values stored in ``unit`` (``DISPLAY_UNITS``; others as stored)."""
    return DISPLAY_UNITS.get(unit, (unit, 1.0))


def axis_label(name, unit, shown=None):
    """An axis label: ``name`` without its unit suffix, then the unit in brackets.

    ``axis_label("clearance_m", "m", "µm")`` is ``"clearance [µm]"``, ``axis_label("max_eps",
    "1")`` ``"max_eps [–]"``, ``axis_label("force_law", "")`` ``"force_law"`` (no unit: names).
    ``unit``: the stored unit (CF style, ``Pa s``, ``min-1``); ``shown``: the unit the values
    are drawn in (default: ``unit``, ``rpm`` for ``min-1``, ``–`` for ``1``).
    """
    if shown is None:  # as stored; rpm for min-1 and – for 1, which are the same numbers
        shown = display(unit)[0] if display(unit)[1] == 1.0 else unit
    return f"{_bare(name, unit)} [{shown}]" if shown else name


def _bare(name, unit):
    """``name`` without the suffix that spells its unit (``clearance_m``: ``clearance``)."""
    suffix = "_rpm" if unit == "min-1" else "_" + unit.replace(" ", "_").replace("-", "")
    return name[:-len(suffix)] if unit not in ("1", "") and name.endswith(suffix) else name


def _tick(v):
    return f"{v:g}" if isinstance(v, (int, float, np.number)) and not isinstance(v, bool) else str(v)


def cell_map(ax, values, xs, ys, *, cmap, norm=None, text=None, status=None):
    """Draw a table of cells on ``ax`` (row i: ``ys[i]``, bottom up; column j: ``xs[j]``).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    values : array_like, shape (len(ys), len(xs))
        Each cell's number, coloured by ``cmap`` and ``norm``; NaN: a blank cell.
    xs, ys : sequence
        The columns' and rows' values: the tick labels (numbers as ``%g``).
    text : array_like of str, optional
        Written in each cell, in black or white, whichever reads on the cell's colour.
    status : array_like of object, optional
        A cell whose status is a string other than ``"ok"`` is hatched and its status written in it.

    Returns
    -------
    matplotlib.image.AxesImage
        The cells, for a colour bar.
    """
    values = np.asarray(values, dtype=float)
    im = ax.imshow(np.ma.masked_invalid(values), origin="lower", cmap=cmap, norm=norm, aspect="auto")
    for (i, j), v in np.ndenumerate(values):
        st = None if status is None else status[i][j]
        failed = isinstance(st, str) and st != "ok"
        txt = "" if text is None else text[i][j]
        colour = "firebrick"
        if failed:
            ax.add_patch(Rectangle((j - 0.5, i - 0.5), 1, 1, fill=False, hatch="///", color="firebrick", lw=0))
            txt = f"{txt}\n{st}" if txt else st
        elif math.isfinite(v):
            r, g, b, _ = im.cmap(im.norm(v))
            colour = "black" if 0.299 * r + 0.587 * g + 0.114 * b > 0.5 else "white"
        if txt:
            ax.text(j, i, txt, ha="center", va="center", fontsize=7, color=colour,
                    bbox=dict(fc="white", ec="none", alpha=0.7, pad=1) if failed else None)
    ax.set_xticks(range(len(xs)), [_tick(v) for v in xs], fontsize=8)
    ax.set_yticks(range(len(ys)), [_tick(v) for v in ys], fontsize=8)
    ax.set_xticks(np.arange(len(xs) + 1) - 0.5, minor=True)
    ax.set_yticks(np.arange(len(ys) + 1) - 0.5, minor=True)
    ax.grid(which="minor", color="white", lw=1.5)
    ax.tick_params(which="minor", length=0)
    return im


# --- runs ----------------------------------------------------------------------------------


def _read_run_file(path):
    """A run file (lubsim's layout) as ``simulate`` returns a run: the channels over ``t``, the
    periodic orbit's as ``orbit_<name>`` over ``orbit_t``, /cycles as ``cycle_<name>``, the
    metrics as 0-d variables, the root attributes as ``attrs``."""
    import h5py
    import xarray as xr

    with h5py.File(path, "r") as f:
        groups, attrs = set(f), {k: _text(v) for k, v in f.attrs.items()}
        metrics = {k: _text(v) for k, v in f["metrics"].attrs.items()} if "metrics" in f else {}
    if attrs.get("program") == "lubsweep" or "series" not in groups:
        raise ValueError(f"{path}: not a run file (lubsim -o; /series): a study file is read with load_study")

    def group(name, prefix="", dim=None):
        with xr.open_dataset(path, group=name, engine="h5netcdf") as ds:
            ds = ds.load()
        ds = ds.rename({v: prefix + v for v in ds.data_vars})
        return ds.rename({"t": dim}) if dim else ds

    ds = group("series")
    for name, prefix, dim in (("orbit", "orbit_", "orbit_t"), ("cycles", "cycle_", None)):
        if name in groups:
            ds = ds.merge(group(name, prefix, dim))
    for k, v in metrics.items():
        if np.ndim(v) == 0 and not isinstance(v, str) and k not in ds:
            ds[k] = ((), v)
    ds.attrs = attrs
    ds.attrs.setdefault("classification", metrics.get("classification", ""))
    return ds


def _run(run):
    """``run`` as a Dataset: a path is read as a run file; None (a case that stored no channels) refused."""
    if isinstance(run, (str, os.PathLike)):
        return _read_run_file(os.fspath(run))
    if run is None:
        raise ValueError("no channels to plot (None: a study case that stored none; the grid's study.channels "
                         "names them)")
    return run


def _steady(ds, names):
    """The channels ``names`` over the run's steady cycle (a dict of arrays) and what that cycle is."""
    if all(f"orbit_{n}" in ds for n in names):
        return {n: ds[f"orbit_{n}"].values for n in names}, "periodic orbit"
    missing = [n for n in names if n not in ds]
    if missing:
        have = [k for k in ds.data_vars if ds[k].dims == ("t",)]
        raise ValueError(f"no channel {', '.join(missing)} in this run (it has {', '.join(have) or 'none'}): "
                         "record it (the scene's outputs.channels, the grid's study.channels)")
    if "cycle_t_start_s" in ds and ds.sizes.get("cycle", 0) and "scene" in ds.attrs:
        n = json.loads(ds.attrs["scene"]).get("simulation", {}).get("metric_cycles", 2)
        n = min(int(n), ds.sizes["cycle"])
        ds = ds.sel(t=slice(float(ds["cycle_t_start_s"].values[-n]), None))
        what = f"last {n} cycle{'s' if n > 1 else ''}" + (f", {ds.attrs['classification']}"
                                                          if ds.attrs.get("classification") else "")
    else:
        what = f"case {ds.attrs['case_id']}: stored cycles" if "case_id" in ds.attrs else "stored cycles"
    return {n: ds[n].values for n in names}, what


def _clearance(d, ds, clearance_m):
    """The radial clearance [m]: given, else |e|/eps from the channels, else the scene's metric joint's."""
    if clearance_m is not None:
        return float(clearance_m)
    if "eps" in d and np.any(d["eps"] > 1e-6):
        moving = d["eps"] > 1e-6
        return float(np.median(np.hypot(d["e_x"], d["e_y"])[moving] / d["eps"][moving]))
    scene = json.loads(ds.attrs.get("scene", "{}"))
    joint = scene.get("metrics", {}).get("joint")
    for j in scene.get("joints", []):
        if j.get("name") == joint and "bearing_radius_m" in j:
            return j["bearing_radius_m"] - j["journal_radius_m"]
    raise ValueError("the clearance is unknown (no eps > 0 recorded, no scene): pass clearance_m")


def _crank_deg(angle, *ys):
    """Crank angle [rad] as degrees in [0, 360), and ``ys``, with a NaN where a cycle wraps round."""
    deg = np.degrees(np.mod(angle, 2 * np.pi))
    wraps = np.flatnonzero(np.abs(np.diff(deg)) > 180) + 1
    return [np.insert(np.asarray(a, dtype=float), wraps, np.nan) for a in (deg, *ys)]


def orbit(run, *, units="clearance", clearance_m=None):
    """The journal centre's path over the run's steady cycle, inside the clearance circle.

    Parameters
    ----------
    run : xarray.Dataset or str or os.PathLike
        ``simulate``'s result, ``Study.series(case)``, or a run file; channels ``e_x``, ``e_y`` [m]
        (``eps`` [1] too where the clearance is to be read from them).
    units : {"clearance", "um"}
        Eccentricity as a fraction of the radial clearance c (the circle of radius 1), or in µm.
    clearance_m : float, optional
        c [m]; by default ``|e|/eps`` from the channels, else the scene's metric joint's (a
        ``simulate`` result or run file).

    Returns
    -------
    matplotlib.figure.Figure
        One axes, equal aspect: the circle, the path, and its first sample.
    """
    if units not in ("clearance", "um", "µm"):
        raise ValueError(f"orbit: units = {units!r}: must be 'clearance' or 'um'")
    ds = _run(run)
    d, what = _steady(ds, ["e_x", "e_y"] + [n for n in ("eps", "crank_angle") if n in ds])
    c = _clearance(d, ds, clearance_m)
    scale, shown = (1.0 / c, "c") if units == "clearance" else (1e6, "µm")
    radius = c * scale
    fig = Figure(figsize=(5.0, 5.6), layout="constrained")
    ax = fig.add_subplot()
    theta = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(radius * np.cos(theta), radius * np.sin(theta), "k-", lw=0.8,
            label=f"clearance circle, c = {c * 1e6:g} µm")
    ax.plot(d["e_x"] * scale, d["e_y"] * scale, lw=1.0, color="C0", label=what)
    start = f"crank angle {np.degrees(np.mod(d['crank_angle'][0], 2 * np.pi)):.0f}°" if "crank_angle" in d else "start"
    ax.plot(d["e_x"][0] * scale, d["e_y"][0] * scale, "o", ms=4, color="C3", label=start)
    ax.set_aspect("equal")
    ax.set_xlim(-1.08 * radius, 1.08 * radius)
    ax.set_ylim(-1.08 * radius, 1.08 * radius)
    ax.set_xlabel("e_x / c [–]" if shown == "c" else "e_x [µm]")
    ax.set_ylabel("e_y / c [–]" if shown == "c" else "e_y [µm]")
    ax.set_title("journal centre orbit", fontsize=10)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2, frameon=False)
    ax.grid(True, lw=0.3, alpha=0.5)
    return fig


def film(run, *, show=FILM_CHANNELS, safe_film_m=None):
    """Minimum film thickness and/or eccentricity ratio over crank angle, on the run's steady cycle.

    Parameters
    ----------
    run : xarray.Dataset or str or os.PathLike
        ``simulate``'s result, ``Study.series(case)``, or a run file; channels ``crank_angle``
        [rad] and those of ``show``.
    show : sequence of {"h_min", "eps"}
        One panel each, top down: ``h_min`` [m, drawn in µm], ``eps`` [1].
    safe_film_m : float, optional
        The safe film thickness [m], drawn across the ``h_min`` panel; by default the run's
        ``safe_film_thickness_m`` metric (a ``simulate`` result or run file has it; for a study
        case: ``study.cases["safe_film_thickness_m"].sel(case=k)``).

    Returns
    -------
    matplotlib.figure.Figure
        One axes per entry of ``show``, sharing the crank angle [deg] in [0, 360): each crank
        cycle drawn is a line of its own (a periodic orbit's lie on one another).
    """
    show = [show] if isinstance(show, str) else list(show)
    if not show or any(s not in FILM_CHANNELS for s in show):
        raise ValueError(f"film: show = {show!r}: one or both of {FILM_CHANNELS}")
    ds = _run(run)
    d, what = _steady(ds, ["crank_angle"] + show)
    x, *ys = _crank_deg(d["crank_angle"], *(d[s] for s in show))
    fig = Figure(figsize=(6.4, 1.2 + 2.4 * len(show)), layout="constrained")
    axs = fig.subplots(len(show), 1, sharex=True, squeeze=False)[:, 0]
    for ax, s, y in zip(axs, show, ys):
        ax.plot(x, y * (1e6 if s == "h_min" else 1.0), lw=1.0, label=what)
        ax.set_ylabel("minimum film thickness [µm]" if s == "h_min" else "eccentricity ratio ε [–]")
        ax.grid(True, lw=0.3, alpha=0.5)
    if "h_min" in show and np.isfinite(d["h_min"]).any():
        k = int(np.nanargmin(d["h_min"]))
        axs[show.index("h_min")].plot(np.degrees(np.mod(d["crank_angle"][k], 2 * np.pi)), d["h_min"][k] * 1e6, "v",
                                      color="C3", ms=6, label=f"least, {d['h_min'][k] * 1e6:.3g} µm")
    if "h_min" in show:
        safe = safe_film_m if safe_film_m is not None else ds.get("safe_film_thickness_m")
        if safe is not None and np.isfinite(float(safe)):
            axs[show.index("h_min")].axhline(float(safe) * 1e6, color="firebrick", ls="--", lw=0.9,
                                             label=f"safe film, {float(safe) * 1e6:g} µm")
    axs[0].legend(fontsize=7, loc="best")
    axs[-1].set_xlabel("crank angle [deg]")
    axs[-1].set_xlim(0, 360)
    axs[-1].set_xticks(range(0, 361, 60))
    axs[0].set_title(f"{' and '.join('film thickness' if s == 'h_min' else 'ε' for s in show)} over the "
                     "crank cycle", fontsize=10)
    return fig


# --- studies -------------------------------------------------------------------------------


def _grid(study, grid, axes):
    """The study (read if a path) and its sub-grid ``grid``; without a name, the one grid with ``axes``."""
    from .study import load_study

    if isinstance(study, (str, os.PathLike)):
        study = load_study(study)
    known = "; ".join(f"{n} ({', '.join(g['case_id'].dims)})" for n, g in study.items())
    if grid is None:
        fits = [n for n, g in study.items() if all(a in g.dims for a in axes)]
        if len(study) != 1 and len(fits) != 1:
            which = f"no grid has the axes {', '.join(axes)}" if axes and not fits else "name the grid (grid=)"
            raise ValueError(f"{study.path}: {which}; its grids (and axes): {known}")
        grid = next(iter(study)) if len(study) == 1 else fits[0]
    if grid not in study:
        raise KeyError(f"{study.path}: no grid {grid!r}; its grids (and axes): {known}")
    g = study[grid]
    for a in axes:
        if a not in g.dims:
            raise ValueError(f"{study.path}: grid {grid!r} has no axis {a!r}; its axes: {', '.join(g.dims)}")
    return study, grid, g


def _numeric(g, dim):
    return g[dim].dtype.kind in "iuf"


def _sorted(g):
    """The grid with its numeric axes in ascending order."""
    return g.sortby([d for d in g["case_id"].dims if _numeric(g, d)])


def _shown(g, dim):
    """A grid axis: its values as drawn, and its axis label."""
    if not _numeric(g, dim):
        return [str(v) for v in g[dim].values], dim
    unit = g[dim].attrs.get("units", "")
    shown, factor = display(unit)
    return g[dim].values * factor, axis_label(dim, unit, shown)


def _value_text(g, dim, value):
    """``speed = 5000 rpm``, ``force_law = frene_long``: one axis value, for a title."""
    if not _numeric(g, dim):
        return f"{dim} = {value}"
    unit = g[dim].attrs.get("units", "")
    shown, factor = display(unit)
    return f"{_bare(dim, unit)} = {value * factor:g} {shown}"


def _fixed(g, fix):
    """``g`` at the values of ``fix`` ({axis: value}): the axes are kept, of length 1."""
    for k, v in (fix or {}).items():
        if k not in g.dims or v not in list(g[k].values):
            values = ", ".join(map(_tick, g[k].values)) if k in g.dims else f"no such axis ({', '.join(g.dims)})"
            raise ValueError(f"fix: {k} = {v!r}: not a value of the grid's axis {k}: {values}")
    return g.sel({k: [v] for k, v in (fix or {}).items()})


def _along(da, axis):
    """The values of ``da`` over ``axis`` alone (its other axes of length 1)."""
    return da.squeeze([d for d in da.dims if d != axis]).transpose(axis).values


def _classification_colours(labels):
    """A colour for each classification in ``labels``: ``CLASSIFICATION_COLOURS``, greys for the others."""
    others = [c for c in labels if c not in CLASSIFICATION_COLOURS]
    greys = [str(v) for v in np.linspace(0.55, 0.85, len(others))]
    return [CLASSIFICATION_COLOURS.get(c) or greys[others.index(c)] for c in labels]


def posedness_note(classification, kappa, drift_exponent, orbits):
    """How well posed a cell's answer is, in a few characters: ``κ 57`` for a located orbit
    (its conditioning 1/min|1 − μ|), ``p 2.5`` for a drifting cell with a drift law (dh/dN =
    −a h^p), "" otherwise. ``orbits``: the classifications with an orbit
    (lubjoint.study.orbit_classifications)."""
    if classification in orbits and math.isfinite(kappa):
        return f"κ {kappa:.2g}"
    if classification == "drifting" and math.isfinite(drift_exponent):
        return f"p {drift_exponent:.2g}"
    return ""


def _posedness_notes(cell, cls, orbits):
    """``posedness_note`` of each cell of ``cell`` (a variable may be absent from an older file)."""
    def values(name):
        return np.atleast_2d(cell[name].values.astype(float)) if name in cell else np.full(cls.shape, np.nan)

    kappa, p = values("orbit_conditioning"), values("drift_exponent")
    notes = np.full(cls.shape, "", dtype=object)
    for (i, j), c in np.ndenumerate(cls):
        notes[i, j] = posedness_note(c, kappa[i, j], p[i, j], orbits)
    return notes


def classification_map(study, grid=None, x=None, y=None, *, fix=None, notes=True):
    """Each cell's steady-cycle classification over two axes of a sub-grid, one panel per value
    of the grid's other axes (force law, crank speed, ...).

    Parameters
    ----------
    study : Study or str or os.PathLike
    grid : str, optional
        The sub-grid (``study[grid]``); by default the one grid with ``x`` and ``y``.
    x, y : str, optional
        The axes across and up each panel (values in µm, rpm, Pa s: ``DISPLAY_UNITS``); by
        default the grid's first two numeric axes of more than one value, else its first.
        Without a second one, a panel is one row.
    fix : dict, optional
        ``{axis: value}``: draw only these values of the other axes.
    notes : bool, optional
        Write in each cell how well posed its answer is: a located orbit's conditioning
        ``κ`` = 1/min|1 − μ| (``orbit_conditioning``), a drifting cell's drift exponent ``p``
        (``drift_exponent``, dh/dN = −a h^p; docs/theory/slow-flow.md). Default True.

    Returns
    -------
    matplotlib.figure.Figure
        One axes per combination of the other axes' values (a column per value of the last of
        them with more than one, a row per combination of the others), and a legend of the
        classifications drawn. A case that is not ``ok`` is hatched and its status written in it.
    """
    from .study import orbit_classifications

    study, name, g = _grid(study, grid, [a for a in (x, y) if a])
    g = _sorted(_fixed(g, fix))
    dims = list(g["case_id"].dims)
    wide = [d for d in dims if g.sizes[d] > 1]
    x = x or next((d for d in wide if _numeric(g, d)), wide[0] if wide else dims[0])
    y = y or next((d for d in wide if _numeric(g, d) and d != x), None)
    rest = [d for d in dims if d not in (x, y)]
    found = {str(c) for c in g["classification"].values.ravel()}
    labels = [c for c in CLASSIFICATION_COLOURS if c in found] + sorted(found - set(CLASSIFICATION_COLOURS))
    colours = _classification_colours(labels)
    from matplotlib.colors import BoundaryNorm, ListedColormap

    cmap, norm = ListedColormap(colours), BoundaryNorm(np.arange(len(labels) + 1) - 0.5, len(labels))
    orbits = set(orbit_classifications(study.cases)) if notes else set()
    xs, xlabel = _shown(g, x)
    ys, ylabel = _shown(g, y) if y else ([""], "")
    ncols = next((g.sizes[d] for d in reversed(rest) if g.sizes[d] > 1), 1)
    panels = list(itertools.product(*(g[d].values for d in rest)))
    nrows = len(panels) // ncols
    fig = Figure(figsize=(ncols * (0.75 * len(xs) + 1.4) + 1.8, nrows * (0.45 * len(ys) + 1.0) + 0.6),
                 layout="constrained")
    axs = fig.subplots(nrows, ncols, squeeze=False)
    for k, values in enumerate(panels):
        ax = axs[k // ncols][k % ncols]
        cell = g.sel(dict(zip(rest, values))).transpose(*([y] if y else []), x)
        cls = np.atleast_2d(cell["classification"].values.astype(str))
        cell_map(ax, np.vectorize(labels.index)(cls), xs, ys, cmap=cmap, norm=norm,
                 text=_posedness_notes(cell, cls, orbits) if notes else None, status=np.atleast_2d(cell["status"].values))
        if not y:
            ax.set_yticks([])
        ax.set_title(", ".join(_value_text(g, d, v) for d, v in zip(rest, values)), fontsize=9)
        ax.set_xlabel(xlabel if k // ncols == nrows - 1 else "", fontsize=8)
        ax.set_ylabel(ylabel if k % ncols == 0 else "", fontsize=8)
    handles = [Rectangle((0, 0), 1, 1, color=c) for c in colours]
    axs[0][-1].legend(handles, labels, title="classification", fontsize=7, title_fontsize=8,
                      loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    fig.suptitle(f"steady-cycle classification ({os.path.basename(study.path)}, grid {name})", fontsize=10)
    return fig


def _law_of(study, g):
    """The force law of a grid without a force_law axis, from its cases, or None."""
    if "force_law" not in study.cases:
        return None
    laws = {str(v) for v in study.cases["force_law"].sel(case=g["case_id"].values.ravel()).values}
    return laws.pop() if len(laws) == 1 else None


def envelope(study, metric="min_film_thickness_m", axis=None, grid=None, *, fix=None):
    """A metric over one axis of a sub-grid, one line per force law.

    Parameters
    ----------
    study : Study or str or os.PathLike
    metric : str
        A variable of the grid (``min_film_thickness_m`` [m, drawn in µm], ``max_eps`` [1],
        ``peak_reaction_N`` [N], ...). Error bars where the grid has ``<metric>_error``, and at
        each orbit its tangent where it has the sensitivity ``d_<metric>_per_<axis>``; the
        safe film thickness (``safe_film_thickness_m``, the threshold of ``below_safe_film``)
        as a dashed line where the metric is a film thickness.
    axis : str, optional
        The axis across (values in µm, rpm, Pa s; a log scale where they span a factor of 10);
        by default the grid's first numeric axis of more than one value.
    grid : str, optional
        The sub-grid (``study[grid]``); by default the one grid with ``axis``.
    fix : dict, optional
        ``{axis: value}``: take the other axes at these values. Another axis left with more
        than one value is spanned: a band from the metric's least to its largest value over it
        (its envelope), without error bars.

    Returns
    -------
    matplotlib.figure.Figure
        One axes; a cell without a value (no steady cycle: see its classification) is an ``x``
        at the bottom.
    """
    study, name, g = _grid(study, grid, [axis] if axis else [])
    g = _sorted(_fixed(g, fix))
    if metric not in g:
        raise ValueError(f"{study.path}: grid {name!r} has no variable {metric!r}")
    axis = axis or next((d for d in g["case_id"].dims if g.sizes[d] > 1 and _numeric(g, d)), None)
    if axis is None:
        raise ValueError(f"{study.path}: grid {name!r} has no numeric axis of more than one value: name one")
    xs, xlabel = _shown(g, axis)
    unit = g[metric].attrs.get("units", "")
    shown, factor = display(unit)
    fig = Figure(figsize=(8.0, 4.4), layout="constrained")
    ax = fig.add_subplot()
    laws = g["force_law"].values if "force_law" in g.dims else [None]
    gaps = [_envelope_line(ax, g if law is None else g.sel(force_law=[law]), metric, axis, xs, factor, k,
                           str(law if law is not None else _law_of(study, g) or metric))
            for k, law in enumerate(laws)]
    if metric in ("min_film_thickness_m", "last_cycle_min_film_m") and "safe_film_thickness_m" in g:
        safe = g["safe_film_thickness_m"].min([d for d in g["case_id"].dims if d != axis])
        ax.plot(xs, _along(safe, axis) * factor, "--", color="firebrick", lw=1.0, label="safe film thickness")
    if f"d_{metric}_per_{axis}" in g and not [d for d in g["case_id"].dims if d not in (axis, "force_law")
                                            and g.sizes[d] > 1]:
        ax.plot([], [], ":", color="0.3", lw=1.6, label=f"tangent: d_{metric}_per_{axis}")
    if any(gaps):
        ax.plot([], [], "x", color="0.3", label="no value (no steady cycle)")
    _log_scales(ax, xs if _numeric(g, axis) else None)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(axis_label(metric, unit, shown))
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    ax.grid(True, lw=0.3, alpha=0.5)
    spanned = [d for d in g["case_id"].dims if d not in (axis, "force_law") and g.sizes[d] > 1]
    at = [_value_text(g, d, g[d].values[0]) for d in g["case_id"].dims if d != axis and g.sizes[d] == 1]
    how = (f"band: least to largest over {', '.join(spanned)}" if spanned else
           f"error bars: {metric}_error" if f"{metric}_error" in g else "")
    ax.set_title(f"{metric} over {axis} ({os.path.basename(study.path)}, grid {name})\n"
                 + "; ".join(s for s in (", ".join(at), how) if s), fontsize=9)
    return fig


def _envelope_line(ax, v, metric, axis, xs, factor, k, label):
    """One force law's line of ``envelope`` (colour ``C<k>``): a band where other axes span values,
    else the values with their error bars; an ``x`` at the bottom where there is none. Returns
    whether there was a cell without a value."""
    spanned = [d for d in v[metric].dims if d != axis and v.sizes[d] > 1]
    if spanned:  # the envelope over the other axes: least to largest (cells without a value left out)
        lo, hi = (_along(getattr(v[metric], f)(spanned), axis) * factor for f in ("min", "max"))
        ax.fill_between(xs, lo, hi, color=f"C{k}", alpha=0.25, lw=0)
        ax.plot(xs, lo, "o-", xs, hi, "o-", color=f"C{k}", lw=1.0, ms=3)
        y = lo
    else:
        y = _along(v[metric], axis) * factor
        ax.plot(xs, y, "o-", color=f"C{k}", lw=1.0, ms=4)
        if f"{metric}_error" in v:  # only where there is a value (errorbar warns of a NaN)
            ok = np.isfinite(y)
            err = np.nan_to_num(_along(v[f"{metric}_error"], axis)[ok] * factor)
            ax.errorbar(np.asarray(xs)[ok], y[ok], yerr=err, fmt="none", ecolor=f"C{k}", capsize=3, lw=1.0)
        if f"d_{metric}_per_{axis}" in v:
            _tangents(ax, xs, y, _along(v[f"d_{metric}_per_{axis}"], axis) * factor / _display_factor(v, axis), k)
    ax.plot([], [], "o-", color=f"C{k}", label=label)
    missing = ~np.isfinite(y)
    ax.plot(np.asarray(xs)[missing], np.full(missing.sum(), 0.03 + 0.035 * k), "x", color=f"C{k}", ms=7,
            mew=1.5, transform=blended_transform_factory(ax.transData, ax.transAxes), clip_on=False)
    return bool(missing.any())


def _display_factor(g, dim):
    """How many drawn units an axis's SI unit is (µm per m: 1e6)."""
    return display(g[dim].attrs.get("units", ""))[1]


def _tangents(ax, xs, y, slope, k):
    """The study's sensitivity at each orbit (``d_<metric>_per_<axis>``, in drawn units) as a
    short dotted tangent, a quarter of the way to each neighbour (``_tangent_span``)."""
    xs = np.asarray(xs, dtype=float)
    for i in np.flatnonzero(np.isfinite(y) & np.isfinite(slope)):
        lo, hi = _tangent_span(xs, i)
        t = np.linspace(lo, hi, 9)  # points, so a log axis draws the straight tangent as it bends
        ax.plot(t, y[i] + slope[i] * (t - xs[i]), ":", color=f"C{k}", lw=1.6)


def _tangent_span(xs, i):
    """From a quarter of the way to the lower neighbour to a quarter to the upper (geometric
    where the values are positive, as a log axis draws them)."""
    def toward(j):
        if j < 0 or j >= len(xs):
            return xs[i]
        if xs[i] > 0 and xs[j] > 0:
            return xs[i] * (xs[j] / xs[i]) ** 0.25
        return xs[i] + 0.25 * (xs[j] - xs[i])
    return toward(i - 1), toward(i + 1)


def _log_scales(ax, xs):
    """Log scales, numbers as %g: x at the values ``xs`` where they span a factor of 10, y where
    the data span a factor of 100."""
    if xs is not None and np.min(xs) > 0 and np.max(xs) / np.min(xs) >= 10:
        ax.set_xscale("log")
        ax.set_xticks(xs, [_tick(v) for v in xs])
        ax.minorticks_off()
    low, high = ax.dataLim.intervaly
    if low > 0 and high / low >= 100:
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))


def safe_envelope(study, x, y, grid=None, *, fix=None, boundaries=None):
    """The safe operating envelope over two axes of a sub-grid, one panel per force law: each
    grid cell a point (safe, below the safe film, an unstable orbit, or none located), the safe-film
    boundaries located between them (``lubjoint.boundaries.safe_film_boundaries``) joined into
    a curve, and the unsafe side of it shaded; where the safe orbit is lost towards a cell
    whose film is below the safe film (it turns unstable, or its branch ends: rows with
    ``edge``), those located values as a dashed curve.

    Parameters
    ----------
    study : Study or str or os.PathLike
    x, y : str
        Two numeric axes of the grid (drawn in µm, rpm, Pa s; log scales where the values span
        a factor of 10).
    grid : str, optional
        The sub-grid; by default the one with both axes.
    fix : dict, optional
        ``{axis: value}`` for the grid's other numeric axes (each must be held at one value).
    boundaries : pandas.DataFrame, optional
        ``safe_film_boundaries(study)``'s result, if computed already (it runs the scenes).

    Returns
    -------
    matplotlib.figure.Figure
    """
    study, name, g = _grid(study, grid, [x, y])
    g = _sorted(_fixed(g, fix))
    spanned = [d for d in g["case_id"].dims if d not in (x, y, "force_law") and g.sizes[d] > 1]
    if spanned:
        raise ValueError(f"{study.path}: grid {name!r}: hold {', '.join(spanned)} at one value (fix=)")
    if boundaries is None:
        from .boundaries import safe_film_boundaries

        boundaries = safe_film_boundaries(study)
    laws = list(g["force_law"].values) if "force_law" in g.dims else [None]
    fig = Figure(figsize=(4.2 * len(laws), 4.0), layout="constrained")
    axes = fig.subplots(1, len(laws), squeeze=False)[0]
    for ax, law in zip(axes, laws):
        v = g if law is None else g.sel(force_law=[law])
        for axis, values, setter in ((ax.xaxis, _shown(g, x)[0], ax.set_xscale), (ax.yaxis, _shown(g, y)[0], ax.set_yscale)):
            if np.min(values) > 0 and np.max(values) / np.min(values) >= 10:
                setter("log")
                axis.set_ticks(values, [_tick(t) for t in values])
                axis.set_minor_locator(NullLocator())
        plane = _plane(v, x, y)
        _envelope_cells(ax, plane)
        _envelope_curve(ax, plane, _plane_boundaries(boundaries, v, x, y, law))
        ends = _plane_boundaries(boundaries, v, x, y, law, "edge")
        if len(ends):  # where the safe orbit is lost towards a cell whose film is below the safe film
            ax.plot(ends[:, 0], ends[:, 1], "--", color="darkorange", lw=1.2, marker="s", ms=4,
                    label="safe orbit lost (located)")
        ax.set_title(str(law if law is not None else _law_of(study, g) or name), fontsize=9)
        ax.set_xlabel(_shown(g, x)[1])
        ax.set_ylabel(_shown(g, y)[1])
    legend = {}
    for ax in axes:  # every panel's entries, once each (a panel without a boundary has no curve)
        for handle, label in zip(*ax.get_legend_handles_labels()):
            legend.setdefault(label, handle)
    axes[-1].legend(legend.values(), legend.keys(), fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0),
                    borderaxespad=0)
    at = [_value_text(g, d, g[d].values[0]) for d in g["case_id"].dims if d not in (x, y, "force_law")]
    fig.suptitle(f"where the film is safe ({os.path.basename(study.path)}, grid {name})"
                 + (f": {', '.join(at)}" if at else ""), fontsize=9)
    return fig


def _plane(v, x, y):
    """One force law's plane: the drawn axis values as a mesh (X, Y), and per cell whether it
    has a stable orbit, an unstable one, and a stable orbit below the safe film (over y, x)."""
    def cells(name):
        da = v[name]
        return da.squeeze([d for d in da.dims if d not in (x, y)]).transpose(y, x).values

    X, Y = np.meshgrid(_shown(v, x)[0], _shown(v, y)[0])
    kind = cells("classification").astype(str)
    stable = kind == "periodic"
    return X, Y, stable, kind == "periodic_unstable", stable & (cells("below_safe_film") == 1)


def _envelope_cells(ax, plane):
    """Each cell of one force law's plane (``_plane``) as a point: safe, below the safe film, an
    unstable orbit (which the journal leaves: no label), no located orbit."""
    X, Y, stable, unstable, below = plane
    kinds = (("safe", stable & ~below, "o", "seagreen", "seagreen"),
             ("below the safe film", below, "o", "firebrick", "firebrick"),
             ("unstable orbit", unstable, "o", "0.3", "none"),
             ("no located orbit", ~stable & ~unstable, "x", "0.45", None))
    for label, where, marker, colour, face in kinds:
        ax.plot(X[where], Y[where], marker, color=colour, mfc=face or colour, ms=6, ls="none", label=label)


def _plane_boundaries(boundaries, v, x, y, law, kind="safe_film"):
    """The boundaries of ``kind`` (``safe_film``, or ``edge``: where a safe orbit is lost) that
    lie in this plane, as drawn points (x, y) sorted along x."""
    if boundaries is None or len(boundaries) == 0:
        return np.empty((0, 2))
    from .boundaries import edge_ends

    fx, fy = _display_factor(v, x), _display_factor(v, y)
    points = []
    wanted = edge_ends(boundaries) if kind == "edge" else boundaries["kind"] == kind
    for _, b in boundaries[wanted].iterrows():
        if law is not None and b.get("force_law") != law:
            continue
        held = [d for d in v["case_id"].dims if d not in (x, y, "force_law")]
        if any(d in b and not (b[d] == v[d].values[0]) for d in held):
            continue
        if b["axis"] == x and y in b:
            points.append((b["value"] * fx, b[y] * fy))
        elif b["axis"] == y and x in b:
            points.append((b[x] * fx, b["value"] * fy))
    return np.array(sorted(points)) if points else np.empty((0, 2))


def _envelope_curve(ax, plane, points):
    """The boundary curve through ``points``, the side of it where the plane's (``_plane``) cells
    are below the safe film shaded."""
    if len(points) == 0:
        return
    ax.plot(points[:, 0], points[:, 1], "-", color="firebrick", lw=1.5, marker="D", ms=4,
            label="safe film reached (located)")
    X, Y, _, _, below = plane
    inside = below & (X >= points[0, 0]) & (X <= points[-1, 0])  # the cells the curve spans
    if not inside.any() or len(points) < 2:
        return
    under = np.mean(Y[inside] < np.interp(X[inside], points[:, 0], points[:, 1])) > 0.5
    limits = ax.get_ylim()
    ax.fill_between(points[:, 0], points[:, 1], limits[0] if under else limits[1], color="firebrick", alpha=0.12,
                    lw=0, label="unsafe side")
    ax.set_ylim(limits)
