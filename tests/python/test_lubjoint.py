"""Tests of the Python module lubjoint (core/python), run by ctest (label python):

    PYTHONPATH=build/python /usr/bin/python3 -m pytest tests/python

Cross-checks against the programs of the same build (lubsim, lubbearing, lubsweep): their
paths come from LUB_BUILD_DIR (set by ctest; default: build/ next to the sources).
"""

import json
import math
import os
import subprocess
import sys
import threading
import warnings
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import h5py
import numpy as np
import pytest
import xarray as xr

import lubjoint

SOURCE = Path(os.environ.get("LUB_SOURCE_DIR") or Path(__file__).resolve().parents[2])
BINARY = Path(os.environ.get("LUB_BUILD_DIR", SOURCE / "build"))
LUBSIM = BINARY / "core" / "lubsim"
LUBBEARING = BINARY / "core" / "lubbearing"
LUBSWEEP = BINARY / "sweep" / "lubsweep"
SCENE = SOURCE / "configs" / "scenes" / "slider_crank.json"

# The paper's bearing (configs/scenes/slider_crank.json, joint rod_slider).
BEARING = dict(radius_m=0.0095, clearance_m=0.0005, length_m=0.040, viscosity_Pa_s=0.400)
# A short scene for the tests that run several simulations: two crank cycles.
SHORT = {"/simulation/max_cycles": 2, "/simulation/metric_cycles": 1}


def run(cmd, **kw):
    return subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)


# --- force laws ----------------------------------------------------------------------------


def lubbearing_force(law, eps, eps_dot, wedge):
    # --gamma-dot 0: lubbearing's wedge speed --omega − 2 --gamma-dot is then --omega exactly.
    p = run([LUBBEARING, "force", "--model", law, "--eps", repr(eps), "--eps-dot", repr(eps_dot),
             "--omega", repr(wedge), "--gamma-dot", "0", "--radius-m", repr(BEARING["radius_m"]),
             "--clearance-m", repr(BEARING["clearance_m"]), "--length-m", repr(BEARING["length_m"]),
             "--viscosity-Pa-s", repr(BEARING["viscosity_Pa_s"])])
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


STATES = [(0.0, 0.0, 0.0), (0.0, 3.0, 500.0), (0.3, -10.0, 0.0), (0.5, 2.5, 523.6), (0.9, 0.0, -300.0),
          (0.999, 1e-3, 1e3)]


@pytest.mark.parametrize("law", lubjoint.FORCE_LAWS)
def test_force_equals_lubbearing(law):
    # Same functions (film_force), same geometry construction (R_B = R_J + c), and
    # lubbearing prints doubles with round-trip precision: equal to the last bit.
    states = STATES if law != "finite_reynolds" else STATES[:4]
    eps, eps_dot, wedge = (np.array(x) for x in zip(*states))
    f = lubjoint.force(law, eps, eps_dot, wedge, **BEARING)
    for i, (e, ed, w) in enumerate(states):
        ref = lubbearing_force(law, e, ed, w)
        assert f.radial_N[i] == ref["radial_N"], (law, states[i])
        assert f.tangential_N[i] == ref["tangential_N"], (law, states[i])


@pytest.mark.parametrize("law", ["frene_long", "frene_short"])
def test_force_closed_form(law):
    eps = np.linspace(0.0, 0.99, 34)[:, None]
    eps_dot = np.array([-50.0, -1.0, 0.0, 0.7, 20.0])[None, :]
    w = 523.6 - 2.0 * eps_dot  # any wedge speed, one per column
    f = lubjoint.force(law, eps, eps_dot, w, **BEARING)
    mu, L, R = BEARING["viscosity_Pa_s"], BEARING["length_m"], BEARING["radius_m"]
    c = (R + BEARING["clearance_m"]) - R  # the module's clearance: R_B − R_J, as lubbearing's
    s2 = (1.0 - eps) * (1.0 + eps)
    if law == "frene_long":  # paper Eqs. (8)-(9)
        C = mu * L * R**3 / c**2
        fr = -12.0 * math.pi * C * eps_dot / s2**1.5
        ft = 12.0 * math.pi * C * eps * w / ((2.0 + eps**2) * np.sqrt(s2))
    else:  # paper Eqs. (6)-(7)
        C = mu * L**3 * R / c**2
        fr = -math.pi * C * eps_dot * (1.0 + 2.0 * eps**2) / s2**2.5
        ft = math.pi * C * eps * w / (2.0 * s2**1.5)
    # Closed forms: the same formula evaluated in another order, ~10 roundings each, and
    # (1 − ε²)^(5/2) near ε = 0.99 amplifies the relative error of 1 − ε² by 2.5:
    # 1e-13 ≈ 450 ulp leaves a wide margin; atol for the exact zeros (ε = 0 or ε̇ = 0).
    np.testing.assert_allclose(f.radial_N, fr, rtol=1e-13, atol=1e-300)
    np.testing.assert_allclose(f.tangential_N, ft, rtol=1e-13, atol=1e-300)
    assert f.radial_N.shape == (34, 5)


