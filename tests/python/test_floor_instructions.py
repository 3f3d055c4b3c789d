"""tools/perf/floor_instructions.py: its interpolation, and the benchmark's one-point mode it
runs under callgrind (bench_floor_accuracy --point): the engine and the floor, two
independent routes, end the same cycles at the same place; bad input exits 2."""
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools" / "perf"))
import floor_instructions as fi  # noqa: E402

BUILD = Path(os.environ.get("LUB_BUILD_DIR", SOURCE / "build"))
BENCH = BUILD / "tests" / "bench" / "bench_floor_accuracy"


def test_cost_at_interpolates_a_power_law_exactly():
    # cost = 10 * err^-0.25: a straight line in log-log, which the interpolation must hit.
    pts = [(e, 10 * e ** -0.25) for e in (1e-2, 1e-4, 1e-6, 1e-8)]
    assert fi.cost_at(pts, 1e-5) == pytest.approx(10 * 1e-5 ** -0.25, rel=1e-12)
    # Errors that do not fall monotonically: the first bracketing pair answers.
    assert fi.cost_at([(1e-3, 1.0), (1e-5, 2.0), (1e-4, 3.0)], 1e-4) == pytest.approx(math.sqrt(2.0), rel=1e-12)
    assert math.isnan(fi.cost_at(pts, 1e-12))  # outside every pair


def point(law, rtol, side):
    out = subprocess.run([str(BENCH), "--point", law, rtol, side], check=True, capture_output=True, text=True)
    return fi.parse_point(out.stdout)


@pytest.mark.skipif(not BENCH.exists(), reason="bench_floor_accuracy not built")
def test_the_engine_and_the_floor_end_each_cycle_at_the_same_eccentricity():
    for law in ("frene_long", "pinkus_sternlicht"):
        steps_e, ends_e = point(law, "1e-9", "engine")
        steps_f, ends_f = point(law, "1e-9", "floor")
        assert len(ends_e) == len(ends_f) == fi.CYCLES
        assert steps_e > 0 and steps_f > 0
        # Both at rtol 1e-9 are within 2e-5 c of the reference (the script's table): 1e-4 c
        # apart would be a different orbit, not integration error.
        assert fi.distance_c(ends_e, ends_f) < 1e-4


@pytest.mark.skipif(not BENCH.exists(), reason="bench_floor_accuracy not built")
def test_bad_input_exits_2_and_names_the_rule():
    r = subprocess.run([str(BENCH), "--point", "no_such_law", "1e-8", "engine"], capture_output=True, text=True)
    assert r.returncode == 2
    assert "LAW one of the five laws" in r.stderr


@pytest.mark.skipif(not BENCH.exists() or shutil.which("valgrind") is None, reason="needs the bench and valgrind")
def test_one_point_is_counted_inside_the_call_only():
    steps, ends, ir = fi.run_point(str(BENCH), "frene_long", 1e-5, "floor", "joint", True)
    assert len(ends) == fi.CYCLES
    # The floor at rtol 1e-5 takes ~262 steps a cycle at ~12k instructions each: 4 cycles
    # are ~1.3e7; the whole process (start-up, dynamic loading) would be several times more.
    assert 3e6 < ir < 3e7
