"""Where the film stops being safe, or the cycle stable, located between a study's grid points.

A study says ``below_safe_film`` at its grid points; the axis value where the minimum film
equals the safe film lies between two neighbours that differ. ``safe_film_boundaries``
locates it by safeguarded Newton steps along that axis from the nearer orbit, each step a
run of the case's scene at the new value with its sensitivity (``simulate(...,
sensitivity=[pointer])``): the step uses h_min and dh_min/dλ of the orbit it starts from,
and stays inside the bracket the two neighbours give (else it bisects). Each run starts
from the nearest orbit located on the line so far (``simulate(..., continue_from=...,
single_step=True)``: one Newton from that orbit), and only where that finds none from the
scene's own start. Where one neighbour has a safe orbit and the other none (its film
collapses, or drifts below the safe film), the safe orbit is followed along the line until
its film reaches the safe film (``safe_film``) or the orbit is lost, bisected between the last
orbit and the first value where none continues from it: a stable orbit is lost where the
orbit continued from it is unstable (its dominant multiplier's crossing names the kind:
``fold``, ``period_doubling``, ``neimark_sacker``) or where none is (``orbit_end``: the edge of
the orbit's branch). These rows have ``edge`` set.
``stability_boundaries`` locates where the dominant Floquet multiplier crosses the unit
circle between neighbours whose orbits differ in stability, by regula falsi on ``|μ|max − 1``
(no derivative of a multiplier is at hand), and names the crossing's kind.

``locate`` does both, ``write`` stores them as the study file's ``/boundaries`` table (which
``lubsweep --summary`` prints and ``read`` returns), and ``python3 -m lubjoint.boundaries
STUDY.h5`` runs the three.
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
    """One lattice edge's axis as a function λ ↦ (h_min − safe film, d/dλ, its error) of the
    scene of ``case``: the axis's pointer set to λ (a clearance c: the journal radius R − c),
    run from the nearest orbit located on the line so far (``orbits``: (λ, effective scene,
    orbit_seed row), the ends' and, if ``continued``, each run's), then, if ``fresh`` and that
    finds none, from the scene's own start."""

    def __init__(self, study, case, axis, pointer, ends=(), fresh=True, continued=True, stable=False):
        from . import study as st

        self.scene = st.scene(study.path, case)
        self.axis, self.pointer = axis, pointer
        self.slope = "d_min_film_thickness_m_per_" + pointer.lstrip("/").replace("/", "_")  # its sensitivity
        self.runs = 0
        self.periods = 0  # crank periods the runs integrated, their sensitivities' included
        self.fresh, self.continued = fresh, continued
        # The orbits the line follows: located ones, or (``stable``) stable ones only, an
        # unstable orbit then counting as the stable one lost.
        self.accepted = ("periodic",) if stable else _ORBITS
        self.last = None  # the last run's Dataset
        self.orbits = []
        for end, value in ends:  # the study's own orbits at the line's ends
            seed = st.orbit_seed_row(study.path, end)
            if seed:
                self.orbits.append((float(value), st.scene(study.path, end), seed))

    def _count(self, ds):
        self.runs += 1
        self.periods += int(ds["periods_integrated"])
        if self.slope in ds:
            self.periods += int(ds[self.slope].attrs.get("periods_integrated", 0))

    def run(self, value, sensitivity=True, extra=None):
        """The run of the line's scene at ``value``: from the nearest located orbit, else
        (``fresh``) from the scene's own start. Records the orbit it locates, unless ``extra``
        (more overrides, e.g. a finer rtol) changes the scene otherwise."""
        from .run import simulate

        override, _ = axis_override(self.scene, self.axis, self.pointer, value)
        overrides = {**override, "/outputs/channels": [], **(extra or {})}
        wrt = [self.pointer] if sensitivity else []
        ds = None
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            if self.orbits:
                far = (lambda o: abs(math.log(value / o[0]))) if value > 0 and all(o[0] > 0 for o in self.orbits) \
                    else (lambda o: abs(value - o[0]))
                _, scene, seed = min(self.orbits, key=far)
                ds = simulate(self.scene, overrides, sensitivity=wrt, continue_from=(scene, seed), single_step=True)
                self._count(ds)
            if (ds is None or ds.attrs["classification"] not in self.accepted) and self.fresh:
                ds = simulate(self.scene, overrides, sensitivity=wrt)
                self._count(ds)
        if self.continued and not extra and ds.attrs["classification"] in self.accepted and ds["orbit_seed"].size:
            self.orbits.append((float(value), ds.attrs["scene"], [float(v) for v in ds["orbit_seed"].values]))
        self.last = ds
        return ds

    def __call__(self, value, sensitivity=True):
        ds = self.run(value, sensitivity)
        if ds.attrs["classification"] not in self.accepted:
            return None
        _, sign = axis_override(self.scene, self.axis, self.pointer, value)
        slope = float(ds[self.slope]) * sign if sensitivity else math.nan
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
            line.why = _no_orbit(new)
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
    line.why = _runs_spent(max_runs, tolerance)
    return x, step_error, line.runs, False