def test_force_broadcasting_shapes():
    eps = np.array([0.1, 0.5, 0.8]).reshape(3, 1)
    eps_dot = np.array([-1.0, 0.0, 1.0, 4.0])
    f = lubjoint.force("pinkus_sternlicht", eps, eps_dot, 100.0, **BEARING)
    assert isinstance(f, lubjoint.FilmForce)
    assert f.radial_N.shape == (3, 4) and f.tangential_N.shape == (3, 4)
    for i in range(3):
        for j in range(4):
            one = lubjoint.force("pinkus_sternlicht", eps[i, 0], eps_dot[j], 100.0, **BEARING)
            assert one.radial_N.shape == ()
            assert one.radial_N == f.radial_N[i, j] and one.tangential_N == f.tangential_N[i, j]
    assert lubjoint.force("frene_long", [], [], [], **BEARING).radial_N.shape == (0,)
    assert lubjoint.force("frene_long", np.zeros((2, 1, 3)), 1.0, np.ones(3), **BEARING).radial_N.shape == (2, 1, 3)
    with pytest.raises(ValueError):  # NumPy: shapes (3,) and (4,) do not broadcast
        lubjoint.force("frene_long", np.zeros(3), np.zeros(4), 0.0, **BEARING)


def test_force_bad_input_names_argument_value_rule():
    with pytest.raises(lubjoint.InputError, match=r"^eps\[2\] = 1\.0: must be in \[0, 1\)"):
        lubjoint.force("frene_long", [0.1, 0.2, 1.0], 0.0, 0.0, **BEARING)
    with pytest.raises(ValueError, match=r"^viscosity_Pa_s = -0\.4: must be > 0 Pa s$"):
        lubjoint.force("frene_long", 0.1, 0.0, 0.0, **{**BEARING, "viscosity_Pa_s": -0.4})
    with pytest.raises(ValueError, match=r"^law = \"nope\": must be one of pinkus_sternlicht, "):
        lubjoint.force("nope", 0.1, 0.0, 0.0, **BEARING)
    with pytest.raises(TypeError):  # the geometry is keyword-only
        lubjoint.force("frene_long", 0.1, 0.0, 0.0, 0.0095, 0.0005, 0.04, 0.4)


def test_steady_bearing_equals_lubbearing():
    for law in ["gumbel_short", "frene_long", "pinkus_sternlicht_continuous"]:
        args = dict(load_N=2000.0, speed_rpm=3000.0, **BEARING)
        r = lubjoint.steady_bearing(law, **args)
        p = run([LUBBEARING, "steady", "--model", law, "--load-N", "2000", "--speed-rpm", "3000",
                 "--radius-m", "0.0095", "--clearance-m", "0.0005", "--length-m", "0.04",
                 "--viscosity-Pa-s", "0.4"])
        assert p.returncode == 0, p.stderr
        assert r == json.loads(p.stdout)  # the same keys and values, to the last bit
        assert r["converged"] and 0.0 < r["eps"] < 1.0
        assert math.hypot(r["radial_N"], r["tangential_N"]) == pytest.approx(2000.0, rel=1e-8)
    with pytest.raises(ValueError, match=r"^speed_rpm = 0\.0: must be != 0 rpm$"):
        lubjoint.steady_bearing("gumbel_short", load_N=1.0, speed_rpm=0.0, **BEARING)


# --- simulation --------------------------------------------------------------------------


def h5_attrs(obj):
    return {k: (v.decode() if isinstance(v, bytes) else v) for k, v in obj.attrs.items()}


def assert_same_dicts(a, b):
    """Equal keys and values; NaN (a value not computed) equals NaN, arrays element-wise."""
    assert a.keys() == b.keys()
    for k in a:
        np.testing.assert_array_equal(a[k], b[k], err_msg=k)


def assert_same_metric(ds, name, value):
    """A run file's /metrics attribute against the module's dataset: strings are dataset
    attributes, the multipliers a variable; NaN (not computed) equals NaN."""
    if name == "missing_value":  # the group's declaration of its integers' sentinel, not a metric
        assert value == lubjoint.run.MISSING_INTEGER
    elif name in ("classification", "steady_method"):
        assert ds.attrs[name] == value, name
    elif name.startswith("multiplier_") and np.ndim(value) == 1:
        np.testing.assert_array_equal(ds[name].values, value, err_msg=name)
    else:
        got = ds[name].item()
        assert got == value or (np.isnan(got) and np.isnan(value)), name


def test_simulate_matches_lubsim(tmp_path):
    ref_file = tmp_path / "lubsim.h5"
    p = run([LUBSIM, SCENE, "-o", ref_file, "--quiet"])
    assert p.returncode == 0, p.stderr
    out = tmp_path / "lubjoint.h5"
    ds = lubjoint.simulate(str(SCENE), output=out)
    assert ds.attrs["status"] == "ok"
    # A fixed-length transient's verdict is the contraction estimate's alone, and says so.
    assert ds.attrs["message"].startswith("periodic by the contraction estimate alone"), ds.attrs["message"]
    with h5py.File(ref_file, "r") as ref, h5py.File(out, "r") as mine:
        # The same scene, the same functions, the same build: a deterministic run gives the
        # same bits, so metrics, counters and series compare with ==; only wall_time_s differs.
        root = h5_attrs(ref)
        assert ds.attrs["scene"] == root["scene"]
        assert ds.attrs["revision"] == root["revision"], "lubsim and the module from different builds"
        for name, value in h5_attrs(ref["metrics"]).items():
            assert_same_metric(ds, name, value)
        for name, value in h5_attrs(ref["solver"]).items():
            if name in ("wall_time_s", "missing_value"):
                continue
            got = ds[name].item() if name in ds else ds.attrs["solver_" + name]
            assert got == value, name
        for name in ref["series"]:
            got = ds[name].values if name != "t" else ds["t"].values
            np.testing.assert_array_equal(got, ref["series"][name][()], err_msg=name)
            assert (ds[name].attrs["units"] if name != "t" else ds["t"].attrs["units"]) == \
                h5_attrs(ref["series"][name])["units"]
        cycles = ref["cycles"]  # a compound table, or (issue 15's layout) a group of columns
        names = cycles.dtype.names if isinstance(cycles, h5py.Dataset) else \
            [k for k in cycles if k not in ("cycle", "row")]
        for name in names:
            np.testing.assert_array_equal(ds["cycle_" + name].values, cycles[name][()], err_msg=name)
        for name in names:  # units and long names as the file's
            assert ds["cycle_" + name].attrs["units"] == h5_attrs(cycles[name])["units"], name
        for name in ref["series"]:
            if name != "t":
                assert ds[name].attrs.get("long_name") == h5_attrs(ref["series"][name]).get("long_name"), name
        # The run file written from Python: the C++ writer, same content but program.
        assert h5_attrs(mine)["program"] == "lubjoint"
        assert_same_dicts(h5_attrs(mine["metrics"]), h5_attrs(ref["metrics"]))
        np.testing.assert_array_equal(mine["series/h_min"][()], ref["series/h_min"][()])
    assert ds["min_film_thickness_m"].attrs["units"] == "m"
    assert ds["eps"].dims == ("t",) and ds["h_min"].attrs["units"] == "m"
    assert ds["slider_a"].attrs["units"] == "m s-2" and ds["h_min"].attrs["long_name"]
    assert ds["steps"].dtype == np.int64 and ds["steps"].attrs["units"] == "1"


