"""lubjoint.bifurcations: where a study's periodic orbit changes between neighbouring cells.

Pure Python (NumPy, pandas), re-exported by ``lubjoint.study``::

    from lubjoint import study
    edges = study.bifurcation_edges(study.cases("out/study.h5"))

Reads the /cases columns every study has (its axes, ``classification``, the Floquet
multipliers ``multiplier_k_modulus`` / ``multiplier_k_angle_rad``), and what the study file
says of itself, as ``lubjoint.study.cases`` puts it in the table's ``attrs``: which
classifications carry an orbit (``orbit_classifications``, ``no_orbit_classifications``)
and the grid's lattice neighbours (``/lattice``). The continuation columns
(``continued_from``, ``orbit_seed``) are not needed, so a study with
``simulation.steady = auto`` has edges too. docs/theory/continuation.md, "Bifurcations
between cells".
"""

import math

#: The kinds of edge, with the letter the classification map draws.
KINDS = {"fold": "F", "period_doubling": "PD", "neimark_sacker": "NS", "unclassified": "?", "orbit_lost": "X"}
COLUMNS = ["case_a", "case_b", "axis", "axis_unit", "value_a", "value_b", "kind", "crossing_value", "mu_a",
           "mu_b", "angle_rad", "class_a", "class_b", "both_ends_agree"]
UNITS = {"case_a": "1", "case_b": "1", "axis": "", "axis_unit": "", "value_a": "axis_unit", "value_b": "axis_unit",
         "kind": "", "crossing_value": "axis_unit", "mu_a": "1", "mu_b": "1", "angle_rad": "rad", "class_a": "",
         "class_b": "", "both_ends_agree": ""}


def lattice_edges(cases, axes):
    """Pairs of lattice neighbours ``(a, b, axis)``, ``a`` at the lower value of ``axis``, as
    the study file lists them (/lattice, written by lubsweep from the lattice its
    continuation tree walks: the cases with equal non-numeric axes, one step apart on one
    numeric axis's sorted values over the grid): those along ``axes`` whose two cases are
    both rows of ``cases``. ``StudyFormatError`` for a table without ``attrs["lattice"]``.
    """
    from .study import lattice_edges as listed

    rows, axes = set(cases.index), set(axes)
    return [(a, b, axis) for a, b, axis in listed(cases) if axis in axes and a in rows and b in rows]


def _kind_of(m1, a1, m2, a2, angle_tol, modulus_rtol):
    """The kind of a crossing from the multiplier that left the unit circle (the dominant one)."""
    if abs(a1) <= angle_tol:
        return "fold"
    if abs(a1) >= math.pi - angle_tol:
        return "period_doubling"
    if math.isfinite(m2) and abs(m1 - m2) <= modulus_rtol * m1 and abs(a1 + a2) <= angle_tol:
        return "neimark_sacker"
    return "unclassified"


def crossing_value(value_a, value_b, f_a, f_b):
    """Where f (|mu|max - 1) crosses 0 between two axis values: linear interpolation of f in
    the logarithm of the value (linearly in the value where one is not positive)."""
    t = f_a / (f_a - f_b)
    if value_a > 0 and value_b > 0:
        return math.exp(math.log(value_a) + t * (math.log(value_b) - math.log(value_a)))
    return value_a + t * (value_b - value_a)


def _get(row, name):
    v = row.get(name, float("nan"))
    return float(v) if v is not None else float("nan")


def _edge(cases, a, b, axis, angle_tol, modulus_rtol, orbit, no_orbit):
    """One edge's row, or None when its ends do not differ in an orbit's stability or existence
    (``orbit``, ``no_orbit``: the classifications with an orbit, and of a run without one)."""
    ra, rb = cases.loc[a], cases.loc[b]
    ca, cb = str(ra.get("classification", "")), str(rb.get("classification", ""))
    mu_a, mu_b = _get(ra, "multiplier_1_modulus"), _get(rb, "multiplier_1_modulus")
    row = dict(case_a=a, case_b=b, axis=axis, value_a=float(ra[axis]), value_b=float(rb[axis]), mu_a=mu_a,
               mu_b=mu_b, class_a=ca, class_b=cb, angle_rad=float("nan"), crossing_value=float("nan"),
               both_ends_agree=False)
    if (ca in orbit and cb in no_orbit) or (cb in orbit and ca in no_orbit):
        return dict(row, kind="orbit_lost")
    if not (math.isfinite(mu_a) and math.isfinite(mu_b)) or (mu_a < 1.0) == (mu_b < 1.0) or 1.0 in (mu_a, mu_b):
        return None
    ends = [ra, rb]
    unstable, stable = (ends[0], ends[1]) if mu_a > 1.0 else (ends[1], ends[0])
    kinds = [_kind_of(_get(r, "multiplier_1_modulus"), _get(r, "multiplier_1_angle_rad"),
                      _get(r, "multiplier_2_modulus"), _get(r, "multiplier_2_angle_rad"), angle_tol, modulus_rtol)
             for r in (unstable, stable)]
    return dict(row, kind=kinds[0], angle_rad=_get(unstable, "multiplier_1_angle_rad"),
                crossing_value=crossing_value(row["value_a"], row["value_b"], mu_a - 1.0, mu_b - 1.0),
                both_ends_agree=kinds[0] == kinds[1])


