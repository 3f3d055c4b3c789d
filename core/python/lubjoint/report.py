"""lubjoint.report: a study as one self-contained HTML page, readable offline.

    python3 -m lubjoint.report STUDY.h5 -o report.html [--baseline tests/baselines/paper.csv]
    lubsweep report STUDY.h5 -o report.html [--baseline BASELINE.csv]      # the same

    from lubjoint import report
    report.write_report("out/study.h5", "out/report.html", baseline="tests/baselines/paper.csv")

The page holds, from the study file alone (``lubjoint.study``):

- the study's summary: one row per case (its axes, status, classification, the steady
  cycle's metrics with their error bars, cost), a table that sorts by any column (click its
  header) and filters (a text box, a classification);
- per sub-grid, each cell's classification (a map over the grid's first numeric axis and the
  other axes' values), and each steady metric (one with an error bar, ``<metric>_error``)
  over that axis, a line per force law (and other axis values), with its error bars;
- a panel per case (a select box): the journal centre's orbit in the clearance circle, the
  minimum film thickness and eccentricity ratio, and the joint's reaction over crank angle,
  from the channels the study stores for it (``/series``: a periodic case's orbit over its
  metric cycles, any other case's last cycles; the page says which, and says so where a
  case, or the study, stores none);
- the grid edges where the periodic orbit changes (``lubjoint.study.bifurcation_edges``);
- the boundaries located between grid points (``/boundaries``, ``lubjoint.boundaries``) and
  the cases a refinement added (``/refinement``, ``lubsweep refine``), where the file has them;
- the solver statistics of each case;
- with ``baseline`` (a CSV of ``lubjoint.baseline``, e.g. tests/baselines/paper.csv): the
  nightly comparison, each metric of each case against its tolerance, outside highlighted.

Charts are drawn by Chart.js 3 (Debian's ``libjs-chart.js``, ``CHART_JS``), inlined into the
page with the page's own small script (sorting, filtering, the select boxes, an error-bar
plugin): no network. ``?selftest=1`` after the file's URL makes the page sort, filter and show
every case and write what it found into ``#selftest`` (the headless-browser test reads it).
"""
import argparse
import datetime
import html
import itertools
import json
import math
import os
import sys

import numpy as np

from . import baseline as baseline_mod
from . import study as study_mod
from ._report_page import PAGE

#: Chart.js 3, as Debian's libjs-chart.js installs it; inlined into every page.
CHART_JS = "/usr/share/javascript/chart.js/chart.min.js"
#: The Debian package that installs ``CHART_JS`` (tools/setup.sh).
CHART_JS_PACKAGE = "libjs-chart.js"
#: The most samples a case's chart draws per channel (every k-th sample, and each channel's extremes).
MAX_SAMPLES = 900
#: The summary table's metric columns: (column, label); a column of the study that is absent is left out.
SUMMARY_METRICS = (("min_film_thickness_m", "h_min"), ("max_eps", "max ε"), ("peak_reaction_N", "peak F"),
                   ("peak_acceleration_m_s2", "peak a"), ("peak_film_pressure_Pa", "p_max"),
                   ("periodicity", "periodicity"), ("multiplier_1_modulus", "|μ|max"),
                   ("last_cycle_min_film_m", "last h"), ("steps", "steps"), ("wall_time_s", "wall"))
#: The colour of a classification not in ``plot.CLASSIFICATION_COLOURS`` (not_run, invalid_scene, error).
OTHER_COLOUR = "#b8b8b8"


class ReportError(ValueError):
    """Input the report cannot be written from (no study file, not a study, a bad baseline),
    or a missing Chart.js; the message names the file and what to do."""


class ChartJsMissing(ReportError):
    """Chart.js (``CHART_JS``) is not installed: the message names the Debian package."""


# --- values -------------------------------------------------------------------------------


def _text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def _num(v, digits=6):
    """A JSON number of ``digits`` significant digits, or None (NaN, inf, not a number)."""
    try:
        f = float(v)
    except (TypeError, ValueError):
        return None
    return float(f"{f:.{digits}g}") if math.isfinite(f) else None


