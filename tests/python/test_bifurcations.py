"""lubjoint.study.bifurcation_edges (core/python/lubjoint/bifurcations.py) on synthetic /cases
tables, and its marks on tools/plot/steady.py's classification map (label python):

    PYTHONPATH=build/python /usr/bin/python3 -m pytest tests/python/test_bifurcations.py

The study written by lubsweep is tested in test_bifurcations_study.py (the nightly fixture)."""
import importlib.util
import itertools
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from lubjoint import study
from lubjoint.bifurcations import COLUMNS, lattice_edges

NAN = float("nan")
AXES = ["clearance_m", "viscosity_Pa_s", "speed_rpm", "force_law"]
UNITS = {"clearance_m": "m", "viscosity_Pa_s": "Pa s", "speed_rpm": "min-1", "force_law": ""}
BASE = dict(clearance_m=2e-4, viscosity_Pa_s=0.4, speed_rpm=5000.0, force_law="pinkus_sternlicht")
# What a study file lubsweep writes says of its classifications (the /cases attributes; the
# test of the file itself: StudyFile.TheFileDescribesItsOwnLayout, test_lubjoint.py).
ORBIT = ["periodic", "periodic_unstable"]
NO_ORBIT = ["drifting", "not_converged", "film_collapse", "solver_failure", "budget_exceeded"]


def mult(m1, a1, m2=NAN, a2=NAN):
    """The multiplier columns of a case: the dominant one (modulus, angle) and the second."""
    return dict(multiplier_1_modulus=m1, multiplier_1_angle_rad=a1, multiplier_2_modulus=m2,
                multiplier_2_angle_rad=a2)


def as_lattice(edges):
    """Edges (a, b, axis) as lubjoint.study.cases puts the file's /lattice in attrs["lattice"]."""
    edges = sorted(edges)
    return {"case_a": np.array([e[0] for e in edges], dtype=np.int64),
            "case_b": np.array([e[1] for e in edges], dtype=np.int64), "axis": np.array([e[2] for e in edges], dtype=str)}


def table(*rows, multipliers=True):
    """A /cases table as lubjoint.study.cases gives it: index case id, attrs axes, units, the
    classifications with and without an orbit, and the lattice (here by the definition, as
    lubsweep writes it: every numeric column of the rows that is an axis, offset_m too)."""
    full = []
    for r in rows:
        cls = r.get("classification", "periodic" if r.get("multiplier_1_modulus", 0.0) < 1.0 else "periodic_unstable")
        full.append({**BASE, **(mult(NAN, NAN) if multipliers else {}), **r, "classification": cls})
    df = pd.DataFrame(full)
    df.index.name = "case"
    lattice = brute_force_neighbours(df, AXES + [a for a in ("offset_m",) if a in df])
    df.attrs = {"axes": np.array(AXES), "units": dict(UNITS), "orbit_classifications": np.array(ORBIT),
                "no_orbit_classifications": np.array(NO_ORBIT), "lattice": as_lattice(lattice)}
    return df


def only_edge(df):
    e = study.bifurcation_edges(df)
    assert len(e) == 1, e
    return e.iloc[0]


def test_a_real_multiplier_through_plus_one_is_a_fold_crossing_where_log_interpolation_says():
    # |mu|max - 1 goes from -0.1 at 0.1 Pa s to +0.2 at 0.4 Pa s: linear in ln(mu_visc), it is
    # 0 a third of the way, ln x = ln 0.1 + (1/3) ln 4, x = 0.1 * 4^(1/3) = 0.15874 Pa s.
    e = only_edge(table({"viscosity_Pa_s": 0.1, **mult(0.9, 0.0, 0.5, 0.0)},
                        {"viscosity_Pa_s": 0.4, **mult(1.2, 0.0, 0.5, 0.0)}))
    assert (e.case_a, e.case_b, e.axis, e.axis_unit, e.kind) == (0, 1, "viscosity_Pa_s", "Pa s", "fold")
    assert (e.value_a, e.value_b, e.mu_a, e.mu_b) == (0.1, 0.4, 0.9, 1.2)
    # Two routes to the same number (the rounding of exp/log: a few ulps).
    assert e.crossing_value == pytest.approx(0.1 * 4.0 ** (1.0 / 3.0), rel=1e-14)
    assert e.crossing_value == pytest.approx(0.158740105196820, rel=1e-14)
    assert e.both_ends_agree


