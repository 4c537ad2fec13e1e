"""The Python module against the CLI and the library's contracts (ctest python_bindings).

Run: PYTHONPATH=build/python IRAD_BINARY=build/bin/irad /usr/bin/python3 -m pytest python/tests
"""
import math
import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import irad

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CORNELL = os.path.join(ROOT, "data", "cornell_box.gltf")
CORNELL_GLOSSY = os.path.join(ROOT, "data", "cornell_glossy.gltf")
IRAD = os.environ.get("IRAD_BINARY", os.path.join(ROOT, "build", "bin", "irad"))


@pytest.fixture(scope="module")
def cornell():
    return irad.load(CORNELL)


def cli_render(tmp_path, estimator, extra=(), paths=16):
    out = tmp_path / f"{estimator}.exr"
    subprocess.run([IRAD, "render", CORNELL, "-o", str(out), "--size", "32x24", "--paths", str(paths),
                    "--spp", "4", "--estimator", estimator, "--quiet", *extra], check=True)
    return irad.read_exr(str(out))


@pytest.mark.parametrize("estimator", ["raster", "rt-vpl", "pt"])
def test_array_equals_the_cli_exr(cornell, tmp_path, estimator):
    image, stats = irad.render(cornell, size=(32, 24), paths=16, spp=4, estimator=estimator)
    assert image.dtype == np.float32 and image.shape == (24, 32, 3)
    assert stats["size"] == (32, 24) and stats["estimator"] == estimator
    exr = cli_render(tmp_path, estimator)
    assert exr.shape == (24, 32, 4)
    assert np.array_equal(image, exr[..., :3])  # bit-identical


def test_clusters_equal_the_cli_clusters(cornell, tmp_path):
    image, stats = irad.render(cornell, size=(32, 24), paths=256, clusters=64)
    assert stats["vpls"] == 64 and stats["walk_vpls"] > 64
    exr = cli_render(tmp_path, "raster", ["--clusters", "64"], paths=256)
    assert np.array_equal(image, exr[..., :3])  # bit-identical


def test_defaults_are_the_cli_light_budget(cornell, tmp_path):
    # paths and clusters None: the light budget, as irad render's --paths auto --clusters auto.
    image, stats = irad.render(cornell, size=(32, 24))
    assert (stats["paths"], stats["walk_vpls"], stats["clusters"]) == (16384, 30570, 1910)
    assert stats["vpls"] == 1910
    out = tmp_path / "auto.exr"
    subprocess.run([IRAD, "render", CORNELL, "-o", str(out), "--size", "32x24", "--quiet"],
                   check=True)
    assert np.array_equal(image, irad.read_exr(str(out))[..., :3])  # bit-identical


def test_rounds_equal_the_cli_rounds(cornell, tmp_path):
    image, stats = irad.render(cornell, size=(32, 24), paths=64, rounds=3)
    assert stats["rounds"] == 3
    exr = cli_render(tmp_path, "raster", ["--rounds", "3"], paths=64)
    assert np.array_equal(image, exr[..., :3])  # bit-identical


@pytest.mark.parametrize("edges", ["traced", "shaded"])
def test_edge_pixels_equal_the_cli(cornell, tmp_path, edges):
    # Traced from 2 rounds on by default (clustered); asked for here at one round, with shadow
    # maps (at 16x12 pixels per VPL `auto` takes rays, which leave no pixel unsure).
    image, stats = irad.render(cornell, size=(32, 24), paths=4096, interleave=2,
                               interleave_edges=edges, visibility="maps")
    assert stats["interleave_edges"] == edges and stats["edge_pixels"] > 0
    assert stats["visibility"] == "maps"
    # The unsure pixels are traced with them, never shaded (4 here, measured).
    assert (stats["unsure_pixels"] > 0) == (edges == "traced")
    exr = cli_render(tmp_path, "raster", ["--interleave", "2", "--interleave-edges", edges,
                                          "--visibility", "maps"], paths=4096)
    assert np.array_equal(image, exr[..., :3])  # bit-identical
    with pytest.raises(irad.Error, match="interleave_edges"):
        irad.render(cornell, size=(8, 8), paths=4, interleave_edges="sometimes")