def _display(unit):
    from .plot import display

    return display(unit)


def _label(name, unit):
    """``name [unit shown]`` (µm for m, ...), as lubjoint.plot labels an axis."""
    from .plot import axis_label

    return axis_label(name, unit, _display(unit)[0])


def chart_js():
    """The text of Chart.js (``CHART_JS``); ``ReportError`` naming the Debian package if it is missing."""
    try:
        with open(CHART_JS, encoding="utf-8") as f:
            return f.read()
    except OSError as e:
        raise ChartJsMissing(f"Chart.js is missing ({CHART_JS}: {e.strerror}): install the Debian package "
                          f"{CHART_JS_PACKAGE} (apt-get install {CHART_JS_PACKAGE}; tools/setup.sh does)") from None


# --- the study's parts --------------------------------------------------------------------


def _axis_value(value, unit):
    """An axis value as shown (µm, rpm, ...), as text."""
    if isinstance(value, (str, bytes)):
        return _text(value)
    factor = _display(unit)[1]
    return f"{float(value) * factor:g}"


def _case_label(row, axes, units):
    """``clearance 500 µm, viscosity 0.4 Pa s, ...``: a case's axis values as shown."""
    from .plot import _bare

    def one(a):
        unit = units.get(a, "")
        shown = _display(unit)[0] if unit not in ("", "1") else ""
        return f"{_bare(a, unit)} {_axis_value(row[a], unit)}" + (f" {shown}" if shown else "")
    return ", ".join(one(a) for a in axes)


def _summary(cases, axes, units):
    """The summary table: columns (name, label, unit shown, kind) and one row of cells per case."""
    cols = [{"name": "case", "label": "case", "kind": "num"}, {"name": "name", "label": "name", "kind": "text"}]
    for a in axes:
        unit = units.get(a, "")
        cols.append({"name": a, "label": _label(a, unit) if unit else a,
                     "kind": "text" if cases[a].dtype == object else "num"})
    cols += [{"name": "status", "label": "status", "kind": "text"},
             {"name": "classification", "label": "classification", "kind": "text"}]
    metrics = [(m, lbl) for m, lbl in SUMMARY_METRICS if m in cases.columns]
    for m, lbl in metrics:
        shown = _display(units.get(m, ""))[0]
        cols.append({"name": m, "label": f"{lbl} [{shown}]" if shown and shown != "–" else lbl, "kind": "num"})
    cols.append({"name": "message", "label": "message", "kind": "text"})
    rows = []
    for cid, r in cases.iterrows():
        cells = [[int(cid)], [_text(r["name"])]]
        cells += [[_text(r[a])] if cases[a].dtype == object else [_num(float(r[a]) * _display(units.get(a, ""))[1])]
                  for a in axes]
        cells += [[_text(r["status"])], [_text(r["classification"])]]
        for m, _ in metrics:
            f = _display(units.get(m, ""))[1]
            err = r.get(f"{m}_error", float("nan"))
            cells.append([_num(float(r[m]) * f, 5), _num(float(err) * f, 2)])
        cells.append([_text(r.get("message", ""))])
        rows.append(cells)
    return {"columns": cols, "rows": rows}


def _grid_axis(g):
    """The axis a sub-grid's charts run along: its first numeric axis of more than one value,
    else its first of more than one value, else its first."""
    dims = list(g["case_id"].dims)
    numeric = [d for d in dims if np.issubdtype(g[d].dtype, np.number)]
    for pool in ([d for d in numeric if g.sizes[d] > 1], [d for d in dims if g.sizes[d] > 1], dims):
        if pool:
            return pool[0]
    return dims[0]


