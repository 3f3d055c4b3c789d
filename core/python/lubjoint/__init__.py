"""lubjoint: planar multibody systems with lubricated revolute joints, from Python.

The engine is the C++ library lubcore (the one behind ``lubsim``, ``lubbearing`` and
``lubsweep``), reached through the compiled extension ``lubjoint._lubjoint``; this file
only turns its results into labelled arrays (xarray, NumPy). SI units throughout: every
argument with a unit names it (``radius_m``, ``viscosity_Pa_s``), every array carries a
``units`` attribute.

- ``simulate(scene, overrides=None, output=None)`` -> ``xarray.Dataset``: one run, as lubsim.
- ``force(law, eps, eps_dot, wedge_rad_s, *, radius_m, clearance_m, length_m, viscosity_Pa_s)``
  -> ``FilmForce(radial_N, tangential_N)``: a force law over NumPy arrays (broadcasting).
- ``steady_bearing(law, *, load_N, speed_rpm, radius_m, clearance_m, length_m, viscosity_Pa_s)``
  -> dict: the steadily loaded bearing, as ``lubbearing steady``.
- ``load_study(path)`` -> ``Study``: a lubsweep study file as {grid name: Dataset} plus ``cases``.

Bad input raises ``InputError`` (a ``ValueError``; alias ``SceneError``) with the message
the command line prints: the JSON path, the value and the rule. A run that cannot be
completed (film collapse, solver failure, budget) is a result, not an exception: see
``ds.attrs["status"]`` and ``ds.attrs["message"]``; the steady cycle's classification
(README "Steady cycles") in ``ds.attrs["classification"]``.

Build and import (README, "Python"):
``PYTHONPATH=build/python /usr/bin/python3 -c "import lubjoint"``.
"""

import json
import os
from collections.abc import Mapping
from typing import NamedTuple

import numpy as np

from . import _lubjoint
from ._lubjoint import InputError

__all__ = ["simulate", "force", "steady_bearing", "load_study", "study_format", "FilmForce", "Study",
           "InputError", "SceneError", "StudyFormatError", "FORCE_LAWS", "__version__"]

#: Bad input (scene, override, argument): the message names the path, the value and the rule.
SceneError = InputError

#: The force laws a scene or ``force`` can name.
FORCE_LAWS = tuple(n.strip() for n in _lubjoint.force_law_names().split(","))

__version__ = _lubjoint.version()
__revision__ = _lubjoint.revision()


def _assignment(pointer, value):
    """``--set POINTER=VALUE`` for one override: the Python value as JSON (a str stays a str)."""
    if not isinstance(pointer, str):
        raise InputError(f"overrides: key {pointer!r} must be a JSON Pointer string, e.g. '/joints/3/viscosity_Pa_s'")
    if isinstance(value, np.generic):
        value = value.item()
    return f"{pointer}={json.dumps(value)}"


