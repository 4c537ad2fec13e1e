#!/usr/bin/python3
"""Error against time on a real interior: godot_occlusion_room (the bench's lit copy, 128x128)
against its 2048-spp pt reference: the raster's rounds (`--rounds M`; before c56fabf also with
`--shadow-res 128`), rt-vpl's rounds and pt, per pixel and per 4x4 block, from
docs/data/light_budget_rounds_session14.csv: docs/images/rounds_godot_128.png.
Run: /usr/bin/python3 scripts/plot_rounds_godot.py"""
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
path = os.path.join(ROOT, "docs", "data", "light_budget_rounds_session14.csv")
rows = [r for r in csv.DictReader(line for line in open(path) if not line.startswith("#"))
        if r["scene"] == "godot_128"]
series = [("raster (R = 64, the default)", "o", "raster_rounds"),
          ("raster before c56fabf", "x", "corners075_raster_rounds"),
          ("raster before c56fabf, --shadow-res 128", "D", "corners075_raster_shadow128_rounds"),
          ("rt-vpl", "s", "rtvpl_rounds"), ("pt", "^", "pt_")]
fig, axes = plt.subplots(1, 2, figsize=(10, 4))
for ax, column, title in zip(axes, ["relmse_pixel", "relmse_block4"], ["per pixel", "4x4 blocks"]):
    for label, marker, prefix in series:
        picked = [r for r in rows if r["label"].startswith(prefix)
                  and r["label"][len(prefix):].isdigit()]
        pts = sorted((float(r["seconds"]), float(r[column])) for r in picked)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=marker, label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("seconds (llvmpipe, 2 cores)")
    ax.set_ylabel("relMSE against the 2048-spp pt")
    ax.set_title("godot_occlusion_room 128x128, " + title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
fig.tight_layout()
out = os.path.join(ROOT, "docs", "images", "rounds_godot_128.png")
fig.savefig(out, dpi=90)
print(out)
