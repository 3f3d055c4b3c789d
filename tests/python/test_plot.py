"""Tests of lubjoint.plot (core/python/lubjoint/plot.py), run by ctest (label python):

    PYTHONPATH=build/python LUB_SOURCE_DIR=. LUB_BUILD_DIR=build /usr/bin/python3 -m pytest tests/python/test_plot.py

On a small study lubsweep writes here (clearance x viscosity x two force laws, the channels
the figures read) and on runs of the paper's scene: each figure is a Figure with the axes it
promises, drawing the data it was given (no number of the engine is restated here); and
tools/plot/sweep_map.py, which draws with the module's cells.
"""

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure

import lubjoint
from lubjoint import plot

CHANNELS = ["crank_angle", "e_x", "e_y", "eps", "h_min"]
LAWS = ["pinkus_sternlicht", "frene_long"]


@pytest.fixture(scope="module")
def scene(source_dir):
    return source_dir / "configs" / "scenes" / "slider_crank.json"


@pytest.fixture(scope="module")
def study(tmp_path_factory, build_dir, scene):
    d = tmp_path_factory.mktemp("plot_study")
    grid = {"scene": str(scene), "set": {"/simulation/steady": "auto"},
            "study": {"max_cycles": 20, "stop_when_steady": True, "metric_cycles": 2, "channels": CHANNELS,
                      "last_cycles": 2, "samples_per_cycle": 180, "on_failure": "continue"},
            "axes": [{"name": "clearance_m", "values": [0.0005, 0.0002]},
                     {"name": "viscosity_Pa_s", "values": [0.4, 0.1, 0.04]},
                     {"name": "force_law", "values": LAWS}]}
    (d / "grid.json").write_text(json.dumps(grid))
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}
    p = subprocess.run([str(build_dir / "sweep" / "lubsweep"), str(d / "grid.json"), "-o", str(d / "study.h5"), "-q"],
                       capture_output=True, text=True, env=env, timeout=300)
    assert p.returncode == 0, p.stderr
    return lubjoint.load_study(d / "study.h5")


@pytest.fixture(scope="module")
def periodic_case(study):
    """A case of the study with a periodic orbit (its stored channels are that orbit)."""
    cases = study.cases.to_dataframe()
    ok = cases[cases["classification"].isin(lubjoint.study.orbit_classifications(study.cases))]
    assert len(ok), cases[["name", "classification"]]
    return int(ok.index[0])


@pytest.fixture(scope="module")
def run(scene, tmp_path_factory):
    """The paper's scene, run to its periodic orbit (shooting), and the run file it wrote."""
    path = tmp_path_factory.mktemp("plot_run") / "run.h5"
    return lubjoint.simulate(scene, {"/simulation/steady": "auto"}, output=path), path


def line_data(ax):
    """The x, y of each line of ``ax`` that has data."""
    return [(np.asarray(l.get_xdata(), float), np.asarray(l.get_ydata(), float)) for l in ax.lines
            if len(l.get_xdata())]


def legend_texts(ax):
    return [t.get_text() for t in ax.get_legend().get_texts()]


# --- a run ---------------------------------------------------------------------------------


def test_orbit_of_a_study_case_draws_its_channels_inside_the_clearance(study, periodic_case):
    for case in study.cases["case"].values:  # the circle: each case's clearance, read from |e| / eps
        (cx, cy), *_ = line_data(plot.orbit(study.series(case), units="um").axes[0])
        np.testing.assert_allclose(np.hypot(cx, cy), study.cases["clearance_m"].sel(case=case) * 1e6, rtol=1e-9)
    s = study.series(periodic_case)
    clearance = float(study.cases["clearance_m"].sel(case=periodic_case))
    fig = plot.orbit(s)
    assert isinstance(fig, Figure) and len(fig.axes) == 1
    ax = fig.axes[0]
    (cx, cy), (px, py), _ = line_data(ax)  # the circle, the path, its first sample
    np.testing.assert_allclose(np.hypot(cx, cy), 1.0, rtol=1e-12)
    np.testing.assert_allclose(px, s["e_x"].values / clearance, rtol=1e-9)
    np.testing.assert_allclose(py, s["e_y"].values / clearance, rtol=1e-9)
    assert np.all(np.hypot(px, py) < 1.0)
    assert "[" in ax.get_xlabel() and "[" in ax.get_ylabel()
    um = plot.orbit(s, units="um").axes[0]
    np.testing.assert_allclose(line_data(um)[1][0], s["e_x"].values * 1e6)
    assert "µm" in um.get_xlabel() and "µm" in um.get_ylabel()