def _grid(name, g, cases, units):
    """One sub-grid as the page draws it: its axis, its rows (the other axes' values), each
    cell's classification, and each steady metric with its error bars."""
    x = _grid_axis(g)
    numeric = bool(np.issubdtype(g[x].dtype, np.number))
    if numeric:
        g = g.sortby(x)
    others = [d for d in g["case_id"].dims if d != x]
    xunit = g[x].attrs.get("units", units.get(x, ""))
    xs = [_axis_value(v, xunit) for v in g[x].values]
    combos = list(itertools.product(*(g[d].values for d in others)))
    law = None if others else _grid_law(g, cases)
    rows = [", ".join(_axis_value(v, g[d].attrs.get("units", "")) for d, v in zip(others, c)) or law or name
            for c in combos]
    rows_title = ", ".join(_label(d, g[d].attrs.get("units", "")) if g[d].attrs.get("units", "") else d
                           for d in others) or ("force_law" if law else "")
    cells, picks = [], []
    for row, combo in zip(rows, combos):
        sub = g.sel(dict(zip(others, combo))) if others else g
        picks.append(sub)
        for j, xv in enumerate(xs):
            cid = int(sub["case_id"].values[j])
            cells.append({"x": xv, "y": row, "case": cid, "name": _text(cases.loc[cid, "name"]),
                          "cls": _text(sub["classification"].values[j]), "status": _text(sub["status"].values[j])})
    shown = [float(v) * _display(xunit)[1] for v in g[x].values] if numeric else None
    out = {"name": name, "axis": x, "axis_label": _label(x, xunit) if xunit else x, "xs": xs, "rows": rows,
           "rows_title": rows_title,
           "cells": cells, "numeric": numeric, "x": shown,
           "log_x": bool(numeric and min(shown) > 0 and max(shown) / min(shown) >= 10)}
    out["metrics"] = {m: _grid_metric(m, picks, rows, units) for m in _steady_metrics(g, cases)}
    return out


def _drop_empty_metrics(grids):
    """Leave out a metric that has no value in any sub-grid (e.g. a peak pressure no force law gives)."""
    names = {m for g in grids for m in g["metrics"]}
    empty = [m for m in names if not any(v is not None for g in grids for s in g["metrics"].get(m, {"series": []})["series"]
                                         for v in s["y"])]
    for g in grids:
        for m in empty:
            g["metrics"].pop(m, None)
    return grids


def _grid_law(g, cases):
    """The force law of a sub-grid whose cases share one force law (and have no such axis), else None."""
    if "force_law" not in cases.columns:
        return None
    laws = {_text(cases.loc[int(c), "force_law"]) for c in np.ravel(g["case_id"].values)}
    return laws.pop() if len(laws) == 1 else None


def _steady_metrics(g, cases):
    """The steady metrics of a grid: the study's metrics with an error bar (``<metric>_error``)."""
    listed = [_text(m) for m in np.atleast_1d(cases.attrs.get("metrics", []))]
    return [m for m in listed if m in g and f"{m}_error" in g and not m.startswith("d_")]


def _grid_metric(m, picks, rows, units):
    """One metric over one sub-grid: a series per row, its values and error bars in the unit shown."""
    unit = picks[0][m].attrs.get("units", units.get(m, ""))
    shown, factor = _display(unit)
    series, missing = [], []
    for row, sub in zip(rows, picks):
        y = [_num(v * factor) for v in sub[m].values]
        err = [_num(v * factor, 3) for v in sub[f"{m}_error"].values]
        series.append({"label": row, "y": y, "err": err})
        missing += [f"{_text(n)} ({_text(c)})" for n, c, v in
                    zip(sub["case_id"].values, sub["classification"].values, y) if v is None]
    values = [v for s in series for v in s["y"] if v is not None]
    log = bool(values and min(values) > 0 and max(values) / min(values) >= 100)
    return {"label": _label(m, unit) if unit else m, "unit": shown, "series": series, "log": log,
            "missing": ["case " + t for t in missing]}


def _decimate(n, arrays):
    """Indices of at most ~``MAX_SAMPLES`` samples out of ``n``: every k-th, and each array's extremes."""
    if n <= MAX_SAMPLES:
        return np.arange(n)
    keep = set(range(0, n, math.ceil(n / MAX_SAMPLES))) | {n - 1}
    for a in arrays:
        if np.isfinite(a).any():
            keep |= {int(np.nanargmin(a)), int(np.nanargmax(a))}
    return np.array(sorted(keep))