def _edges(study, orbits=2):
    """The lattice edges of ``study`` along an axis that sets a scene number with ``orbits``
    of their ends located orbits (2: both; 1: exactly one, that end first):
    ``(case_a, case_b, axis, pointer, row_a, row_b)``."""
    from . import study as st

    df = st.cases(study.path)  # with the lattice in its attrs
    pointers = axis_pointers(study)
    for a, b, axis in st.lattice_edges(df):
        ra, rb = df.loc[a], df.loc[b]
        located = (ra["classification"] in _ORBITS, rb["classification"] in _ORBITS)
        if axis not in pointers or sum(located) != orbits:
            continue
        if orbits == 1 and not located[0]:
            a, b, ra, rb = b, a, rb, ra
        yield a, b, axis, pointers[axis], ra, rb


def _edge(line, a, b, tolerance, max_runs, mu_a=math.nan, term=None):
    """Along a line from a safe orbit ``a`` = (λ, gap > 0, slope) towards ``b``, a value
    where no orbit is located and the film is below the safe film: the value where the
    orbit's film reaches the safe film, by ``_locate`` once an orbit below it is found, or
    where the orbit is lost, bisected (in the logarithm of positive values) between the
    last orbit and the first value where none continues from it; secant steps towards the
    safe film first where they land inside (from the last safe orbit, the first with the
    study's own sensitivity at ``a``; the runs ask for none). On a ``stable`` line an unstable orbit counts as
    the stable one lost: the kind is then its dominant multiplier's crossing (``_kind``),
    else ``orbit_end``. Returns (value, error, kind, converged, what the run at the lost end
    said: its classification and message, "" where that end is the grid's neighbour, and
    for a crossing the last bracket's (λ, ``|μ|max − 1``) pair, ``mu_a`` the start's
    ``|μ|max``; else None). ``term``, given such a pair, says how far the multipliers'
    accuracy moves the crossing (``_multiplier_error``): for a crossing it is added to the
    error once the bracket has converged, and where the sum exceeds ``tolerance`` but a
    narrower bracket would meet it, the bisection goes on to that width."""
    log = a[0] > 0 and b > 0
    mid = (lambda x, y: math.sqrt(x * y)) if log else (lambda x, y: 0.5 * (x + y))
    crossing = None  # the dominant multiplier's angle at b, where an unstable orbit was found there
    lost = ""  # what the run at b said
    fa, fb = mu_a - 1.0, math.nan  # |μ|max − 1 at a and (an unstable orbit) at b
    width, extra = tolerance, None  # the half-bracket aimed at (relative); the multipliers' term
    for _ in range(max_runs):
        lo, hi = sorted((a[0], b))
        if hi - lo <= 2.0 * width * mid(lo, hi):
            if term is None or crossing is None or not math.isfinite(fa) or extra is not None:
                break
            extra = term(((a[0], fa), (b, fb)))
            budget = tolerance * mid(lo, hi) - extra  # what the half-bracket may take of the error
            if not budget > 0.0 or 0.5 * (hi - lo) <= budget:
                break
            width = budget / mid(lo, hi)
            continue
        new = a[0] - a[1] / a[2] if a[2] else math.inf
        if not lo < new < hi:
            new = mid(lo, hi)
        # No sensitivity: the step towards the safe film takes the secant from the last
        # safe orbit (the study's end its own sensitivity); its only use here.
        at = line(new, sensitivity=False)
        last = line.last
        if at is not None:
            at = (at[0], (at[0] - a[1]) / (new - a[0]), at[2])
        if at is None:
            b = new
            located = last.attrs["classification"] in _ORBITS
            crossing = float(last["multiplier_1_angle_rad"]) if located else None
            fb = float(last["multiplier_1_modulus"]) - 1.0 if located else math.nan
            lost = f"{last.attrs['classification']}: {last.attrs.get('message', '')}"
        elif at[0] > 0:
            a = (new, at[0], at[1])
            fa = float(last["multiplier_1_modulus"]) - 1.0
        else:  # an orbit below the safe film: the crossing lies between two orbits
            value, error, _, converged = _locate(line, a, (new, at[0], at[1]), tolerance, max_runs)
            return value, error, "safe_film", converged, "", None
    lo, hi = sorted((a[0], b))
    kind = "orbit_end" if crossing is None else _kind(crossing)
    ends = ((a[0], fa), (b, fb)) if crossing is not None and math.isfinite(fa) else None
    error = 0.5 * (hi - lo) + (extra or 0.0)
    narrow = hi - lo <= 2.0 * width * mid(lo, hi)
    converged = narrow and error <= tolerance * mid(lo, hi)
    if not converged:
        line.why = _runs_spent(max_runs, tolerance) if not narrow else _refined(extra, mid(lo, hi))
    return mid(lo, hi), error, kind, converged, lost, ends