def test_simulate_dict_and_overrides_as_set(tmp_path):
    overrides = {"/joints/3/force_law": "frene_long", "/joints/3/viscosity_Pa_s": 0.04, **SHORT}
    ref_file = tmp_path / "ref.h5"
    sets = [a for k, v in overrides.items() for a in ("--set", f"{k}={v}")]
    p = run([LUBSIM, SCENE, "-o", ref_file, "--quiet", *sets])
    assert p.returncode in (0, 3), p.stderr
    scene = json.loads(SCENE.read_text())
    ds = lubjoint.simulate(scene, overrides)
    with h5py.File(ref_file, "r") as ref:
        assert json.loads(ds.attrs["scene"]) == json.loads(h5_attrs(ref)["scene"])
        assert ds.attrs["status"] == h5_attrs(ref)["status"]
        for name, value in h5_attrs(ref["metrics"]).items():
            assert_same_metric(ds, name, value)
    assert "output" not in ds.attrs  # no file without output=
    assert list(tmp_path.iterdir()) == [ref_file]


def test_invalid_scene_raises_lubsim_message(tmp_path):
    scene = json.loads(SCENE.read_text())
    scene["joints"][3]["viscosity_Pa_s"] = -0.4
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(scene))
    out = tmp_path / "run.h5"
    p = run([LUBSIM, bad, "-o", out])
    assert p.returncode == 2 and not out.exists()
    cli = p.stderr.splitlines()[0]
    assert cli.startswith("lubsim: ")
    with pytest.raises(lubjoint.SceneError) as e:
        lubjoint.simulate(bad, output=out)
    assert str(e.value) == cli[len("lubsim: "):]  # "BAD.json: joints[3].viscosity_Pa_s = -0.4: must be > 0 Pa s"
    assert "joints[3].viscosity_Pa_s = -0.4" in str(e.value) and "must be > 0" in str(e.value)
    assert isinstance(e.value, ValueError) and not out.exists()
    # The same through overrides (lubsim --set), and from a dict.
    p = run([LUBSIM, SCENE, "-o", out, "--set", "/joints/3/force_law=nope"])
    assert p.returncode == 2
    with pytest.raises(ValueError) as e:
        lubjoint.simulate(SCENE, {"/joints/3/force_law": "nope"})
    assert str(e.value) == p.stderr.splitlines()[0][len("lubsim: "):]
    with pytest.raises(ValueError, match=r"^<scene dict>: joints\[3\]\.viscosity_Pa_s = -0\.4: must be > 0 Pa s"):
        lubjoint.simulate(scene)
    with pytest.raises(ValueError, match=r"names no value of the scene"):
        lubjoint.simulate(SCENE, {"/nowhere/x": 1})
    # A bad output path: lubsim's rule and message (option `output` for `-o`), before any work.
    missing = tmp_path / "no" / "run.h5"
    p = run([LUBSIM, SCENE, "-o", missing])
    assert p.returncode == 2
    with pytest.raises(ValueError) as e:
        lubjoint.simulate(SCENE, output=missing)
    assert str(e.value) == p.stderr.splitlines()[0].replace("lubsim: -o ", "output ", 1)
    with pytest.raises(ValueError, match=r"must name a file, not a directory"):
        lubjoint.simulate(SCENE, output=tmp_path)


# --- plausibility warnings (issue 29) -----------------------------------------------------

VISCOSITY_400 = ("/joints/3/viscosity_Pa_s = 400 Pa s is outside the plausible 1e-4 – 5 Pa s "
                 "(400 cP is 0.4 Pa s)")


def test_simulate_warns_of_an_implausible_value_as_lubsim_does(tmp_path):
    slip = {**SHORT, "/joints/3/viscosity_Pa_s": 400}
    out = tmp_path / "run.h5"
    with pytest.warns(lubjoint.PlausibilityWarning) as record:
        ds = lubjoint.simulate(SCENE, slip, output=out)
    assert [str(w.message) for w in record if w.category is lubjoint.PlausibilityWarning] == [VISCOSITY_400]
    assert issubclass(lubjoint.PlausibilityWarning, UserWarning)
    assert ds.attrs["warnings"] == [VISCOSITY_400]
    with h5py.File(out, "r") as f:
        assert [w.decode() if isinstance(w, bytes) else w for w in f.attrs["warnings"]] == [VISCOSITY_400]
    # lubsim: the same line on stderr, prefixed "lubsim: warning: ".
    sets = [a for k, v in slip.items() for a in ("--set", f"{k}={v}")]
    p = run([LUBSIM, SCENE, "-o", tmp_path / "lubsim.h5", "--quiet", *sets])
    assert p.returncode == 0, p.stderr
    assert p.stderr == f"lubsim: warning: {VISCOSITY_400}\n"