def test_stats_report_the_caches_and_the_one_time_stages(cornell, tmp_path, monkeypatch):
    # A fresh cache folder: the first render builds and writes the shadow hierarchy and the
    # thinnest-wall scan, the second reads both back and draws the same image (as the CLI's
    # --stats reports them, tests/test_cornell.cpp).
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    first, stats = irad.render(cornell, size=(48, 32), paths=16, visibility="maps")
    assert (stats["hierarchy_cache"], stats["wall_cache"]) == ("written", "written")
    assert stats["shadow_planes"] is False and 0.0 < stats["thinnest_wall"]
    assert stats["shadow_triangles"] > 0 and stats["gpu_bytes"]["scene"] > 0
    assert stats["gpu_bytes"]["shadow_pages"] > 0 and stats["gpu_bytes"]["camera_pages"] == 0
    assert set(stats["shadow_levels"]) == {"built", "read", "seconds"}
    setup = [name for name, seconds in stats["seconds"]["raster_setup"]]
    assert "hierarchy wait" in setup and setup[-1] == "planes scan"
    beside = dict(stats["seconds"]["hierarchy_beside"])
    assert "hierarchy levels" in beside and all(t >= 0.0 for t in beside.values())
    again, stats = irad.render(cornell, size=(48, 32), paths=16, visibility="maps")
    assert (stats["hierarchy_cache"], stats["wall_cache"]) == ("hit", "hit")
    assert "hierarchy cache read" in dict(stats["seconds"]["hierarchy_beside"])
    assert np.array_equal(first, again)


def test_visibility_by_rays_equals_the_cli(cornell, tmp_path):
    image, stats = irad.render(cornell, size=(32, 24), paths=64, visibility="rays")
    assert stats["visibility"] == "rays" and stats["seconds"]["visibility"] > 0.0
    exr = cli_render(tmp_path, "raster", ["--visibility", "rays"], paths=64)
    assert np.array_equal(image, exr[..., :3])  # bit-identical
    with pytest.raises(irad.Error, match="visibility"):
        irad.render(cornell, size=(8, 8), paths=4, visibility="sometimes")
    with pytest.raises(irad.Error, match="visibility"):
        irad.render(cornell, size=(8, 8), paths=4, visibility="rays", jitter=True)


def test_glossy_pass_equals_the_cli(tmp_path):
    glossy = irad.load(CORNELL_GLOSSY)
    image, stats = irad.render(glossy, size=(32, 24), paths=64, traced_roughness=0.5,
                               glossy_samples=8)
    assert stats["seconds"]["glossy"] > 0.0
    out = tmp_path / "glossy.exr"
    subprocess.run([IRAD, "render", CORNELL_GLOSSY, "-o", str(out), "--size", "32x24", "--paths",
                    "64", "--traced-roughness", "0.5", "--glossy-samples", "8", "--quiet"],
                   check=True)
    assert np.array_equal(image, irad.read_exr(str(out))[..., :3])  # bit-identical
    with pytest.raises(irad.Error, match="traced_roughness"):
        irad.render(glossy, size=(8, 8), paths=4, traced_roughness=2.0)


def test_scene_summary(cornell):
    assert cornell.triangles > 0
    lo, hi = cornell.bounds
    assert all(a < b for a, b in zip(lo, hi))
    assert len(cornell.cameras) >= 1
    assert cornell.lights["emissive_triangles"] > 0
    assert cornell.duration == 0.0
    # The walk's rho_bar, as the render's stats report it.
    _, stats = irad.render(cornell, size=(8, 8), paths=4)
    assert 0.0 < cornell.rho_bar < 1.0
    assert cornell.rho_bar == pytest.approx(stats["rho_bar"], rel=1e-6)


def test_vpl_power_sums_to_the_emitters_power(cornell):
    vpls, stats = irad.walk(cornell, paths=64)
    assert stats["paths"] == 64 and vpls.dtype.names[:3] == ("position", "normal", "intensity")
    first = vpls[vpls["depth"] == 0]
    # Surface VPLs (kind 0) radiate pi I, two-sided ones (kind 1) 2 pi I.
    profile = np.where(first["kind"] == 1, 2.0, 1.0) * math.pi
    power = float(np.sum(profile * first["intensity"].astype(np.float64).mean(axis=1)))
    assert power == pytest.approx(cornell.light_power, rel=1e-5)


def test_compare_matches_identical_and_scaled_images(cornell):
    image, _ = irad.render(cornell, size=(16, 16), paths=8)
    same = irad.compare(image, image)
    assert same["rmse"] == 0.0 and same["mean_ratio"] == (1.0, 1.0, 1.0)
    double = irad.compare(image * 2, image, block=4)
    assert double["mean_ratio"] == pytest.approx((2.0, 2.0, 2.0)) and double["block"] == 4


def test_exr_round_trip(tmp_path):
    image = np.random.default_rng(1).random((5, 7, 3), dtype=np.float32)
    irad.write_exr(str(tmp_path / "a.exr"), image)
    back = irad.read_exr(str(tmp_path / "a.exr"))
    assert np.array_equal(back[..., :3], image) and np.all(back[..., 3] == 1.0)