def _no_orbit(value):
    return f"no orbit located at {value:.6g} {{unit}}"


def _runs_spent(runs, tolerance):
    return f"not within {100 * tolerance:g} % of its value in {runs} runs"


def _refined(term, value):
    """Why a bracket that met the tolerance did not: its multipliers' accuracy (``_multiplier_error``)."""
    if not math.isfinite(term):
        return "a bracket end run again at rtol/10 located no orbit"
    return f"its multipliers at rtol/10 move it by {100 * term / abs(value):.2g} % of its value"


def _row(study, a, b, axis, ra, line, value, error, kind, converged, edge=False, lost=""):
    """One boundary's row: the fixed columns, then the other axes' values of its line. A row
    that has not converged says why (``line.why``, set where its search gave up)."""
    cases = study.cases
    unit = cases[axis].attrs.get("units", "")
    others = {k: ra[k] for k in cases.attrs.get("axes", []) if k != axis and k in ra}
    reason = "" if converged else getattr(line, "why", "").replace("{unit}", unit).strip()
    return {"axis": axis, "value": value, "error": error, "unit": unit, "kind": kind,
            "case_a": a, "case_b": b, "runs": line.runs, "periods": line.periods, "converged": converged,
            "edge": edge, "lost": lost, "reason": reason, **others}