def test_simulate_plausible_scene_warns_nothing():
    with warnings.catch_warnings():
        warnings.simplefilter("error", lubjoint.PlausibilityWarning)
        ds = lubjoint.simulate(SCENE, SHORT)
    assert ds.attrs["warnings"] == []


def test_simulate_notes_a_law_outside_its_assumptions_and_strict_does_not_refuse(tmp_path):
    # frene_short at the paper's L/D = 40/19: a short-bearing law used far outside L/D <= 0.5,
    # and a full-film law whose load (the rod's force) reverses every cycle.
    over = {**SHORT, "/joints/3/force_law": "frene_short"}
    with pytest.warns(lubjoint.ValidityNote) as record:
        ds = lubjoint.simulate(SCENE, over, strict=True)
    notes = [str(w.message) for w in record if w.category is lubjoint.ValidityNote]
    assert notes == ds.attrs["notes"]
    assert notes[0].startswith('/joints/3/force_law = "frene_short" is a short-bearing law')
    assert "reverses" in notes[1]
    assert int(ds["load_reverses"]) == 1
    assert ds.attrs["warnings"] == []
    sets = [a for k, v in over.items() for a in ("--set", f"{k}={v}")]
    p = run([LUBSIM, SCENE, "-o", tmp_path / "lubsim.h5", "--quiet", "--strict", *sets])
    assert p.returncode == 0, p.stderr
    assert p.stderr == "".join(f"lubsim: note: {n}\n" for n in notes)


def test_simulate_strict_raises_and_writes_nothing(tmp_path):
    out = tmp_path / "run.h5"
    with pytest.raises(lubjoint.InputError) as e:
        lubjoint.simulate(SCENE, {"/joints/3/viscosity_Pa_s": 400}, output=out, strict=True)
    assert str(e.value) == f"{SCENE}: {VISCOSITY_400}; refused under strict=True"
    assert not out.exists()
    with pytest.raises(TypeError):  # keyword only
        lubjoint.simulate(SCENE, None, None, True)
    assert lubjoint.simulate(SCENE, SHORT, strict=True).attrs["warnings"] == []


def test_steady_bearing_warns_of_mm_typed_as_m():
    with pytest.warns(lubjoint.PlausibilityWarning, match=r"^clearance_m / radius_m = 0\.5 m / 0\.01 m = 50 is outside"):
        r = lubjoint.steady_bearing("gumbel_short", load_N=2000.0, speed_rpm=3000.0, radius_m=0.01, clearance_m=0.5,
                                    length_m=0.04, viscosity_Pa_s=0.4)
    assert len(r["warnings"]) == 1 and "0.5 mm is 0.0005 m" in r["warnings"][0]


def scalars(ds):
    return {k: v.item() for k, v in ds.data_vars.items() if v.ndim == 0 and k != "wall_time_s"}


def test_threads_run_side_by_side_same_as_serial():
    cases = [{**SHORT, "/joints/3/viscosity_Pa_s": mu} for mu in (0.4, 0.1)]
    serial = [lubjoint.simulate(SCENE, c) for c in cases]
    with ThreadPoolExecutor(max_workers=2) as pool:
        threaded = list(pool.map(lambda c: lubjoint.simulate(SCENE, c), cases))
    for s, t in zip(serial, threaded):
        assert_same_dicts(scalars(s), scalars(t))
        for name in s.data_vars:
            if s[name].ndim:
                np.testing.assert_array_equal(s[name].values, t[name].values, err_msg=name)
    assert scalars(serial[0]) != scalars(serial[1])


def test_gil_released_during_run():
    # While a run holds the GIL, no other Python thread executes a bytecode: count how far
    # this thread gets while a 12-cycle run (~0.3 s) proceeds on another.
    done = threading.Event()
    t = threading.Thread(target=lambda: (lubjoint.simulate(SCENE, {"/simulation/max_cycles": 12}), done.set()))
    count = 0
    t.start()
    while not done.is_set() and t.is_alive():
        count += 1
    t.join()
    assert done.is_set()
    assert count > 10000, count  # held GIL: a handful of iterations at most


# --- study files ---------------------------------------------------------------------------


@pytest.fixture(scope="module")
def study_file(tmp_path_factory):
    d = tmp_path_factory.mktemp("study")
    grid = {"scene": str(SCENE), "study": {"max_cycles": 2, "metric_cycles": 1, "channels": ["h_min"]},  # 2: a steady stage (1: the transient alone)
            "set": {"/simulation/steady": "auto"}, "axes": [{"name": "viscosity_Pa_s", "values": [0.4, 0.2]}]}
    (d / "grid.json").write_text(json.dumps(grid))
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}
    p = run([LUBSWEEP, d / "grid.json", "-o", d / "study.h5"], env=env, timeout=300)
    assert p.returncode == 0, p.stderr
    return d / "study.h5"


