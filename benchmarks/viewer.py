"""Viewer benchmark: how fast a PR2 capability map and surface map open in the browser, and how fast the
theta slider updates (issue 14: under 3 s to open at 0.05 m, under 200 ms per slider move).

Prints JSON. Each scene is timed in parts:
  load_s       reading the map file (compiled loader)
  scene_s      building the scene on the server (numpy, colour maps, viser messages queued)
  wire_bytes   the scene's messages as viser encodes them (its .viser recording, uncompressed size);
  serialise_s  the time of that recording (msgpack + zstd level 12: an upper bound of the wire's level 1)
  boot_s       page request until the page's websocket connects (page load and viser's client start-up)
  transfer_s   connect until the last scene message reached the page (JS clock, worker -> page)
  draw_s       last message until the browser has drawn the scene: a viser get_render() capture (the
               client's camera, after every earlier message is handled and committed) that shows the
               scene's colours; the capture's round trip is included, so this is an upper bound
  page_s       boot_s + transfer_s + draw_s (page request until the scene is drawn); open_s adds load and scene
  js_frames_s  main-thread time spent in animation frames (React commits, three.js set-up, GL calls) from
               connect to drawn; rasterisation runs in Chromium's GPU process (SwiftShader here)
  frame_s      median round trip of a full-size capture of the steady scene (one draw + JPEG + transfer)
The slider: per theta move, the server-side update time and the time until a capture shows the change.

References measured in the same run: an empty viewer page (boot and draw of nothing), the capability map
drawn the old way (every voxel below the cut, one instance each), and the slider the old way (the surface
map's node re-sent on every move).

Maps: --capability FILE --surface FILE, or --build RES to build the PR2's right-arm capability map and the
two-arm table surface map at RES into --cache (0.05 m: about a minute per arm).

    .venv/bin/python benchmarks/viewer.py --build 0.05
    .venv/bin/python benchmarks/viewer.py --capability build/viewer_bench/pr2_right_arm_0.05.orcm \\
        --surface build/viewer_bench/pr2_table_either_arm_0.05.orsm
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import threading
import time

import numpy as np

import octoreach
from octoreach import arms, map_files
from octoreach.viewer import Viewer, cells, colours
from octoreach.viewer.browser import Browser
from octoreach.viewer.capability_map import CapabilityMapLayer

TARGETS = {"open_s": 3.0, "slider_s": 0.2}
CAPTURE = (400, 640)  # height, width of the polling captures

# Injected before the page's own scripts: timestamps (epoch ms) of the messages viser's websocket worker hands
# to the page, and the main-thread time of each animation-frame callback.
TIMING_JS = """
(() => {
  const T = window.__octoreach_timing = {messages: [], frames: []};
  const now = () => performance.timeOrigin + performance.now();
  const W = window.Worker;
  window.Worker = class extends W {
    constructor(...args) { super(...args); this.addEventListener('message', () => T.messages.push(now())); }
  };
  const raf = window.requestAnimationFrame.bind(window);
  window.requestAnimationFrame = (cb) => raf((t) => {
    const s = now(); cb(t); T.frames.push([s, now() - s]);
  });
})();
"""


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


class AllVoxels(CapabilityMapLayer):
    """The reference: the capability map drawn the old way, every voxel below the cut one instance."""

    def cut(self, z: float) -> None:
        self.z = float(z)
        self.shown = self.drawn = np.flatnonzero(self.centres[:, 2] <= self.z + 1e-9)
        self.handle = cells.add_cells(self.scene, f"{self.name}/voxels", self.centres[self.shown],
                                      self.colours[self.shown], self.edge * 0.9)


def old_show(layer, k: int) -> None:
    """The reference slider move: the surface map's node re-sent with the cells shown at theta bin k."""
    rs = layer.values[:, k]
    shown = np.flatnonzero(rs > 0)
    layer.handle = cells.add_cells(layer.scene, layer.name, layer.centres[shown],
                                   colours.scale(rs[shown], layer.vmax), layer.edge * 0.92, layer.tile_height)


def _has_colours(img: np.ndarray, groups, tol: int = 40, share: float = 2e-4) -> bool:
    """Whether, for every group of colours (K, 3), at least `share` of the capture's pixels are near one of
    them (no groups: any capture)."""
    px = img.reshape(-1, 3)[::7].astype(np.int16)
    for wanted in groups:
        near = np.zeros(len(px), dtype=bool)
        for c in wanted:
            near |= (np.abs(px - np.asarray(c, np.int16)) <= tol).all(axis=1)
        if near.mean() < share:
            return False
    return True


def _capture(client, size=CAPTURE) -> np.ndarray:
    return np.asarray(client.get_render(size[0], size[1], transport_format="jpeg", timeout=30.0))[..., :3]


