"""The nightly comparison (tools/compare/nightly.py) on the paper grid's study: it passes against
the committed baseline, and editing one baseline value by 1 % makes it fail, naming the
case and the metric."""
import csv
import subprocess
import sys

import pytest

REFERENCE = ("0.0005", "0.4", "5000.0", "pinkus_sternlicht")  # the paper's reference case


def compare(source_dir, study, baseline, report=None):
    cmd = [sys.executable, str(source_dir / "tools" / "compare.py"), "nightly", str(study), "--baseline", str(baseline)]
    if report:
        cmd += ["--report", str(report)]
    return subprocess.run(cmd, capture_output=True, text=True)


def edited_baseline(source_dir, tmp_path, metric, factor, key=REFERENCE):
    """A copy of the committed baseline with `metric` of case `key` times `factor`."""
    lines = (source_dir / "tests" / "baselines" / "paper.csv").read_text().splitlines(keepends=True)
    comments = [ln for ln in lines if ln.startswith("#")]
    rows = list(csv.DictReader([ln for ln in lines if not ln.startswith("#")]))
    hit = [r for r in rows if (r["clearance_m"], r["viscosity_Pa_s"], r["speed_rpm"], r["force_law"]) == key]
    assert len(hit) == 1, f"the baseline has no single row {key}"
    hit[0][metric] = repr(float(hit[0][metric]) * factor)
    out = tmp_path / "baseline.csv"
    with open(out, "w", newline="") as f:
        f.writelines(comments)
        w = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    return out, hit[0]["case"]


def test_the_committed_baseline_passes(source_dir, paper_study, tmp_path):
    r = compare(source_dir, paper_study, source_dir / "tests" / "baselines" / "paper.csv", tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "0 regressions" in r.stdout
    assert (tmp_path / "report.md").read_text().startswith("# Nightly reproduction: ok")


@pytest.mark.parametrize("metric", ["min_film_thickness_m", "peak_reaction_N", "peak_acceleration_m_s2"])
@pytest.mark.parametrize("factor", [1.01, 0.99])
def test_a_one_percent_edit_is_a_regression_naming_case_and_metric(source_dir, paper_study, tmp_path, metric, factor):
    baseline, case = edited_baseline(source_dir, tmp_path, metric, factor)
    r = compare(source_dir, paper_study, baseline, tmp_path / "report")
    assert r.returncode == 1, r.stdout + r.stderr
    line = (f"REGRESSION clearance_m=0.0005 viscosity_Pa_s=0.4 speed_rpm=5000 force_law=pinkus_sternlicht "
            f"({case}): {metric} = ")
    assert line in r.stdout, r.stdout
    assert "1 regression " in r.stdout, r.stdout  # that one, nothing else
    report = (tmp_path / "report" / "report.md").read_text()
    assert f"### {case}" in report and metric in report
    assert (tmp_path / "report" / f"{case}.png").stat().st_size > 0  # the figure of the changed case


def test_a_one_percent_change_of_the_film_thickness_via_eps_is_a_regression(source_dir, paper_study, tmp_path):
    # max_eps is 1 - h/c: a 1 % thinner film at eps = 0.976 is eps + 0.01 (1 - eps).
    lines = (source_dir / "tests" / "baselines" / "paper.csv").read_text()
    eps = float(next(r for r in csv.DictReader([ln for ln in lines.splitlines() if not ln.startswith("#")])
                     if r["case"] == "case_0000")["max_eps"])
    baseline, case = edited_baseline(source_dir, tmp_path, "max_eps", (eps + 0.01 * (1 - eps)) / eps)
    r = compare(source_dir, paper_study, baseline)
    assert r.returncode == 1 and f"({case}): max_eps = " in r.stdout, r.stdout


def test_a_changed_status_and_a_missing_case_are_regressions(source_dir, paper_study, tmp_path):
    lines = (source_dir / "tests" / "baselines" / "paper.csv").read_text().splitlines(keepends=True)
    data = [ln for ln in lines if not ln.startswith("#")]
    rows = list(csv.DictReader(data))
    rows[1]["status"] = "film_collapse"
    del rows[2]
    out = tmp_path / "b.csv"
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    r = compare(source_dir, paper_study, out)
    assert r.returncode == 1
    assert f"({rows[1]['case']}): status ok, baseline film_collapse" in r.stdout, r.stdout
    assert "not in the baseline" in r.stdout, r.stdout


def test_a_missing_baseline_is_bad_input(source_dir, paper_study, tmp_path):
    r = compare(source_dir, paper_study, tmp_path / "absent.csv")
    assert r.returncode == 2 and "tools/check/nightly.sh --accept" in r.stderr, r.stderr
