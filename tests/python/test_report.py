"""The HTML report of a study (lubjoint.report, `lubsweep report`) on the paper grid's study,
with its boundaries and a refinement, opened in headless Chromium (Debian's chromium): the
page loads without a console error, its charts draw (each records what it drew; a screenshot
shows the map's classification colours and a case's orbit), its table sorts and filters,
every case's panel draws, the boundaries and the refined cases are listed; with the baseline
it shows the nightly comparison, a 1 % edit highlighted; bad input exits 2 naming the file
and writes nothing."""
import csv
import html
import json
import os
import re
import shutil
import subprocess
import sys

import pytest

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
#: The classification colours of lubjoint.plot (periodic, drifting) and the orbit's line.
PERIODIC, DRIFTING, ORBIT = (0x2a, 0x9d, 0x8f), (0xe7, 0x6f, 0x51), (0x1f, 0x77, 0xb4)


def lubsweep(build_dir):
    return build_dir / "sweep" / "lubsweep"


def chromium(tmp_path, url, *extra):
    """Headless Chromium on ``url``: (stdout, stderr)."""
    if not os.path.exists(CHROMIUM):
        pytest.fail(f"no {CHROMIUM}: install the Debian package chromium (tools/setup.sh)")
    cmd = [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--enable-logging=stderr",
           "--v=0", f"--user-data-dir={tmp_path / 'profile'}", "--virtual-time-budget=10000", *extra, url]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=180)
    assert p.returncode == 0, p.stderr[-3000:]
    return p.stdout, p.stderr


def console_errors(stderr):
    """Console messages and uncaught exceptions Chromium logged for the page."""
    return [ln for ln in stderr.splitlines() if ":CONSOLE" in ln or "Uncaught" in ln]


def attribute(dom, name):
    m = re.search(rf'<body[^>]*\s{name}="([^"]*)"', dom)
    assert m, f"no body attribute {name}"
    return html.unescape(m.group(1))


@pytest.fixture(scope="module")
def study_with_boundaries(build_dir, paper_study, tmp_path_factory):
    """A copy of the paper study with its /boundaries (python3 -m lubjoint.boundaries) and a
    refinement of one case (lubsweep refine --budget 1), as a user's study grows."""
    path = tmp_path_factory.mktemp("grown") / "study.h5"
    shutil.copy(paper_study, path)
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}
    for cmd in ([sys.executable, "-m", "lubjoint.boundaries", path], [lubsweep(build_dir), "refine", path, "--budget", "1"]):
        p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=300)
        assert p.returncode == 0, p.stderr
    return path