def test_film_draws_h_min_and_eps_over_crank_angle(study, periodic_case):
    s = study.series(periodic_case)
    fig = plot.film(s)
    assert isinstance(fig, Figure) and len(fig.axes) == 2
    for ax, channel, factor in zip(fig.axes, ("h_min", "eps"), (1e6, 1.0)):
        x, y = line_data(ax)[0]
        drawn = ~np.isnan(y)
        np.testing.assert_array_equal(y[drawn], s[channel].values * factor)
        assert np.all((x[drawn] >= 0) & (x[drawn] < 360)) and np.isnan(x).sum() == np.isnan(y).sum()
        assert "[" in ax.get_ylabel()
    assert fig.axes[1].get_xlabel() == "crank angle [deg]"
    assert len(plot.film(s, show="h_min").axes) == 1


def test_film_of_a_run_draws_its_safe_film(run):
    ds, _ = run
    ax = plot.film(ds, show=["h_min"]).axes[0]
    safe = ds["safe_film_thickness_m"].item() * 1e6
    assert any(np.allclose(y, safe) for _, y in line_data(ax)), line_data(ax)
    assert any("safe film" in t for t in legend_texts(ax))
    ax = plot.film(ds, show=["h_min"], safe_film_m=2 * ds["safe_film_thickness_m"].item()).axes[0]
    assert any(np.allclose(y, 2 * safe) for _, y in line_data(ax))


def test_a_run_file_draws_as_the_run(run):
    # The run file simulate wrote (lubsim's layout) reads back as the run: the same orbit,
    # its periodic orbit (/orbit) where the run located one.
    ds, path = run
    assert "orbit_e_x" in ds
    for draw in (plot.orbit, plot.film):
        a, b = draw(ds), draw(path)
        for ax_a, ax_b in zip(a.axes, b.axes):
            for (xa, ya), (xb, yb) in zip(line_data(ax_a), line_data(ax_b)):
                np.testing.assert_array_equal(xa, xb)
                np.testing.assert_array_equal(ya, yb)
    joint = next(j for j in json.loads(ds.attrs["scene"])["joints"] if j["type"] == "lubricated_revolute")
    ax = plot.orbit(path).axes[0]
    np.testing.assert_allclose(line_data(ax)[1][0], ds["orbit_e_x"].values
                               / (joint["bearing_radius_m"] - joint["journal_radius_m"]), rtol=1e-9)
    assert "periodic orbit" in legend_texts(ax)


def test_a_transient_run_draws_its_last_metric_cycles(scene):
    ds = lubjoint.simulate(scene)  # no steady stage: the last simulation.metric_cycles cycles
    n = json.loads(ds.attrs["scene"])["simulation"]["metric_cycles"]
    start = ds["cycle_t_start_s"].values[-n]
    _, y = line_data(plot.film(ds, show="h_min").axes[0])[0]
    np.testing.assert_array_equal(y[~np.isnan(y)], ds["h_min"].sel(t=slice(start, None)).values * 1e6)
    assert ds.sizes["t"] > np.sum(~np.isnan(y))


def test_a_run_without_the_channels_says_which(study, periodic_case):
    with pytest.raises(ValueError, match="no channel crank_angle"):
        plot.film(study.series(periodic_case).drop_vars("crank_angle"))
    with pytest.raises(ValueError, match="study.channels"):
        plot.orbit(None)


# --- a study -------------------------------------------------------------------------------