def test_a_real_multiplier_through_minus_one_is_period_doubling_whichever_end_is_unstable():
    # The unstable end is the lower clearance here (case_a); std::arg gives pi or -pi for a
    # negative real number, both are period doubling.
    for angle in (math.pi, -math.pi):
        e = only_edge(table({"clearance_m": 1e-4, **mult(1.05, angle)}, {"clearance_m": 2e-4, **mult(0.95, angle)}))
        assert (e.kind, e.axis, e.case_a, e.case_b, e.angle_rad) == ("period_doubling", "clearance_m", 0, 1, angle)
        # f = +0.05 at 1e-4 m, -0.05 at 2e-4 m: halfway in the log, the geometric mean.
        assert e.crossing_value == pytest.approx(math.sqrt(1e-4 * 2e-4), rel=1e-14)


def test_a_complex_pair_through_the_unit_circle_is_neimark_sacker():
    e = only_edge(table({"speed_rpm": 2500.0, **mult(0.98, 0.7, 0.98, -0.7)},
                        {"speed_rpm": 5000.0, **mult(1.02, 0.8, 1.02, -0.8)}))
    assert (e.kind, e.axis, e.angle_rad) == ("neimark_sacker", "speed_rpm", 0.8)
    assert e.both_ends_agree
    assert 2500.0 < e.crossing_value < 5000.0


def test_an_angle_with_no_conjugate_partner_is_unclassified_and_a_disagreeing_end_is_flagged():
    # Unstable end: angle 0.8 but multiplier 2 of another modulus (not a real matrix's pair).
    e = only_edge(table({"speed_rpm": 2500.0, **mult(0.98, 0.0, 0.5, 0.0)},
                        {"speed_rpm": 5000.0, **mult(1.02, 0.8, 0.9, -0.8)}))
    assert e.kind == "unclassified" and not e.both_ends_agree
    # Same modulus, but not the conjugate angle: unclassified too.
    e = only_edge(table({"speed_rpm": 2500.0, **mult(0.98, 0.0, 0.5, 0.0)},
                        {"speed_rpm": 5000.0, **mult(1.02, 0.8, 1.02, 0.3)}))
    assert e.kind == "unclassified"
    # A fold whose stable end is dominated by a complex pair: labelled from the unstable end.
    e = only_edge(table({"speed_rpm": 2500.0, **mult(0.98, 0.5, 0.98, -0.5)},
                        {"speed_rpm": 5000.0, **mult(1.02, 0.0, 0.9, 0.5)}))
    assert e.kind == "fold" and not e.both_ends_agree


def test_an_orbit_at_one_end_and_none_at_the_other_is_an_orbit_lost_edge_without_crossing():
    for other in ("drifting", "not_converged", "film_collapse", "solver_failure", "budget_exceeded"):
        e = only_edge(table({"speed_rpm": 50.0, "classification": other},
                            {"speed_rpm": 500.0, **mult(0.9, 0.0)}))
        assert (e.kind, e.class_a, e.class_b, e.case_a, e.case_b) == ("orbit_lost", other, "periodic", 0, 1)
        assert math.isnan(e.crossing_value) and math.isnan(e.mu_a) and e.mu_b == 0.9
    # A case that did not run says nothing about the journal: no edge.
    for other in ("not_run", "invalid_scene", "error"):
        assert study.bifurcation_edges(table({"speed_rpm": 50.0, "classification": other},
                                             {"speed_rpm": 500.0, **mult(0.9, 0.0)})).empty


def test_ends_of_equal_stability_or_without_multipliers_give_no_edge():
    for m in ((0.8, 0.95), (1.1, 1.3), (0.9, NAN)):
        e = study.bifurcation_edges(table({"viscosity_Pa_s": 0.1, **mult(m[0], 0.0)},
                                          {"viscosity_Pa_s": 0.4, **mult(m[1], 0.0)}))
        assert e.empty and list(e.columns) == COLUMNS
    # Two cells without an orbit: nothing to say.
    assert study.bifurcation_edges(table({"viscosity_Pa_s": 0.1, "classification": "drifting"},
                                         {"viscosity_Pa_s": 0.4, "classification": "film_collapse"})).empty


