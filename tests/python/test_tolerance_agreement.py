"""tools/compare.py tolerance: a study against the same grid integrated more tightly, on
/cases tables whose answers follow by hand (labels, error bars, angles on the circle,
cases missing), and its command line on bad input (exit 2)."""
import math
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tools" / "compare"))
import tolerance as ta  # noqa: E402


def cases(rows):
    """A /cases table over the axes (clearance_m, force_law) as lubjoint.study.cases gives it."""
    df = pd.DataFrame(rows)
    df.attrs["axes"] = ["clearance_m", "force_law"]
    df.attrs["orbit_classifications"] = ["periodic", "periodic_unstable"]  # as the study file says
    return df


def row(c, law, label, h=1e-5, h_err=1e-8, angle=1.0, angle_err=1e-3, flow=0.0, film=1e-6):
    return {"clearance_m": c, "force_law": law, "classification": label,
            "min_film_thickness_m": h, "min_film_thickness_m_error": h_err,
            "crank_angle_at_min_film_rad": angle, "crank_angle_at_min_film_rad_error": angle_err,
            "slow_flow_cycles": flow, "last_cycle_min_film_m": film}


def test_the_same_study_agrees_with_itself():
    a = cases([row(1e-4, "frene_long", "periodic"), row(2e-4, "frene_long", "periodic_unstable"),
               row(1e-4, "frene_short", "drifting", flow=1500.0, film=2e-6)])
    r = ta.agreement(a, a.copy())
    assert r["matched"] == 3 and r["same_label"] == 3 and r["missing"] == []
    assert r["orbits"] == 2
    assert r["metrics"]["min_film_thickness_m"] == {"within_1": 2, "within_2": 2, "worst": 0.0, "cases": 2,
                                                    "unbarred": 0, "apart_median": 0.0, "apart_max": 0.0,
                                                    "apart_unit": "relative"}
    assert r["flows"] == 1 and r["film_ratio"] == [1.0] * 5 and r["cycle_ratio"] == [1.0] * 5


def test_a_film_outside_its_bars_and_a_changed_label_are_counted():
    a = cases([row(1e-4, "frene_long", "periodic"), row(2e-4, "frene_long", "periodic"),
               row(1e-4, "frene_short", "drifting")])
    # The tight run: the first orbit's film 1.5 × the summed bars (1e-8 + 2e-8) away, the
    # second's within them; the third case now not_converged. Matched by the axes, in
    # another order.
    b = cases([row(1e-4, "frene_short", "not_converged"),
               row(2e-4, "frene_long", "periodic", h=1e-5 + 2e-8, h_err=2e-8),
               row(1e-4, "frene_long", "periodic", h=1e-5 + 4.5e-8, h_err=2e-8)])
    r = ta.agreement(a, b)
    assert r["labels"] == {("periodic", "periodic"): 2, ("drifting", "not_converged"): 1}
    assert r["same_label"] == 2
    m = r["metrics"]["min_film_thickness_m"]
    assert (m["within_1"], m["within_2"]) == (1, 2)
    assert m["worst"] == pytest.approx(1.5, rel=1e-9)


def test_angles_are_compared_on_the_circle_and_missing_cases_reported():
    a = cases([row(1e-4, "frene_long", "periodic", angle=0.01, angle_err=0.02),
               row(2e-4, "frene_long", "periodic")])
    b = cases([row(1e-4, "frene_long", "periodic", angle=2 * math.pi - 0.01, angle_err=0.02)])
    r = ta.agreement(a, b)
    assert r["missing"] == [(2e-4, "frene_long")]
    assert r["metrics"]["crank_angle_at_min_film_rad"]["worst"] == pytest.approx(0.5, rel=1e-9)
    # An angle of 0 and one a rounding short of 2π agree, with no error bars at all.
    z = cases([row(1e-4, "frene_long", "periodic", angle=0.0, angle_err=0.0)])
    r = ta.agreement(z, z.assign(crank_angle_at_min_film_rad=6.2831853071795845))
    assert r["metrics"]["crank_angle_at_min_film_rad"]["worst"] == 0.0
    # NaN bars are no agreement, and are counted; how far apart the two are is said anyway
    # (relative to the default's value; in rad for an angle).
    c = cases([row(1e-4, "frene_long", "periodic", h=2e-5, h_err=math.nan)])
    m = ta.agreement(c, c.assign(min_film_thickness_m=3e-5))["metrics"]["min_film_thickness_m"]
    assert m["within_2"] == 0 and m["unbarred"] == 1
    assert m["apart_max"] == pytest.approx(0.5, rel=1e-12) and m["apart_unit"] == "relative"
    assert "1 without error bars" in ta.report(ta.agreement(c, c.assign(min_film_thickness_m=3e-5)))
    r = ta.agreement(a, b)
    assert r["metrics"]["crank_angle_at_min_film_rad"]["apart_max"] == pytest.approx(0.02, rel=1e-9)


def test_studies_of_other_axes_and_bad_files_are_refused(tmp_path):
    a = cases([row(1e-4, "frene_long", "periodic")])
    b = a.copy()
    b.attrs["axes"] = ["clearance_m"]
    with pytest.raises(ValueError, match="different axes"):
        ta.agreement(a, b)
    bad = tmp_path / "not_a_study.h5"
    bad.write_text("nothing")
    p = subprocess.run([sys.executable, str(SOURCE / "tools" / "compare.py"), "tolerance", str(bad), str(bad)],
                       capture_output=True, text=True)
    assert p.returncode == 2, p.stderr
    assert "not_a_study.h5" in p.stderr