def test_load_study(study_file):
    assert lubjoint.study_format(study_file) == "lubsweep-study-5"  # the xarray layout (issue 15), scene patches (16)
    # The reader's one format is lubsweep's kStudyFormat, generated by the build.
    assert lubjoint.study.STUDY_FORMAT == "lubsweep-study-5"
    assert "kStudyFormat" in (Path(lubjoint.study.__file__).parent / "_study_format.py").read_text()
    s = lubjoint.load_study(study_file)
    assert list(s) == ["grid"]
    g = s["grid"]
    assert "viscosity_Pa_s" in g.dims
    np.testing.assert_array_equal(g["viscosity_Pa_s"].values, [0.4, 0.2])
    assert g["viscosity_Pa_s"].attrs["units"] == "Pa s"
    assert s.cases.sizes["case"] == 2
    assert list(s.cases["status"].values.astype(str)) == ["ok", "ok"]
    # A case's metric equals simulate's on the case's effective scene (its JSON Patch of
    # reference_scene, applied by python3-jsonpatch): the same functions, bit for bit.
    for case in (0, 1):
        one = lubjoint.simulate(lubjoint.study.scene(study_file, case))
        assert s.cases["max_eps"].values[case] == one["max_eps"].item()
    assert s.cases["max_eps"].values[0] != s.cases["max_eps"].values[1]


def test_the_cases_table_is_what_the_netcdf_reader_decodes(study_file):
    # lubjoint.study reads /cases with h5py (the netCDF reader takes seconds to size its
    # dimension over a few hundred columns); what it returns is what xarray's CF decoding
    # gives: every column, dtype, mask, attribute and unit.
    import pandas as pd
    import xarray as xr

    with xr.open_dataset(study_file, group="cases", engine="h5netcdf") as ds:
        decoded = ds.load()
    xr.testing.assert_identical(lubjoint.load_study(study_file).cases, decoded)
    df = lubjoint.study.cases(study_file)
    pd.testing.assert_frame_equal(df, decoded.to_dataframe())
    assert df.attrs["units"] == {k: decoded[k].attrs.get("units", "") for k in decoded.variables}
    assert {k: str(v) for k, v in df.attrs.items() if k not in ("units", "lattice")} == \
        {k: str(v) for k, v in decoded.attrs.items() if k != "units"}


def test_study_series_is_the_readers_series_by_id_or_name(study_file):
    # Study.series reads through lubjoint.study.series: the same Dataset by the case's id or name.
    s = lubjoint.load_study(study_file)
    names = [str(n) for n in s.cases["name"].values]
    for case, name in zip(s.cases["case"].values, names):
        expected = lubjoint.study.series(study_file, name)
        assert expected is not None and expected["h_min"].size > 1
        for key in (int(case), case, name):  # an int, a NumPy integer, a str
            assert s.series(key).identical(expected), key
    assert not s.series(0)["h_min"].equals(s.series(1)["h_min"])  # two cases, two series


@pytest.mark.parametrize("unknown", ["case_9999", 99, -1, "0", 1.0, True])
def test_study_series_of_an_unknown_case_names_it(study_file, unknown):
    s = lubjoint.load_study(study_file)
    with pytest.raises(KeyError) as e:
        s.series(unknown)
    message = e.value.args[0]
    assert repr(unknown) in message and "cases['case']" in message and "cases['name']" in message, message


def test_load_study_reads_xarray_layout(tmp_path):
    # The reader alone, on a file in the layout issue 15 describes (netCDF-4 groups, written
    # here with xarray/h5netcdf): /grids/<name> labelled variables over the axes, /cases
    # columns over `case`.
    path = tmp_path / "s.h5"
    c = xr.Dataset({"max_eps": ("case", [0.5, 0.6, 0.7]), "status": ("case", ["ok", "ok", "film_collapse"])})
    g = xr.Dataset({"max_eps": (("clearance_m",), [0.5, 0.6], {"units": "1"})},
                   coords={"clearance_m": ("clearance_m", [5e-4, 1e-4], {"units": "m"})})
    c.to_netcdf(path, group="cases", engine="h5netcdf")
    g.to_netcdf(path, group="grids/clearance", engine="h5netcdf", mode="a")
    with h5py.File(path, "a") as f:
        f.attrs["program"] = "lubsweep"
        f.attrs["format"] = "lubsweep-study-5"
    s = lubjoint.load_study(path)
    assert list(s) == ["clearance"] and s.attrs["format"] == "lubsweep-study-5"
    np.testing.assert_array_equal(s["clearance"]["max_eps"].sel(clearance_m=1e-4).values, 0.6)
    assert s.cases.to_dataframe()["status"].tolist() == ["ok", "ok", "film_collapse"]
    with h5py.File(path, "a") as f:
        f.attrs["format"] = "lubsweep-study-1"
    with pytest.raises(lubjoint.StudyFormatError):
        lubjoint.load_study(path)


def test_the_study_reader_reads_one_format_and_says_what_to_do(tmp_path):
    # One list of accepted formats (lubjoint.study.STUDY_FORMAT, what lubsweep writes): an
    # older file, e.g. lubsweep-study-3, is refused by load_study and by the tools' check alike.
    path = tmp_path / "old.h5"
    xr.Dataset({"max_eps": ("case", [0.5])}).to_netcdf(path, group="cases", engine="h5netcdf")
    with h5py.File(path, "a") as f:
        f.attrs["program"] = "lubsweep"
        f.attrs["format"] = "lubsweep-study-3"
    message = (f"{path}: a study file of format lubsweep-study-3; lubjoint.study reads lubsweep-study-5 "
               "(re-run the sweep with --restart to rewrite it)")
    for read in (lubjoint.load_study, lubjoint.study.check):
        with pytest.raises(lubjoint.StudyFormatError) as e:
            read(path)
        assert str(e.value) == message
    with pytest.raises(SystemExit) as e:
        lubjoint.study.check_or_exit(path)
    assert str(e.value) == message
    (tmp_path / "text.h5").write_text("not HDF5")
    with pytest.raises(lubjoint.StudyFormatError, match="not an HDF5 file"):
        lubjoint.load_study(tmp_path / "text.h5")