def test_only_lattice_neighbours_are_edges():
    # Levels of viscosity over the study: 0.1, 0.2, 0.4. Pinkus-Sternlicht has 0.1 and 0.4
    # (two levels apart: not neighbours); Frene long has 0.2 and 0.4 (neighbours); 0.1 of
    # one law and 0.2 of the other differ in the law (a categorical axis: never an edge);
    # the last pair differs on two axes.
    df = table({"viscosity_Pa_s": 0.1, **mult(0.9, 0.0)}, {"viscosity_Pa_s": 0.4, **mult(1.1, 0.0)},
               {"viscosity_Pa_s": 0.2, "force_law": "frene_long", **mult(0.9, 0.0)},
               {"viscosity_Pa_s": 0.4, "force_law": "frene_long", **mult(1.1, 0.0)},
               {"viscosity_Pa_s": 0.2, "clearance_m": 1e-4, **mult(1.1, 0.0)})
    e = study.bifurcation_edges(df)
    assert [(r.case_a, r.case_b) for r in e.itertuples()] == [(2, 3)]


def brute_force_neighbours(df, axes):
    """Neighbours by the definition, pair by pair: equal on every axis but one numeric axis,
    whose two values are consecutive in that axis's sorted distinct values."""
    levels = {a: sorted(set(df[a].dropna())) for a in axes if df[a].dtype.kind == "f"}
    same = lambda a, i, j: df.at[i, a] == df.at[j, a] or (a in levels and np.isnan(df.at[i, a]) and np.isnan(df.at[j, a]))
    out = set()
    for i, j in itertools.combinations(df.index, 2):
        diff = [a for a in axes if not same(a, i, j)]
        if len(diff) == 1 and diff[0] in levels and not np.isnan(df.at[i, diff[0]]) and not np.isnan(df.at[j, diff[0]]):
            a = diff[0]
            lo, hi = sorted((i, j), key=lambda k: df.at[k, a])
            if levels[a].index(df.at[hi, a]) - levels[a].index(df.at[lo, a]) == 1:
                out.add((lo, hi, a))
    return out


def test_the_neighbours_are_the_files_lattice_along_the_axes_asked_of_the_cases_present():
    # The lattice is lubsweep's (/lattice; its definition is tested in C++,
    # ContinuationTree.TheLatticeOfAFullFactorialEqualsThePairwiseDefinition): read, not
    # recomputed. Here the file's word is obeyed even where it is not the definition.
    df = table({"viscosity_Pa_s": 0.1, **mult(0.9, 0.0)}, {"viscosity_Pa_s": 0.2, **mult(0.95, 0.0)},
               {"viscosity_Pa_s": 0.4, **mult(1.1, 0.0)})
    assert lattice_edges(df, AXES) == [(0, 1, "viscosity_Pa_s"), (1, 2, "viscosity_Pa_s")]
    df.attrs["lattice"] = as_lattice([(0, 2, "viscosity_Pa_s"), (2, 7, "viscosity_Pa_s"), (1, 2, "speed_rpm")])
    assert lattice_edges(df, AXES) == [(0, 2, "viscosity_Pa_s"), (1, 2, "speed_rpm")]  # case 7 is not a row
    assert lattice_edges(df, ["viscosity_Pa_s"]) == [(0, 2, "viscosity_Pa_s")]
    e = only_edge(df.loc[[0, 2]])  # a subset keeps its attrs: the file's edges between its rows
    assert (e.case_a, e.case_b, e.kind) == (0, 2, "fold")


def test_which_classifications_carry_an_orbit_is_the_files_word():
    # An orbit at one end and none at the other is an orbit_lost edge by the file's lists:
    # told that periodic_unstable is no orbit, a periodic/periodic_unstable pair is one.
    pair = lambda: table({"speed_rpm": 50.0, "classification": "periodic_unstable"},
                         {"speed_rpm": 500.0, "classification": "periodic"}, multipliers=False)
    assert study.bifurcation_edges(pair()).empty
    df = pair()
    df.attrs["orbit_classifications"] = np.array(["periodic"])
    df.attrs["no_orbit_classifications"] = np.array(["periodic_unstable"])
    assert list(study.bifurcation_edges(df).kind) == ["orbit_lost"]
    assert study.orbit_classifications(df) == ("periodic",)
    # A table without the file's word (a study file written before lubsweep wrote it) is
    # refused, naming what is missing and what to do.
    for name in ("orbit_classifications", "no_orbit_classifications", "lattice"):
        df = pair()
        del df.attrs[name]
        with pytest.raises(study.StudyFormatError, match=f"{name}.*re-run the sweep"):
            study.bifurcation_edges(df)