@pytest.fixture(scope="module")
def page(build_dir, source_dir, study_with_boundaries, tmp_path_factory):
    """The report of the paper study (grown by its boundaries and a refinement) against the
    committed baseline, written by `lubsweep report`."""
    d = tmp_path_factory.mktemp("report")
    out = d / "report.html"
    p = subprocess.run([lubsweep(build_dir), "report", study_with_boundaries, "-o", out, "--baseline",
                        source_dir / "tests" / "baselines" / "paper.csv"], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    assert "wrote" in p.stdout and "0 regressions" in p.stdout, p.stdout
    return out


@pytest.fixture(scope="module")
def selftest_dom(page, tmp_path_factory):
    dom, err = chromium(tmp_path_factory.mktemp("chrome"), page.as_uri() + "?selftest=1", "--dump-dom")
    return dom, err


def test_the_page_is_self_contained(page):
    text = page.read_text()
    assert "Chart.js v3" in text                                    # the library, inlined
    assert not re.search(r'<(script|link|img)[^>]+(src|href)="(https?:)?//', text)  # nothing fetched


def test_the_page_loads_without_console_errors(selftest_dom):
    dom, err = selftest_dom
    assert console_errors(err) == [], console_errors(err)
    assert attribute(dom, "data-ready") == "1"
    assert attribute(dom, "data-errors") == "0", re.search(r'id="page-errors"[^>]*>([^<]*)', dom).group(1)


def test_every_chart_draws(selftest_dom):
    dom, _ = selftest_dom
    drawn = json.loads(attribute(dom, "data-charts"))
    grids = ("clearance", "force_law", "ideal", "speed", "viscosity")   # configs/grids/paper.json's sub-grids
    for name in [f"map-{g}" for g in grids] + [f"metric-{g}" for g in grids] + ["orbit", "film", "reaction", "solver"]:
        assert drawn.get(name, 0) > 0, (name, drawn)
    assert drawn["map-speed"] == 4 and drawn["map-force_law"] == 3     # a cell per case of the sub-grid
    assert drawn["orbit"] > 100 and drawn["film"] > 200               # the reference case's orbit and film


def selftest(dom):
    m = re.search(r'<pre id="selftest">([^<]*)</pre>', dom)
    assert m and m.group(1), "the page's selftest wrote nothing"
    return json.loads(html.unescape(m.group(1)))


def test_the_boundaries_and_the_refinement_are_shown(selftest_dom, study_with_boundaries):
    from lubjoint import boundaries, study

    t = selftest(selftest_dom[0])
    located = boundaries.read(study_with_boundaries)
    assert sorted(t["boundaryKinds"]) == sorted(located["kind"]) and "fold" in t["boundaryKinds"]
    # An edge says what the run beyond it found (the paper's fold: an unstable orbit, or none).
    beyond = dict(zip(t["boundaryKinds"], t["boundaryLost"]))
    assert beyond["fold"] in ("periodic_unstable", "not_converged") and beyond["safe_film"] == ""
    assert t["refinementCases"] == list(study.cases(study_with_boundaries, group="refinement")["name"])


def test_a_boundary_that_has_not_converged_says_why_in_its_row():
    from lubjoint import report

    assert report._converged({"converged": True, "reason": ""}) == "yes"
    assert report._converged({"converged": False, "reason": "no orbit located at 0.05 Pa s"}) == \
        "no: no orbit located at 0.05 Pa s"
    assert report._converged({"converged": False}) == "no"  # a file from before the column


def test_the_table_sorts_and_filters(selftest_dom, paper_study):
    from lubjoint import study

    t = selftest(selftest_dom[0])
    h = study.cases(paper_study).set_index("name")["min_film_thickness_m"]
    finite = [n for n in t["ascending"] if h[n] == h[n]]
    assert t["sortedBy"] == "min_film_thickness_m ascending"
    assert [h[n] for n in finite] == sorted(h[n] for n in finite)          # ascending by h_min
    assert t["ascending"][len(finite):] == [n for n in t["before"] if h[n] != h[n]]  # no value: last
    down = [h[n] for n in t["descending"][:len(finite)]]
    assert down == sorted(down, reverse=True) and set(t["descending"][:len(finite)]) == set(finite)  # again: descending
    assert sorted(t["before"]) == t["before"] and len(t["before"]) == len(h)
    laws = study.cases(paper_study).set_index("name")["force_law"]
    assert sorted(t["filtered"]) == sorted(n for n in h.index if "frene" in laws[n])    # typed "frene"


def test_every_case_panel_and_metric_draws(selftest_dom, paper_study):
    from lubjoint import study

    t = selftest(selftest_dom[0])
    cases = study.cases(paper_study).set_index("name")
    assert sorted(t["caseDrawn"]) == sorted(cases.index)
    for name, (orbit, film, reaction) in t["caseDrawn"].items():
        assert film > 0 and reaction > 0, name
        # An ideal joint's journal does not move: no orbit (the page says why); any other has one.
        assert (orbit > 0) == (cases.at[name, "force_law"] != "ideal"), (name, orbit)
    assert "min_film_thickness_m" in t["metricDrawn"] and "peak_reaction_N" in t["metricDrawn"]
    for metric, drawn in t["metricDrawn"].items():
        assert sum(drawn) > 0, metric


def png_pixels(path):
    from PIL import Image  # Debian python3-pil (python3-matplotlib's dependency)

    import numpy as np
    return np.asarray(Image.open(path).convert("RGB")).astype(int)


def near(pixels, colour, tol=6):
    import numpy as np
    return int(np.all(np.abs(pixels - np.array(colour)) <= tol, axis=-1).sum())


def test_the_screenshot_shows_the_map_and_an_orbit(page, tmp_path):
    shot = tmp_path / "report.png"
    chromium(tmp_path, page.as_uri(), "--window-size=1360,4600", f"--screenshot={shot}")
    px = png_pixels(shot)
    assert px.shape[:2] == (4600, 1360)
    assert px.std() > 20                                     # not blank
    # The maps: 14 periodic cells and 2 drifting ones, each tens of pixels a side.
    assert near(px, PERIODIC) > 14 * 400, near(px, PERIODIC)
    assert near(px, DRIFTING) > 2 * 400, near(px, DRIFTING)
    assert near(px, ORBIT, tol=20) > 2000                    # the metric lines, the orbit, the film


def edited_baseline(source_dir, tmp_path, metric="min_film_thickness_m", case="case_0000", factor=1.01):
    lines = (source_dir / "tests" / "baselines" / "paper.csv").read_text().splitlines(keepends=True)
    rows = list(csv.DictReader([ln for ln in lines if not ln.startswith("#")]))
    next(r for r in rows if r["case"] == case)[metric] = repr(float(next(r for r in rows if r["case"] == case)[metric])
                                                              * factor)
    out = tmp_path / "baseline.csv"
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    return out


def test_a_one_percent_edit_is_highlighted(source_dir, paper_study, tmp_path):
    from lubjoint import report

    out = tmp_path / "r.html"
    data = report.write_report(paper_study, out, baseline=edited_baseline(source_dir, tmp_path))
    c = data["comparison"]
    assert len(c["regressions"]) == 1 and "(case_0000): min_film_thickness_m" in c["regressions"][0]
    dom, err = chromium(tmp_path, out.as_uri(), "--dump-dom")
    assert console_errors(err) == []
    outside = re.findall(r'<td class="outside" data-metric="([^"]+)"', dom)
    assert outside == ["min_film_thickness_m"], outside
    assert len(re.findall(r'<td class="within"', dom)) > 100
    assert re.search(r'id="verdict"[^>]*>REGRESSION: 1 regression', dom)


@pytest.mark.parametrize("how", ["lubsweep", "python"])
def test_bad_input_exits_2_naming_the_file(build_dir, source_dir, tmp_path, how):
    not_study = tmp_path / "notes.h5"
    not_study.write_text("not HDF5\n")
    for study, says in ((tmp_path / "nope.h5", "nope.h5: no such study file"), (not_study, "notes.h5: not an HDF5")):
        out = tmp_path / "r.html"
        cmd = ([lubsweep(build_dir), "report"] if how == "lubsweep" else [sys.executable, "-m", "lubjoint.report"])
        p = subprocess.run(cmd + [study, "-o", out], capture_output=True, text=True, timeout=120)
        assert p.returncode == 2, p.stderr
        assert says in p.stderr, p.stderr
        assert not out.exists() and not (tmp_path / "r.html.partial").exists()