def test_classification_map_draws_each_cells_classification(study):
    g = study["grid"]
    fig = plot.classification_map(study)
    assert isinstance(fig, Figure) and len(fig.axes) == len(LAWS)  # one panel per force law
    labels = legend_texts(fig.axes[-1])
    assert set(labels) == {str(c) for c in g["classification"].values.ravel()}
    for ax in fig.axes:
        law = ax.get_title().split(" = ")[1]
        cells = np.asarray(ax.images[0].get_array())
        assert cells.shape == (g.sizes["viscosity_Pa_s"], g.sizes["clearance_m"])  # viscosity up, clearance across
        expected = g["classification"].sel(force_law=law).sortby(["viscosity_Pa_s", "clearance_m"])
        expected = expected.transpose("viscosity_Pa_s", "clearance_m").values.astype(str)
        assert [[labels[int(v)] for v in row] for row in cells] == expected.tolist()
        assert "[µm]" in ax.get_xlabel() or not ax.get_xlabel()
        # each located orbit's cell names its conditioning κ, as the file holds it
        kappa = g["orbit_conditioning"].sel(force_law=law).sortby(["viscosity_Pa_s", "clearance_m"])
        kappa = kappa.transpose("viscosity_Pa_s", "clearance_m").values
        orbits = set(lubjoint.study.orbit_classifications(study.cases))
        wanted = sorted(f"κ {k:.2g}" for c, k in zip(expected.ravel(), kappa.ravel()) if c in orbits and np.isfinite(k))
        assert wanted and sorted(t.get_text() for t in ax.texts if t.get_text().startswith("κ")) == wanted
    one = plot.classification_map(study, x="viscosity_Pa_s", y="clearance_m", fix={"force_law": LAWS[1]})
    assert len(one.axes) == 1 and "viscosity [Pa s]" == one.axes[0].get_xlabel()


def test_envelope_draws_the_metric_per_force_law_with_error_bars_and_the_safe_film(study):
    g = study["grid"].sortby("clearance_m")
    fig = plot.envelope(study, axis="clearance_m", fix={"viscosity_Pa_s": 0.4})
    assert isinstance(fig, Figure) and len(fig.axes) == 1
    ax = fig.axes[0]
    texts = legend_texts(ax)
    assert [t for t in texts if t in LAWS] == LAWS and "safe film thickness" in texts
    lines = line_data(ax)
    for law in LAWS:
        film = g["min_film_thickness_m"].sel(force_law=law, viscosity_Pa_s=0.4).values * 1e6
        if np.isfinite(film).any():
            assert any(np.array_equal(y, film, equal_nan=True) for _, y in lines), law
    assert ax.collections, "no error bars"  # min_film_thickness_m_error: a LineCollection
    assert ax.get_xlabel() == "clearance [µm]" and ax.get_ylabel() == "min_film_thickness [µm]"
    eps = plot.envelope(study, "max_eps", axis="clearance_m", fix={"viscosity_Pa_s": 0.4}).axes[0]
    assert "safe film thickness" not in legend_texts(eps) and eps.get_ylabel() == "max_eps [–]"


def test_envelope_draws_each_orbits_tangent_from_the_study_sensitivity(study):
    g = study["grid"].sortby("viscosity_Pa_s").sel(clearance_m=0.0005, force_law="pinkus_sternlicht")
    ax = plot.envelope(study, axis="viscosity_Pa_s", fix={"clearance_m": 0.0005, "force_law": "pinkus_sternlicht"}).axes[0]
    assert "tangent: d_min_film_thickness_m_per_viscosity_Pa_s" in legend_texts(ax)
    film = g["min_film_thickness_m"].values * 1e6  # drawn in µm over Pa s
    slope = g["d_min_film_thickness_m_per_viscosity_Pa_s"].values * 1e6
    mu = g["viscosity_Pa_s"].values
    dotted = [l for l in ax.get_lines() if l.get_linestyle() == ":" and len(l.get_xdata()) > 1]
    orbits = np.flatnonzero(np.isfinite(film) & np.isfinite(slope))
    assert len(orbits) and len(dotted) == len(orbits)
    for i, line in zip(orbits, dotted):  # through the orbit's point, with the study's slope
        x, y = np.asarray(line.get_xdata()), np.asarray(line.get_ydata())
        assert x.min() <= mu[i] <= x.max() and x.max() > x.min()  # a quarter of the way to each neighbour
        assert np.allclose(np.diff(y) / np.diff(x), slope[i], rtol=1e-9)
        assert np.interp(mu[i], x, y) == pytest.approx(film[i], rel=1e-12)