def test_a_non_positive_axis_value_is_interpolated_linearly():
    df = table({"offset_m": 0.0, **mult(0.5, 0.0)}, {"offset_m": 1e-3, **mult(1.5, 0.0)})
    e = study.bifurcation_edges(df, axes=AXES + ["offset_m"]).iloc[0]
    assert e.crossing_value == pytest.approx(0.5e-3, rel=1e-14) and e.axis_unit == ""


def test_units_and_axes_are_said_and_missing_axes_are_refused():
    e = study.bifurcation_edges(table({"viscosity_Pa_s": 0.1, **mult(0.9, 0.0)},
                                      {"viscosity_Pa_s": 0.4, **mult(1.2, 0.0)}))
    u = e.attrs["units"]
    assert (u["mu_a"], u["angle_rad"], u["crossing_value"]) == ("1", "rad", "axis_unit")
    df = table({"viscosity_Pa_s": 0.1})
    df.attrs = {}
    with pytest.raises(ValueError, match="no attrs\\['axes'\\]"):
        study.bifurcation_edges(df)
    with pytest.raises(ValueError, match="journal_radius_m"):
        study.bifurcation_edges(df, axes=["journal_radius_m"])


def test_a_study_without_multiplier_columns_has_only_orbit_lost_edges():
    df = table({"speed_rpm": 50.0, "classification": "drifting"}, {"speed_rpm": 500.0, "classification": "periodic"},
               {"speed_rpm": 5000.0, "classification": "periodic"}, multipliers=False)
    assert "multiplier_1_modulus" not in df
    e = study.bifurcation_edges(df)
    assert list(e.kind) == ["orbit_lost"] and (e.case_a[0], e.case_b[0]) == (0, 1)


# --- the classification map -----------------------------------------------------------------


