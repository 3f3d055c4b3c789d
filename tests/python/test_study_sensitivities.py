"""A study's sensitivities against central differences of separately located orbits (issue
44's check), on the paper grid's study (the nightly_paper fixture), by
tools/docs/study_sensitivities.py: every located orbit of a lubricated joint, each axis,
each of its metrics within the larger of the summed error bars and 2 % (at ± 1 %, or at
± 0.25 % where a metric's kink lies within ± 1 %: docs/validation/sensitivities.md); the ideal
mechanism (no freedom: every state a function of the crank angle) has none."""
import os
import subprocess
import sys


def rows(text):
    """The tool's Markdown table as dicts by column name."""
    lines = [l for l in text.splitlines() if l.startswith("|")]
    head = [h.strip() for h in lines[0].strip("|").split("|")]
    return [dict(zip(head, (c.strip() for c in l.strip("|").split("|")))) for l in lines[2:]]


def test_every_located_orbit_agrees_with_central_differences(paper_study, source_dir):
    tool = source_dir / "tools" / "docs" / "study_sensitivities.py"
    p = subprocess.run([sys.executable, str(tool), str(paper_study)], capture_output=True, text=True,
                       env=dict(os.environ), timeout=600)
    assert p.returncode == 0, p.stdout + p.stderr
    table = rows(p.stdout)
    axes = {r["axis"] for r in table}
    assert axes == {"clearance_m", "viscosity_Pa_s", "speed_rpm"}, axes
    for r in table:
        orbits, without = int(r["orbits"]), int(r["without sensitivities"])
        agree = int(r["agree at ± 1 %"]) + int(r["agree at ± 0.25 %"])
        if r["force law"] == "ideal":
            assert without == orbits, r
        else:
            assert agree > 0 and int(r["disagree"]) == 0 and without == 0, r