def _case_series(study_path, cid, name, orbit_classes, classification):
    """A case's channels over its stored cycles, as the page draws them, or None (none stored)."""
    from .plot import _clearance, _crank_deg

    ds = study_mod.series(study_path, name)
    if ds is None:
        return None
    with ds:
        have = {k: np.asarray(ds[k].values, dtype=float) for k in ("crank_angle", "e_x", "e_y", "eps", "h_min",
                                                                  "reaction_force") if k in ds}
        units = {k: ds[k].attrs.get("units", "") for k in have}
    keep = _decimate(len(next(iter(have.values()))), list(have.values()))
    have = {k: v[keep] for k, v in have.items()}
    out = {"what": ("periodic orbit over the metric cycles" if classification in orbit_classes
                    else f"the run's last stored cycles (no periodic orbit: {classification})"),
           "samples": int(len(keep)), "channels": sorted(have), "units": units,
           "not_stored": [k for k in ("e_x", "e_y", "eps", "h_min", "reaction_force", "crank_angle") if k not in have]}
    if {"e_x", "e_y"} <= set(have):
        try:
            c = _clearance(have, ds, None)
            out["orbit"] = {"x": [_num(v / c, 5) for v in have["e_x"]], "y": [_num(v / c, 5) for v in have["e_y"]],
                            "clearance_um": _num(c * 1e6)}
        except ValueError as e:
            out["orbit_note"] = str(e)
    if "orbit" in out and not np.any(have.get("eps", np.ones(1)) > 1e-6):
        out.pop("orbit")
        out["orbit_note"] = "the journal does not move in its bearing (eps = 0: an ideal joint)"
    if "crank_angle" in have:
        wrapped = _crank_deg(have["crank_angle"], *(have[k] for k in ("h_min", "eps", "reaction_force")
                                                    if k in have))
        names = [k for k in ("h_min", "eps", "reaction_force") if k in have]
        scale = {"h_min": 1e6}
        out["angle"] = [_num(v, 5) for v in wrapped[0]]
        for k, values in zip(names, wrapped[1:]):
            out[k] = [_num(v * scale.get(k, 1.0), 5) for v in values]
    return out


def _cases_panel(study_path, cases, axes, units):
    """Each case's label, facts and channels (``_case_series``)."""
    orbit_classes = set(study_mod.orbit_classifications(cases)) if "orbit_classifications" in cases.attrs else set()
    facts = [m for m, _ in SUMMARY_METRICS if m in cases.columns] + ["safe_film_thickness_m"]
    out = []
    for cid, r in cases.iterrows():
        cls = _text(r["classification"])
        info = {"case": int(cid), "name": _text(r["name"]), "label": _case_label(r, axes, units),
                "status": _text(r["status"]), "classification": cls, "message": _text(r.get("message", "")),
                "facts": [[_label(m, units.get(m, "")), _num(float(r[m]) * _display(units.get(m, ""))[1], 5),
                           _num(float(r.get(f"{m}_error", float("nan"))) * _display(units.get(m, ""))[1], 2)]
                          for m in facts if m in cases.columns]}
        safe = r.get("safe_film_thickness_m", float("nan"))
        info["safe_film_um"] = _num(float(safe) * 1e6)
        info["series"] = _case_series(study_path, cid, info["name"], orbit_classes, cls)
        out.append(info)
    return out


def _edges(cases, units):
    """The bifurcation edges as rows of text and numbers, or a note why there are none."""
    try:
        e = study_mod.bifurcation_edges(cases)
    except (study_mod.StudyFormatError, ValueError) as err:
        return {"note": str(err), "rows": []}
    rows = []
    for _, r in e.iterrows():
        unit = units.get(r["axis"], "")
        rows.append([_text(cases.loc[r["case_a"], "name"]), _text(cases.loc[r["case_b"], "name"]),
                     _label(r["axis"], unit), _axis_value(r["value_a"], unit), _axis_value(r["value_b"], unit),
                     r["kind"], _axis_value(r["crossing_value"], unit) if math.isfinite(r["crossing_value"]) else "",
                     f"{r['class_a']} → {r['class_b']}", _num(r["mu_a"], 5), _num(r["mu_b"], 5)])
    return {"note": "", "rows": rows}


