"""Every code block of the user guide (docs/guide/*.md) and of the README runs as written.

A page's `sh` and `python` blocks run in order, in one scratch directory per page that
looks like the repository after `bash tools/study.sh`: `build/` (this build), `configs/`,
`tools/`, and `out/study.h5` (a copy of the paper grid's study, written by the nightly_paper
test). `sh` blocks run under `bash -euo pipefail`, `python` blocks under /usr/bin/python3,
with PYTHONPATH=build/python. A `json` block must parse (a grid: `lubsweep --check` accepts
it). A block that only illustrates (a command that takes minutes, a fragment) is preceded by
the line `<!-- not-run: REASON -->` and is skipped; `test_quick_start_runs` makes sure the
README's quick start is never skipped. The README's opening block (`bash tools/study.sh`,
`bash tools/test.sh`) is what CI itself runs and is left out.
"""
import json
import os
import re
import shutil
import subprocess

import pytest

FENCE = re.compile(r"(?:^<!-- not-run: (?P<why>[^>]*) -->\n)?^```(?P<lang>[a-z]*)[^\n]*\n(?P<body>.*?)^```$",
                   re.M | re.S)
RUN = ("sh", "bash", "python")


def blocks(path):
    """(language, body, reason it is not run or None) of each fenced block of a Markdown page."""
    return [(m["lang"], m["body"], m["why"]) for m in FENCE.finditer(path.read_text())]


def is_setup(body):
    """The README's opening block, `bash tools/study.sh` and `bash tools/test.sh`: they are
    what CI runs (.ci/run runs tools/test.sh, which runs this test), so not run here."""
    return [line.split("#")[0].strip() for line in body.strip().splitlines()] == \
        ["bash tools/study.sh", "bash tools/test.sh"]


def pages(source_dir):
    return [source_dir / "README.md"] + sorted((source_dir / "docs" / "guide").glob("*.md"))


def scratch(tmp_path, source_dir, build_dir, paper_study):
    """A directory that looks like the repository after `bash tools/study.sh`."""
    os.symlink(build_dir, tmp_path / "build")
    for name in ("configs", "tools", "core", "docs"):
        os.symlink(source_dir / name, tmp_path / name)
    (tmp_path / "out").mkdir()
    shutil.copy(paper_study, tmp_path / "out" / "study.h5")
    return tmp_path


def environment(build_dir):
    env = dict(os.environ)
    env["PYTHONPATH"] = str(build_dir / "python")
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    env["MPLBACKEND"] = "Agg"
    env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
    env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    if (os.cpu_count() or 1) < 2:
        env["OMPI_MCA_rmaps_base_oversubscribe"] = "1"
    return env


def run_block(lang, body, cwd, env):
    if lang in ("sh", "bash"):
        cmd = ["bash", "-euo", "pipefail", "-c", body]
    else:
        cmd = ["/usr/bin/python3", "-c", body]
    return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=240)


@pytest.mark.parametrize("page", ["README.md", "docs/guide/install.md", "docs/guide/lubsim.md",
                                  "docs/guide/lubsweep.md", "docs/guide/grids.md", "docs/guide/python.md",
                                  "docs/guide/post-processing.md", "docs/guide/lubbearing.md"])
def test_listed_pages_exist(source_dir, page):
    assert (source_dir / page).exists(), page


def test_every_guide_page_runs(source_dir, build_dir, paper_study, tmp_path):
    env = environment(build_dir)
    ran = 0
    for page in pages(source_dir):
        (tmp_path / page.stem).mkdir()
        cwd = scratch(tmp_path / page.stem, source_dir, build_dir, paper_study)
        for lang, body, why in blocks(page):
            where = f"{page.relative_to(source_dir)}: block\n{body}"
            if why is not None:
                assert why.strip(), f"{where}: not-run needs a reason"
                continue
            if lang == "json":
                grid = json.loads(body)  # a JSON block must parse
                if "scene" in grid:      # a grid: lubsweep validates it, cases and all
                    local = cwd / "grid.json"
                    local.write_text(body.replace('"../scenes/', f'"{source_dir}/configs/scenes/'))
                    r = subprocess.run([str(build_dir / "sweep" / "lubsweep"), str(local), "--check"],
                                       capture_output=True, text=True, env=env, timeout=120)
                    assert r.returncode == 0, f"{where}\n{r.stdout}\n{r.stderr}"
                continue
            if lang not in RUN or is_setup(body):
                continue
            r = run_block(lang, body, cwd, env)
            assert r.returncode == 0, f"{where}\nexit {r.returncode}\nstdout:\n{r.stdout}\nstderr:\n{r.stderr}"
            ran += 1
    assert ran >= 10, ran


def test_quick_start_runs(source_dir):
    """The README's quick start (its sh and python blocks) is never marked not-run."""
    found = blocks(source_dir / "README.md")
    runnable = [(lang, why) for lang, _, why in found if lang in RUN]
    assert len(runnable) >= 4, runnable
    assert all(why is None for _, why in runnable), runnable


def test_oneliners_print_what_they_say(source_dir, build_dir, paper_study, tmp_path):
    """The three xarray/pandas one-liners of the Python guide: a sub-grid over its axis, the
    case table indexed by case id, a run's channels indexed by time."""
    text = (source_dir / "docs" / "guide" / "python.md").read_text()
    lines = re.findall(r"^/usr/bin/python3 -c '(.*)'$", text.split("<!-- one-liners -->")[1], flags=re.M)
    assert len(lines) == 3, lines
    cwd = scratch(tmp_path, source_dir, build_dir, paper_study)
    env = environment(build_dir)
    subprocess.run([str(build_dir / "core" / "lubsim"), "configs/scenes/slider_crank.json", "-o", "run.h5", "-q"],
                   cwd=cwd, env=env, check=True)
    out = [subprocess.run(["/usr/bin/python3", "-c", code], cwd=cwd, env=env, capture_output=True, text=True)
           for code in lines]
    for r in out:
        assert r.returncode == 0, r.stderr
    assert "frene_long" in out[0].stdout and "min_film_thickness_m" in out[0].stdout, out[0].stdout
    assert "case_0015" in out[1].stdout and "pinkus_sternlicht" in out[1].stdout, out[1].stdout
    head = out[2].stdout.splitlines()
    assert "h_min" in head[0] and head[1].split() == ["t"] and len(head) >= 6, out[2].stdout