def test_the_study_reader_says_when_there_is_no_file(tmp_path, monkeypatch):
    # A path that names no file is not "not an HDF5 file": FileNotFoundError, as open() says it.
    monkeypatch.chdir(tmp_path)
    for read in (lubjoint.load_study, lubjoint.study.check):
        with pytest.raises(FileNotFoundError) as e:
            read("nope.h5")
        assert str(e.value) == "no such file: nope.h5"
    with pytest.raises(SystemExit) as e:
        lubjoint.study.check_or_exit(Path("nope.h5"))
    assert str(e.value) == "no such file: nope.h5"
    with pytest.raises(IsADirectoryError, match="^a directory, not a study file: "):
        lubjoint.load_study(tmp_path)


def test_the_study_reader_needs_no_compiled_extension(tmp_path):
    # The package's Python files alone (a build without LUB_BUILD_PYTHON): lubjoint.study
    # imports and reads; what needs the extension fails only when it is used.
    package = tmp_path / "lubjoint"
    package.mkdir()
    for src in Path(lubjoint.__file__).parent.glob("*.py"):
        (package / src.name).write_text(src.read_text())
    code = ("import sys; from lubjoint import study, load_study; import lubjoint; "
            "assert 'lubjoint._lubjoint' not in sys.modules; print(study.STUDY_FORMAT)\n"
            "try:\n    lubjoint.simulate\nexcept ImportError as e:\n    print('ImportError', e)")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       env={**os.environ, "PYTHONPATH": str(tmp_path)})
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert lines[0] == "lubsweep-study-5" and lines[1].startswith("ImportError") and "_lubjoint" in lines[1], p.stdout


def test_the_binding_returns_named_fields():
    f = lubjoint._lubjoint.force("frene_long", np.array([0.5]), np.array([0.0]), np.array([100.0]),
                                 0.0095, 0.0005, 0.04, 0.4)
    assert sorted(f) == ["radial_N", "tangential_N"]
    assert lubjoint.bearing.force("frene_long", 0.5, 0.0, 100.0, **BEARING).radial_N == f["radial_N"][0]
    assert {"name", "value", "units", "integer", "long_name"} <= set(dir(lubjoint._lubjoint.Scalar))
    assert {"name", "units", "long_name", "values"} <= set(dir(lubjoint._lubjoint.Column))


def test_one_missing_value_convention(study_file, tmp_path):
    # NaN for every unknown float (the first cycle's periodicity, a study case's
    # periodicity after one cycle), in the run, the run file, /cases and /grids alike; an
    # unknown integer (cycles_to_steady, never steady) holds -1 and says so (missing_value).
    one = lubjoint.simulate(SCENE, {"/simulation/max_cycles": 2, "/simulation/stop_when_steady": False},
                            output=tmp_path / "run.h5")
    assert np.isnan(one["cycle_periodicity"].values[0]) and np.isfinite(one["cycle_periodicity"].values[1])
    assert one["cycles_to_steady"].item() == -1 and one["cycles_to_steady"].attrs["missing_value"] == -1
    with h5py.File(tmp_path / "run.h5", "r") as f:
        assert f.attrs["format"] == "lubsim-run-3"
        assert np.isnan(f["cycles/periodicity"][0]) and np.isnan(f["cycles/periodicity"].attrs["_FillValue"])
        assert f["metrics"].attrs["cycles_to_steady"] == -1 and f["metrics"].attrs["missing_value"] == -1
    with h5py.File(study_file, "r") as f:  # one metric cycle: no periodicity
        assert np.isnan(f["cases/periodicity"][:]).all() and np.isnan(f["grids/grid/periodicity"][:]).all()
        assert f["cases/cycles_to_steady"].attrs["missing_value"] == -1
        assert np.isnan(f["cases/periodicity"].attrs["_FillValue"])
    cases = lubjoint.study.cases(study_file)  # the reader: NaN for the unknown integer too
    assert cases["periodicity"].isna().all() and cases["cycles_to_steady"].dtype.kind == "f"
    assert (cases["steps"] > 0).all()


def test_tools_read_study_files_only_through_lubjoint_study():
    # One reader of study files (lubjoint.study: one list of formats, one message for an old
    # file): no tool opens HDF5 itself, except compare/identical.py, which compares any two
    # HDF5 files byte for byte and reads no study semantics. Tools in subfolders included.
    tools = SOURCE / "tools"
    scripts = sorted(tools.rglob("*.py")) + sorted(tools.rglob("*.sh"))
    assert len(scripts) > 20, [str(p) for p in scripts]
    readers = [str(p.relative_to(tools)) for p in scripts
               if str(p.relative_to(tools)) not in ("compare/identical.py", "setup.sh")  # setup.sh installs python3-h5py
               and ("h5py" in p.read_text() or "open_dataset" in p.read_text())]
    assert readers == [], f"tools reading HDF5 without lubjoint.study: {readers}"
    for p in ("compare/study.py", "compare/nightly.py", "compare/tolerance.py", "plot/paper.py", "plot/steady.py",
              "plot/sweep_map.py", "perf/work_precision.py", "perf/scaling_model.py"):
        assert "from lubjoint import study" in (tools / p).read_text(), p


