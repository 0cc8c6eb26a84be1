#!/usr/bin/python3
"""Notebook-style: simulate a scene, plot it with matplotlib, read a design.json and
compare the tuned design with the start. Writes a PNG (Agg backend: no display needed).

    PYTHONPATH=build/python /usr/bin/python3 examples/notebook_simulate_plot.py [OUT.png]
"""
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import pronk  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "out/notebook_study2.png")

# %% Study 2's starting scene (~50 % duty) and its tuned design (design.json), both started
# 0.3 m beside the setpoint with a 0.2 m/s sideways kick.
design = pronk.read_design(ROOT / "results" / "study2_legged_pulse_duty50" / "design.json")
kick = {"/initial/position/1": 0.3, "/initial/velocity": [0, 0.2, 0]}
runs = {
    "start": pronk.simulate(ROOT / "studies" / "scenes" / "legged_pulse_duty50.json", overrides=kick),
    "study 2 tuned": pronk.simulate(design["scene"], overrides=kick),
}
for name, r in runs.items():
    m = r.metrics
    print(f"{name:24} {r.status:9} strides {m['strides']:3d}  duty {m['mean_duty_cycle']:.3f}  "
          f"settle {m['settle_strides']:3d}  final y error {m['final_y_error_m']:+.4f} m")
print("tuned parameters:", ", ".join(f"{k} {v:.4g}" for k, v in design["parameters"].items()))

# %% Plot: CoM height and lateral error over time, apex height per stride.
fig, ax = plt.subplots(3, 1, figsize=(8, 8), constrained_layout=True)
for name, r in runs.items():
    tr, st = r.trajectory, r.strides
    ax[0].plot(tr["t"], tr["z"], label=name)
    ax[1].plot(tr["t"], tr["y"] - tr["y_d"], label=name)
    apex = st["apex_height"] > 0
    ax[2].plot(st["stride"][apex], st["apex_height"][apex], "o-", ms=3, label=name)
ax[0].set(ylabel="CoM height [m]")
ax[1].set(ylabel="y - y_d [m]", xlabel="time [s]")
ax[2].set(ylabel="apex height [m]", xlabel="stride")
for a in ax:
    a.grid(True)
    a.legend()
out.parent.mkdir(parents=True, exist_ok=True)
fig.savefig(out, dpi=100)
print(f"figure: {out}")