def test_errors_carry_the_file_and_element(tmp_path):
    with pytest.raises(irad.Error, match="no_such.gltf"):
        irad.load(str(tmp_path / "no_such.gltf"))
    bad = tmp_path / "bad.gltf"
    bad.write_text('{"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": '
                   '{"POSITION": 7}}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]}')
    with pytest.raises(irad.Error, match=r"bad\.gltf: .*meshes\[0\]"):
        irad.load(str(bad), quiet=True)
    with pytest.raises(irad.Error, match="max-triangles|triangles"):
        irad.load(CORNELL, max_triangles=1)
    assert issubclass(irad.Error, RuntimeError)


@pytest.mark.parametrize("kwargs, match", [
    (dict(size=(0, 10)), "size"),
    (dict(estimator="nope"), "estimator"),
    (dict(paths=0), "paths"),
    (dict(sequence="nope"), "sequence"),
    (dict(camera="nope"), "camera"),
    (dict(gl="nope"), "gl"),
])
def test_bad_options_raise_irad_error(cornell, kwargs, match):
    with pytest.raises(irad.Error, match=match):
        irad.render(cornell, **kwargs)


@pytest.mark.parametrize("kwargs", [dict(paths=1.5), dict(size=(1.5, 2)), dict(size="32x32"),
                                    dict(estimator=3), dict(paths=-1)])
def test_wrong_types_raise_type_error(cornell, kwargs):
    with pytest.raises(TypeError):
        irad.render(cornell, **kwargs)


@pytest.mark.parametrize("array", [np.zeros((4, 4, 3), np.float64), np.zeros((4, 4), np.float32),
                                   np.zeros((4, 4, 2), np.float32), np.zeros((0, 4, 3),
                                                                             np.float32)])
def test_compare_refuses_what_is_not_float32_hxwx3(array):
    with pytest.raises(irad.Error, match="image"):
        irad.compare(array, np.zeros((4, 4, 3), np.float32))


def test_compare_refuses_different_sizes():
    with pytest.raises(irad.Error, match="size"):
        irad.compare(np.zeros((4, 4, 3), np.float32), np.zeros((4, 5, 3), np.float32))


@pytest.mark.parametrize("second", [dict(), dict(estimator="pt", spp=2)])
def test_two_threads_render_two_scenes_as_one_after_the_other(cornell, second):
    # Two rasters at once: one GL context each, on their own threads.
    mirror = irad.load(os.path.join(ROOT, "data", "cornell_mirror.gltf"))
    jobs = [(cornell, dict(size=(64, 64), paths=64)),
            (mirror, dict(size=(64, 64), paths=64, **second))]
    alone = [irad.render(scene, **job)[0] for scene, job in jobs]
    results = [None, None]

    def run(i):
        results[i] = irad.render(jobs[i][0], **jobs[i][1])[0]

    threads = [threading.Thread(target=run, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(alone, results):
        assert np.array_equal(a, b)


def test_ctrl_c_cancels_a_render_quickly():
    # A pt render of minutes, interrupted after the module started it: KeyboardInterrupt soon.
    script = ("import irad, sys\n"
              f"s = irad.load({CORNELL!r})\n"
              "print('start', flush=True)\n"
              "irad.render(s, size=(256, 256), estimator='pt', spp=1024)\n")
    env = dict(os.environ)
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, env=env, text=True)
    assert p.stdout.readline().strip() == "start"
    time.sleep(0.5)
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=30)
    assert time.monotonic() - sent < 5.0
    assert p.returncode != 0 and "KeyboardInterrupt" in err


def test_walkthrough_frames_equal_the_cli_frames(cornell, tmp_path):
    subprocess.run([IRAD, "walkthrough", CORNELL, "-o", str(tmp_path / "%04d.exr"), "--frames",
                    "0:3", "--size", "32x24", "--paths", "8", "--quiet"], check=True,
                   stdout=subprocess.DEVNULL)
    frames = irad.walkthrough(cornell, frames=(0, 3), size=(32, 24), paths=8)
    assert frames.mode == "ring" and frames.paths == 8
    images = list(frames)
    assert len(images) == 3
    for i, image in enumerate(images):
        assert image.shape == (24, 32, 3)
        assert np.array_equal(image, irad.read_exr(str(tmp_path / f"{i:04d}.exr"))[..., :3])


def test_walkthrough_refuses_bad_values(cornell):
    with pytest.raises(irad.Error, match="frames"):
        irad.walkthrough(cornell, frames=(3, 3))
    with pytest.raises(irad.Error, match="mode"):
        irad.walkthrough(cornell, mode="nope")
    with pytest.raises(irad.Error, match="fps"):
        irad.walkthrough(cornell, fps=0.0)
