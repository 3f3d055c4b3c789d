"""The README's three Python one-liners (section "Reading the results in Python"), run as
written on the paper grid's study and on a lubsim run file: they must work with Debian's
python3-xarray, python3-h5netcdf and python3-pandas, without the project's code."""
import re
import subprocess

import pytest


def oneliners(source_dir):
    text = (source_dir / "README.md").read_text()
    block = text.split("<!-- one-liners -->")[1]
    found = re.findall(r"^/usr/bin/python3 -c '(.*)'$", block, flags=re.M)
    assert len(found) == 3, found
    return found


@pytest.fixture(scope="module")
def run_file(source_dir, build_dir, tmp_path_factory):
    out = tmp_path_factory.mktemp("run") / "run.h5"
    subprocess.run([str(build_dir / "core" / "lubsim"), str(source_dir / "configs" / "scenes" / "slider_crank.json"),
                    "-o", str(out), "-q"], check=True)
    return out


def run(code, study, run_file):
    code = code.replace('"out/study.h5"', f'"{study}"').replace('"run.h5"', f'"{run_file}"')
    return subprocess.run(["/usr/bin/python3", "-c", code], capture_output=True, text=True)


def test_subgrid_as_an_xarray_dataset(source_dir, paper_study, run_file):
    r = run(oneliners(source_dir)[0], paper_study, run_file)
    assert r.returncode == 0, r.stderr
    assert "frene_long" in r.stdout and "min_film_thickness_m" in r.stdout, r.stdout


def test_cases_as_a_pandas_table(source_dir, paper_study, run_file):
    r = run(oneliners(source_dir)[1], paper_study, run_file)
    assert r.returncode == 0, r.stderr
    assert "case_0015" in r.stdout and "pinkus_sternlicht" in r.stdout, r.stdout


def test_run_series_indexed_by_time(source_dir, paper_study, run_file):
    r = run(oneliners(source_dir)[2], paper_study, run_file)
    assert r.returncode == 0, r.stderr
    head = r.stdout.splitlines()
    assert "h_min" in head[0] and head[1].split() == ["t"] and len(head) >= 6, r.stdout  # samples, indexed by t