def test_envelope_over_an_axis_left_free_is_a_band(study):
    ax = plot.envelope(study, axis="clearance_m").axes[0]  # viscosity spans two values
    assert "band" in ax.get_title() and "viscosity_Pa_s" in ax.get_title()
    assert sum(isinstance(c, PolyCollection) for c in ax.collections) == len(LAWS)


def test_a_grid_or_value_the_study_lacks_is_named(study):
    with pytest.raises(KeyError, match="no grid 'nope'.*grid"):
        plot.envelope(study, grid="nope")
    with pytest.raises(ValueError, match="no axis 'speed_rpm'"):
        plot.classification_map(study, x="speed_rpm")
    with pytest.raises(ValueError, match="viscosity_Pa_s = 0.3"):
        plot.envelope(study, fix={"viscosity_Pa_s": 0.3})


# --- the package and the tools -------------------------------------------------------------


def test_import_lubjoint_needs_no_matplotlib_until_plot_is_used():
    code = ("import sys, lubjoint; assert 'matplotlib' not in sys.modules; "
            "from lubjoint import plot; assert lubjoint.plot is plot and 'matplotlib' in sys.modules")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr


def test_sweep_map_draws_with_the_shared_cells(study, source_dir, tmp_path):
    p = subprocess.run([sys.executable, str(source_dir / "tools" / "plot" / "sweep_map.py"), study.path,
                        "-x", "clearance_m", "-y", "viscosity_Pa_s", "--fix", "force_law=frene_long",
                        "-m", "max_eps", "-o", str(tmp_path)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "map_max_eps_clearance_m_viscosity_Pa_s.png").stat().st_size > 0


def test_safe_envelope_draws_cells_and_the_located_boundaries(study):
    import pandas as pd

    # A boundary handed in (safe_film_boundaries runs scenes): on the viscosity axis of the
    # Pinkus–Sternlicht plane at 0.5 mm, drawn in µm and Pa s.
    b = pd.DataFrame([{"axis": "viscosity_Pa_s", "value": 0.07, "error": 1e-4, "unit": "Pa s", "kind": "safe_film",
                       "force_law": "pinkus_sternlicht", "clearance_m": 0.0005},
                      {"axis": "clearance_m", "value": 0.0003, "error": 1e-7, "unit": "m", "kind": "safe_film",
                       "force_law": "pinkus_sternlicht", "viscosity_Pa_s": 0.04}])
    fig = plot.safe_envelope(study, "clearance_m", "viscosity_Pa_s", boundaries=b)
    assert len(fig.axes) == len(LAWS)
    ax = fig.axes[0]
    assert ax.get_title() == "pinkus_sternlicht" and ax.get_xlabel() == "clearance [µm]"
    curve = [l for l in ax.get_lines() if l.get_label() == "safe film reached (located)"]
    assert len(curve) == 1
    assert sorted(zip(curve[0].get_xdata(), curve[0].get_ydata())) == [(300.0, 0.04), (500.0, 0.07)]
    g = study["grid"].sel(force_law="pinkus_sternlicht")
    cells = sum(len(l.get_xdata()) for l in ax.get_lines() if l.get_label() in
                ("safe", "below the safe film", "no located orbit"))
    assert cells == g.sizes["clearance_m"] * g.sizes["viscosity_Pa_s"]
    assert not [l for l in fig.axes[1].get_lines() if l.get_label() == "safe film reached (located)"]
    assert "safe film reached (located)" in legend_texts(fig.axes[-1])