def simulate(scene, overrides=None, output=None):
    """Run one scene, as ``lubsim`` does, and return it as an ``xarray.Dataset``.

    Parameters
    ----------
    scene : dict or str or os.PathLike
        The scene: a dict (the JSON object of README "Scene format") or the path of a scene
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
          int64, units ``1``); a name already taken by a channel gets the prefix ``metric_`` or
          ``solver_``;
        - the per-cycle extremes (the run file's /cycles) as ``cycle_<name>`` over the
          dimension ``cycle`` (1, 2, ...);
        - ``attrs``: ``status`` (``ok``, ``film_collapse``, ``solver_failure``,
          ``budget_exceeded``), ``message``, ``scene`` (the effective scene JSON),
          ``program``, ``version``, ``revision``, ``solver_method``,
          ``solver_formulation``, ``solver_jacobian``, ``solver_rtol``, ``solver_atol``
          (the absolute tolerance of lengths [m]; README "Integration") and ``output`` (the run file, if written).

    Raises
    ------
    InputError
        (a ``ValueError``) for a bad scene, override or output path (lubsim's rules: a
        file in an existing, writable directory), with lubsim's message
        (``SCENE: joints[3].viscosity_Pa_s = -0.4: must be > 0 Pa s``). Nothing is run or
        written then.

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

    r = _lubjoint.simulate(scene_path, scene_text, origin, assignments, out_path)

    def attrs_of(unit, long_name, **more):
        a = {"units": unit} if unit else {}
        if long_name:
            a["long_name"] = long_name
        return {**a, **more}

    coords, data_vars = {}, {}
    series = r["series"]
    if series:
        name, unit, long_name, t = series[0]  # "t" first
        coords["t"] = ("t", t, attrs_of(unit, long_name or "time"))
        for name, unit, long_name, values in series[1:]:
            data_vars[name] = ("t", values, attrs_of(unit, long_name))
    orbit = r["orbit"]
    if orbit:  # the periodic orbit found by shooting (run file /orbit), on its own time axis
        name, unit, long_name, t = orbit[0]
        coords["orbit_t"] = ("orbit_t", t, attrs_of(unit, "time on the periodic orbit"))
        for name, unit, long_name, values in orbit[1:]:
            data_vars["orbit_" + name] = ("orbit_t", values, attrs_of(unit, f"{name} on the periodic orbit"))
    cycles = r["cycles"]
    n_cycles = len(cycles[0][3]) if cycles else 0
    coords["cycle"] = ("cycle", np.arange(1, n_cycles + 1, dtype=np.int64),
                       {"units": "1", "long_name": "crank cycle number (1: the first)"})
    for name, unit, long_name, values in cycles:
        data_vars["cycle_" + name] = ("cycle", values, attrs_of(unit, long_name))
    for kind, fields in (("metric", r["metrics"]), ("solver", r["solver"])):
        for name, value, unit, integer, long_name in fields:
            key = name if name not in data_vars and name not in coords else f"{kind}_{name}"
            data_vars[key] = ((), np.int64(value) if integer else np.float64(value),
                              attrs_of(unit, long_name, kind=kind))
    # Every Floquet multiplier of the steady cycle (shooting), largest first.
    data_vars["multiplier_modulus"] = ("multiplier", r["multiplier_modulus"],
                                       {"units": "1", "long_name": "Floquet multipliers' moduli, largest first"})
    data_vars["multiplier_angle_rad"] = ("multiplier", r["multiplier_angle_rad"],
                                         {"units": "rad", "long_name": "Floquet multipliers' angles"})
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
    }
    if out_path is not None:
        attrs["output"] = out_path
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


class FilmForce(NamedTuple):
    """Film force on the journal [N], arrays of the broadcast shape of the inputs.

    ``radial_N`` along the eccentricity e (outward; < 0 pushes the journal towards the
    centre), ``tangential_N`` along e rotated +90 deg (same sign as the wedge speed).
    """

    radial_N: np.ndarray
    tangential_N: np.ndarray


def force(law, eps, eps_dot, wedge_rad_s, *, radius_m, clearance_m, length_m, viscosity_Pa_s,
          cavitation=None, n_theta=None, n_z=None, groove_at_max_film=False):
    """Film force of a journal bearing, vectorised: the computation of ``lubbearing force``.

    Parameters
    ----------
    law : str
        A force law (``FORCE_LAWS``): ``pinkus_sternlicht``, ``frene_long``,
        ``frene_short``, ``gumbel_long``, ``gumbel_short``,
        ``pinkus_sternlicht_continuous``, ``finite_reynolds``.
    eps : array_like
        Eccentricity ratio ε = |e|/c, dimensionless, 0 <= ε < 1.
    eps_dot : array_like
        Its rate ε̇ [1/s], > 0 when the journal moves towards the wall.
    wedge_rad_s : array_like
        Wedge speed w = ω_J + ω_B − 2γ̇ [rad/s] (lubbearing: ``--omega − 2 --gamma-dot``).
        ``eps``, ``eps_dot`` and ``wedge_rad_s`` are broadcast together (NumPy rules).
    radius_m : float
        Journal radius R_J [m] > 0 (the bearing radius is R_J + c, as in lubbearing).
    clearance_m : float
        Radial clearance c [m] > 0.
    length_m : float
        Bearing length L [m] > 0.
    viscosity_Pa_s : float
        Dynamic viscosity μ [Pa s] > 0.
    cavitation, n_theta, n_z, groove_at_max_film
        ``finite_reynolds`` only: cavitation condition (``gumbel``, ``reynolds``
        (default), ``sommerfeld``), cells around the circumference (default 48), axial
        nodes over half the length (default 8), ambient pressure along the line of maximum
        film thickness.

    Returns
    -------
    FilmForce
        ``(radial_N, tangential_N)``, float64 arrays of the broadcast shape (0-d for scalar
        inputs) [N]; the force on the journal (the bearing feels the opposite).

    Raises
    ------
    InputError
        (a ``ValueError``) naming the argument, its value and the rule; for ε, ε̇ and w the
        index is into the broadcast arrays, flattened (C order).

    The GIL is released while the law is evaluated.
    """
    e, ed, w = np.broadcast_arrays(*(np.asarray(x, dtype=np.float64) for x in (eps, eps_dot, wedge_rad_s)))
    shape = e.shape
    fr, ft = _lubjoint.force(law, e.ravel(), ed.ravel(), w.ravel(), float(radius_m), float(clearance_m),
                             float(length_m), float(viscosity_Pa_s), cavitation, n_theta, n_z,
                             bool(groove_at_max_film))
    return FilmForce(fr.reshape(shape), ft.reshape(shape))


def steady_bearing(law, *, load_N, speed_rpm, radius_m, clearance_m, length_m, viscosity_Pa_s,
                   cavitation=None, n_theta=None, n_z=None, groove_at_max_film=False):
    """Equilibrium of a steadily loaded journal bearing: the computation of ``lubbearing steady``.

    A journal turning at ``speed_rpm`` [rev/min] (≠ 0; bearing at rest) under a constant
    load ``load_N`` [N] > 0; the geometry and ``law`` as in ``force`` (R_J = ``radius_m``,
    R_B = R_J + ``clearance_m``, L = ``length_m``, μ = ``viscosity_Pa_s``).

    Returns
    -------
    dict
        The keys of lubbearing's JSON: ``model``, the inputs, ``sommerfeld_number``
        (S = (R_J/c)² μ N/P, N [rev/s], P = W/(L D)), ``converged``; if converged ``eps``,
        ``attitude_angle_deg`` [deg] (load line to line of centres),
        ``min_film_thickness_m`` [m], ``radial_N``, ``tangential_N`` [N] (|F| = W),
        ``force_law_evaluations``; if not, ``message`` (lubbearing's exit status 3).

    Raises
    ------
    InputError
        (a ``ValueError``) naming the argument, its value and the rule.
    """
    return _lubjoint.steady_bearing(law, float(load_N), float(speed_rpm), float(radius_m), float(clearance_m),
                                    float(length_m), float(viscosity_Pa_s), cavitation, n_theta, n_z,
                                    bool(groove_at_max_film))


# ---------------------------------------------------------------------------------------
# Study files (lubsweep)

#: Study-file formats written before the xarray layout (issue 15): /cases is one compound
#: table and /grids/<name> holds case ids, which xarray cannot open as labelled variables.
OLD_STUDY_FORMATS = ("lubsweep-study-1",)


class StudyFormatError(ValueError):
    """A study file whose layout ``load_study`` cannot read (e.g. written before issue 15)."""


def study_format(path):
    """The ``format`` root attribute of a study file (``lubsweep-study-N``), or None."""
    import h5py

    with h5py.File(path, "r") as f:
        fmt = f.attrs.get("format")
    if isinstance(fmt, bytes):
        fmt = fmt.decode()
    return None if fmt is None else str(fmt)


class Study(Mapping):
    """A lubsweep study: ``{grid name: xarray.Dataset}``, plus ``cases`` and ``attrs``.

    Each grid is the netCDF-4 group ``/grids/<name>``: labelled N-d variables over its
    axes (dimension scales with ``units``). ``cases`` is the ``/cases`` group: one 1-D
    variable per column over the dimension ``case`` (``cases.to_dataframe()`` gives the
    pandas table). ``attrs`` are the file's root attributes (``format``, ``grid``,
    ``complete``, ...).
    """

    def __init__(self, path, grids, cases, attrs):
        self.path = path
        self.grids = grids
        self.cases = cases
        self.attrs = attrs

    def __getitem__(self, name):
        return self.grids[name]

    def __iter__(self):
        return iter(self.grids)

    def __len__(self):
        return len(self.grids)

    def __repr__(self):
        return f"Study({self.path!r}, grids={list(self.grids)}, cases={self.cases.sizes.get('case', 0)})"


def load_study(path):
    """Open a lubsweep study file as xarray objects.

    Returns a ``Study``: a mapping ``{grid name: xarray.Dataset}``, each
    ``xr.open_dataset(path, group="grids/<name>", engine="h5netcdf")``, plus
    ``.cases`` = ``xr.open_dataset(path, group="cases", engine="h5netcdf")`` (columns over
    the dimension ``case``) and ``.attrs`` (root attributes). The data are loaded into
    memory and the file closed.

    Raises
    ------
    StudyFormatError
        (a ``ValueError``) for a file in a format before the xarray layout
        (``OLD_STUDY_FORMATS``: re-run lubsweep with a build that writes the new one), or a
        file that is not a study.
    """
    import h5py
    import xarray as xr

    path = os.fspath(path)
    with h5py.File(path, "r") as f:
        attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
        fmt = attrs.get("format")
        if attrs.get("program") != "lubsweep" or fmt is None:
            raise StudyFormatError(f"{path}: not a lubsweep study file (no program = lubsweep and format attributes)")
        if fmt in OLD_STUDY_FORMATS:
            raise StudyFormatError(
                f"{path}: study format {fmt} predates the xarray layout (/grids/<name> as labelled "
                f"variables, /cases as columns; issue 15): re-run lubsweep with a build that writes it, "
                f"or read it with tools/study_io.py")
        names = sorted(f["grids"].keys()) if "grids" in f else []

    def open_group(group):
        with xr.open_dataset(path, group=group, engine="h5netcdf") as ds:
            return ds.load()

    grids = {name: open_group(f"grids/{name}") for name in names}
    cases = open_group("cases")
    return Study(path, grids, cases, attrs)