@pytest.fixture(scope="module")
def continued_study(tmp_path_factory):
    # Two speeds of the printed law with simulation.steady = continuation: the 2500 rpm
    # case starts from the 5000 rpm case's orbit (the seed: largest mu omega / c^2).
    d = tmp_path_factory.mktemp("continued")
    grid = {"scene": str(SCENE), "study": {"max_cycles": 40, "stop_when_steady": True, "channels": []},
            "set": {"/simulation/steady": "continuation", "/solver/formulation": "partitioned"},
            "driver": "crank_speed", "axes": [{"name": "speed_rpm", "values": [5000, 2500]}]}
    (d / "grid.json").write_text(json.dumps(grid))
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}
    p = run([LUBSWEEP, d / "grid.json", "-o", d / "study.h5", "-q"], env=env, timeout=300)
    assert p.returncode == 0, p.stderr
    return d / "study.h5"


def test_a_continued_study_keeps_each_orbit_and_its_parent(continued_study):
    # Each case's orbit is in /cases, readable by lubjoint.study.orbit_seed.
    df = lubjoint.study.cases(continued_study)
    assert list(df["classification"].astype(str)) == ["periodic", "periodic"]
    assert list(df["continued_from"]) == [-1, 0]
    for case in (0, 1):
        seed = lubjoint.study.orbit_seed(continued_study, case)
        n = 2 * len(seed["chart"])  # the independent coordinates and their velocities
        assert seed["monodromy"].shape == (n, n) and len(seed["deviation"]) == len(seed["winding"])
        # The seed's monodromy is the orbit's, in each state's unit (S^-1 M S): the same
        # eigenvalues as the multipliers the file reports (4 of them, largest first).
        mu = sorted(np.abs(np.linalg.eigvals(seed["monodromy"])), reverse=True)
        reported = [df.loc[case, f"multiplier_{k}_modulus"] for k in range(1, 5)]
        np.testing.assert_allclose(mu[:4], reported, rtol=1e-9, atol=1e-12)
    assert lubjoint.study.orbit_seed(continued_study, 0)["max_eps"] > 0


def copy_of(path, tmp_path, name="copy.h5"):
    import shutil

    return Path(shutil.copyfile(path, tmp_path / name))


def strings(values):
    """A list of str as HDF5 variable-length strings, as lubsweep writes its string attributes."""
    return np.array([str(v.decode() if isinstance(v, bytes) else v) for v in values], dtype=h5py.string_dtype())


def test_the_study_file_describes_itself_and_the_reader_restates_none_of_it(continued_study, tmp_path):
    # What lubsweep wrote (from lub::orbit_seed_fields, CaseClass, lattice_edges), as the
    # reader gives it.
    cases = lubjoint.study.cases(continued_study)
    assert lubjoint.study.orbit_classifications(cases) == ("periodic", "periodic_unstable")
    assert lubjoint.study.no_orbit_classifications(cases) == (
        "drifting", "not_converged", "film_collapse", "solver_failure", "budget_exceeded")
    assert lubjoint.study.lattice_edges(cases) == [(1, 0, "speed_rpm")]  # 2500 rpm below 5000 rpm
    layout = lubjoint.study.orbit_seed_layout(continued_study)
    assert layout["layout"] == 1
    assert [f[:3] for f in layout["fields"]] == [
        ("deviation", "vector", "float64"), ("modes", "vector", "int64"), ("chart", "vector", "int64"),
        ("monodromy", "square_matrix_column_major", "float64"), ("winding", "vector", "float64"),
        ("max_eps", "scalar", "float64"), ("steps_per_period", "scalar", "float64")]
    seed = lubjoint.study.orbit_seed(continued_study, 1)

    # The file's word is obeyed. Its orbit labels: told that periodic is no orbit, the two
    # cells' edge is an orbit lost.
    other = copy_of(continued_study, tmp_path)
    with h5py.File(other, "a") as f:
        f["cases"].attrs["orbit_classifications"] = strings(["periodic_unstable"])
        f["cases"].attrs["no_orbit_classifications"] = strings(["periodic"])
    told = lubjoint.study.cases(other)
    assert lubjoint.study.orbit_classifications(told) == ("periodic_unstable",)
    assert "orbit_lost" not in list(lubjoint.study.bifurcation_edges(told).kind)  # no orbit at either end
    with h5py.File(other, "a") as f:
        f["cases"].attrs["orbit_classifications"] = strings(["periodic"])
        f["cases"].attrs["no_orbit_classifications"] = strings(["periodic"])
    assert list(lubjoint.study.bifurcation_edges(lubjoint.study.cases(other)).kind) == ["orbit_lost"]
    # Its seed layout: fields decoded by the names and order the file gives (here the two
    # scalars renamed and swapped in the list: the values follow the list, not the reader).
    with h5py.File(other, "a") as f:
        a = f["cases/orbit_seed"].attrs
        for key in ("fields", "field_shapes", "field_types", "field_units", "field_long_names"):
            v = list(a[key])
            a[key] = strings(v[:5] + [v[6], v[5]])
        a["fields"] = strings(list(a["fields"])[:5] + ["first", "second"])
    renamed = lubjoint.study.orbit_seed(other, 1)
    assert sorted(renamed) == sorted(["deviation", "modes", "chart", "monodromy", "winding", "first", "second"])
    assert (renamed["first"], renamed["second"]) == (seed["max_eps"], seed["steps_per_period"])
    np.testing.assert_array_equal(renamed["monodromy"], seed["monodromy"])
    # Its lattice: the edges the file lists, not a recomputed lattice.
    with h5py.File(other, "a") as f:
        del f["lattice"]
        g = f.create_group("lattice")
        g["case_a"], g["case_b"], g["axis"] = np.array([0], dtype=np.int64), np.array([1], dtype=np.int64), strings(["speed_rpm"])
    assert lubjoint.study.lattice_edges(lubjoint.study.cases(other)) == [(0, 1, "speed_rpm")]
    # Another layout number is refused, naming it.
    with h5py.File(other, "a") as f:
        f["cases/orbit_seed"].attrs["layout"] = 2
    with pytest.raises(lubjoint.StudyFormatError, match="layout 1.*the file says 2"):
        lubjoint.study.orbit_seed(other, 1)


