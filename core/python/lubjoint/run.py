"""lubjoint.run: one run of a scene, as lubsim does it, returned as an ``xarray.Dataset``.

``simulate`` calls the compiled ``_lubjoint.simulate`` (the functions lubsim calls: read,
override, validate, run, write) and labels what it returns: ``Column`` records (name,
units, long_name, values) for the series, the orbit and the cycles, ``Scalar`` records
(name, value, units, integer, long_name) for the metrics and solver statistics.
"""

import json
import os
import warnings
from collections.abc import Mapping

import numpy as np

from . import _lubjoint
from ._lubjoint import InputError

#: Bad input (scene, override, argument): the message names the path, the value and the rule.
SceneError = InputError

#: An integer metric or statistic that is unknown (e.g. ``cycles_to_steady`` of a run that
#: never settled) holds this, and says so in its ``missing_value`` attribute; an unknown
#: float is NaN (docs/reference/run-file.md, missing values).
MISSING_INTEGER = -1


class PlausibilityWarning(UserWarning):
    """A value the rules accept but that is most likely a unit slip (docs/reference/plausible-ranges.md,
    plausible ranges): a viscosity outside 1e-4 – 5 Pa s, a clearance/radius outside 1e-4 –
    0.3, a driver speed above 50 000 rpm. The message is lubsim's warning line: the JSON
    Pointer, the value, the range and the likely slip."""


class ValidityNote(UserWarning):
    """A force law used outside its assumptions (docs/theory/force-laws.md, validity notes): a
    short-bearing law at L/D > 0.5 or a long-bearing law at L/D < 2, with its measured deviation
    from the finite bearing at the scene's L/D, or a full-film law whose load reversed in the
    run. The message is lubsim's note line. Informative: ``strict=True`` does not refuse it."""


def _assignment(pointer, value):
    """``--set POINTER=VALUE`` for one override: the Python value as JSON (a str stays a str)."""
    if not isinstance(pointer, str):
        raise InputError(f"overrides: key {pointer!r} must be a JSON Pointer string, e.g. '/joints/3/viscosity_Pa_s'")
    if isinstance(value, np.generic):
        value = value.item()
    return f"{pointer}={json.dumps(value)}"