def _lost(row):
    """An edge row's ``lost`` as the page shows it: what the run just beyond the edge found
    (its classification; "" for other rows and in files without the column)."""
    lost = row.get("lost", "")
    return lost.split(":", 1)[0] if isinstance(lost, str) else ""


def _converged(row):
    """A boundary's "converged" cell: yes, or no and why (files since the reason came)."""
    from .boundaries import reason

    if row["converged"]:
        return "yes"
    why = reason(row)
    return f"no: {why}" if why else "no"


def _boundaries(study_path, cases, axes, units):
    """The study's /boundaries (``lubjoint.boundaries``) and /refinement (``lubsweep refine``)
    as table rows, each with a note saying how to make it where the file has none."""
    from . import boundaries as bd

    names = {int(i): _text(n) for i, n in cases["name"].items()}
    added = study_mod.cases(study_path, group="refinement")
    if added is not None:
        names.update({int(i): _text(n) for i, n in added["name"].items()})
    out = {"boundaries": [], "refinement": [], "boundaries_note": "", "refinement_note": ""}
    frame = bd.read(study_path)
    if frame is None or not len(frame):
        out["boundaries_note"] = ("none in the file: python3 -m lubjoint.boundaries STUDY.h5 locates them "
                                  "(docs/theory/sensitivities.md)")
    else:
        for _, r in frame.iterrows():
            unit = units.get(r["axis"], "")
            line = ", ".join(f"{_label(a, units.get(a, ''))} = {_axis_value(r[a], units.get(a, ''))}" for a in axes
                             if a != r["axis"] and a in r and r[a] == r[a] and r[a] != "")
            factor = _display(unit)[1]
            out["boundaries"].append([r["kind"], _label(r["axis"], unit), float(r["value"]) * factor,
                                      float(r["error"]) * factor, line,
                                      f"{names.get(int(r['case_a']), r['case_a'])} – {names.get(int(r['case_b']), r['case_b'])}",
                                      int(r["runs"]), int(r.get("periods", -1)), _converged(r),
                                      _lost(r)])
    if added is None or not len(added):
        out["refinement_note"] = "none in the file: lubsweep refine STUDY.h5 --budget K adds cases (docs/guide/lubsweep.md)"
    else:
        for i, r in added.iterrows():
            unit = units.get(_text(r["axis"]), "")
            out["refinement"].append([names[int(i)], f"{names.get(int(r['case_a']))} – {names.get(int(r['case_b']))}",
                                      _label(_text(r["axis"]), unit), _axis_value(r[_text(r["axis"])], unit),
                                      _text(r["reason"]), _text(r["classification"]),
                                      _num(float(r["min_film_thickness_m"]) * 1e6, 6)])
    return out


def _solver(cases, units):
    """The solver statistics: a column per statistic, a row per case."""
    stats = [_text(s) for s in np.atleast_1d(cases.attrs.get("solver", [])) if _text(s) in cases.columns]
    cols = [{"name": "name", "label": "case", "kind": "text"}, {"name": "classification", "label": "classification",
                                                                 "kind": "text"}]
    cols += [{"name": s, "label": _label(s, units.get(s, "")) if units.get(s, "") not in ("", "1") else s,
              "kind": "num"} for s in stats]
    rows = [[[_text(r["name"])], [_text(r["classification"])]] + [[_num(r[s], 5)] for s in stats]
            for _, r in cases.iterrows()]
    return {"columns": cols, "rows": rows}


