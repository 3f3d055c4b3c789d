"""tools/perf/scaling_model.py: the discrete-event model of lubsweep's scheduler against cases whose
walls follow by hand (one rank; equal cases on P ranks; a coordinator-bound grid; the
longest case), and its command line on a small study file."""
import json
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools" / "perf"))
import scaling_model as sm  # noqa: E402


def test_one_rank_is_the_sum_of_everything():
    costs = [0.01, 0.02, 0.03]
    wall, busy, _ = sm.simulate(costs, 1, service_s=1e-3, latency_s=5e-4, worker_overhead_s=2e-4, fixed_s=0.5)
    # Each case, its worker overhead and its result's service run on rank 0's one core.
    assert wall == pytest.approx(0.5 + sum(costs) + 3 * (2e-4 + 1e-3), rel=1e-12)
    assert busy == pytest.approx(3e-3)


def test_equal_cases_share_out_evenly_without_costs():
    # 64 cases of 1 s on 4 ranks, nothing else: 16 rounds.
    wall, _, _ = sm.simulate([1.0] * 64, 4, service_s=0.0, latency_s=0.0, worker_overhead_s=0.0)
    assert wall == pytest.approx(16.0)


def test_prefetch_hides_the_latency():
    costs = [0.01] * 400
    slow, _, _ = sm.simulate(costs, 3, 1e-5, 2e-3, 0.0, prefetch=1)
    fast, _, _ = sm.simulate(costs, 3, 1e-5, 2e-3, 0.0, prefetch=2)
    assert fast < slow
    # With the next case held, a remote worker never waits for an answer: near the ideal
    # 400 x 10 ms / 3 ranks (only the first and the last cases pay the latency).
    assert fast == pytest.approx(400 * 0.01 / 3, rel=0.03)


def test_a_busy_coordinator_bounds_the_sweep():
    # 2000 cases of 1 ms on 101 ranks with a 100 µs service: rank 0 can serve 10 000
    # results a second, the workers would return 100 000: the wall is the service of every
    # message, 2000 results and the 100 workers' first (ready) ones.
    wall, busy, end = sm.simulate([1e-3] * 2000, 101, 1e-4, 0.0, 0.0)
    assert wall == pytest.approx((2000 + 100) * 1e-4, rel=0.01)
    assert busy / end > 0.95


def test_the_longest_case_bounds_the_sweep():
    costs = [5.0] + [0.01] * 100
    wall, _, _ = sm.simulate(costs, 64, 0.0, 0.0, 0.0)
    assert wall == pytest.approx(5.0)


def test_command_line_on_a_study_file(tmp_path):
    study = tmp_path / "s.h5"
    rng = np.random.default_rng(1)
    walls = rng.uniform(0.01, 0.02, 200)
    # A study file as the one reader (lubjoint.study) accepts it: /cases over `case`.
    import xarray as xr
    from lubjoint import study as study_reader
    order = rng.permutation(200)  # rows in arrival order: the costs come back in case-id order
    xr.Dataset({"wall_time_s": ("case", walls[order])}, coords={"case": order}).to_netcdf(
        study, group="cases", engine="h5netcdf")
    with h5py.File(study, "a") as f:
        f.attrs["program"] = "lubsweep"
        f.attrs["format"] = study_reader.STUDY_FORMAT
    np.testing.assert_array_equal(sm.read_costs(study), walls)
    overhead = tmp_path / "o.json"
    overhead.write_text(json.dumps({"cases": 1000, "service_us": 40.0, "round_trip_us": 250.0,
                                    "finalize_s": 0.07}) + "\n")
    out = tmp_path / "model.json"
    wall1 = walls.sum() + 0.5
    r = subprocess.run([sys.executable, str(SOURCE / "tools/perf/scaling_model.py"), str(study), "--overhead", str(overhead),
                        "--wall1", str(wall1), "--ranks", "1", "2", "16", "--json", str(out),
                        "--check", f"2={study}:{wall1 / 2}"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    rows = json.loads(out.read_text())
    assert [row["ranks"] for row in rows] == [1, 2, 16]
    assert rows[0]["wall_s"] == pytest.approx(wall1, rel=1e-9)  # calibrated on the -np 1 run
    assert rows[0]["efficiency"] == pytest.approx(1.0)
    assert 0.9 < rows[1]["efficiency"] <= 1.0
    assert rows[2]["efficiency"] < rows[1]["efficiency"]
    assert "# check: 2 ranks" in r.stdout