def test_a_study_file_without_its_self_description_reads_and_says_what_is_missing(continued_study, tmp_path):
    # A file of format 5 written before lubsweep described itself: everything that does not
    # need the description reads as before; what needs it raises, naming what is missing
    # and what to do.
    old = copy_of(continued_study, tmp_path, "old.h5")
    with h5py.File(old, "a") as f:
        for a in ("orbit_classifications", "no_orbit_classifications"):
            del f["cases"].attrs[a]
        for a in ("layout", "fields", "field_shapes", "field_types", "field_units", "field_long_names", "packing"):
            del f["cases/orbit_seed"].attrs[a]
        del f["lattice"]
    s = lubjoint.load_study(old)
    assert s.cases.sizes["case"] == 2
    cases = lubjoint.study.cases(old)
    assert "lattice" not in cases.attrs and list(cases["continued_from"]) == [-1, 0]
    with pytest.raises(lubjoint.StudyFormatError, match="has no attribute layout: a study file written before "
                                                        "lubsweep described its own layout: re-run the sweep"):
        lubjoint.study.orbit_seed(old, 1)
    with pytest.raises(lubjoint.StudyFormatError, match="no /cases attribute orbit_classifications.*re-run the sweep"):
        lubjoint.study.bifurcation_edges(cases)
    with pytest.raises(lubjoint.StudyFormatError, match="orbit_classifications"):
        lubjoint.study.orbit_classifications(cases)


@pytest.mark.parametrize("law", ["frene_long", "frene_short", "gumbel_long", "gumbel_short",
                                 "pinkus_sternlicht_continuous"])
def test_pressure_field_integrates_to_the_laws_force(law):
    # F_r = R ∫∫ p cos θ dθ dz, F_t = R ∫∫ p sin θ dθ dz: the mid-plane field times L for the
    # long laws, times (2/3) L for the short ones (their pressure is parabolic in z). The
    # trapezoidal rule on 20 000 points of a periodic, piecewise smooth field (a ruptured film
    # has a kink): 1e-5 of the force.
    g = dict(radius_m=0.0095, clearance_m=5e-4, length_m=0.04, viscosity_Pa_s=0.4)
    theta = np.linspace(0.0, 2.0 * np.pi, 20001)[:-1]
    width = g["length_m"] * (2.0 / 3.0 if law.endswith("short") else 1.0)
    for eps, eps_dot, wedge in [(0.3, 0.0, 500.0), (0.7, 20.0, 300.0), (0.9, -5.0, 400.0)]:
        p = lubjoint.pressure(law, theta, eps, eps_dot, wedge, **g)
        dth = theta[1] - theta[0]
        fr = g["radius_m"] * width * np.sum(p * np.cos(theta)) * dth
        ft = g["radius_m"] * width * np.sum(p * np.sin(theta)) * dth
        f = lubjoint.force(law, eps, eps_dot, wedge, **g)
        scale = float(np.hypot(f.radial_N, f.tangential_N))
        assert abs(fr - float(f.radial_N)) < 1e-5 * scale, (eps, fr, f)
        assert abs(ft - float(f.tangential_N)) < 1e-5 * scale, (eps, ft, f)


def test_pressure_of_the_finite_bearing_peaks_where_its_steady_solution_says():
    g = dict(radius_m=0.0095, clearance_m=5e-4, length_m=0.04, viscosity_Pa_s=0.4)
    s = lubjoint.steady_bearing("finite_reynolds", load_N=2000.0, speed_rpm=3000.0, **g)
    theta = np.linspace(0.0, 2.0 * np.pi, 4001)
    p = lubjoint.pressure("finite_reynolds", theta, s["eps"], 0.0, 3000.0 * np.pi / 30.0, **g)
    # Linear interpolation between cell centres against the solver's parabola through the
    # largest cell: within the 48-cell grid's resolution near the peak (2 %).
    assert p.max() == pytest.approx(s["peak_pressure_Pa"], rel=0.02)
    with pytest.raises(lubjoint.InputError, match="eps = 1"):
        lubjoint.pressure("frene_long", theta, 1.0, 0.0, 1.0, **g)


def test_simulate_sensitivities_are_variables_with_units():
    # The printed law's force is mu L times a function of the state: mu dh/dmu = L dh/dL.
    over = {"/simulation/steady": "auto", "/outputs/channels": []}
    ds = lubjoint.simulate(SCENE, over, sensitivity=["/joints/3/viscosity_Pa_s", "/joints/3/length_m"])
    mu = ds["d_min_film_thickness_m_per_joints_3_viscosity_Pa_s"]
    length = ds["d_min_film_thickness_m_per_joints_3_length_m"]
    assert mu.attrs["units"] == "m/(Pa s)" and length.attrs["units"] == "m/m"
    assert mu.attrs["parameter"] == "/joints/3/viscosity_Pa_s"
    assert float(mu) * 0.4 == pytest.approx(float(length) * 0.04, rel=1e-3)
    assert ds.attrs["sensitivities"] == ["/joints/3/viscosity_Pa_s: ok", "/joints/3/length_m: ok"]
    with pytest.raises(lubjoint.InputError, match="sensitivity /joints/3/force_law: names no number"):
        lubjoint.simulate(SCENE, over, sensitivity="/joints/3/force_law")
