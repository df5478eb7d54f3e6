"""Viewer benchmark: how fast a PR2 capability map and surface map open in the browser, and how fast the
theta slider updates (issue 14: under 3 s to open at 0.05 m, under 200 ms per slider move).

Prints JSON. For each map: seconds to load the file, to build the scene on the server (every message
queued), and until headless Chromium shows a steady scene (from the page request); for the surface map,
the slider: server-side update time per theta bin and the time until the page's pixels change. The
reference measured in the same run is an empty viewer page (browser start-up and page load alone).

Maps: --capability FILE --surface FILE, or --build RES to build the PR2's right-arm capability map (with
solutions) and the two-arm table surface map at RES into --cache (0.05 m: about a minute per arm).

    .venv/bin/python benchmarks/viewer.py --build 0.05
    .venv/bin/python benchmarks/viewer.py --capability demo_out/x.orcm --surface demo_out/table_either_arm.orsm
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import time

import numpy as np

import octoreach
from octoreach import arms
from octoreach.viewer import Viewer, files
from octoreach.viewer.browser import Browser

TARGETS = {"open_s": 3.0, "slider_s": 0.2}


def build_maps(res: float, cache: str) -> tuple[str, str]:
    os.makedirs(cache, exist_ok=True)
    cap_path = os.path.join(cache, f"pr2_right_arm_{res}.orcm")
    sm_path = os.path.join(cache, f"pr2_table_either_arm_{res}.orsm")
    if os.path.exists(cap_path) and os.path.exists(sm_path):
        return cap_path, sm_path
    robot = octoreach.robots.pr2()
    table = octoreach.Surface.rectangle(1.4, 0.65, 0.72)
    table.add_legs()
    maps = []
    for name in ("right_arm", "left_arm"):
        cap = arms.capability_map(robot, name, resolution=res, progress=False)
        if name == "right_arm":
            cap.save(cap_path)
        maps.append(octoreach.SurfaceMap.build(robot, cap, table, resolution=res, z_range=(0.0, 0.0),
                                               reference=arms.default_reference(robot, name), progress=False))
    octoreach.SurfaceMap.combine(maps, "max").save(sm_path)
    return cap_path, sm_path


def page_time(browser: Browser, viewer: Viewer, poll: float = 0.05, timeout: float = 60.0) -> float:
    """Seconds from the page request until the scene is drawn and steady (the first of two equal frames)."""
    t0 = time.perf_counter()
    browser.driver.get(viewer.url)
    last, t_last = None, None
    while time.perf_counter() - t0 < timeout:
        px = browser.pixels().astype(np.int16)
        now = time.perf_counter()
        if last is not None and np.abs(px - last).mean() < 0.05 and px.std() > 5:
            return t_last - t0
        last, t_last = px, now
        time.sleep(poll)
    raise TimeoutError("no steady scene")


def open_map(kind: str, path: str | None, browser: Browser) -> dict:
    t0 = time.perf_counter()
    v = Viewer(port=0, verbose=False)
    try:
        if path is None:
            loaded, obj = 0.0, None
        else:
            _, obj = files.load(path)
            loaded = time.perf_counter() - t0
        t1 = time.perf_counter()
        if kind == "surface_map":
            layer = v.add_surface_map(obj)
            cells = len(layer.centres)
        elif kind == "capability_map":
            layer = v.add_capability_map(obj)
            cells = len(layer.centres)
        else:
            layer, cells = None, 0
        scene = time.perf_counter() - t1
        page = page_time(browser, v)
        out = {"map": path, "cells": cells, "load_s": round(loaded, 3), "scene_s": round(scene, 3),
               "page_s": round(page, 3), "open_s": round(loaded + scene + page, 3)}
        if kind == "capability_map":
            out["cells_total"] = int(obj.stats.get("reachable_cells", 0)) if hasattr(obj, "stats") else None
        if kind == "surface_map":
            out["slider"] = slider_times(v, browser, obj.theta_bins)
        return out
    finally:
        v.close()


def slider_times(v: Viewer, browser: Browser, bins: int) -> dict:
    server, page = [], []
    for k in range(0, bins, max(1, bins // 8)):
        before = browser.pixels().astype(np.int16)
        t0 = time.perf_counter()
        server.append(v.show_theta(k))
        while time.perf_counter() - t0 < 5.0:
            if np.abs(browser.pixels().astype(np.int16) - before).mean() > 0.05:
                break
        page.append(time.perf_counter() - t0)
        time.sleep(0.3)  # let the frame settle before the next move
    return {"moves": len(server), "server_s_max": round(max(server), 4), "server_s_median": round(float(np.median(server)), 4),
            "page_s_max": round(max(page), 3), "page_s_median": round(float(np.median(page)), 3),
            "note": "page_s includes one screenshot of the headless page (software WebGL), an upper bound"}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--capability", help="capability map file (.orcm)")
    p.add_argument("--surface", help="surface map file (.orsm)")
    p.add_argument("--build", type=float, help="build PR2 maps at this resolution into --cache instead")
    p.add_argument("--cache", default=os.path.join("build", "viewer_bench"), help="folder for --build maps")
    args = p.parse_args()
    cap, sm = args.capability, args.surface
    if args.build:
        cap, sm = build_maps(args.build, args.cache)
    result = {"machine": platform.processor() or platform.machine(), "cpus": os.cpu_count(), "targets": TARGETS}
    with Browser(1280, 800) as b:
        result["reference_empty_page"] = open_map("empty", None, b)
        if cap:
            result["capability_map"] = open_map("capability_map", cap, b)
        if sm:
            result["surface_map"] = open_map("surface_map", sm, b)
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
