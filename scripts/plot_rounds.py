#!/usr/bin/python3
"""Error against time of the raster's rounds (`--rounds M`), rt-vpl and pt on the Cornell box at
256x256, per pixel and per 4x4 block, from docs/data/light_budget_rounds_session13.csv (and the
session-12 raster from light_budget_rounds_session12.csv, its final rows d_*):
docs/images/rounds_cornell_256.png. Run: /usr/bin/python3 scripts/plot_rounds.py"""
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "docs", "data")
now = [r for r in csv.DictReader(open(os.path.join(DATA, "light_budget_rounds_session13.csv")))
       if r["scene"] == "cornell_256"]
before = list(csv.DictReader(open(os.path.join(DATA, "light_budget_rounds_session12.csv"))))
series = [
    ("raster (session 13)", "o", [r for r in now if r["label"].startswith("final_raster_rounds")],
     "relmse_pixel", "relmse_block4"),
    ("raster (session 12)", "x", [r for r in before if r["label"] in ("final_r1", "final_r2", "final_r4", "final_r8")], "px",
     "block4"),
    ("rt-vpl", "s", [r for r in now if r["label"].startswith("rtvpl")], "relmse_pixel",
     "relmse_block4"),
    ("pt", "^", [r for r in now if r["label"].startswith("pt_")], "relmse_pixel",
     "relmse_block4"),
]
fig, axes = plt.subplots(1, 2, figsize=(10, 4))
for ax, which, title in zip(axes, [0, 1], ["per pixel", "4x4 blocks"]):
    for label, marker, rows, px, block in series:
        if not rows:
            continue
        column = px if which == 0 else block
        pts = sorted((float(r["seconds"]), float(r[column]), r["label"]) for r in rows)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=marker, label=label)
        if label == "raster (session 13)":
            for t, e, name in pts:
                ax.annotate(name.replace("final_raster_rounds", "M="), (t, e), fontsize=6,
                            xytext=(3, 3), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("seconds (2 cores, llvmpipe)")
    ax.set_ylabel("relMSE " + title)
    ax.set_title(f"Cornell box 256x256, {title}")
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(ROOT, "docs", "images", "rounds_cornell_256.png"), dpi=90)
