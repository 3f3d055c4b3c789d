"""Reading a lubsweep study file (HDF5) from Python: the helpers the plotting and
comparison tools share. Needs h5py and numpy (Debian: /usr/bin/python3).

    import study_io
    s = study_io.Study("out/study.h5")
    s.cases            # numpy structured array of /cases (strings decoded)
    s.axes             # axis column names, e.g. ['clearance_m', 'viscosity_Pa_s', ...]
    s.grid("clearance")    # {'case_id': N-D ids, 'axes': [(name, values), ...]}
    s.series("case_0003")  # {'t': array, 'h_min': array, ...} or None
    s.on_grid("clearance", "max_eps")  # the metric reshaped onto the sub-grid's axes
"""
import json

import h5py
import numpy as np


def _decode(a):
    """bytes columns of a structured array -> str."""
    if a.dtype.names is None:
        return a
    out = {}
    for name in a.dtype.names:
        col = a[name]
        if col.dtype.kind == "O":
            col = np.array([x.decode() if isinstance(x, bytes) else x for x in col], dtype=object)
        out[name] = col
    return out


class Study:
    def __init__(self, path):
        self.path = path
        with h5py.File(path, "r") as f:
            if f.attrs.get("program") != "lubsweep" or "cases" not in f:
                raise SystemExit(f"{path}: not a lubsweep study file")
            self.attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
            t = f["cases"]
            self.columns = list(t.dtype.names)
            self.units = dict(zip([c.decode() if isinstance(c, bytes) else c for c in t.attrs["columns"]],
                                  [u.decode() if isinstance(u, bytes) else u for u in t.attrs["units"]]))
            self.axes = [a.decode() if isinstance(a, bytes) else a for a in t.attrs.get("axes", [])]
            self.metrics = [a.decode() if isinstance(a, bytes) else a for a in t.attrs.get("metrics", [])]
            self.solver = [a.decode() if isinstance(a, bytes) else a for a in t.attrs.get("solver", [])]
            self.cases = _decode(t[:])
            self.n = len(t)
            self.grids = {}
            for name, g in f.get("grids", {}).items():
                ids = g["case_id"][()]
                axes = []
                for a in g.attrs.get("axes", []):
                    a = a.decode() if isinstance(a, bytes) else a
                    d = g[a]
                    vals = d.asstr()[()] if d.dtype.kind == "O" else d[()]
                    axes.append((a, vals))
                self.grids[name] = {"case_id": ids, "axes": axes,
                                    "kind": g.attrs.get("kind", "factorial")}
            self._row = {int(c): i for i, c in enumerate(self.cases["case_id"])}

    def row(self, case_id):
        """Row index of a case id (equal to it in a finished file)."""
        return self._row.get(int(case_id))

    def value(self, column, case_id):
        r = self.row(case_id)
        return None if r is None else self.cases[column][r]

    def series(self, case_name):
        with h5py.File(self.path, "r") as f:
            g = f.get(f"series/{case_name}")
            if g is None:
                return None
            return {k: g[k][()] for k in g.keys()}

    def scene(self, case_id):
        with h5py.File(self.path, "r") as f:
            return json.loads(f["scenes"].asstr()[int(case_id)])

    def on_grid(self, grid, column):
        """`column` of /cases reshaped onto a sub-grid (NaN where a case has no row)."""
        g = self.grids[grid]
        ids = np.asarray(g["case_id"])
        col = self.cases[column]
        out = np.full(ids.shape, np.nan, dtype=float) if col.dtype.kind != "O" else np.empty(ids.shape, dtype=object)
        for idx, cid in np.ndenumerate(ids):
            r = self.row(cid)
            if r is not None:
                out[idx] = col[r]
        return out
