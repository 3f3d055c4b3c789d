"""lubjoint: planar multibody systems with lubricated revolute joints, from Python.

The engine is the C++ library lubcore (the one behind ``lubsim``, ``lubbearing`` and
``lubsweep``), reached through the compiled extension ``lubjoint._lubjoint``; this package
only turns its results into labelled arrays (xarray, NumPy). SI units throughout: every
argument with a unit names it (``radius_m``, ``viscosity_Pa_s``), every array carries a
``units`` attribute.

- ``simulate(scene, overrides=None, output=None)`` -> ``xarray.Dataset``: one run, as lubsim.
- ``force(law, eps, eps_dot, wedge_rad_s, *, radius_m, clearance_m, length_m, viscosity_Pa_s)``
  -> ``FilmForce(radial_N, tangential_N)``: a force law over NumPy arrays (broadcasting).
- ``steady_bearing(law, *, load_N, speed_rpm, radius_m, clearance_m, length_m, viscosity_Pa_s)``
  -> dict: the steadily loaded bearing, as ``lubbearing steady``.
- ``load_study(path)`` -> ``Study``: a lubsweep study file as {grid name: Dataset} plus ``cases``;
  ``Study.series(case)``: a case's recorded channels.
- ``plot.orbit``, ``plot.film``, ``plot.classification_map``, ``plot.envelope``: figures of a run
  or a study, each a ``matplotlib.figure.Figure``.

Bad input raises ``InputError`` (a ``ValueError``; alias ``SceneError``) with the message
the command line prints: the JSON path, the value and the rule. A run that cannot be
completed (film collapse, solver failure, budget) is a result, not an exception: see
``ds.attrs["status"]`` and ``ds.attrs["message"]``; the steady cycle's classification
(docs/theory/steady-cycles.md) in ``ds.attrs["classification"]``.

By concern: ``lubjoint.run`` (``simulate``), ``lubjoint.bearing`` (``force``,
``steady_bearing``, ``FORCE_LAWS``), ``lubjoint.study`` (``load_study`` and the look-ups
the tools share: the one reader of study files), ``lubjoint.plot`` (figures; imported on
first use, so that ``import lubjoint`` needs no matplotlib). This package face re-exports them.

``lubjoint.study`` is pure Python: the compiled extension is imported only when a name that
needs it is first used (``simulate``, ``force``, ``InputError``, ``__version__``, ...), so
``from lubjoint import study`` works in a build without the extension (``LUB_BUILD_PYTHON=OFF``
still copies the Python files into build/python).

Build and import (docs/guide/python.md):
``PYTHONPATH=build/python /usr/bin/python3 -c "import lubjoint"``.
"""

import importlib
import sys

from .study import Study, StudyFormatError, load_study, study_format

__all__ = ["simulate", "force", "pressure", "steady_bearing", "load_study", "study_format", "FilmForce", "Study",
           "InputError", "SceneError", "PlausibilityWarning", "ValidityNote", "StudyFormatError", "FORCE_LAWS",
           "plot", "__version__"]

# The names that need the compiled extension, and the submodule each comes from: imported
# on first use (PEP 562), so that lubjoint.study does not need the extension.
_FROM_SUBMODULE = {
    "simulate": "run", "InputError": "run", "SceneError": "run", "PlausibilityWarning": "run",
    "ValidityNote": "run",
    "force": "bearing", "pressure": "bearing", "steady_bearing": "bearing", "FilmForce": "bearing", "FORCE_LAWS": "bearing",
}


def __getattr__(name):
    """A name that needs the compiled extension, or the submodule ``plot`` (matplotlib), imported
    on first use (PEP 562)."""
    if name == "plot":
        return importlib.import_module(f"{__name__}.plot")
    if name not in _FROM_SUBMODULE and name not in ("__version__", "__revision__"):
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    try:
        if name in _FROM_SUBMODULE:
            value = getattr(importlib.import_module(f"{__name__}.{_FROM_SUBMODULE[name]}"), name)
        else:
            from . import _lubjoint

            value = _lubjoint.version() if name == "__version__" else _lubjoint.revision()
    except ImportError as e:
        raise ImportError(_wrong_python(e)) from e
    globals()[name] = value
    return value


def _wrong_python(error):
    """The message when the compiled extension or NumPy cannot be imported: the Python
    lubjoint was built for (written by the build into _built_for.py) against this one."""
    try:
        from ._built_for import PYTHON, VERSION
    except ImportError:
        PYTHON, VERSION = "/usr/bin/python3", "?"
    this = f"{sys.executable} (Python {sys.version_info[0]}.{sys.version_info[1]})"
    return (f"lubjoint: {error}. lubjoint's compiled part was built for {PYTHON} (Python {VERSION}), "
            f"with Debian's python3-numpy and python3-xarray; this is {this}. "
            f"Run it with {PYTHON}, e.g. PYTHONPATH=<dir of lubjoint> {PYTHON} ...")


def __dir__():
    """The module's names, the lazily imported ones included (for dir() and help())."""
    return sorted(set(globals()) | set(__all__) | {"__revision__"})