def safe_film_boundaries(study, tolerance=5e-3, max_runs=8, edge_runs=12, pairs=True, edges=True):
    """The axis values where the minimum film reaches the safe film, between every two lattice
    neighbours of ``study`` (lubjoint.study.lattice_edges) whose ``below_safe_film`` differ and
    that both have a located orbit with sensitivities; and between a safe orbit and a
    neighbour without one whose film is below the safe film (it collapsed, or its drift law
    crosses it): where the safe orbit's film reaches the safe film, or where that orbit is
    lost (``orbit_end``).

    Parameters
    ----------
    study : Study
        ``load_study(path)`` of a lubsweep study whose grid has sensitivities (the default).
    tolerance : float
        Relative accuracy of each value (0.5 %: issue 44's).
    max_runs : int
        Runs of the scene per boundary between two orbits at most.
    edge_runs : int
        Runs per boundary from a safe orbit towards a neighbour without one at most (a
        bisection of a factor 10 to 0.5 % takes 9).
    pairs : bool
        Whether to locate the boundaries between two orbits.
    edges : bool
        Whether to follow a safe orbit towards a neighbour without one (the edge search,
        most of what boundaries cost: docs/validation/sensitivities.md).

    Returns
    -------
    pandas.DataFrame
        One row per boundary: ``axis``, ``value`` and ``error`` (in the axis's unit, ``unit``),
        ``kind`` (``safe_film``; where the safe orbit is lost before its film reaches the
        safe film, ``orbit_end``, or for a stable orbit that turns unstable the crossing's
        kind, ``fold``, ``period_doubling`` or ``neimark_sacker``: ``value`` then the middle
        of the last orbit's value and the first without, ``error`` half their distance),
        ``case_a`` (the orbit's end where one has none), ``case_b`` (the neighbours), ``runs``,
        ``periods``, ``converged``, ``edge`` (found by following a safe orbit towards a
        neighbour without one), ``lost`` (an edge's: what the run nearest beyond it said, its
        classification and message), and the other axes' values of the line.
    """
    import pandas as pd

    rows = []
    key = "d_min_film_thickness_m_per_{}".format

    def end(r, axis):
        return float(r[axis]), float(r["min_film_thickness_m"] - r["safe_film_thickness_m"]), float(r[key(axis)])

    for a, b, axis, pointer, ra, rb in (_edges(study) if pairs else ()):
        la, lb = ra["below_safe_film"], rb["below_safe_film"]
        if not (la == la and lb == lb) or int(la) == int(lb):  # unknown (NaN: an unstable orbit), or alike
            continue
        if key(axis) not in ra or not (math.isfinite(ra[key(axis)]) and math.isfinite(rb[key(axis)])):
            continue
        line = _Line(study, a, axis, pointer, ends=((a, ra[axis]), (b, rb[axis])))
        value, error, _, converged = _locate(line, end(ra, axis), end(rb, axis), tolerance, max_runs)
        rows.append(_row(study, a, b, axis, ra, line, value, error, "safe_film", converged))
    # A safe orbit at one end, none at the other, whose film is below the safe film (it
    # collapsed, or drifts there): the safe orbit followed until its film reaches the safe
    # film or it is lost; no run from the scene's own start, which may find another orbit.
    for a, b, axis, pointer, ra, rb in (_edges(study, orbits=1) if edges else ()):
        if not (ra["below_safe_film"] == 0 and rb["below_safe_film"] == 1):  # missing: NaN
            continue
        if key(axis) not in ra or not math.isfinite(ra[key(axis)]):
            continue
        # From a stable orbit, the stable orbit followed: where it turns unstable the
        # journal leaves it, and the crossing's kind is named.
        stable = ra["classification"] == "periodic"
        line = _Line(study, a, axis, pointer, ends=((a, ra[axis]),), fresh=False, stable=stable)
        # A crossing's error has the multipliers' accuracy in it, as a stability crossing's.
        value, error, kind, converged, lost, _ = _edge(line, end(ra, axis), float(rb[axis]), tolerance, edge_runs,
                                                       float(ra["multiplier_1_modulus"]),
                                                       lambda ends: _multiplier_error(line, ends, lost_end=True))
        rows.append(_row(study, a, b, axis, ra, line, value, error, kind, converged, edge=True, lost=lost))
    return pd.DataFrame(rows)


def _kind(modulus_angle, angle_tol_rad=1e-3):
    """The crossing's kind from the dominant multiplier's angle where it left the circle."""
    angle = abs(modulus_angle)
    if angle <= angle_tol_rad:
        return "fold"
    if abs(angle - math.pi) <= angle_tol_rad:
        return "period_doubling"
    return "neimark_sacker"


class _Stability(_Line):
    """An edge's axis as λ ↦ (``|μ|max − 1``, the dominant multiplier's angle, its run)."""

    def __call__(self, value):
        ds = self.run(value, sensitivity=False)
        if ds.attrs["classification"] not in _ORBITS:
            return None
        return float(ds["multiplier_1_modulus"]) - 1.0, float(ds["multiplier_1_angle_rad"])


def _falsi(line, a, b, tolerance, max_runs):
    """λ where ``|μ|max − 1`` changes sign in [a, b] (each (λ, ``|μ|max − 1``, angle)): regula falsi
    (Illinois) in the logarithm of λ. Returns (value, error, angle, runs, converged, ends):
    the error half the last bracket's width; the angle the unstable end's; ``ends`` the last
    bracket's (λ, ``|μ|max − 1``) pair."""
    log = a[0] > 0 and b[0] > 0
    t = (lambda v: math.log(v)) if log else (lambda v: v)
    inv = (lambda u: math.exp(u)) if log else (lambda u: u)
    (ua, fa, aa), (ub, fb, ab) = (t(a[0]), a[1], a[2]), (t(b[0]), b[1], b[2])
    raw = [a[1], b[1]]  # |μ|max − 1 at the bracket's ends (fa, fb are Illinois-scaled)
    side = 0
    for _ in range(max_runs):
        u = ub - fb * (ub - ua) / (fb - fa) if fb != fa else 0.5 * (ua + ub)
        if not (min(ua, ub) < u < max(ua, ub)):
            u = 0.5 * (ua + ub)
        at = line(inv(u))
        if at is None:
            line.why = _no_orbit(inv(u))
            break
        f, angle = at
        if (f > 0) == (fb > 0):
            ub, fb, ab, raw[1] = u, f, angle, f
            if side == -1:
                fa /= 2.0
            side = -1
        else:
            ua, fa, aa, raw[0] = u, f, angle, f
            if side == 1:
                fb /= 2.0
            side = 1
        lo, hi = sorted((inv(ua), inv(ub)))
        if hi - lo <= tolerance * abs(0.5 * (lo + hi)):
            break
    lo, hi = sorted((inv(ua), inv(ub)))
    unstable_angle = aa if fa > 0 else ab
    converged = hi - lo <= tolerance * abs(0.5 * (lo + hi))
    if not converged and not getattr(line, "why", ""):
        line.why = _runs_spent(max_runs, tolerance)
    ends = ((inv(ua), raw[0]), (inv(ub), raw[1]))
    return 0.5 * (lo + hi), 0.5 * (hi - lo), unstable_angle, line.runs, converged, ends


