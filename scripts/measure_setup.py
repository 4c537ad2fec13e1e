#!/usr/bin/env python3
"""Profiles the one-time stages of a render, load to first VPL: for each GLB, `irad render` with
the default options at --size (256x256) three times, the raster with an empty cache (cold), the
raster again (warm: the shadow hierarchy and the thinnest-wall scan read back), and rt-vpl over
the same VPLs, each in a fresh process with its --stats. Prints a Markdown table per file: every
stage's seconds and share of the whole process (wall clock), the peak resident memory (the
process's own, from wait4), and the passes (what the raster stage spends after its set-up, the
shadow rays' share apart where the raster took visibility by rays). The
estimates that --stats alone asks for (seconds.statistics) are left out of the whole process,
as a render without --stats does not compute them. The
shadow hierarchy's build runs on a thread of its own from the start of the render: its stages,
marked "(beside)", overlap the others and are not in their sum; "hierarchy wait" is the raster's
wait for what was left of it. The cache lives in a temporary XDG_CACHE_HOME, never the user's.
docs/performance.md "Big scenes" quotes its output.

  LP_NUM_THREADS=2 python3 scripts/measure_setup.py build/sphere_box_2m.glb [more.glb ...]
      [--irad build/bin/irad] [--size 256x256]
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time


def run(irad, scene, size, estimator, cache, out):
    """One render; returns (stats, wall seconds, peak KiB: the child's own ru_maxrss)."""
    stats = out / "stats.json"
    env = dict(os.environ, XDG_CACHE_HOME=str(cache))
    cmd = [irad, "render", scene, "--size", size, "--estimator", estimator,
           "-o", str(out / "image.exr"), "--stats", str(stats), "-q"]
    start = time.monotonic()
    child = subprocess.Popen(cmd, env=env)
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.monotonic() - start
    child.returncode = os.waitstatus_to_exitcode(status)
    if child.returncode != 0:
        sys.exit(f"measure_setup: {' '.join(cmd)} exited with {child.returncode}")
    return json.loads(stats.read_text()), wall, usage.ru_maxrss


def rows(stats, wall):
    """(stage, seconds) of one run, the raster's set-up stages inside its raster stage."""
    s = stats["seconds"]
    out = [("load (glTF, BVH)", s["load"]), ("walk", s["walk"])]
    if "cluster" in s:
        out.append(("clusters (rows, columns)", s["cluster"]))
    if "raster" in s:
        setup = 0.0
        for name, t in s.get("raster_setup", []):
            out.append((name, t))
            setup += t
        out.append(("passes (shadow maps or rays, shading, resolve)", s["raster"] - setup))
        if "visibility" in s:  # visibility by rays: the tracer's share of the passes
            out.append(("of which shadow rays", s["visibility"]))
        # The hierarchy's build on its own thread, beside load, walk and clusters (the raster's
        # "hierarchy wait" is what was left of it): outside the sum of the stages above.
        for name, t in s.get("hierarchy_beside", []):
            out.append((f"{name} (beside)", t))
    else:
        out.append(("trace", s["trace"]))
    for key in ("compensation", "glossy"):
        if key in s:
            out.append((key, s[key]))
    out.append(("rest (process start, writing, exit)",
                wall - s["total"] - s.get("statistics", 0.0)))
    return out


def render_wall(stats, wall):
    """The process's wall clock less the --stats estimates (seconds.statistics)."""
    return wall - stats["seconds"].get("statistics", 0.0)


def table(scene, runs):
    names = []  # every run's stages, each new one after the stage that precedes it in its run
    for _, stats, wall, _ in runs:
        at = 0
        for name, _ in rows(stats, wall):
            if name in names:
                at = names.index(name) + 1
            else:
                names.insert(at, name)
                at += 1
    header = " | ".join(f"{label} s | share" for label, *_ in runs)
    lines = [f"**{pathlib.Path(scene).name}** "
             f"({runs[0][1]['triangles']:,} triangles, {runs[0][1]['vpls']} VPLs)", "",
             f"| stage | {header} |", "| --- |" + " --- | --- |" * len(runs)]
    by_run = [dict(rows(stats, wall)) for _, stats, wall, _ in runs]
    for name in names:
        cells = []
        for (_, stats, wall, _), r in zip(runs, by_run):
            t = r.get(name)
            cells.append("|" if t is None else
                         f"{t:.2f} | {100 * t / render_wall(stats, wall):.0f} %")
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    lines.append("| **whole process** | " + " | ".join(
        f"**{render_wall(stats, wall):.2f}** | 100 %" for _, stats, wall, _ in runs) + " |")
    lines.append("| peak resident memory | " +
                 " | ".join(f"{peak / 1024:.0f} MiB |" for *_, peak in runs) + " |")
    def outcomes(key):
        return ", ".join(stats.get(key, {}).get("outcome", "-") for _, stats, _, _ in runs)
    lines.append("")
    lines.append("hierarchy cache: " + outcomes("hierarchy_cache") + "; wall cache: " +
                 outcomes("wall_cache") + "; visibility: " +
                 ", ".join(stats.get("visibility") or "-" for _, stats, _, _ in runs) +
                 "; shadow triangles per VPL: " +
                 f"{runs[0][1]['shadow_triangles'] / max(1, runs[0][1]['vpls']):.0f}")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--irad", default="build/bin/irad")
    ap.add_argument("--size", default="256x256")
    args = ap.parse_args()
    for scene in args.scenes:
        with tempfile.TemporaryDirectory(prefix="irad_setup_") as tmp:
            tmp = pathlib.Path(tmp)
            runs = []
            for label, estimator in (("raster cold", "raster"), ("raster warm", "raster"),
                                     ("rt-vpl", "rt-vpl")):
                stats, wall, peak = run(args.irad, scene, args.size, estimator, tmp / "cache", tmp)
                runs.append((label, stats, wall, peak))
                print(f"{scene}: {label} {render_wall(stats, wall):.2f} s", file=sys.stderr)
            print(table(scene, runs))
            print()


if __name__ == "__main__":
    main()
