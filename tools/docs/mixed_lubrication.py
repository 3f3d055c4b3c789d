#!/usr/bin/python3
"""Mixed lubrication near the wall (docs/validation/mixed-lubrication.md): the reference case
(Frene short, 0.5 mm, 400 cP, 5000 rpm) started at rest 1 and 0.5 um from the wall, with and
without effects.mixed_lubrication (an engine-bearing surface pair: sigma = 0.5 um,
eta beta sigma = 0.04, sigma/beta = 1e-3, E' = 80 GPa), the study default `auto` at rtol 1e-10;
prints the Markdown table of what each run finds, and the asperities' largest load in this
joint (at a film of 1 nm) by a quadrature of its own.

    PYTHONPATH=build/python /usr/bin/python3 tools/docs/mixed_lubrication.py    (~10 s on 2 cores)

With --factorial it runs the full factorial with and without the effect instead
(configs/grids/full_factorial_mixed.json and full_factorial.json, `mpirun -np 2`, ~80 s) and
prints the classification counts of both and the cells whose films the asperities reach.
"""
import concurrent.futures
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

import lubjoint  # noqa: E402  PYTHONPATH=build/python
import lubjoint.study  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "configs", "scenes", "slider_crank.json")
R_J, LENGTH, CLEARANCE = 0.0095, 0.04, 0.5e-3  # [m], the scene's joint
# The start's direction: where the reference case's transient from rest is at cycle 40 000.
ANGLE = math.atan2(-2.0726884e-5, -4.975019963e-4)
SURFACES = {"roughness_m": 5e-7, "asperity_density_per_m2": 1.6e8, "asperity_radius_m": 5e-4,
            "composite_modulus_Pa": 8e10}
FILMS_UM = (1.0, 0.5)


def run(film_um, mixed):
    e = CLEARANCE - film_um * 1e-6
    overrides = {
        "/joints/3/force_law": "frene_short",
        "/joints/3/initial_eccentricity_m": [e * math.cos(ANGLE), e * math.sin(ANGLE)],
        "/solver/rtol": 1e-10,
        "/simulation/steady": "auto",
        "/simulation/max_cycles": 2000,
        "/outputs/channels": [],
    }
    if mixed:
        overrides["/effects/mixed_lubrication"] = SURFACES
    return lubjoint.simulate(SCENE, overrides)


def capacity_N(film_m):
    """W_a = 2 R L int_0^pi p_a(h) cos(phi) dphi, p_a = K E' F_5/2(h/sigma), by numpy."""
    s, b, eta, E = (SURFACES[k] for k in ("roughness_m", "asperity_radius_m", "asperity_density_per_m2",
                                          "composite_modulus_Pa"))
    K = 16 * math.sqrt(2) / 15 * math.pi * (eta * b * s) ** 2 * math.sqrt(s / b)
    x = np.linspace(0.0, 12.0, 20001)

    def f52(H):
        return np.trapz(x ** 2.5 * np.exp(-0.5 * (x + H) ** 2), x) / math.sqrt(2 * math.pi)

    phi = np.linspace(0.0, 0.2, 4001)  # h < 12 sigma well inside 0.2 rad at this clearance
    eps = 1.0 - film_m / CLEARANCE
    p = np.array([K * E * f52(CLEARANCE * (1 - eps * math.cos(f)) / s) for f in phi])
    return 2 * R_J * LENGTH * np.trapz(p * np.cos(phi), phi)


def row(film_um, mixed, ds):
    def v(name):
        return float(ds[name].values)
    cls = ds.attrs["classification"]
    orbit = cls in ("periodic", "periodic_unstable")
    film = v("min_film_thickness_m") if orbit else v("last_cycle_min_film_m")
    err = v("min_film_thickness_m_error")
    film_txt = f"{film * 1e6:.3f}" + (f" ± {err * 1e6:.2g}" if orbit and math.isfinite(err) else "")
    drift = v("min_film_drift_m_per_cycle")
    drift_txt = f"{drift:.2g} ± {v('min_film_drift_m_per_cycle_error'):.2g}" if not orbit and drift != 0 else "–"
    kappa = v("orbit_conditioning")
    if not math.isfinite(kappa):  # not located: the conditioning its refinement measured, if any
        found = re.search(r"kappa ([0-9.e+-]+)", ds.attrs["message"])
        kappa = float(found.group(1)) if found else float("nan")
    return (f"| {film_um} | {'yes' if mixed else 'no'} | {cls} | {film_txt} | {drift_txt} | "
            f"{kappa:.3g} | {v('peak_asperity_load_N'):.3g} | {v('peak_reaction_N'):.4g} |")


def main():
    cases = [(f, m) for f in FILMS_UM for m in (False, True)]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:  # the GIL is released in a run
        runs = dict(zip(cases, pool.map(lambda c: run(*c), cases)))
    print("| start: film from rest [µm] | asperities | classification | film: orbit's, or where the flow "
          "got to [µm] | drift [m/cycle] | κ | peak asperity load [N] | peak joint force [N] |")
    print("|---|---|---|---|---|---|---|---|")
    for c in cases:
        print(row(*c, runs[c]))
    print()
    print(f"Largest asperity load in this joint (film 1 nm): {capacity_N(1e-9):.3g} N; "
          f"at 0.1 µm: {capacity_N(1e-7):.3g} N; at 0.5 µm: {capacity_N(5e-7):.3g} N.")


def factorial():
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    lubsweep = os.path.join(ROOT, "build", "sweep", "lubsweep")
    studies = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name in ("full_factorial", "full_factorial_mixed"):
            out = os.path.join(tmp, name + ".h5")
            subprocess.run(["mpirun", "-np", "2", lubsweep, os.path.join(ROOT, "configs", "grids", name + ".json"),
                            "-o", out], check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            studies[name] = lubjoint.study.cases(out).set_index("name")
    a, b = studies["full_factorial"], studies["full_factorial_mixed"]
    labels = sorted(set(a.classification) | set(b.classification))
    print("| asperities | " + " | ".join(labels) + " |")
    print("|---|" + "---|" * len(labels))
    for title, s in (("no", a), ("yes", b)):
        counts = s.classification.value_counts()
        print(f"| {title} | " + " | ".join(str(counts.get(k, 0)) for k in labels) + " |")
    print()
    touched = b[b.peak_asperity_load_N > 0]
    print("| clearance [mm] | viscosity [Pa s] | speed [rpm] | force law | without | with | film without → with "
          "[µm] | asperity load [N] | of the peak force |")
    print("|---|---|---|---|---|---|---|---|---|")
    for n, r in touched.iterrows():
        print(f"| {r.clearance_m * 1e3:g} | {r.viscosity_Pa_s:g} | {r.speed_rpm:g} | {r.force_law} | "
              f"{a.classification[n]} | {r.classification} | {a.last_cycle_min_film_m[n] * 1e6:.3g} → "
              f"{r.last_cycle_min_film_m * 1e6:.3g} | {r.peak_asperity_load_N:.3g} | {r.asperity_load_ratio:.3g} |")


if __name__ == "__main__":
    factorial() if "--factorial" in sys.argv[1:] else main()