def _multiplier_error(line, ends, refine=0.1, lost_end=False, sure=1e-2):
    """How far a stability crossing moves with its multipliers' own accuracy: each end of the
    last bracket (λ, ``|μ|max − 1``) run again at rtol × ``refine`` (continued from its
    orbit), the larger change of ``|μ|max`` over the slope of ``|μ|max − 1`` across the
    bracket. Near |μ| = 1 a change of 1e-5 in a multiplier can move the crossing by more
    than the bracket's width. Inf where a refined run locates no orbit, except at the second
    end with ``lost_end`` (an edge's, where the stable orbit is lost either way). Zero, with
    no run, where both ends are ``sure`` or more from the circle: a hundred times the largest
    change refinement has shown (1e-4), so the crossing lies inside the bracket (the printed
    law's folds, whose multiplier jumps past 1)."""
    rtol = float(_at(line.scene, "/solver/rtol"))
    (la, fa), (lb, fb) = ends
    if la == lb or fa == fb:
        return math.inf
    if min(abs(fa), abs(fb)) >= sure:
        return 0.0
    spread = 0.0
    for value, f in ends:
        ds = line.run(value, sensitivity=False, extra={"/solver/rtol": refine * rtol})
        if ds.attrs["classification"] not in _ORBITS:
            if lost_end and value == lb:
                continue
            return math.inf
        spread = max(spread, abs(float(ds["multiplier_1_modulus"]) - 1.0 - f))
    return spread * abs(lb - la) / abs(fb - fa)


def stability_boundaries(study, tolerance=5e-3, max_runs=10):
    """The axis values where the dominant Floquet multiplier crosses the unit circle, between
    every two lattice neighbours of ``study`` whose located orbits differ in stability
    (``|μ|max < 1`` at one, ``> 1`` at the other). Each by regula falsi on ``|μ|max − 1`` in the
    logarithm of the axis value, a run of the case's scene a step (from the nearest orbit
    located on the line), to ``tolerance`` of the value (the error: half the last bracket plus
    how far the multipliers' change at rtol/10 moves it, ``_multiplier_error``).
    ``kind``: ``fold`` (the unstable end's dominant multiplier real, through +1),
    ``period_doubling`` (through −1) or ``neimark_sacker`` (a complex pair). Columns as ``safe_film_boundaries``'."""
    import pandas as pd

    rows = []
    for a, b, axis, pointer, ra, rb in _edges(study):
        ma, mb = float(ra["multiplier_1_modulus"]), float(rb["multiplier_1_modulus"])
        if not (math.isfinite(ma) and math.isfinite(mb)) or (ma > 1.0) == (mb > 1.0):
            continue
        ends = [(float(r[axis]), float(r["multiplier_1_modulus"]) - 1.0, float(r["multiplier_1_angle_rad"]))
                for r in (ra, rb)]
        # Each run continued from the nearest orbit on the line (one Newton, whose stall at
        # the map's noise near |mu| = 1 is accepted or retried), from the scene's own
        # start only where that finds none: a run from the start may reach another orbit.
        line = _Stability(study, a, axis, pointer, ends=((a, ra[axis]), (b, rb[axis])))
        value, error, angle, _, converged, last = _falsi(line, ends[0], ends[1], tolerance, max_runs)
        if converged:  # the bracket's half-width and the multipliers' accuracy
            term = _multiplier_error(line, last)
            error += term
            converged = error <= tolerance * abs(value)
            if not converged:
                line.why = _refined(term, value)
        rows.append(_row(study, a, b, axis, ra, line, value, error, _kind(angle), converged))
    return pd.DataFrame(rows)


