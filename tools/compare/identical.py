"""compare.py identical: are two HDF5 files (run or study files) identical, wall-clock values aside?

    /usr/bin/python3 tools/compare.py identical A.h5 B.h5 [--ignore NAME ...]

Walks both files: every group, dataset (shape, dtype, bytes) and attribute must match,
bit for bit (object references by the names they point to). Ignored by default: what a
clock or the build stamps, and which MPI rank ran a case (rank, wall_time_s, revision:
DEFAULT_IGNORE); --ignore adds names. Shows that a refactor changed no number, steps and
counters included. Exit 0: identical; 1: the first differences listed; 2: bad input.
"""
import sys

import h5py
import numpy as np

DEFAULT_IGNORE = {"rank", "wall_time_s", "wall_s", "case_wall_time_s", "revision", "created", "created_utc",
                  "host", "hostname", "total_wall_time_s", "elapsed_s"}


def resolve(v, f):
    """Object references (dimension scales' DIMENSION_LIST, REFERENCE_LIST) as the names they point to."""
    if isinstance(v, h5py.Reference):
        return f[v].name if v else None
    if isinstance(v, np.void) and v.dtype.names:
        return tuple(resolve(v[n], f) for n in v.dtype.names)
    if isinstance(v, np.ndarray) and v.dtype.kind in "OV":
        return [resolve(x, f) for x in v]
    return v


def same_value(a, b, fa=None, fb=None):
    if fa is not None and (np.asarray(a).dtype.kind in "OV"):
        return resolve(np.asarray(a), fa) == resolve(np.asarray(b), fb)
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind == "f":
        # Bit for bit: −0.0 differs from 0.0; a NaN equals the same NaN.
        return bool(np.array_equal(a.reshape(-1).view(np.uint8), b.reshape(-1).view(np.uint8)))
    if a.dtype.kind in "SUO":
        return a.tolist() == b.tolist()
    return bool(np.array_equal(a, b))


def compare(a, b, ignore, path, diffs):
    for k in sorted(set(a.attrs) | set(b.attrs)):
        if k in ignore:
            continue
        if k not in a.attrs or k not in b.attrs:
            diffs.append(f"{path}@{k}: only in {'B' if k not in a.attrs else 'A'}")
        elif not same_value(a.attrs[k], b.attrs[k], a.file, b.file):
            diffs.append(f"{path}@{k}: {str(a.attrs[k])[:200]} != {str(b.attrs[k])[:200]}")
    if isinstance(a, h5py.Dataset) or isinstance(b, h5py.Dataset):
        if not (isinstance(a, h5py.Dataset) and isinstance(b, h5py.Dataset)):
            diffs.append(f"{path}: a dataset in one file only")
        elif a.name.rsplit("/", 1)[-1] not in ignore:
            x, y = a[()], b[()]
            if a.dtype.names:  # compound: field by field, ignored fields skipped
                for f in a.dtype.names:
                    if f in ignore:
                        continue
                    if b.dtype.names is None or f not in b.dtype.names or not same_value(x[f], y[f]):
                        diffs.append(f"{path}.{f}: differs")
            elif not same_value(x, y):
                diffs.append(f"{path}: differs (shape {np.shape(x)} / {np.shape(y)})")
        return
    for k in sorted(set(a) | set(b)):
        if k in ignore:
            continue
        if k not in a or k not in b:
            diffs.append(f"{path}/{k}: only in {'B' if k not in a else 'A'}")
            continue
        compare(a[k], b[k], ignore, f"{path}/{k}" if path != "/" else f"/{k}", diffs)


def add_arguments(ap):
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--ignore", action="append", default=[], help="a group, dataset, attribute or field name")


def run(args):
    diffs = []
    try:
        with h5py.File(args.a, "r") as fa, h5py.File(args.b, "r") as fb:
            compare(fa, fb, DEFAULT_IGNORE | set(args.ignore), "/", diffs)
    except OSError as e:
        print(f"compare identical: {e}", file=sys.stderr)
        return 2
    for d in diffs[:40]:
        print(d)
    if len(diffs) > 40:
        print(f"... and {len(diffs) - 40} more")
    print("identical" if not diffs else f"{len(diffs)} differences")
    return 0 if not diffs else 1