def _comparison(study_path, baseline, cases):
    """The nightly comparison (``lubjoint.baseline``) as the page shows it."""
    try:
        now, base = baseline_mod.study_rows(study_path, cases), baseline_mod.read_baseline(baseline)
    except baseline_mod.BaselineError as e:
        raise ReportError(str(e)) from None
    c = baseline_mod.compare(now, base)
    metrics = list(baseline_mod.TOLERANCES)
    by_case = {}
    for chk in c["checks"]:
        row = by_case.setdefault(chk["key"], {"case": chk["case"], "key": baseline_mod.key_text(chk["key"]),
                                              "cells": {}, "changed": []})
        if chk["metric"] in ("status", "classification"):
            row["changed"].append(f"{chk['metric']} {chk['now']}, baseline {chk['baseline']}")
            continue
        row["cells"][chk["metric"]] = {k: (_num(chk[k], 9) if isinstance(chk[k], float) else chk[k])
                                       for k in ("baseline", "now", "deviation", "tolerance", "ratio", "within")}
    worst = [[m, _num(w[0], 4), _num(w[1], 4), _num(w[3], 4), w[4]] for m, w in c["worst"].items()]
    return {"baseline": baseline, "cases": len(base), "in_study": len(now), "regressions": c["regressions"],
            "notes": c["notes"], "metrics": metrics, "rows": sorted(by_case.values(), key=lambda r: r["case"]),
            "worst": worst, "tolerances": {m: list(t) for m, t in baseline_mod.TOLERANCES.items()}}


def _classes(cases):
    """The classifications of the study, in the order of ``plot.CLASSIFICATION_COLOURS``, each with its colour."""
    from .plot import CLASSIFICATION_COLOURS

    found = {_text(c) for c in cases["classification"]}
    ordered = [c for c in CLASSIFICATION_COLOURS if c in found] + sorted(found - set(CLASSIFICATION_COLOURS))
    return [{"name": c, "colour": CLASSIFICATION_COLOURS.get(c, OTHER_COLOUR)} for c in ordered]


