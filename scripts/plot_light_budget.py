#!/usr/bin/python3
"""Error against time of the default render (the light budget) against pt, per scene, from
docs/data/light_budget_default.csv: docs/images/light_budget_<scene>_<size>.png (per pixel and per
4x4 block side by side). Run: /usr/bin/python3 scripts/plot_light_budget.py"""
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
rows = list(csv.DictReader(open(os.path.join(ROOT, "docs", "data", "light_budget_default.csv"))))
for scene, size in sorted({(r["scene"], r["size"]) for r in rows}):
    mine = [r for r in rows if r["scene"] == scene and r["size"] == size]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, column, title in zip(axes, ["relmse", "relmse_block4"], ["per pixel", "4x4 blocks"]):
        series = [("raster", "2", "raster k = 2", "o"), ("raster", "4", "raster k = 4", "D"),
                  ("rt-vpl", "", "rt-vpl", "s"), ("pt", "", "pt", "^")]
        for estimator, k, label, marker in series:
            pts = sorted((float(r["seconds"]), float(r[column]), r["setting"])
                         for r in mine if r["estimator"] == estimator and r["interleave"] == k)
            if not pts:
                continue
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=marker, linestyle="-"
                    if estimator == "pt" else "", label=label)
            for t, e, setting in pts:
                if estimator != "pt":
                    short = setting.replace(" (--paths 256 --clusters 0)", "").replace(
                        "default with --interleave 4", "default k=4").replace(
                        " --interleave 4", "").replace("default with", "default,")
                    ax.annotate(short, (t, e), fontsize=6, xytext=(3, 3),
                                textcoords="offset points")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("seconds (2 cores, llvmpipe)")
        ax.set_ylabel("relMSE " + title)
        ax.set_title(f"{scene} {size}x{size}, {title}")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(ROOT, "docs", "images", f"light_budget_{scene}_{size}.png"), dpi=80)
