"""Boundaries located between a study's grid points (lubjoint.boundaries, issue 44), on the
paper grid's study (the nightly_paper fixture): the printed law at 0.5 mm and 5000 rpm
crosses the safe film between 0.1 and 0.2 Pa s, the located viscosity against a bisection
of separate runs (each its own steady stage), to issue 44's 0.5 %; at 0.4 Pa s its stable safe
orbit turns unstable between 500 and 50 rpm, the located fold against continuation with halved
steps on either side; a run continued from a case's orbit locates that orbit, and a single
Newton stalled at the map's noise is located anyway; on a small Frene long study, stability
crossings along two axes lie on one similarity line."""
import math
import warnings

import pytest

import lubjoint
from lubjoint import boundaries


@pytest.fixture(scope="module")
def found(paper_study):
    """The paper study's safe-film boundaries, located once for the tests that read them."""
    return boundaries.safe_film_boundaries(lubjoint.load_study(paper_study))


def one_row(found, **where):
    rows = found
    for column, value in where.items():
        rows = rows[rows[column] == value]
    assert len(rows) == 1, found
    return rows.iloc[0]


def test_the_safe_film_viscosity_matches_a_bisection_of_separate_runs(paper_study, found):
    row = one_row(found, axis="viscosity_Pa_s", force_law="pinkus_sternlicht")
    assert row["converged"] and row["unit"] == "Pa s" and row["kind"] == "safe_film"
    assert 0.1 < row["value"] < 0.2 and row["error"] < 5e-3 * row["value"]
    scene = lubjoint.study.scene(paper_study, int(row["case_a"]))

    def gap(mu):  # h_min − safe film of the case's scene at viscosity mu, its own orbit
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ds = lubjoint.simulate(scene, {"/joints/3/viscosity_Pa_s": mu, "/outputs/channels": []})
        assert ds.attrs["classification"] == "periodic", ds.attrs["message"]
        return float(ds["min_film_thickness_m"]) - float(ds["safe_film_thickness_m"])

    lo, hi = 0.1, 0.2
    assert gap(lo) < 0 < gap(hi)
    while hi - lo > 1e-3 * lo:  # to 0.1 %: five times finer than the bound below
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if gap(mid) < 0 else (lo, mid)
    assert row["value"] == pytest.approx(0.5 * (lo + hi), rel=5e-3)


