"""Opening a lubsweep study file from Python: the file is netCDF-4 style (README, "The
study file"), so xarray and pandas read it directly; this module only adds the format
check and the few look-ups the tools share. Debian: /usr/bin/python3 with python3-xarray,
python3-h5netcdf, python3-pandas.

    import study_io
    study_io.check("out/study.h5")                     # a lubsweep study of this format, or SystemExit
    cases = study_io.cases("out/study.h5")              # pandas DataFrame, index: case id
    ds = study_io.grid("out/study.h5", "clearance")     # xarray Dataset over the sub-grid's axes
    s = study_io.series("out/study.h5", "case_0003")    # xarray Dataset indexed by t, or None
    sc = study_io.scene("out/study.h5", 3)              # case 3's effective scene (dict)
"""
import json

import h5py
import xarray as xr

FORMAT = "lubsweep-study-4"


def _open(path, group=None):
    return xr.open_dataset(path, group=group, engine="h5netcdf")


def check(path):
    """Root attributes of a study file of this format; SystemExit with the reason otherwise."""
    try:
        with h5py.File(path, "r") as f:
            attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
    except OSError as e:
        raise SystemExit(f"{path}: not an HDF5 file ({e})")
    if attrs.get("program") != "lubsweep":
        raise SystemExit(f"{path}: not a lubsweep study file")
    if attrs.get("format") != FORMAT:
        raise SystemExit(f"{path}: a study file of format {attrs.get('format')}; these tools read {FORMAT} "
                         "(re-run the sweep with --restart to rewrite it)")
    return attrs


def cases(path):
    """/cases as a pandas DataFrame indexed by case id (its `attrs`: the group's attributes)."""
    ds = _open(path, "cases")
    df = ds.to_dataframe()
    df.attrs = dict(ds.attrs, units={k: ds[k].attrs.get("units", "") for k in ds.variables})
    return df


def grid_names(path):
    with h5py.File(path, "r") as f:
        return list(f.get("grids", {}).keys())


def grid(path, name):
    return _open(path, f"grids/{name}")


def series(path, case_name):
    """The stored channels of a case (xarray Dataset on t), or None."""
    with h5py.File(path, "r") as f:
        if f"series/{case_name}" not in f:
            return None
    return _open(path, f"series/{case_name}")


def scene(path, case_id):
    """The effective scene of a case (a dict): its JSON Patch applied to reference_scene."""
    import jsonpatch  # Debian: python3-jsonpatch

    with h5py.File(path, "r") as f:
        reference = f.attrs["reference_scene"]
        ids = list(f["scene"][:])
        patch = f["scene_patches"][ids.index(int(case_id))]
    as_text = lambda b: b.decode() if isinstance(b, bytes) else b
    return jsonpatch.apply_patch(json.loads(as_text(reference)), json.loads(as_text(patch)))
