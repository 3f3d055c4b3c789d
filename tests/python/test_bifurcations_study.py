"""The chain on a study lubsweep wrote: the paper grid of the nightly test (the ctest fixture
paper_study; simulation.steady = auto, so periodic cases carry their Floquet multipliers),
through lubjoint.study.cases, bifurcation_edges and tools/plot/steady.py (label nightly;python)."""
import math
import subprocess
import sys

from lubjoint import study
from test_bifurcations import brute_force_neighbours

DID_NOT_RUN = {"not_run", "invalid_scene", "error"}  # says nothing about the journal


def test_every_edge_of_the_paper_study_follows_the_rule(paper_study):
    cases = study.cases(paper_study)
    axes = [str(a) for a in cases.attrs["axes"]]
    # What the file says of itself: the classifications with an orbit, those of a run without
    # one (every other the cases that did not run), and its lattice, the pairwise definition.
    orbit, no_orbit = study.orbit_classifications(cases), study.no_orbit_classifications(cases)
    assert orbit == ("periodic", "periodic_unstable")
    assert not set(orbit) & set(no_orbit) and not (set(orbit) | set(no_orbit)) & DID_NOT_RUN
    neighbours = brute_force_neighbours(cases, axes)
    assert set(study.lattice_edges(cases)) == neighbours
    edges = study.bifurcation_edges(cases)
    assert {(r.case_a, r.case_b, r.axis) for r in edges.itertuples()} <= neighbours
    expected_lost = {(a, b, ax) for a, b, ax in neighbours
                     if (cases.at[a, "classification"] in orbit) != (cases.at[b, "classification"] in orbit)
                     and not {cases.at[a, "classification"], cases.at[b, "classification"]} & DID_NOT_RUN}
    assert {(r.case_a, r.case_b, r.axis) for r in edges.itertuples() if r.kind == "orbit_lost"} == expected_lost
    # The paper grid loses its orbit on its lines (the baseline: drifting at 50 rpm,
    # not_converged at 0.05 mm); that the study has such edges is what this test reads.
    assert expected_lost, cases[["classification"]]
    for r in edges.itertuples():
        assert r.value_a < r.value_b
        if r.kind != "orbit_lost":  # a stability change: |mu|max on either side of 1, crossing between
            assert (r.mu_a - 1.0) * (r.mu_b - 1.0) < 0.0
            assert r.value_a < r.crossing_value < r.value_b
    with_mu = cases["multiplier_1_modulus"].notna()
    stable_changes = {(a, b, ax) for a, b, ax in neighbours if with_mu[a] and with_mu[b] and
                      (cases.at[a, "multiplier_1_modulus"] - 1.0) * (cases.at[b, "multiplier_1_modulus"] - 1.0) < 0}
    assert {(r.case_a, r.case_b, r.axis) for r in edges.itertuples() if r.kind != "orbit_lost"} == stable_changes
    print(f"{with_mu.sum()} cases with multipliers; edges:\n{edges.to_string()}")


def test_plot_steady_draws_the_edges_of_the_paper_study(source_dir, paper_study, tmp_path):
    p = subprocess.run([sys.executable, str(source_dir / "tools" / "plot" / "steady.py"), str(paper_study), "-o",
                        str(tmp_path)], capture_output=True, text=True, timeout=240)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "steady_classification.png").stat().st_size > 0
    edges = study.bifurcation_edges(study.cases(paper_study))
    written = (tmp_path / "steady_edges.csv").read_text().splitlines()
    assert len(written) == 1 + len(edges) and written[0].split(",")[:3] == ["case_a", "case_b", "axis"]
    assert not math.isnan(edges.value_a.iloc[0])
