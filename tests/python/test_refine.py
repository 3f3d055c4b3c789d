"""lubsweep refine (issue 44, deliverable 4) on a three-case study (tests/mpi/refine_grid.json:
the printed law at 0.5 mm and 5000 rpm, viscosities 0.1, 0.2 and 0.4 Pa s, the lowest below
the safe film): which edge it picks and where, the budget, the rounds, resuming without
running a case again, -np 1 against -np 2, bad input, and the readers (lubjoint, --summary).
The study is swept once per session (a few seconds); each test refines its own copy."""
import hashlib
import math
import os
import re
import shutil
import subprocess

import h5py
import numpy as np
import pytest

import lubjoint

#: The refinement's columns that say who ran a case and how long it took: the only ones
#: allowed to differ between runs on other numbers of ranks.
RUN_COLUMNS = {"rank", "wall_time_s"}


def _env():
    return {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


def _mpirun():
    found = shutil.which("mpirun")
    if not found:
        pytest.skip("no mpirun")
    return found


def lubsweep(build_dir, *args, ranks=2, env=None):
    cmd = [_mpirun(), "--oversubscribe", "-np", str(ranks), str(build_dir / "sweep" / "lubsweep"), *map(str, args)]
    return subprocess.run(cmd, capture_output=True, text=True, env={**_env(), **(env or {})}, timeout=120)


@pytest.fixture(scope="module")
def study(source_dir, build_dir, tmp_path_factory):
    path = tmp_path_factory.mktemp("refine") / "study.h5"
    done = lubsweep(build_dir, source_dir / "tests" / "mpi" / "refine_grid.json", "-o", path, "-q", "--no-summary")
    assert done.returncode == 0, done.stderr
    return path


@pytest.fixture
def copy(study, tmp_path):
    path = tmp_path / "study.h5"
    shutil.copy(study, path)
    return path


def md5(path):
    return hashlib.md5(path.read_bytes()).hexdigest()


def table(path, group="refinement/cases"):
    """A table group's columns as numpy arrays (strings decoded)."""
    with h5py.File(path, "r") as f:
        g = f[group]
        return {n: (g[n].asstr()[()] if h5py.check_string_dtype(g[n].dtype) else g[n][()]) for n in g.attrs["columns"]}


def new_lines(stderr):
    """The progress lines of the cases a run computed."""
    return [line for line in stderr.splitlines() if re.match(r"lubsweep: \[\s*\d+/\d+\] case_", line)]


def test_the_edge_whose_below_safe_film_differs_is_refined_at_its_geometric_midpoint(copy, build_dir):
    cases = lubjoint.study.cases(copy)
    assert list(cases["below_safe_film"]) == [1, 0, 0], cases["min_film_thickness_m"]  # the grid's premise
    with h5py.File(copy, "r") as f:
        before = {n: f[n][()] for n in ("lattice/case_a", "lattice/case_b", "cases/min_film_thickness_m")}
    done = lubsweep(build_dir, "refine", copy, "--budget", 1)
    assert done.returncode == 0, done.stderr
    rows = lubjoint.study.cases(copy, group="refinement")
    assert list(rows.index) == [3]  # ids continue the study's
    row = rows.loc[3]
    assert (row["case_a"], row["case_b"], row["axis"], row["round"]) == (0, 1, "viscosity_Pa_s", 0)
    assert row["reason"] == "below_safe_film" and row["score"] == 1.0
    # 0.1, 0.2, 0.4 are spaced by a factor: the geometric mean, in the column and the scene.
    assert row["viscosity_Pa_s"] == math.sqrt(0.1 * 0.2)
    assert lubjoint.study.scene(copy, 3)["joints"][3]["viscosity_Pa_s"] == math.sqrt(0.1 * 0.2)
    assert rows.attrs["units"]["viscosity_Pa_s"] == "Pa s" and rows.attrs["units"]["min_film_thickness_m"] == "m"
    assert row["status"] == "ok" and row["classification"] == "periodic"
    with h5py.File(copy, "r") as f:  # the study's own groups as they were
        for name, value in before.items():
            assert np.array_equal(f[name][()], value), name
    summary = subprocess.run([str(build_dir / "sweep" / "lubsweep"), "--summary", str(copy)], capture_output=True,
                             text=True)
    assert summary.returncode == 0, summary.stderr
    assert "refinement: 1 cases between lattice neighbours" in summary.stdout
    line = next(s for s in summary.stdout.splitlines() if s.startswith("case_0003"))
    assert "0-1" in line and "below_safe_film" in line and "0.141421" in line, line


def test_rerunning_the_sweep_keeps_the_refinement_and_the_boundaries_of_its_grid(copy, build_dir, source_dir):
    # A re-run of the complete study (the README's study command does it) rewrites the file:
    # what lubsweep refine and lubjoint.boundaries added stays, row for row. A grid with
    # another case drops them and says so, even with -q.
    assert lubsweep(build_dir, "refine", copy, "--budget", 1).returncode == 0
    from lubjoint import boundaries

    boundaries.write(copy, boundaries.safe_film_boundaries(lubjoint.load_study(copy)))
    before = (table(copy), table(copy, "boundaries"))
    grid = source_dir / "tests" / "mpi" / "refine_grid.json"
    again = lubsweep(build_dir, grid, "-o", copy, "-q", "--no-summary")
    assert again.returncode == 0, again.stderr
    for old, new in zip(before, (table(copy), table(copy, "boundaries"))):
        assert old.keys() == new.keys()
        for name in old:
            assert np.array_equal(old[name], new[name], equal_nan=old[name].dtype.kind == "f"), name
    import json

    doc = json.loads(grid.read_text())
    doc["scene"] = str((grid.parent / doc["scene"]).resolve())
    doc["axes"][0]["values"].append(0.8)
    other = copy.parent / "other.json"
    other.write_text(json.dumps(doc))
    grown = lubsweep(build_dir, other, "-o", copy, "-q", "--no-summary")
    assert grown.returncode == 0, grown.stderr
    assert "/refinement, /boundaries belong to its earlier cases" in grown.stderr, grown.stderr
    with h5py.File(copy, "r") as f:
        assert "refinement" not in f and "boundaries" not in f


def test_rounds_stay_in_the_budget_and_a_killed_run_resumes_without_running_a_case_again(copy, build_dir):
    killed = lubsweep(build_dir, "refine", copy, "--budget", 3, env={"LUBSWEEP_TEST_KILL_AFTER": "1"})
    assert killed.returncode != 0
    first = table(copy)
    assert list(first["case"]) == [3]
    resumed = lubsweep(build_dir, "refine", copy, "--budget", 3)
    assert resumed.returncode == 0, resumed.stderr
    assert "/refinement/cases holds 1" in resumed.stderr
    assert len(new_lines(resumed.stderr)) == 2  # case 3 not run again
    rows = table(copy)
    assert list(rows["case"]) == [3, 4, 5]  # the budget: 3, in id order
    for name in ("wall_time_s", "rank", "periods_integrated", "hash"):  # case 3's row as the killed run wrote it
        assert rows[name][0] == first[name][0], name
    # Round 1 refines the half of round 0's edge that still straddles the safe film.
    assert list(rows["round"]) == [0, 0, 1]
    assert (rows["case_a"][2], rows["case_b"][2], rows["reason"][2]) == (3, 1, "below_safe_film")
    assert rows["viscosity_Pa_s"][2] == math.sqrt(rows["viscosity_Pa_s"][0] * 0.2)
    # The periods the resumed run reports are its two cases' only.
    spent = int(re.search(r"(\d+) periods", resumed.stderr.splitlines()[-1]).group(1))
    assert spent == sum(int(rows[c][k]) for c in ("periods_integrated", "sensitivity_periods") for k in (1, 2))
    # Run again: the budget is spent, nothing runs, the file is as it was.
    digest = md5(copy)
    again = lubsweep(build_dir, "refine", copy, "--budget", 3)
    assert again.returncode == 0 and "the budget is already spent" in again.stderr, again.stderr
    assert md5(copy) == digest


def test_one_rank_and_two_ranks_give_the_same_rows(study, build_dir, tmp_path):
    rows = {}
    for ranks in (1, 2):
        path = tmp_path / f"np{ranks}.h5"
        shutil.copy(study, path)
        done = lubsweep(build_dir, "refine", path, "--budget", 3, ranks=ranks)
        assert done.returncode == 0, done.stderr
        rows[ranks] = table(path)
    assert len(rows[1]["case"]) == 3 and set(rows[1]) == set(rows[2])
    for name in set(rows[1]) - RUN_COLUMNS:
        a, b = rows[1][name], rows[2][name]
        same = np.array_equal(a, b, equal_nan=True) if a.dtype.kind == "f" else np.array_equal(a, b)
        assert same, name


def test_without_sensitivities_it_refines_on_labels_and_says_so(source_dir, build_dir, tmp_path):
    import json

    grid = json.loads((source_dir / "tests" / "mpi" / "refine_grid.json").read_text())
    grid["scene"] = str(source_dir / "configs" / "scenes" / "slider_crank.json")
    grid["study"]["sensitivities"] = False
    (tmp_path / "grid.json").write_text(json.dumps(grid))
    path = tmp_path / "plain.h5"
    assert lubsweep(build_dir, tmp_path / "grid.json", "-o", path, "-q", "--no-summary").returncode == 0
    done = lubsweep(build_dir, "refine", path, "--budget", 4)
    assert done.returncode == 0, done.stderr
    assert "has no sensitivities" in done.stderr and "labels" in done.stderr
    rows = table(path)
    # Labels only: the safe-film edge and its straddling halves, never the 0.2-0.4 edge.
    assert set(rows["reason"]) == {"below_safe_film"} and 2 not in set(rows["case_b"]), rows["case_b"]
    assert "d_min_film_thickness_m_per_viscosity_Pa_s" not in rows


def test_a_continuation_study_continues_each_new_case_from_its_lower_end(source_dir, build_dir, tmp_path):
    import json

    grid = json.loads((source_dir / "tests" / "mpi" / "refine_grid.json").read_text())
    grid["scene"] = str(source_dir / "configs" / "scenes" / "slider_crank.json")
    grid["set"]["/simulation/steady"] = "continuation"
    (tmp_path / "grid.json").write_text(json.dumps(grid))
    path = tmp_path / "continued.h5"
    assert lubsweep(build_dir, tmp_path / "grid.json", "-o", path, "-q", "--no-summary").returncode == 0
    done = lubsweep(build_dir, "refine", path, "--budget", 3)
    assert done.returncode == 0, done.stderr
    rows = table(path)
    assert list(rows["case_a"]) == [0, 1, 3]  # the third: a half of the first's edge
    assert list(rows["continued_from"]) == list(rows["case_a"])
    assert set(rows["classification"]) == {"periodic"}


@pytest.mark.parametrize("args, says", [
    (["MISSING", "--budget", "2"], "no such file"),
    (["STUDY", "--budget", "0"], "--budget = 0: must be at least 1"),
    (["STUDY", "--budget", "2", "--metric-tolerance", "-0.1"], "--metric-tolerance = -0.1: must be"),
    (["GRID", "--budget", "2"], "not a lubsweep study file"),
    (["REFINED", "--budget", "4", "--metric-tolerance", "0.1"], "was made with 0.05"),
    (["INCOMPLETE", "--budget", "2"], "the study is incomplete (1 of 3 cases"),
])
def test_bad_input_exits_2_naming_the_field_and_leaves_the_file_as_it_was(copy, build_dir, source_dir, args, says):
    if args[0] == "REFINED":
        assert lubsweep(build_dir, "refine", copy, "--budget", 1).returncode == 0
    if args[0] == "INCOMPLETE":  # a sweep killed after its first row
        copy.unlink()
        killed = lubsweep(build_dir, source_dir / "tests" / "mpi" / "refine_grid.json", "-o", copy, "-q",
                          env={"LUBSWEEP_TEST_KILL_AFTER": "1"})
        assert killed.returncode != 0 and copy.exists()
        for stale in copy.parent.glob("*.lock"):  # the killed sweep's lock file, released by the kernel
            stale.unlink()
    paths = {"MISSING": copy.parent / "nope.h5", "STUDY": copy, "REFINED": copy, "INCOMPLETE": copy,
             "GRID": source_dir / "tests" / "mpi" / "refine_grid.json"}
    target = paths[args[0]]
    digest = md5(copy)
    done = lubsweep(build_dir, "refine", target, *args[1:])
    assert done.returncode == 2, done.stderr
    assert says in done.stderr, done.stderr
    assert md5(copy) == digest
    assert not (copy.parent / "nope.h5").exists()
    assert not any(p.name.endswith(".lock") for p in copy.parent.iterdir())