def open_scene(browser: Browser, build, wanted, name: str) -> tuple[dict, Viewer]:
    """Builds a scene with build(viewer) (a dict of facts, load_s: the file's share of the time), opens it in the
    browser and times the parts (see the docstring); drawn means a capture shows colours near each of the
    colour groups wanted(viewer) returns (the layer added last among them, so the earlier ones are in too)."""
    t0 = time.perf_counter()
    v = Viewer(port=0, verbose=False)
    connected = threading.Event()
    t_connect = [0.0]

    @v.server.on_client_connect
    def _(_client) -> None:
        t_connect[0] = time.time()
        connected.set()

    info = build(v)
    load = info.pop("load_s", 0.0)
    scene = time.perf_counter() - t0 - load
    wanted_colours = [np.unique(np.asarray(g, int).reshape(-1, 3) // 16, axis=0) * 16 + 8 for g in wanted(v)]
    t1 = time.perf_counter()
    recording = v.server.get_scene_serializer().serialize()
    serialise = time.perf_counter() - t1
    wire_bytes = int.from_bytes(recording[:8], "little")
    t_request = time.time()
    browser.driver.get(v.url)
    if not connected.wait(60.0):
        raise TimeoutError(f"{name}: the page did not connect")
    client = next(iter(v.server.get_clients().values()))
    t_end = time.time() + 60.0
    while True:
        t_ask = time.time()
        img = _capture(client)
        if _has_colours(img, wanted_colours):
            t_drawn = time.time()
            break
        if time.time() > t_end:
            raise TimeoutError(f"{name}: the scene's colours never showed")
    timing = browser.driver.execute_script("return window.__octoreach_timing;")
    arrivals = [t / 1000.0 for t in timing["messages"] if t / 1000.0 <= t_ask]
    t_last = max(arrivals) if arrivals else t_connect[0]
    frames = sum(d for s, d in timing["frames"] if t_connect[0] * 1000 <= s <= t_drawn * 1000) / 1000.0
    frame = [time.perf_counter()]
    for _ in range(3):
        _capture(client, (browser.height, browser.width))
        frame.append(time.perf_counter())
    out = dict(info, load_s=round(load, 3), scene_s=round(scene, 3),
               wire_bytes=wire_bytes, serialise_s=round(serialise, 3),
               boot_s=round(t_connect[0] - t_request, 3), transfer_s=round(t_last - t_connect[0], 3),
               draw_s=round(t_drawn - t_last, 3), page_s=round(t_drawn - t_request, 3),
               js_frames_s=round(frames, 3), frame_s=round(float(np.median(np.diff(frame))), 3))
    out["open_s"] = round(out["load_s"] + out["scene_s"] + out["page_s"], 3)
    return out, v


def slider_times(v: Viewer, browser: Browser, old: bool) -> dict:
    """Theta moves over 8 bins: server-side time and the time until a capture shows the change."""
    layer = v.surface_map
    client = next(iter(v.server.get_clients().values()))
    bins = layer.smap.theta_bins
    server, page = [], []
    before = _capture(client)
    for k in range(0, bins, max(1, bins // 8)):
        t0 = time.perf_counter()
        if old:
            old_show(layer, k)
        else:
            layer.show(k)
        server.append(time.perf_counter() - t0)
        while True:
            img = _capture(client)
            if np.abs(img.astype(np.int16) - before).mean() > 0.05 or time.perf_counter() - t0 > 10.0:
                break
        page.append(time.perf_counter() - t0)
        before = img
    return {"moves": len(server), "server_s_max": round(max(server), 4),
            "server_s_median": round(float(np.median(server)), 4), "page_s_max": round(max(page), 3),
            "page_s_median": round(float(np.median(page)), 3)}


def _timed_load(path: str):
    t = time.perf_counter()
    m = map_files.load(path)
    return m, time.perf_counter() - t


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--capability", help="capability map file (.orcm)")
    p.add_argument("--surface", help="surface map file (.orsm)")
    p.add_argument("--build", type=float, help="build PR2 maps at this resolution into --cache instead")
    p.add_argument("--cache", default=os.path.join("build", "viewer_bench"), help="folder for --build maps")
    args = p.parse_args()
    cap_path, sm_path = args.capability, args.surface
    if args.build:
        cap_path, sm_path = build_maps(args.build, args.cache)
    result = {"machine": platform.processor() or platform.machine(), "cpus": os.cpu_count(),
              "browser": "headless Chromium, software WebGL (SwiftShader)", "window": [1280, 800],
              "capture": list(CAPTURE[::-1]), "targets": TARGETS}
    with Browser(1280, 800) as b:
        b.driver.execute_cdp_cmd("Page.addScriptToEvaluateOnNewDocument", {"source": TIMING_JS})
        empty, v = open_scene(b, lambda v: {}, lambda v: [], "empty")
        v.close()
        result["reference_empty_page"] = empty
        result["reference_empty_page"]["note"] = "no map: page load, viser start-up, a capture of the empty scene"
        if cap_path:
            for key, layer_class in (("reference_capability_map_all_voxels", AllVoxels),
                                     ("capability_map", CapabilityMapLayer)):
                def build_cap(v, layer_class=layer_class):
                    cap, load = _timed_load(cap_path)
                    layer = v.capability_map = layer_class(v.scene, cap)
                    v._frame_camera(layer.centres)
                    return {"map": cap_path, "voxels": len(layer.centres), "cells": int(cap.stats["reachable_cells"])
                            if "reachable_cells" in cap.stats else None, "below_cut": len(layer.shown),
                            "drawn": len(layer.drawn), "load_s": load}

                out, v = open_scene(b, build_cap, lambda v: [v.capability_map.colours[v.capability_map.drawn]], key)
                v.close()
                result[key] = out
        if sm_path:
            for key, old in (("reference_surface_map_slider_resend", True), ("surface_map", False)):
                def build_sm(v):
                    sm, load = _timed_load(sm_path)
                    layer = v.add_surface_map(sm)
                    return {"map": sm_path, "cells": len(layer.centres), "theta_bins": sm.theta_bins,
                            "load_s": load}

                out, v = open_scene(b, build_sm, lambda v: [v.surface_map.colours_at(-1), [colours.ARROW]], key)
                try:
                    slider = slider_times(v, b, old=old)
                finally:
                    v.close()
                if old:
                    result[key] = {"slider": slider}
                else:
                    out["slider"] = slider
                    result[key] = out
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