def bifurcation_edges(cases, axes=None, angle_tol_rad=1e-3, modulus_rtol=1e-6):
    """The grid edges whose ends differ in their periodic orbit: its stability, or whether there is one.

    ``cases``: the /cases table (``lubjoint.study.cases(path)``), indexed by case id; its
    ``attrs["axes"]`` name the axis columns (``axes`` overrides). Returns a pandas DataFrame,
    one row per edge (``attrs["units"]``: each column's unit; ``axis_unit`` is the unit of
    ``value_a``, ``value_b`` and ``crossing_value``):

    - ``case_a``, ``case_b``: lattice neighbours (``lattice_edges``: equal non-numeric axes,
      one step of one numeric axis's sorted values), ``value_a`` < ``value_b`` on ``axis``;
    - ``kind``: where both ends have multipliers and |mu|max < 1 at one end, > 1 at the
      other, the crossing is read from the dominant multiplier of the unstable end, the one
      that left the unit circle: angle within ``angle_tol_rad`` of 0 (a real multiplier
      through +1) ``fold``; of pi (through -1) ``period_doubling``; else, when multiplier 2
      is its conjugate (same modulus within ``modulus_rtol``, opposite angle),
      ``neimark_sacker``; otherwise ``unclassified``. Where one end has an orbit
      (its classification in ``orbit_classifications``) and the other ended without one (in
      ``no_orbit_classifications``): ``orbit_lost``;
    - ``crossing_value``: the axis value where |mu|max = 1, by linear interpolation of
      |mu|max - 1 in the logarithm of the axis value (in the value if one is not
      positive); NaN for ``orbit_lost``;
    - ``mu_a``, ``mu_b``: |mu|max at each end; ``angle_rad``: the crossing multiplier's
      angle; ``class_a``, ``class_b``: the ends' classifications; ``both_ends_agree``: the
      stable end's dominant multiplier is of the same kind (real near +1, real near -1,
      complex pair).

    Which classifications carry an orbit (the /cases attributes ``orbit_classifications``,
    ``no_orbit_classifications``) and which cases are neighbours (/lattice) are the study
    file's word, read from ``cases.attrs`` (``lubjoint.study.cases`` puts them there); a table
    without them raises ``StudyFormatError`` (a ``ValueError``) saying what to do.

    Limits: an edge says that something happened between two grid points, not what. The
    crossing value is an estimate from two coarse points (|mu| is not linear in the
    parameter; its error is of the order of the curvature of |mu| over the step). Two
    crossings in one step (out and back) leave no edge, and one multiplier leaving while
    another returns looks like nothing. A real multiplier through +1 seen only through |mu|
    is ambiguous: a fold (saddle-node, where the branch turns back and the other end's orbit
    is on another branch), a transcritical or a symmetry-breaking pitchfork look alike
    here. The kind is read at the unstable end: if the stable end's dominant multiplier is
    of another kind (``both_ends_agree`` False), a different multiplier dominates there and
    the label rests on one end. Multipliers near the map's noise floor (|mu| within ~1e-4 of
    1, docs/theory/continuation.md) make the stability itself uncertain. ``angle_tol_rad``
    (1e-3: a pair turning once in more than 6000 periods is read as real; a numerically
    split double real multiplier has such a small angle) and ``modulus_rtol`` (1e-6: a
    conjugate pair of a real matrix has equal moduli to rounding) are choices.
    """
    import pandas as pd

    if axes is None:
        axes = cases.attrs.get("axes")
        if axes is None:
            raise ValueError("bifurcation_edges: the cases table has no attrs['axes'] (read it with "
                             "lubjoint.study.cases, or pass axes=[...])")
    axes = [str(a) for a in ([axes] if isinstance(axes, str) else list(axes))]
    missing = [a for a in axes if a not in cases.columns]
    if missing:
        raise ValueError(f"bifurcation_edges: axes {missing} are not columns of the cases table")
    from .study import no_orbit_classifications, orbit_classifications

    orbit, no_orbit = orbit_classifications(cases), no_orbit_classifications(cases)
    units = cases.attrs.get("units", {})
    rows = []
    for a, b, axis in lattice_edges(cases, axes):
        r = _edge(cases, a, b, axis, angle_tol_rad, modulus_rtol, orbit, no_orbit)
        if r is not None:
            rows.append(dict(r, axis_unit=units.get(axis, "")))
    df = pd.DataFrame(rows, columns=COLUMNS)
    df.attrs["units"] = dict(UNITS)
    return df
