"""Safe-film boundaries located between a study's grid points (lubjoint.boundaries, issue 44),
on the paper grid's study (the nightly_paper fixture): the printed law at 0.5 mm and
5000 rpm crosses the safe film between 0.1 and 0.2 Pa s; the located viscosity against a
bisection of separate runs (each its own steady stage), to issue 44's 0.5 %."""
import warnings

import pytest

import lubjoint
from lubjoint import boundaries


def test_the_safe_film_viscosity_matches_a_bisection_of_separate_runs(paper_study):
    study = lubjoint.load_study(paper_study)
    found = boundaries.safe_film_boundaries(study)
    rows = found[(found["axis"] == "viscosity_Pa_s") & (found["force_law"] == "pinkus_sternlicht")]
    assert len(rows) == 1, found
    row = rows.iloc[0]
    assert row["converged"] and row["unit"] == "Pa s" and row["kind"] == "safe_film"
    assert 0.1 < row["value"] < 0.2 and row["error"] < 5e-3 * row["value"]
    scene = lubjoint.study.scene(study.path, int(row["case_a"]))

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
