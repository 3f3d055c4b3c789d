"""Where the film stops being safe, located between a study's grid points (issue 44).

A study says ``below_safe_film`` at its grid points; the axis value where the minimum film
equals the safe film lies between two neighbours that differ. ``safe_film_boundaries``
locates it by safeguarded Newton steps along that axis from the nearer orbit, each step a
run of the case's scene at the new value with its sensitivity (``simulate(...,
sensitivity=[pointer])``): the step uses h_min and dh_min/dλ of the orbit it starts from,
and stays inside the bracket the two neighbours give (else it bisects).
"""
import math
import warnings

_ORBITS = ("periodic", "periodic_unstable")  # the classifications of a located orbit


def _at(doc, pointer):
    for token in pointer.lstrip("/").split("/"):
        doc = doc[int(token)] if isinstance(doc, list) else doc[token]
    return doc


def axis_pointers(study):
    """``{axis: the scene pointer it sets}`` of the study's numeric axes (a clearance's is
    the journal radius), from the grids' dimension scales (attribute ``pointer``)."""
    return {d: g[d].attrs["pointer"] for g in study.values() for d in g.dims if g[d].attrs.get("pointer")}


def axis_override(scene, axis, pointer, value):
    """The override (``{pointer: scene value}``, for ``simulate``) that puts a scene at the axis
    value ``value``: the value itself, or for a clearance c the journal radius R − c, the
    scene's bearing radius R held. Returns the override and d(scene value)/d(axis value)."""
    if axis == "clearance_m":
        return {pointer: _at(scene, pointer.rsplit("/", 1)[0] + "/bearing_radius_m") - value}, -1.0
    return {pointer: value}, 1.0


class _Line:
    """One lattice edge's axis as a function λ ↦ (h_min − safe film, d/dλ, its run) of the
    scene of ``case``: the axis's pointer set to λ (a clearance c: the journal radius R − c)."""

    def __init__(self, study, case, axis, pointer):
        from . import study as st

        self.scene = st.scene(study.path, case)
        self.axis, self.pointer = axis, pointer
        self.runs = 0

    def __call__(self, value):
        from .run import simulate

        override, sign = axis_override(self.scene, self.axis, self.pointer, value)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ds = simulate(self.scene, {**override, "/outputs/channels": []}, sensitivity=[self.pointer])
        self.runs += 1
        if ds.attrs["classification"] not in _ORBITS:
            return None
        key = "d_min_film_thickness_m_per_" + self.pointer.lstrip("/").replace("/", "_")
        slope = float(ds[key]) * sign
        gap = float(ds["min_film_thickness_m"]) - float(ds["safe_film_thickness_m"])
        return gap, slope, float(ds["min_film_thickness_m_error"])


def _locate(line, lo, hi, tolerance, max_runs):
    """λ where the gap h_min − safe changes sign within [lo, hi] (each an (λ, gap, slope)):
    Newton from the end nearer the boundary, bisection where a step leaves the bracket. Returns
    (value, error, runs, converged)."""
    a, b = lo, hi
    x, g, s = min((a, b), key=lambda e: abs(e[1] / e[2]) if e[2] else math.inf)
    step_error = abs(b[0] - a[0])
    for _ in range(max_runs):
        step = -g / s if s else math.inf
        new = x + step
        if not (min(a[0], b[0]) < new < max(a[0], b[0])):
            new = 0.5 * (a[0] + b[0])
        at = line(new)
        if at is None:  # no located orbit there: bisect towards the end that has one
            return new, abs(b[0] - a[0]), line.runs, False
        gn, sn, _ = at
        if (gn > 0) == (a[1] > 0):
            a = (new, gn, sn)
        else:
            b = (new, gn, sn)
        step_error = abs(new - x)
        x, g, s = new, gn, sn
        # the next Newton step's size bounds the remaining error (quadratic convergence)
        if sn and abs(gn / sn) <= 0.25 * tolerance * abs(new):
            return new - gn / sn, abs(gn / sn) + abs(at[2] / sn), line.runs, True
    return x, step_error, line.runs, False


def safe_film_boundaries(study, tolerance=5e-3, max_runs=8):
    """The axis values where the minimum film reaches the safe film, between every two lattice
    neighbours of ``study`` (lubjoint.study.lattice_edges) whose ``below_safe_film`` differ and
    that both have a located orbit with sensitivities.

    Parameters
    ----------
    study : Study
        ``load_study(path)`` of a lubsweep study whose grid has sensitivities (the default).
    tolerance : float
        Relative accuracy of each value (0.5 %: issue 44's).
    max_runs : int
        Runs of the scene per boundary at most.

    Returns
    -------
    pandas.DataFrame
        One row per boundary: ``axis``, ``value`` and ``error`` (in the axis's unit, ``unit``),
        ``kind`` (``safe_film``), ``case_a``, ``case_b`` (the neighbours), ``runs``,
        ``converged``, and the other axes' values of the line.
    """
    import pandas as pd

    from . import study as st

    cases = study.cases
    df = st.cases(study.path)  # with the lattice in its attrs
    pointers = axis_pointers(study)
    rows = []
    for a, b, axis in st.lattice_edges(df):
        ra, rb = df.loc[a], df.loc[b]
        if ra["classification"] not in _ORBITS or rb["classification"] not in _ORBITS:
            continue
        if int(ra["below_safe_film"]) == int(rb["below_safe_film"]) or axis not in pointers:
            continue
        key = f"d_min_film_thickness_m_per_{axis}"
        if key not in df or not (math.isfinite(ra[key]) and math.isfinite(rb[key])):
            continue
        ends = [(float(r[axis]), float(r["min_film_thickness_m"] - r["safe_film_thickness_m"]), float(r[key]))
                for r in (ra, rb)]
        value, error, runs, converged = _locate(_Line(study, a, axis, pointers[axis]), ends[0], ends[1], tolerance,
                                                max_runs)
        others = {k: ra[k] for k in cases.attrs.get("axes", []) if k != axis and k in ra}
        rows.append({"axis": axis, "value": value, "error": error, "unit": cases[axis].attrs.get("units", ""),
                     "kind": "safe_film", "case_a": a, "case_b": b, "runs": runs, "converged": converged, **others})
    return pd.DataFrame(rows)
