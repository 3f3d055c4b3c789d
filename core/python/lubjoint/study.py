"""lubjoint.study: the one reader of lubsweep study files, for the module, ``tools/`` and the tests.

Pure Python (h5py, xarray with h5netcdf, pandas; ``scene`` needs jsonpatch): it does not load
the compiled extension, so ``import lubjoint.study`` works in a build without it (see the
package docstring). The study file is netCDF-4 style (docs/reference/study-file.md); this module
adds the format check and the look-ups the tools share:

    from lubjoint import study
    s = study.load_study("out/study.h5")          # {grid name: Dataset}, .cases, .attrs
    study.check("out/study.h5")                   # root attributes, or StudyFormatError
    cases = study.cases("out/study.h5")           # pandas DataFrame, index: case id
    ds = study.grid("out/study.h5", "clearance")  # xarray Dataset over the sub-grid's axes
    s = study.series("out/study.h5", "case_0003") # xarray Dataset indexed by t, or None
    sc = study.scene("out/study.h5", 3)           # case 3's effective scene (dict)
    e = study.bifurcation_edges(cases)            # grid edges where the orbit changes (lubjoint.bifurcations)

The formats read are ``ACCEPTED_FORMATS`` (one: ``STUDY_FORMAT``, what this build's lubsweep
writes); any other is refused with one message that says what to do (re-run the sweep with
``--restart``).

Missing values (docs/reference/run-file.md): a float that is unknown is NaN (``_FillValue`` =
NaN); an integer column of ``/cases`` (counts, flags) holds -1 and says so in its
``missing_value`` attribute, so xarray and pandas (``cases``) show NaN there too.
"""

import json
import os
from collections.abc import Mapping

# Re-exported: the study's look-ups in one place.
from .bifurcations import KINDS as BIFURCATION_LETTERS, bifurcation_edges  # noqa: F401

#: The study-file format lubsweep writes (kStudyFormat, sweep/include/lub/sweep/study_file.hpp).
#: 5: NaN for every unknown float (4 wrote -1 for an unknown periodicity).
STUDY_FORMAT = "lubsweep-study-5"
#: The one list of formats this reader accepts (every reader of study files goes through ``check``).
ACCEPTED_FORMATS = (STUDY_FORMAT,)
#: What to do with a file of another format, in every refusal.
OLD_FORMAT_ADVICE = "re-run the sweep with --restart to rewrite it"


class StudyFormatError(ValueError):
    """A file that is not a lubsweep study of ``ACCEPTED_FORMATS`` (not HDF5, not lubsweep's, another format)."""


def _text(value):
    return value.decode() if isinstance(value, bytes) else value


def _open(path, group=None):
    import xarray as xr

    return xr.open_dataset(path, group=group, engine="h5netcdf")


def study_format(path):
    """The ``format`` root attribute of a study file (``lubsweep-study-N``), or None."""
    import h5py

    with h5py.File(path, "r") as f:
        fmt = f.attrs.get("format")
    fmt = _text(fmt)
    return None if fmt is None else str(fmt)


def check(path):
    """Root attributes of a study file of ``STUDY_FORMAT``; ``StudyFormatError`` with the reason otherwise."""
    import h5py

    try:
        with h5py.File(path, "r") as f:
            attrs = {k: _text(v) for k, v in f.attrs.items()}
    except OSError as e:
        raise StudyFormatError(f"{path}: not an HDF5 file ({e})") from None
    if attrs.get("program") != "lubsweep":
        raise StudyFormatError(f"{path}: not a lubsweep study file")
    if attrs.get("format") not in ACCEPTED_FORMATS:
        raise StudyFormatError(f"{path}: a study file of format {attrs.get('format')}; lubjoint.study reads "
                               f"{', '.join(ACCEPTED_FORMATS)} ({OLD_FORMAT_ADVICE})")
    return attrs


def check_or_exit(path):
    """``check`` for command-line tools: a ``StudyFormatError`` becomes ``SystemExit`` with its message (exit 1)."""
    try:
        return check(path)
    except StudyFormatError as e:
        raise SystemExit(str(e)) from None


def cases(path):
    """/cases as a pandas DataFrame indexed by case id (its ``attrs``: the group's attributes, plus ``units``)."""
    ds = _open(path, "cases")
    df = ds.to_dataframe()
    df.attrs = dict(ds.attrs, units={k: ds[k].attrs.get("units", "") for k in ds.variables})
    return df


def grid_names(path):
    """The names of the study's sub-grids (/grids/<name>), in the file's order."""
    import h5py

    with h5py.File(path, "r") as f:
        return list(f.get("grids", {}).keys())


def grid(path, name):
    """The sub-grid ``name``: an xarray Dataset over its axes (the file stays open: lazy)."""
    return _open(path, f"grids/{name}")


def series(path, case_name):
    """The stored channels of a case (xarray Dataset on t), or None."""
    import h5py

    with h5py.File(path, "r") as f:
        if f"series/{case_name}" not in f:
            return None
    return _open(path, f"series/{case_name}")


def scene(path, case_id):
    """The effective scene of a case (a dict): its JSON Patch applied to reference_scene."""
    import h5py
    import jsonpatch  # Debian: python3-jsonpatch

    with h5py.File(path, "r") as f:
        reference = f.attrs["reference_scene"]
        ids = list(f["scene"][:])
        patch = f["scene_patches"][ids.index(int(case_id))]
    return jsonpatch.apply_patch(json.loads(_text(reference)), json.loads(_text(patch)))


def orbit_seed(path, case_id):
    """The periodic orbit a case found (``simulation.steady`` continuation or shooting in a
    study), decoded from /cases ``orbit_seed`` (layout ``lub::pack_seed``), or None.

    A dict: ``deviation`` (the state (q, v) at crank angle 0 minus the scene's initial
    state, each coordinate in its own unit: dimensionless), ``modes`` (film modes),
    ``chart`` (the independent coordinates, indices of q), ``monodromy`` (2 m x 2 m numpy array
    over the m independent coordinates and their velocities, in the same units; empty: none), ``winding`` [rad per period], ``max_eps`` [1] and
    ``steps_per_period`` [1]. See docs/theory/continuation.md.
    """
    import numpy as np

    df = cases(path)
    if "orbit_seed" not in df.columns:
        return None
    text = _text(df.loc[int(case_id), "orbit_seed"])
    if not text:
        return None
    row = json.loads(text)
    if int(row[0]) != 1:
        raise StudyFormatError(f"{path}: case {case_id}: an orbit seed of layout {row[0]}; this reader knows 1")
    sizes = [int(x) for x in row[1:6]]
    at, fields = 6, []
    for n in sizes:
        fields.append(row[at:at + n])
        at += n
    n = 2 * len(fields[2])  # the chart's coordinates and their velocities
    return {
        "deviation": np.array(fields[0]),
        "modes": [int(x) for x in fields[1]],
        "chart": [int(x) for x in fields[2]],
        "monodromy": np.array(fields[3]).reshape((n, n), order="F") if fields[3] else np.zeros((0, 0)),
        "winding": np.array(fields[4]),
        "max_eps": row[at],
        "steps_per_period": row[at + 1],
    }


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
        (a ``ValueError``) for a file that is not HDF5, not a lubsweep study, or of a format
        not in ``ACCEPTED_FORMATS`` (the message says: re-run the sweep with ``--restart``).
    """
    path = os.fspath(path)
    attrs = check(path)
    names = sorted(grid_names(path))

    def load(group):
        with _open(path, group) as ds:
            return ds.load()

    grids = {name: load(f"grids/{name}") for name in names}
    return Study(path, grids, load("cases"), attrs)