@pytest.fixture(scope="module")
def plot_steady():
    path = Path(__file__).resolve().parents[2] / "tools" / "plot" / "steady.py"
    spec = importlib.util.spec_from_file_location("plot_steady", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_the_mark_sits_where_the_crossing_was_interpolated(plot_steady):
    e = only_edge(table({"viscosity_Pa_s": 0.1, **mult(0.9, 0.0)}, {"viscosity_Pa_s": 0.4, **mult(1.2, 0.0)}))
    assert plot_steady.edge_fraction(e) == pytest.approx(1.0 / 3.0, rel=1e-12)
    lost = only_edge(table({"viscosity_Pa_s": 0.1, "classification": "drifting"},
                           {"viscosity_Pa_s": 0.4, **mult(0.9, 0.0)}))
    assert plot_steady.edge_fraction(lost) == 0.5


def classification_map(plot_steady, df, out):
    from matplotlib.colors import BoundaryNorm, ListedColormap
    n = len(plot_steady.CLASSES)
    norm = BoundaryNorm(np.arange(n + 1) - 0.5, n)
    value = lambda r: plot_steady.CLASSES.index(r["classification"])
    edges = study.bifurcation_edges(df)
    plot_steady.grid_panels(df, value, "test", out, cmap=ListedColormap(plot_steady.COLOURS), norm=norm,
                            categorical=True, edges=edges)
    return edges


def test_the_map_draws_every_kind_of_edge_in_and_between_panels(plot_steady, tmp_path, monkeypatch):
    # A 2 x 2 cell panel at each of two speeds: a fold along the viscosity, PD along the
    # clearance, NS along the speed (between panels), an orbit lost.
    rows = [
        {"clearance_m": 1e-4, "viscosity_Pa_s": 0.1, "speed_rpm": 500.0, **mult(0.9, 0.0)},
        {"clearance_m": 1e-4, "viscosity_Pa_s": 0.4, "speed_rpm": 500.0, **mult(1.1, 0.0)},
        {"clearance_m": 2e-4, "viscosity_Pa_s": 0.1, "speed_rpm": 500.0, **mult(1.2, math.pi)},
        {"clearance_m": 2e-4, "viscosity_Pa_s": 0.4, "speed_rpm": 500.0, "classification": "drifting"},
        {"clearance_m": 1e-4, "viscosity_Pa_s": 0.1, "speed_rpm": 5000.0, **mult(1.05, 0.6, 1.05, -0.6)},
    ]
    df = table(*rows)
    texts = []
    import matplotlib.axes
    real = matplotlib.axes.Axes.text
    monkeypatch.setattr(matplotlib.axes.Axes, "text",
                        lambda ax, x, y, s, **kw: texts.append(s) or real(ax, x, y, s, **kw))
    edges = classification_map(plot_steady, df, tmp_path / "map.png")
    assert sorted(edges.kind) == sorted(["fold", "period_doubling", "neimark_sacker", "orbit_lost", "orbit_lost"])
    # One letter per edge in a panel, two for the edge between panels (one in each, its arrow
    # toward the other: 5000 rpm is the panel to the left).
    assert sorted(texts) == sorted(["F", "PD", "X", "X", "\u2190NS", "NS\u2192"])
    assert (tmp_path / "map.png").stat().st_size > 0


def test_the_map_of_a_study_without_multipliers_is_drawn_as_before(plot_steady, tmp_path):
    rows = [{"clearance_m": c, "viscosity_Pa_s": v, "classification": "periodic"}
            for c in (1e-4, 2e-4) for v in (0.1, 0.4)]
    edges = classification_map(plot_steady, table(*rows, multipliers=False), tmp_path / "map.png")
    assert edges.empty and (tmp_path / "map.png").stat().st_size > 0


# --- the chain on a study lubsweep writes ----------------------------------------------------


def test_the_chain_on_a_two_cell_continuation_study(plot_steady, tmp_path):
    # Frene long at 0.5 and 0.2 mm, continued (a few seconds): the multipliers come from
    # lubsweep, the edge from bifurcation_edges, the marks from plot_steady. Whether |mu|max
    # crosses 1 between them is the physics' answer (at this build: 0.998 and 1.0001, a
    # complex pair: Neimark-Sacker); the test checks the edge against the /cases columns by
    # hand either way.
    import json
    import os
    import subprocess
    build = Path(os.environ.get("LUB_BUILD_DIR", Path(__file__).resolve().parents[2] / "build"))
    lubsweep = build / "sweep" / "lubsweep"
    if not lubsweep.exists():
        pytest.skip(f"no {lubsweep} (build lubsweep)")
    source = Path(__file__).resolve().parents[2]
    grid = {"scene": str(source / "configs" / "scenes" / "slider_crank.json"), "joint": "rod_slider",
            "driver": "crank_speed",
            "set": {"/solver/formulation": "partitioned", "/simulation/steady": "continuation"},
            "study": {"max_cycles": 40, "stop_when_steady": True, "steady_tolerance": 0.001, "metric_cycles": 2,
                      "channels": [], "on_failure": "continue"},
            "axes": [{"name": "clearance_m", "values": [0.0005, 0.0002]}, {"name": "viscosity_Pa_s", "values": [0.4]},
                     {"name": "speed_rpm", "values": [5000]}, {"name": "force_law", "values": ["frene_long"]}]}
    (tmp_path / "grid.json").write_text(json.dumps(grid))
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}
    p = subprocess.run([str(lubsweep), str(tmp_path / "grid.json"), "-o", str(tmp_path / "study.h5"), "-q",
                        "--no-summary"], capture_output=True, text=True, env=env, timeout=300)
    assert p.returncode == 0, p.stderr
    cases = study.cases(tmp_path / "study.h5")
    assert sorted(cases["continued_from"]) == [-1, 1]  # the 0.2 mm cell is the seed (largest mu omega / c^2)
    edges = classification_map(plot_steady, cases, tmp_path / "map.png")
    mu = cases["multiplier_1_modulus"]
    assert mu.notna().all()
    if (mu[0] - 1.0) * (mu[1] - 1.0) > 0:
        assert edges.empty
        return
    e = edges.iloc[0]
    assert len(edges) == 1 and (e.case_a, e.case_b, e.axis) == (1, 0, "clearance_m")
    u = cases.loc[0 if mu[0] > 1 else 1]
    # The rule with its tolerances (1e-3 rad, 1e-6 relative: bifurcation_edges' docstring).
    angle = u["multiplier_1_angle_rad"]
    pair = (abs(u["multiplier_2_modulus"] / u["multiplier_1_modulus"] - 1.0) <= 1e-6
            and abs(u["multiplier_2_angle_rad"] + angle) <= 1e-3)
    expected = ("fold" if abs(angle) <= 1e-3 else "period_doubling" if abs(angle) >= math.pi - 1e-3
                else "neimark_sacker" if pair else "unclassified")
    assert e.kind == expected
    # |mu| - 1 linear in ln c between (ln 0.2 mm, mu[1] - 1) and (ln 0.5 mm, mu[0] - 1).
    t = (mu[1] - 1.0) / (mu[1] - mu[0])
    assert e.crossing_value == pytest.approx(2e-4 * (5e-4 / 2e-4) ** t, rel=1e-12)
    assert (tmp_path / "map.png").stat().st_size > 0