def edge_ends(frame):
    """Which rows of a /boundaries ``frame`` are where a safe orbit, followed towards a
    neighbour without one, is lost (``edge`` set, the kind not ``safe_film``; in files
    without the column, kind ``orbit_end``): a boolean Series."""
    if "edge" not in frame:
        return frame["kind"] == "orbit_end"
    edge = frame["edge"]
    return edge.where(edge == edge, frame["kind"] == "orbit_end").astype(bool) & (frame["kind"] != "safe_film")


#: What ``locate`` (``--kinds``) can be asked for: safe-film boundaries between two orbits,
#: the edges where a safe orbit is lost (their rows' kind says how: a crossing, or
#: ``orbit_end``), the stability crossings.
KINDS = ("safe_film", "edge", "stability")
#: Earlier names still accepted: ``orbit_end`` asked for every edge, whatever its kind.
_FORMER = {"orbit_end": "edge"}


def _unknown(kinds):
    """The names in ``kinds`` that are neither a ``KINDS`` name nor a former one."""
    return [k for k in kinds if _FORMER.get(k, k) not in KINDS]


def asked(kinds):
    """``kinds`` (names of ``KINDS``, or their former names) as ``KINDS`` names; ValueError
    naming the first that is neither."""
    unknown = _unknown(kinds)
    if unknown:
        raise ValueError(f"kinds: {unknown[0]!r}: each must be one of {', '.join(KINDS)}")
    return tuple(_FORMER.get(k, k) for k in kinds)


def locate(study, tolerance=5e-3, kinds=KINDS):
    """The boundaries of ``study`` of ``kinds`` (``KINDS``, all by default):
    ``safe_film_boundaries`` then ``stability_boundaries``, one DataFrame (``attrs["units"]``:
    each column's unit)."""
    import pandas as pd

    kinds = asked(kinds)
    found = []
    if "safe_film" in kinds or "edge" in kinds:
        found.append(safe_film_boundaries(study, tolerance, pairs="safe_film" in kinds, edges="edge" in kinds))
    if "stability" in kinds:
        found.append(stability_boundaries(study, tolerance))
    parts = [f for f in found if len(f)]
    frame = pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=_FIXED)
    frame.attrs["units"] = {"value": "(the row's unit)", "error": "(the row's unit)", "runs": "1", "periods": "1",
                            "converged": "1", "edge": "1",
                            **{k: study.cases[k].attrs.get("units", "") for k in study.cases.attrs.get("axes", [])}}
    return frame


#: The /boundaries columns every row has; the study's other axes follow.
_FIXED = ["axis", "value", "error", "unit", "kind", "case_a", "case_b", "runs", "periods", "converged", "edge", "lost",
          "reason"]


def write(path, frame):
    """Store ``frame`` (``locate``'s) as the study file's ``/boundaries`` table, replacing one:
    a group of one-dimensional columns (lubsweep's table layout: attribute ``columns``,
    ``units`` on each), strings variable-length, the row's own axis NaN (or "")."""
    import h5py
    import numpy as np
    import pandas as pd

    strings = h5py.string_dtype()
    with h5py.File(path, "a") as f:
        if "boundaries" in f:
            del f["boundaries"]
        g = f.create_group("boundaries")
        names = list(frame.columns) if len(frame.columns) else list(_FIXED)
        units = getattr(frame, "attrs", {}).get("units", {})
        for name in names:
            col = frame[name] if name in frame else pd.Series([], dtype=float)
            if name in ("case_a", "case_b", "runs", "periods", "converged", "edge"):
                g.create_dataset(name, data=np.asarray(col, dtype=np.int64), maxshape=(None,))
            elif name in ("axis", "unit", "kind", "lost", "reason") or col.dtype == object:
                text = ["" if not isinstance(v, str) else v for v in col]  # NaN: the row's own axis
                g.create_dataset(name, data=np.array(text, dtype=object), dtype=strings, maxshape=(None,))
            else:
                g.create_dataset(name, data=np.asarray(col, dtype=np.float64), maxshape=(None,))
            g[name].attrs["units"] = units.get(name, "1")
        g.attrs["columns"] = np.array(names, dtype=object).astype(strings)
        g.attrs["long_name"] = ("boundaries located between grid points: where the minimum film reaches the safe film "
                                "(kind safe_film), or the dominant multiplier crosses the unit circle (fold, "
                                "period_doubling, neimark_sacker), or, following a safe orbit towards a neighbour "
                                "whose film is below it (edge 1), where that orbit is lost (orbit_end); "
                                "lubjoint.boundaries")