def collect(study_path, baseline=None):
    """Everything the page shows, as one JSON-ready dict (``write_report`` embeds it)."""
    attrs = study_mod.check(study_path)
    cases = study_mod.cases(study_path)  # once: reading /cases takes seconds
    grids = {}
    for name in sorted(study_mod.grid_names(study_path)):
        with study_mod.grid(study_path, name) as g:
            grids[name] = g.load()
    axes = [_text(a) for a in np.atleast_1d(cases.attrs.get("axes", []))]
    units = cases.attrs.get("units", {})
    meta = {k: _text(attrs.get(k, "")) for k in ("program", "version", "revision", "description", "grid_file",
                                                  "base_scene_file", "format")}
    meta.update(file=os.path.basename(study_path), path=os.path.abspath(study_path),
                complete=bool(int(attrs.get("complete", 0))), cases=len(cases),
                cases_total=int(attrs.get("cases_total", len(cases))),
                warnings=[_text(w) for w in np.atleast_1d(attrs.get("warnings", [])) if _text(w)],
                notes=[_text(w) for w in np.atleast_1d(attrs.get("notes", [])) if _text(w)],
                written=datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"))
    meta["statuses"] = {k: int(v) for k, v in cases["status"].map(_text).value_counts().items()}
    meta["classifications"] = {k: int(v) for k, v in cases["classification"].map(_text).value_counts().items()}
    data = {"meta": meta, "axes": axes, "classes": _classes(cases), "summary": _summary(cases, axes, units),
            "grids": _drop_empty_metrics([_grid(name, g, cases, units) for name, g in grids.items()]),
            "cases": _cases_panel(study_path, cases, axes, units), "edges": _edges(cases, units),
            "boundaries": _boundaries(study_path, cases, axes, units),
            "solver": _solver(cases, units), "comparison": None}
    if baseline is not None:
        data["comparison"] = _comparison(study_path, os.fspath(baseline), cases)
    return data


# --- the page -----------------------------------------------------------------------------


def _json_for_script(data):
    """``data`` as JSON that can sit inside a <script> element."""
    text = json.dumps(data, allow_nan=False, ensure_ascii=False, separators=(",", ":"))
    return text.replace("</", "<\\/").replace("<!--", "<\\!--")


def render(data, chart_js_text):
    """The page's HTML for ``collect``'s ``data``, with Chart.js's text inlined."""
    title = f"Study {data['meta']['file']}"
    return (PAGE.replace("@TITLE@", html.escape(title))
            .replace("@CHARTJS@", chart_js_text.replace("</script", "<\\/script"))
            .replace("@DATA@", _json_for_script(data)))


def _check_inputs(study_path, out_html, baseline):
    """Bad input as ``ReportError`` before anything is written."""
    try:
        study_mod.check(study_path)
    except FileNotFoundError:
        raise ReportError(f"{study_path}: no such study file") from None
    except IsADirectoryError:
        raise ReportError(f"{study_path}: a directory, not a study file") from None
    except study_mod.StudyFormatError as e:
        raise ReportError(str(e)) from None
    if baseline is not None and not os.path.isfile(baseline):
        raise ReportError(f"--baseline {baseline}: no such file (a CSV of lubjoint.baseline, "
                          "e.g. tests/baselines/paper.csv)")
    out_dir = os.path.dirname(os.path.abspath(out_html))
    if os.path.isdir(out_html):
        raise ReportError(f"-o {out_html}: a directory; name the HTML file to write")
    if not os.path.isdir(out_dir):
        raise ReportError(f"-o {out_html}: the directory {out_dir} does not exist")


def write_report(study_path, out_html, baseline=None):
    """Write the study's HTML report to ``out_html`` (see the module's docstring).

    Parameters
    ----------
    study_path : str or os.PathLike
        A lubsweep study file (``lubjoint.study.check``).
    out_html : str or os.PathLike
        The page to write: one file, replaced only once it is complete.
    baseline : str or os.PathLike, optional
        A baseline CSV (``lubjoint.baseline.read_baseline``, e.g. tests/baselines/paper.csv):
        the page then shows the nightly comparison.

    Returns
    -------
    dict
        What the page shows (``collect``), e.g. ``["comparison"]["regressions"]``.

    Raises
    ------
    ReportError
        (a ``ValueError``) naming the file: no such study file, not a study file, a baseline
        that cannot be read, an output path that cannot be written, Chart.js missing (the
        Debian package ``libjs-chart.js``). Nothing is written then.
    """
    study_path, out_html = os.fspath(study_path), os.fspath(out_html)
    baseline = None if baseline is None else os.fspath(baseline)
    _check_inputs(study_path, out_html, baseline)
    js = chart_js()
    data = collect(study_path, baseline)
    page = render(data, js)
    tmp = out_html + ".partial"
    try:
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(page)
        os.replace(tmp, out_html)
    except OSError as e:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise ReportError(f"-o {out_html}: {e.strerror}") from None
    return data


def main(argv=None):
    """``python3 -m lubjoint.report STUDY.h5 -o report.html [--baseline CSV]``: exit 0 written,
    2 bad input (the message names the file; nothing written), 1 Chart.js missing."""
    ap = argparse.ArgumentParser(prog="lubjoint.report", description="Write a study's self-contained HTML report "
                                 "(summary, classification maps, metrics with error bars, each case's orbit and "
                                 "film, bifurcation edges, solver statistics; with --baseline the nightly "
                                 "comparison).")
    ap.add_argument("study", help="the study file (lubsweep -o)")
    ap.add_argument("-o", "--output", required=True, help="the HTML file to write")
    ap.add_argument("--baseline", help="a baseline CSV (tests/baselines/paper.csv): show each metric against "
                                       "its tolerance")
    args = ap.parse_args(argv)
    prog = os.environ.get("LUB_REPORT_PROG", "lubjoint.report")
    try:
        data = write_report(args.study, args.output, args.baseline)
    except ReportError as e:
        print(f"{prog}: {e}", file=sys.stderr)
        return 1 if isinstance(e, ChartJsMissing) else 2
    c = data["comparison"]
    verdict = "" if c is None else (f"; against {c['baseline']}: {len(c['regressions'])} regression"
                                    f"{'s' if len(c['regressions']) != 1 else ''}")
    print(f"{prog}: wrote {args.output} ({data['meta']['cases']} cases{verdict})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