def test_the_boundaries_are_stored_in_the_study_file_and_the_summary_prints_them(paper_study, build_dir, tmp_path):
    # The command a user runs: locate, store as /boundaries, print; then lubsweep --summary.
    import os
    import shutil
    import subprocess
    import sys

    copy = tmp_path / "study.h5"
    shutil.copy(paper_study, copy)
    env = {**os.environ, "PYTHONPATH": str(build_dir / "python")}
    done = subprocess.run([sys.executable, "-m", "lubjoint.boundaries", str(copy)], env=env, capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr
    assert "safe_film: viscosity_Pa_s = 0.18" in done.stdout, done.stdout
    table = boundaries.read(copy)
    rows = table[table["kind"] == "safe_film"]
    assert len(rows) == 1 and rows.iloc[0]["unit"] == "Pa s" and rows.iloc[0]["force_law"] == "pinkus_sternlicht"
    assert 0.1 < rows.iloc[0]["value"] < 0.2 and bool(rows.iloc[0]["converged"])
    # A converged row has no reason; one that is not says why (the unit test below).
    assert (table.loc[table["converged"], "reason"] == "").all()
    summary = subprocess.run([str(build_dir / "sweep" / "lubsweep"), "--summary", str(copy)], capture_output=True,
                             text=True)
    assert summary.returncode == 0, summary.stderr
    assert "boundaries located between grid points" in summary.stdout
    line = next(s for s in summary.stdout.splitlines() if "safe_film: viscosity_Pa_s" in s)
    assert "between cases" in line and "force_law = pinkus_sternlicht" in line, line
    # The edge's row says how the safe orbit was lost, in the file and the summary.
    edge = table[table["edge"]].iloc[0]
    assert edge["kind"] == "fold" and edge["lost"].startswith("periodic_unstable"), edge
    line = next(s for s in summary.stdout.splitlines() if "fold: speed_rpm" in s)
    assert line.endswith("; the safe orbit turns unstable)"), line
    # A row that has not converged: the summary says why, from the file's reason column.
    unsure = table.copy()
    unsure.loc[unsure["kind"] == "safe_film", ["converged", "reason"]] = [False, "no orbit located at 0.15 Pa s"]
    boundaries.write(copy, unsure)
    summary = subprocess.run([str(build_dir / "sweep" / "lubsweep"), "--summary", str(copy)], capture_output=True,
                             text=True)
    line = next(s for s in summary.stdout.splitlines() if "safe_film: viscosity_Pa_s" in s)
    assert line.endswith(", not converged: no orbit located at 0.15 Pa s"), line
    boundaries.write(copy, table)
    # Bad input: exit 2, the file named, nothing created.
    missing = tmp_path / "nope.h5"
    bad = subprocess.run([sys.executable, "-m", "lubjoint.boundaries", str(missing)], env=env, capture_output=True,
                         text=True)
    assert bad.returncode == 2 and "nope.h5" in bad.stderr, bad.stderr
    assert not missing.exists()
    before = copy.read_bytes()
    bad = subprocess.run([sys.executable, "-m", "lubjoint.boundaries", str(copy), "--kinds", "safe_film,fold"], env=env,
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "--kinds = safe_film,fold: fold is not one of" in bad.stderr, bad.stderr
    assert copy.read_bytes() == before


def test_only_the_kinds_asked_for_are_located(paper_study, found):
    # The orbit's edge is most of what the paper study's boundaries cost: asked for the
    # safe-film boundaries alone, the same row, and none of the edge's runs.
    only = boundaries.locate(lubjoint.load_study(paper_study), kinds=("safe_film",))
    assert list(only["kind"]) == ["safe_film"]
    assert only.iloc[0]["value"] == one_row(found, kind="safe_film")["value"]
    assert only["runs"].sum() < found["runs"].sum()
    with pytest.raises(ValueError, match="kinds: 'fold'"):
        boundaries.locate(lubjoint.load_study(paper_study), kinds=("fold",))
    # The edges' former name asks for every edge, whatever kind each row turns out to be.
    assert boundaries.asked(("orbit_end", "stability")) == ("edge", "stability")


@pytest.mark.parametrize("angle, kind", [(0.0, "fold"), (3.14159265, "period_doubling"), (1.2, "neimark_sacker")])
def test_a_stability_crossing_is_located_by_regula_falsi_and_named(angle, kind):
    # |mu|max - 1 = k ln(lambda / lambda*), a straight line in the logarithm, curved by a
    # square: the crossing at lambda* = 0.137 to 0.5 % within the runs allowed, and its
    # kind from the unstable end's multiplier.
    import math

    class Line:
        runs = 0

        def __call__(self, value):
            self.runs += 1
            u = math.log(value / 0.137)
            return 2e-3 * u + 1e-3 * u * u, angle

    a, b = (0.1, *Line()(0.1)), (0.2, *Line()(0.2))
    line = Line()
    value, error, found_angle, runs, converged, ends = boundaries._falsi(line, a, b, 5e-3, 10)
    assert converged and runs <= 10
    assert value == pytest.approx(0.137, rel=5e-3) and error <= 5e-3 * value
    assert boundaries._kind(found_angle) == kind
    # The last bracket's ends with their own |mu|max - 1 (not Illinois' halved ones).
    (la, fa), (lb, fb) = ends
    assert min(la, lb) <= value <= max(la, lb) and fa * fb < 0
    assert fa == line(la)[0] and fb == line(lb)[0]


def test_a_crossing_that_does_not_converge_says_why():
    # Regula falsi where a run between the ends locates no orbit: it stops there, and the
    # row it makes names the value and the axis's unit; where the runs run out, it says so.
    import math

    class Line:
        runs = 0

        def __init__(self, lost_above=math.inf):
            self.lost_above = lost_above

        def __call__(self, value):
            self.runs += 1
            if value > self.lost_above:
                return None
            return 2e-3 * math.log(value / 0.137), 0.5

    a, b = (0.1, *Line()(0.1)), (0.2, *Line()(0.2))
    line = Line(lost_above=0.13)
    *_, converged, _ = boundaries._falsi(line, a, b, 5e-3, 10)
    assert not converged and line.why.startswith("no orbit located at 0.1")
    assert line.why.endswith("{unit}")  # _row puts the axis's unit there
    line = Line()
    *_, converged, _ = boundaries._falsi(line, a, b, 5e-3, 1)
    assert not converged and line.why == "not within 0.5 % of its value in 1 runs"
    # A bracket that met the tolerance, but not with its multipliers' accuracy added.
    assert boundaries._refined(0.01, 0.5) == "its multipliers at rtol/10 move it by 2 % of its value"
    assert boundaries._refined(float("inf"), 0.5) == "a bracket end run again at rtol/10 located no orbit"


def test_an_edge_where_the_safe_orbit_turns_unstable_gives_its_multipliers_at_both_ends():
    # A stable orbit whose dominant pair leaves the circle at lambda* = 1 (|mu| = lambda*/lambda,
    # angle 0.5): bisected from 2 towards 0.6, the edge is a Neimark-Sacker crossing at 1 to
    # 0.5 %, and the last bracket's ends carry |mu|max - 1 of the stable orbit above and of
    # the unstable one below, for the multipliers' error term.
    import xarray as xr

    class Line:
        runs = 0
        last = None

        def __call__(self, value, sensitivity=True):
            self.runs += 1
            mu = 1.0 / value
            self.last = xr.Dataset({"multiplier_1_modulus": mu, "multiplier_1_angle_rad": 0.5})
            self.last.attrs.update(classification="periodic" if mu < 1.0 else "periodic_unstable", message="")
            return (1e-6, 0.0, 1e-9) if mu < 1.0 else None

    line = Line()
    value, error, kind, converged, lost, ends = boundaries._edge(line, (2.0, 1e-6, 0.0), 0.6, 5e-3, 12, 0.5)
    assert kind == "neimark_sacker" and converged and lost.startswith("periodic_unstable")
    assert value == pytest.approx(1.0, rel=5e-3) and error <= 5e-3 * value
    (la, fa), (lb, fb) = ends
    assert lb <= 1.0 < la and fa == pytest.approx(1.0 / la - 1.0) and fb == pytest.approx(1.0 / lb - 1.0)
    # The multipliers' accuracy joins the error. Where the sum is above 0.5 % but a narrower
    # bracket meets it, the bisection goes on; where the accuracy alone exceeds it, no
    # bracket can: not converged.
    half = error  # the bracket's own half-width, at lambda ~ 1 (the allowed error: 5e-3 * value)
    for share in (0.5 * (5e-3 - half) / 5e-3, 0.8, 1.2):  # the term's share of the allowed error
        again = Line()
        v, e, _, c, _, _ = boundaries._edge(again, (2.0, 1e-6, 0.0), 0.6, 5e-3, 12, 0.5, lambda ends: share * 5e-3)
        more = half + share * 5e-3 > 5e-3 * value and share < 1.0
        assert (again.runs > line.runs) == more and c == (share < 1.0), (share, again.runs, line.runs)
        assert e >= share * 5e-3
        if c:
            assert e <= 5e-3 * v and v == pytest.approx(1.0, abs=e)


def test_an_edge_whose_film_reaches_the_safe_film_is_found_by_secant_steps_without_sensitivities():
    # The safe orbit's film gap (lambda - 1)(1 + 0.1 lambda) reaches zero at lambda = 1 before
    # the orbit is lost (below 0.7). Followed from 2 towards 0.5, the search steps along the
    # secant from the last safe orbit (the start's slope its own), asking no sensitivity
    # until an orbit below the safe film brackets the crossing; then Newton locates it.
    import xarray as xr

    class Line:
        runs = 0
        last = None
        asked = []

        def __call__(self, value, sensitivity=True):
            self.runs += 1
            self.asked.append(sensitivity)
            self.last = xr.Dataset({"multiplier_1_modulus": 0.5, "multiplier_1_angle_rad": 0.0})
            self.last.attrs.update(classification="periodic" if value >= 0.7 else "not_converged", message="")
            if value < 0.7:
                return None
            gap = (value - 1.0) * (1.0 + 0.1 * value)
            return gap, (0.9 + 0.2 * value) if sensitivity else math.nan, 1e-9

    line = Line()
    start = (2.0, 1.0 * 1.2, 1.3)
    value, error, kind, converged, lost, ends = boundaries._edge(line, start, 0.5, 5e-3, 12, 0.5)
    assert kind == "safe_film" and converged and ends is None
    assert value == pytest.approx(1.0, rel=5e-3) and error <= 5e-3 * value
    first_below = line.asked.index(True)  # sensitivities only once the crossing is bracketed
    assert first_below > 0 and not any(line.asked[:first_below])


def test_a_stability_crossings_error_includes_how_far_its_multipliers_move_on_refinement():
    # Ends of a bracket where |mu|max - 1 changes by 2e-4 over 0.01 of the axis; run again at
    # rtol/10 each multiplier moves by 1e-5 (the larger): the crossing moves by 1e-5 / slope =
    # 5e-4 of the axis. A refined run that locates no orbit leaves the error unknown.
    import xarray as xr

    class Line:
        scene = {"solver": {"rtol": 1e-8}}
        asked = []

        def __init__(self, shift, classification="periodic"):
            self.shift, self.classification = shift, classification

        def run(self, value, sensitivity=True, extra=None):
            self.asked.append(extra)
            f = 1e-4 if value > 1.0 else -1e-4
            ds = xr.Dataset({"multiplier_1_modulus": 1.0 + f + self.shift[value]})
            ds.attrs["classification"] = self.classification
            return ds

    ends = ((1.0, -1e-4), (1.01, 1e-4))
    assert boundaries._multiplier_error(Line({1.0: 5e-6, 1.01: -1e-5}), ends) == pytest.approx(5e-4)
    assert Line.asked == [{"/solver/rtol": 1e-9}] * 2
    assert boundaries._multiplier_error(Line({1.0: 0.0, 1.01: 0.0}, "not_converged"), ends) == float("inf")
    # Both ends far from the circle (a fold whose multiplier jumps from 0.77 to 4.7): the
    # crossing is inside the bracket whatever such errors, and nothing is run.
    Line.asked.clear()
    assert boundaries._multiplier_error(Line({}), ((1.0, -0.23), (1.01, 3.7))) == 0.0 and not Line.asked


def _scene_and_seed(path, case):
    return lubjoint.study.scene(path, case), lubjoint.study.orbit_seed_row(path, case)


def test_a_run_continued_from_a_cases_orbit_locates_that_orbit(paper_study):
    # The study's reference case continued to its own scene: the same orbit (its film within
    # the two error bars), for a fraction of the periods its steady stage took; the orbit
    # comes back packed for the next continuation. An empty seed is refused.
    cases = lubjoint.study.cases(paper_study)
    case = int(cases.index[(cases["force_law"] == "pinkus_sternlicht") & (cases["clearance_m"] == 5e-4)
                           & (cases["viscosity_Pa_s"] == 0.4) & (cases["speed_rpm"] == 5000.0)][0])
    scene, seed = _scene_and_seed(paper_study, case)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = lubjoint.simulate(scene, {"/outputs/channels": []}, continue_from=(scene, seed), single_step=True)
    row = cases.loc[case]
    assert ds.attrs["classification"] == "periodic", ds.attrs["message"]
    bars = float(ds["min_film_thickness_m_error"]) + row["min_film_thickness_m_error"]
    assert abs(float(ds["min_film_thickness_m"]) - row["min_film_thickness_m"]) <= bars
    assert int(ds["periods_integrated"]) < row["periods_integrated"]
    assert ds["orbit_seed"].size == len(seed)
    with pytest.raises(lubjoint.InputError, match="continue_from"):
        lubjoint.simulate(scene, continue_from=(scene, []))


def test_where_the_safe_orbit_turns_unstable_it_is_stable_on_one_side_only(paper_study, found):
    # The printed law at 0.5 mm and 0.4 Pa s: a safe orbit at 500 rpm, and at 50 rpm none (the
    # journal drifts onto the wall). Its real dominant multiplier grows as the speed falls and
    # jumps through +1 (0.77 to 4.7 within 0.1 rpm), where the orbit continued from it is
    # unstable: a fold to 0.5 %, not the end of the unstable orbit's branch a little lower.
    # By another route, continuation along the path with its steps halved where Newton fails
    # (not the single Newton the search used): from the 500 rpm orbit the orbit is stable two
    # error bars inside the value, and two beyond it unstable or not continued.
    row = one_row(found, edge=True, axis="speed_rpm")
    assert row["kind"] == "fold", row
    assert row["converged"] and 50.0 < row["value"] < 500.0 and row["error"] <= 5e-3 * row["value"]
    scene, seed = _scene_and_seed(paper_study, int(row["case_a"]))
    assert lubjoint.study.cases(paper_study).loc[int(row["case_a"]), "speed_rpm"] == 500.0

    def classification(rpm):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ds = lubjoint.simulate(scene, {"/drivers/0/speed_rpm": rpm, "/outputs/channels": []},
                                   continue_from=(scene, seed))
        return ds.attrs["classification"], ds.attrs["message"]

    inside = classification(row["value"] + 2.0 * row["error"])
    outside = classification(row["value"] - 2.0 * row["error"])
    assert inside[0] == "periodic", inside
    assert outside[0] == "periodic_unstable" or "was not continued" in outside[1], outside


def _continued_and_fresh(paper_study, at, there):
    """Frene long's scene of the paper study with ``at`` set: its orbit located by its own
    steady stage, then continued in one Newton to ``there`` (more settings), and the
    scene at ``there`` by its own steady stage."""
    import json

    cases = lubjoint.study.cases(paper_study)
    base = lubjoint.study.scene(paper_study, int(cases.index[cases["force_law"] == "frene_long"][0]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        start = lubjoint.simulate(base, {**at, "/outputs/channels": []})
        assert start.attrs["classification"] in ("periodic", "periodic_unstable"), start.attrs["message"]
        scene = json.loads(start.attrs["scene"])
        seed = [float(v) for v in start["orbit_seed"].values]
        continued = lubjoint.simulate(scene, {**there, "/outputs/channels": []}, continue_from=(scene, seed),
                                      single_step=True)
        fresh = lubjoint.simulate(base, {**at, **there, "/outputs/channels": []})
    for ds in (continued, fresh):
        assert ds.attrs["classification"] == "periodic_unstable", ds.attrs["message"]
        assert 1.0 < float(ds["multiplier_1_modulus"]) < 1.001
    # The same orbit: films within twice the two error bars (each bar an estimate, the
    # map's error at rtol against rtol/100, not a bound).
    bars = float(continued["min_film_thickness_m_error"]) + float(fresh["min_film_thickness_m_error"])
    assert abs(float(continued["min_film_thickness_m"]) - float(fresh["min_film_thickness_m"])) <= 2.0 * bars
    return continued


def test_a_single_step_stalled_at_the_maps_noise_is_located_where_it_moves_the_orbit_little(paper_study):
    # Frene long at 0.5 mm and 0.4 Pa s: at 2500 rpm a stable orbit whose dominant pair has
    # |mu| within 4e-4 of 1 at 0.48 rad (|1 - mu| ~ 0.5), at 2044 rpm, past its
    # Neimark-Sacker crossing, an unstable one. One Newton from the first to the second
    # stalls at the period map's noise, its residual above the 1e-6 Newton accepts; through
    # the first's monodromy that residual moves the orbit by ~1e-5 clearances, within a
    # tenth of steady_tolerance: located there, its error bars then measured. By another
    # route, the scene's own steady stage from its transient: the same orbit.
    continued = _continued_and_fresh(paper_study, {"/drivers/0/speed_rpm": 2500.0}, {"/drivers/0/speed_rpm": 2044.41})
    assert float(continued["orbit_residual"]) > 1e-6


def test_a_single_step_stalled_where_it_would_move_the_orbit_far_is_retried_on_tighter_periods(paper_study):
    # Frene long at 0.2 mm, 2500 rpm and 0.2 Pa s: an unstable orbit whose dominant pair
    # leaves the circle at 0.018 rad (|1 - mu| ~ 0.018). One Newton to 0.2017 Pa s stalls
    # at residual ~3e-5, which moves that orbit by ~2e-3 clearances, more than
    # steady_tolerance: not accepted. Once more on periods at rtol/10 it gets well below
    # that stall (to the tighter map's noise, where its line search stops) and is located
    # there: the orbit the scene's own steady stage finds.
    at = {"/joints/3/journal_radius_m": 0.0098, "/drivers/0/speed_rpm": 2500.0, "/joints/3/viscosity_Pa_s": 0.2}
    continued = _continued_and_fresh(paper_study, at, {"/joints/3/viscosity_Pa_s": 0.2017})
    assert float(continued["orbit_residual"]) < 1e-5


def test_stability_crossings_along_two_axes_lie_on_one_similarity_line(source_dir, build_dir, tmp_path):
    # Frene long at 0.5 mm (tests/mpi/stability_grid.json): its orbit turns unstable between
    # 0.4 and 0.2 Pa s at 5000 rpm and between 5000 and 2500 rpm at 0.2 Pa s. Each crossing
    # is located by runs continued from the nearest orbit on its line, converged to 0.5 %,
    # a Neimark-Sacker pair. By another route: the inertia loads scale as N^2 and the film's
    # force as mu N, so (gravity aside) the orbit depends on mu/N alone, and the two
    # crossings must give one mu*/N*: within 1.5 % (each value to 0.5 %, and the multipliers'
    # own accuracy, |mu| - 1 known to ~1e-5 where it changes by ~1e-6 per rpm).
    import os
    import shutil
    import subprocess

    mpirun = shutil.which("mpirun")
    if not mpirun:
        pytest.skip("no mpirun")
    path = tmp_path / "study.h5"
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}
    done = subprocess.run([mpirun, "--oversubscribe", "-np", "1", str(build_dir / "sweep" / "lubsweep"),
                           str(source_dir / "tests" / "mpi" / "stability_grid.json"), "-o", str(path), "-q",
                           "--no-summary"], capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        found = boundaries.stability_boundaries(lubjoint.load_study(path))
    assert sorted(found["axis"]) == ["speed_rpm", "viscosity_Pa_s"], found
    assert found["converged"].all() and (found["kind"] == "neimark_sacker").all(), found
    assert (found["error"] <= 5e-3 * found["value"]).all(), found
    viscosity, speed = one_row(found, axis="viscosity_Pa_s"), one_row(found, axis="speed_rpm")
    mu, speed_mu = viscosity["value"] / 5000.0, 0.2 / speed["value"]
    assert mu == pytest.approx(speed_mu, rel=1.5e-2)