def read(path):
    """The study file's ``/boundaries`` table as a DataFrame (None where it has none)."""
    import h5py
    import pandas as pd

    with h5py.File(path, "r") as f:
        if "boundaries" not in f:
            return None
        g = f["boundaries"]
        names = [n.decode() if isinstance(n, bytes) else n for n in g.attrs["columns"]]
        data = {}
        for n in names:
            d = g[n]
            data[n] = d.asstr()[()] if h5py.check_string_dtype(d.dtype) else d[()]
        frame = pd.DataFrame(data)
        frame.attrs["units"] = {n: g[n].attrs.get("units", "") for n in names}
    for flag in ("converged", "edge"):
        if flag in frame:
            frame[flag] = frame[flag].astype(bool)
    return frame


def reason(row):
    """Why a /boundaries row has not converged: its ``reason``, "" for a converged row and
    for one from a file written before the column."""
    why = "" if row["converged"] else row.get("reason", "")
    return why if isinstance(why, str) else ""


def not_converged(row):
    """", not converged: why" for a row that has not converged ("" for one that has)."""
    if row["converged"]:
        return ""
    why = reason(row)
    return ", not converged" + (f": {why}" if why else "")


def main(argv=None):
    """``python3 -m lubjoint.boundaries STUDY.h5``: locate, store and print the boundaries."""
    import argparse
    import sys

    from . import study as st

    ap = argparse.ArgumentParser(prog="python3 -m lubjoint.boundaries",
                                 description="Locate a study's boundaries (safe film, stability) between its grid "
                                             "points and store them as its /boundaries table.")
    ap.add_argument("study", help="a lubsweep study file (its grid with sensitivities, the default)")
    ap.add_argument("--tolerance", type=float, default=5e-3, help="relative accuracy of each value (default 0.005)")
    ap.add_argument("--no-write", action="store_true", help="print only; leave the study file as it is")
    ap.add_argument("--kinds", default=",".join(KINDS),
                    help="which boundaries, comma separated (default all: " + ",".join(KINDS) + "): safe_film "
                         "between two orbits, edge where a safe orbit followed towards a neighbour without one is "
                         "lost (orbit_end, its former name, is accepted), stability crossings; edge and "
                         "stability cost most")
    args = ap.parse_args(argv)
    if not (0.0 < args.tolerance < 1.0):
        print(f"--tolerance = {args.tolerance}: must lie in (0, 1)", file=sys.stderr)
        return 2
    kinds = [k.strip() for k in args.kinds.split(",") if k.strip()]
    bad = _unknown(kinds) or ([] if kinds else ["(none)"])
    if bad:
        print(f"--kinds = {args.kinds}: {bad[0]} is not one of {', '.join(KINDS)}", file=sys.stderr)
        return 2
    try:
        st.check(args.study)
    except (st.StudyFormatError, FileNotFoundError, IsADirectoryError) as e:
        print(f"{ap.prog}: {e}", file=sys.stderr)
        return 2
    frame = locate(st.load_study(args.study), args.tolerance, kinds)
    if not args.no_write:
        write(args.study, frame)
    if len(frame) == 0:
        print("boundaries: none (no two grid neighbours differ in below_safe_film or stability)")
    else:
        cases = st.cases(args.study)
        own = sum(float(cases[c].clip(lower=0).sum()) for c in ("periods_integrated", "sensitivity_periods")
                  if c in cases)
        spent = float(frame["periods"].sum())
        print(f"boundaries: {len(frame)} located in {int(frame['runs'].sum())} runs, {spent:.0f} periods "
              f"({100 * spent / own if own else 0:.1f} % of the study's {own:.0f})")
    for _, r in frame.iterrows():
        others = ", ".join(f"{k} = {r[k]}" for k in frame.columns if k not in _FIXED and r[k] == r[k] and r[k] != "")
        print(f"{r['kind']}: {r['axis']} = {r['value']:.6g} ± {r['error']:.2g} {r['unit']} between cases "
              f"{r['case_a']} and {r['case_b']} ({others}; {r['runs']} runs{not_converged(r)})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
