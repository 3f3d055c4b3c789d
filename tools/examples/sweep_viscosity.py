"""Minimum film thickness of the paper's slider-crank against viscosity, swept from Python.
Run: PYTHONPATH=build/python /usr/bin/python3 tools/examples/sweep_viscosity.py  ->  out/sweep_viscosity.png"""
import os, matplotlib; matplotlib.use("Agg")
import matplotlib.pyplot as plt, numpy as np, lubjoint

mu = np.geomspace(0.04, 0.4, 6)  # viscosity [Pa s]
runs = [lubjoint.simulate("configs/scenes/slider_crank.json", {"/joints/3/viscosity_Pa_s": m}) for m in mu]
h = np.array([r["min_film_thickness_m"].item() for r in runs]) * 1e6  # [µm]
ok = np.array([r.attrs["status"] == "ok" for r in runs])
fig, ax = plt.subplots(figsize=(5, 3.5))
ax.loglog(mu, h, "-", color="0.7")
ax.loglog(mu[ok], h[ok], "o", label="completed (status ok)")
ax.loglog(mu[~ok], h[~ok], "rx", label="run ended early (status != ok)")
ax.set(xlabel="viscosity μ [Pa s]", ylabel="min film thickness [µm]", title="slider-crank, 5000 rpm, c = 0.5 mm")
ax.legend()
os.makedirs("out", exist_ok=True)
fig.savefig("out/sweep_viscosity.png", dpi=120, bbox_inches="tight")