def simulate(scene, overrides=None, output=None, *, strict=False, sensitivity=(), continue_from=None,
             single_step=False):
    """Run one scene, as ``lubsim`` does, and return it as an ``xarray.Dataset``.

    Parameters
    ----------
    scene : dict or str or os.PathLike
        The scene: a dict (the JSON object of docs/reference/scene.md) or the path of a scene
        file.
    overrides : dict, optional
        ``{JSON Pointer: value}`` applied in order before validation, with the semantics of
        lubsim's ``--set POINTER=VALUE`` (the pointer must name an existing value or a new
        key of an existing object), e.g. ``{"/joints/3/viscosity_Pa_s": 0.04,
        "/joints/3/force_law": "frene_long"}``. Values are Python/JSON values: ``"0.04"`` is
        a string, ``0.04`` a number.
    output : str or os.PathLike, optional
        Write the run file (lubsim's run.h5 layout, ``program`` = ``lubjoint``) there. No
        file is written without it.
    strict : bool, optional
        lubsim's ``--strict``: an implausible value is an ``InputError`` (nothing run or
        written) instead of a ``PlausibilityWarning``.
    sensitivity : sequence of str, optional
        lubsim's ``--sensitivity``: JSON Pointers of scene numbers; every steady metric of the
        located orbit is differentiated with respect to each (docs/theory/sensitivities.md).
        In the Dataset: ``d_<metric>_per_<key>`` (``<key>`` the pointer without its leading
        slash, ``/`` as ``_``) with ``units`` "metric unit/(parameter unit)", ``parameter``
        and ``long_name``, and ``..._error``; ``attrs["sensitivities"]``: each pointer's
        status and message.
    continue_from : (scene, orbit_seed), optional
        Start from a neighbour's orbit instead of the scene's own start: ``scene`` the
        neighbour's effective scene (a dict or JSON text) and ``orbit_seed`` its orbit packed
        as a lubsweep study's ``/cases/orbit_seed`` row (``lubjoint.study.orbit_seed_row``,
        or this function's own ``orbit_seed`` variable). The orbit is continued along the
        path of scenes between the two (docs/theory/continuation.md); where it is lost on
        the way the run ends ``not_converged`` and says where, with no run from the scene's
        own start: the question "does this orbit continue to this scene?".
    single_step : bool, optional
        With ``continue_from``: one Newton from the neighbour's orbit straight at the scene,
        no shorter steps along the path where it fails (a cheap existence test where the
        neighbour is close). Where it stalls at the period map's noise it is accepted if,
        through the neighbour's monodromy, its residual moves the orbit by less than a tenth
        of steady_tolerance (the error bars then measure the orbit), else run once more on
        periods at a tenth of rtol, as a start from the transient is.

    Returns
    -------
    xarray.Dataset
        - one variable per recorded channel over the dimension ``t`` [s], each with its
          ``units`` (CF style, as the run file: ``m s-2``) and ``long_name`` (the scene's
          ``outputs.channels``; none if it lists none);
        - the steady-cycle metrics (``min_film_thickness_m``, ``max_eps``,
          ``peak_reaction_N``, ...) and solver statistics (``steps``, ``rhs_evals``,
          ``wall_time_s``, ``max_position_drift``, ...) as 0-d variables with ``units``,
          ``long_name`` and ``kind`` = ``metric`` or ``solver`` (counts and flags are
          int64, units ``1``, ``missing_value`` = -1: the value of an unknown one, e.g.
          ``cycles_to_steady`` of a run that never settled; an unknown float is NaN); a
          name already taken by a channel gets the prefix ``metric_`` or ``solver_``;
        - the per-cycle extremes (the run file's /cycles) as ``cycle_<name>`` over the
          dimension ``cycle`` (1, 2, ...);
        - ``attrs``: ``status`` (``ok``, ``film_collapse``, ``solver_failure``,
          ``budget_exceeded``), ``message``, ``scene`` (the effective scene JSON),
          ``program``, ``version``, ``revision``, ``solver_method``,
          ``solver_formulation``, ``solver_jacobian``, ``solver_rtol``, ``solver_atol``
          (the absolute tolerance of lengths [m]; docs/theory/formulations.md), ``warnings`` (the
          plausibility warnings, a list of str, empty if none; each also issued as a
          ``PlausibilityWarning``), ``notes`` (the validity notes, likewise, each issued as a
          ``ValidityNote``) and ``output`` (the run file, if written).

    Raises
    ------
    InputError
        (a ``ValueError``) for a bad scene, override or output path (lubsim's rules: a
        file in an existing, writable directory), with lubsim's message
        (``SCENE: joints[3].viscosity_Pa_s = -0.4: must be > 0 Pa s``), or with
        ``strict=True`` an implausible value. Nothing is run or written then.

    Warns
    -----
    PlausibilityWarning
        Once per implausible value (lubsim's warning line), before the run.
    ValidityNote
        Once per validity note (lubsim's note line), after the run.

    The GIL is released during the run: Python threads can run scenes side by side.
    """
    import xarray as xr

    if isinstance(scene, Mapping):
        scene_path, scene_text, origin = None, json.dumps(scene), "<scene dict>"
    elif isinstance(scene, (str, os.PathLike)):
        scene_path = os.fspath(scene)
        scene_text, origin = None, scene_path
    else:
        raise InputError(f"scene: {type(scene).__name__}: must be a dict or the path of a scene file")
    assignments = [_assignment(p, v) for p, v in (overrides or {}).items()]
    out_path = None if output is None else os.fspath(output)

    if isinstance(sensitivity, str):
        sensitivity = [sensitivity]
    from_scene, from_orbit = None, []
    if continue_from is not None:
        try:
            from_scene, from_orbit = continue_from
        except (TypeError, ValueError):
            raise InputError("continue_from: must be a pair (the neighbour's scene, its orbit_seed row)") from None
        from_scene = from_scene if isinstance(from_scene, str) else json.dumps(from_scene)
        from_orbit = [float(v) for v in from_orbit]
        if not from_orbit:
            raise InputError("continue_from: the neighbour's orbit_seed is empty: it located no orbit")
    r = _lubjoint.simulate(scene_path, scene_text, origin, assignments, out_path, strict=bool(strict),
                           sensitivity=[str(p) for p in sensitivity], from_scene=from_scene, from_orbit=from_orbit,
                           single_step=bool(single_step))
    for w in r["warnings"]:
        warnings.warn(w, PlausibilityWarning, stacklevel=2)
    for n in r["notes"]:
        warnings.warn(n, ValidityNote, stacklevel=2)

    def attrs_of(unit, long_name, **more):
        a = {"units": unit} if unit else {}
        if long_name:
            a["long_name"] = long_name
        return {**a, **more}

    coords, data_vars = {}, {}
    series = r["series"]  # _lubjoint.Column: name, units, long_name, values
    if series:
        t = series[0]  # "t" first
        coords["t"] = ("t", t.values, attrs_of(t.units, t.long_name or "time"))
        for c in series[1:]:
            data_vars[c.name] = ("t", c.values, attrs_of(c.units, c.long_name))
    orbit = r["orbit"]
    if orbit:  # the periodic orbit found by shooting (run file /orbit), on its own time axis
        t = orbit[0]
        coords["orbit_t"] = ("orbit_t", t.values, attrs_of(t.units, "time on the periodic orbit"))
        for c in orbit[1:]:
            data_vars["orbit_" + c.name] = ("orbit_t", c.values, attrs_of(c.units, f"{c.name} on the periodic orbit"))
    cycles = r["cycles"]
    n_cycles = len(cycles[0].values) if cycles else 0
    coords["cycle"] = ("cycle", np.arange(1, n_cycles + 1, dtype=np.int64),
                       {"units": "1", "long_name": "crank cycle number (1: the first)"})
    for c in cycles:
        data_vars["cycle_" + c.name] = ("cycle", c.values, attrs_of(c.units, c.long_name))
    for kind, fields in (("metric", r["metrics"]), ("solver", r["solver"])):  # _lubjoint.Scalar
        for f in fields:
            key = f.name if f.name not in data_vars and f.name not in coords else f"{kind}_{f.name}"
            if f.integer:  # unknown (NaN from the engine): the sentinel, declared (docs/reference/run-file.md)
                value = np.int64(f.value) if np.isfinite(f.value) else np.int64(MISSING_INTEGER)
                data_vars[key] = ((), value, attrs_of(f.units, f.long_name, kind=kind, missing_value=MISSING_INTEGER))
            else:
                data_vars[key] = ((), np.float64(f.value), attrs_of(f.units, f.long_name, kind=kind))
    # Every Floquet multiplier of the steady cycle (shooting), largest first.
    data_vars["multiplier_modulus"] = ("multiplier", r["multiplier_modulus"],
                                       {"units": "1", "long_name": "Floquet multipliers' moduli, largest first"})
    data_vars["multiplier_angle_rad"] = ("multiplier", r["multiplier_angle_rad"],
                                         {"units": "rad", "long_name": "Floquet multipliers' angles"})
    data_vars["orbit_seed"] = ("orbit_seed_value", np.asarray(r["orbit_seed"], dtype=np.float64), {
        "units": "1", "long_name": "the located orbit packed as a lubsweep study's /cases/orbit_seed row, for "
                                   "continue_from (empty: no orbit)"})
    sens_status = []
    for s in r["sensitivities"]:
        key = s["parameter"].lstrip("/").replace("/", "_")
        sens_status.append(f"{s['parameter']}: {'ok' if s['ok'] else 'failed'}" + (f": {s['message']}" if s["message"] else ""))
        for name, units, d, e in zip(r["steady_metric_names"], s["units"], s["d_metric"], s["d_metric_error"]):
            for suffix, v, what in (("", d, "d"), ("_error", e, "error bar of d")):
                data_vars[f"d_{name}_per_{key}{suffix}"] = ((), np.float64(v), attrs_of(
                    units, f"{what} {name} / d {s['parameter']} on the located orbit", kind="sensitivity",
                    parameter=s["parameter"], periods_integrated=int(s["periods"])))
    settings = r["solver_settings"]
    attrs = {
        "status": r["status"],
        "message": r["message"],
        "classification": r["classification"],
        "steady_method": r["steady_method"],
        "scene": r["scene"],
        "program": r["program"],
        "version": r["version"],
        "revision": r["revision"],
        "solver_method": settings["method"],
        "solver_formulation": settings["formulation"],
        "solver_jacobian": settings["jacobian"],
        "solver_rtol": settings["rtol"],
        "solver_atol": settings["atol"],
        "warnings": list(r["warnings"]),
        "notes": list(r["notes"]),
        "sensitivities": sens_status,
    }
    if out_path is not None:
        attrs["output"] = out_path
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)
