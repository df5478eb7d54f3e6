"""Viewer benchmark: how fast a PR2 capability map and surface map open in the browser, and how fast the
theta slider updates (targets: under 3 s to open at 0.05 m, under 200 ms per slider move).

Prints JSON. Each scene is timed in parts:
  load_s       reading the map file (compiled loader)
  scene_s      building the scene on the server (numpy, colour maps, robot meshes, viser messages queued)
  wire_bytes   the scene's messages as viser encodes them (its .viser recording, uncompressed size);
  serialise_s  the time of that recording (msgpack + zstd level 12: an upper bound of the wire's level 1)
  boot_s       page request until the page's websocket is open (page load and viser's client start-up; JS
               clock from here on, synchronised with the server's through Date.now)
  transfer_s   open until the last scene message reached the page (sent, decoded in viser's worker, posted)
  draw_s       last message that frame shows until the first frame drawing the whole scene (as many
               triangles as the steady scene's last frame) has been drawn: its 1-pixel read-back returned (JS
               timing injected into the page)
  page_s       page request until then (boot_s + transfer_s + draw_s); open_s = load_s + scene_s + page_s
  js_frames_s  main-thread time of the animation frames from connect to drawn (React commits, three.js
               set-up, shader compiles, GL calls); first_frame_js_s: that of the first full frame alone
  triangles    triangles the steady scene draws per frame
  shader_programs, shader_compile_wait_s   programs the page linked (three.js: one per material kind) and
               the main thread's waits for their compiles
Each scene is opened --repeat times (a new viewer and page each time); the JSON holds the medians and every
page_s. The slider: --moves theta moves per opening, each timed from the server-side call to the first frame
whose pixels differ from the frame before the move has been drawn (drawn: its 1-pixel read-back returned, as
for draw_s; while the slider is timed every frame is then also read back whole to tell frames apart, which can
delay the frame after it: an upper bound; read_back_s is that whole read-back's time); frame_js_s / frame_gpu_s
split that frame into its main-thread part and the wait for SwiftShader to draw it.

Two configurations, interleaved opening by opening, each in its own headless Chromium (1280 x 800; a
browser shows about:blank while another configuration is timed, so it draws nothing then):
  before  main before this round: Chromium's earlier flags (PREVIOUS_FLAGS: the page composited on
          SwiftShader, the GPU in its own process), the slider re-sending one node's colours and scales
          (RecolourLayer) and the sampled poses labelled in 3D text
  after   the viewer's flags (browser.FLAGS: software compositing, GPU thread in-process) and one node a theta
          selection; also the recolour slider under these flags (surface_map_recolour_slider), which splits
          the slider's gain between the flags and the nodes.
  after_no_antialiasing   the surface map under the viewer's flags with WebGL's multisampling off (not the
          viewer's setting: jagged edges): antialiasing's share of a software-rendered frame.
Both include the empty page (viser's start-up and drawing nothing: the floor under every scene). Also the
robot meshes the old way (trimesh, in a fresh process: its import and the PR2's meshes).

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
import subprocess
import sys
import threading
import time

import numpy as np

import octoreach
from octoreach import arms, map_files
from octoreach.viewer import Viewer, cells, colours
from octoreach.viewer import app
from octoreach.viewer.browser import FLAGS, Browser
from octoreach.viewer.capability_map import CapabilityMapLayer
from octoreach.viewer.surface_map import BEST, SurfaceMapLayer

TARGETS = {"open_s": 3.0, "slider_s": 0.2}
# Chromium's flags before this round: the page composited on SwiftShader too, the GPU in its own process.
PREVIOUS_FLAGS = tuple(f for f in FLAGS if f not in ("--disable-gpu-compositing", "--in-process-gpu"))
# Not the viewer's: WebGL without multisampling (jagged edges, which screenshots for docs should not have); timed
# to show antialiasing's share of each software-rendered frame.
NO_MSAA = ("--webgl-antialiasing-mode=none",)

# Injected before the page's own scripts (epoch ms, synchronised with Date.now()): when viser's websocket worker
# hands each message batch to the page; per animation frame with draws: start, end of its main-thread work,
# draw calls, triangles, and `finished`, when a 1-pixel read-back returned (the GPU process, SwiftShader here,
# has drawn the frame). While `watch` is set, every
# frame is also read back whole, after its 1-pixel read-back, and `hash` records a digest of its pixels (the slider:
# the first frame that differs; its `finished` is the 1-pixel read-back's, `read_back` the whole one's time).
TIMING_JS = r"""
(() => {
  const T = window.__octoreach_timing = {messages: [], frames: [], watch: false};
  const offset = Date.now() - performance.now();
  const now = () => offset + performance.now();
  const W = window.Worker;
  window.Worker = class extends W {
    constructor(...args) { super(...args); this.addEventListener('message', () => T.messages.push(now())); }
  };
  let cur = null, curGl = null, buf = null;
  const P = WebGL2RenderingContext.prototype;
  const wrap = (name, count) => {
    const g = P[name];
    P[name] = function (...a) {
      if (cur) { cur.draws += 1; cur.tris += count(a); curGl = this; }
      return g.apply(this, a);
    };
  };
  wrap('drawElements', (a) => a[1] / 3);
  wrap('drawArrays', (a) => a[2] / 3);
  wrap('drawElementsInstanced', (a) => a[1] / 3 * a[4]);
  wrap('drawArraysInstanced', (a) => a[2] / 3 * a[3]);
  // Shader programs linked, and the main thread's waits for their compiles (three.js reads their logs).
  T.programs = 0; T.compile_ms = 0;
  const link = P.linkProgram;
  P.linkProgram = function (...a) { T.programs += 1; return link.apply(this, a); };
  for (const name of ['getShaderInfoLog', 'getProgramInfoLog', 'getProgramParameter', 'getShaderParameter']) {
    const g = P[name];
    P[name] = function (...a) { const s = performance.now(); const r = g.apply(this, a); T.compile_ms += performance.now() - s; return r; };
  }
  const raf = window.requestAnimationFrame.bind(window);
  window.requestAnimationFrame = (cb) => raf((t) => {
    const f = cur = {start: now(), draws: 0, tris: 0};
    curGl = null;
    try { cb(t); } finally {
      cur = null;
      f.end = now();
      const gl = curGl;  // the context that drew this frame
      if (f.draws) {
        if (gl && T.watch) {
          gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
          f.finished = now();  // drawn; the whole read-back below only tells frames apart
          const n = gl.drawingBufferWidth * gl.drawingBufferHeight * 4;
          if (!buf || buf.length !== n) buf = new Uint8Array(n);
          const bound = gl.getParameter(gl.READ_FRAMEBUFFER_BINDING);
          gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);  // the canvas, not the last render target
          gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, buf);
          gl.bindFramebuffer(gl.READ_FRAMEBUFFER, bound);
          f.read_back = now() - f.finished;
          let h = 0;
          for (let i = 0; i < n; i += 61) h = (h * 31 + buf[i]) >>> 0;
          f.hash = h;
        } else if (gl) {
          gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
          f.finished = now();
        }
        T.frames.push(f);
      }
    }
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


class RecolourLayer(SurfaceMapLayer):
    """The reference slider (main before per-theta nodes): one node holds every cell; a move re-sends its colours
    (3 bytes a cell) and scales (4 bytes a cell, 0 hides a cell), which the page applies to every instance."""

    def _add_nodes(self) -> None:
        n, bins = self.values.shape
        rs = np.vstack([self.values.T, self.values.max(axis=1, initial=0.0)[None, :]])  # row BEST = -1: best
        self._colours = colours.scale(rs.reshape(-1), self.vmax).reshape(bins + 1, n, 3)
        self._scales = (rs > 0).astype(np.float32)
        self._node = cells.add_cells(self.scene, self.name + "/all", self.drawn_centres, self._colours[BEST],
                                     self.edge * 0.92, self.tile_height, scales=self._scales[BEST])

    def show(self, theta_bin: int) -> None:
        self.theta_bin = k = int(theta_bin)
        self._node.batched_colors = self._colours[k]
        self._node.batched_scales = self._scales[k]


def _timing(browser: Browser) -> dict:
    T = browser.driver.execute_script("return window.__octoreach_timing;")
    for f in T["frames"]:
        for k in ("start", "end", "finished"):
            if k in f:
                f[k] /= 1000.0
    T["messages"] = [m / 1000.0 for m in T["messages"]]
    return T


def open_scene(browser: Browser, build, name: str, quiet: float = 1.5, timeout: float = 60.0) -> tuple[dict, Viewer]:
    """Builds a scene with build(viewer) (a dict of facts; load_s: the file's share of the time), opens it in the
    browser and times the parts (see the docstring). Drawn: the first frame, after the last scene message, that
    draws as many triangles as the steady scene (no message and no new frame size for `quiet` s), finished."""
    t0 = time.perf_counter()
    v = Viewer(port=0, verbose=False)
    connected = threading.Event()
    v.server.on_client_connect(lambda _client: connected.set())

    info = build(v)
    load = info.pop("load_s", 0.0)
    scene = time.perf_counter() - t0 - load
    t1 = time.perf_counter()
    recording = v.server.get_scene_serializer().serialize()
    serialise = time.perf_counter() - t1
    wire_bytes = int.from_bytes(recording[:8], "little")
    t_request = time.time()
    browser.driver.get(v.url)
    if not connected.wait(timeout):
        raise TimeoutError(f"{name}: the page did not connect")
    while True:
        time.sleep(0.25)
        T = _timing(browser)
        if T["messages"] and time.time() - max(T["messages"]) > quiet:
            t_open, last = T["messages"][0], max(T["messages"])
            frames = [f for f in T["frames"] if f["start"] >= t_open]
            if frames:  # the steady scene: what the last frame drew; drawn: the first frame that drew as much
                tris = frames[-1]["tris"]
                first = next(f for f in frames if f["tris"] == tris)
                if "finished" in first:
                    break
        if time.time() - t_request > timeout:
            raise TimeoutError(f"{name}: no steady scene")
    t_drawn = first["finished"]
    last = max(m for m in T["messages"] if m <= first["start"])  # the last message the drawn frame shows
    frames = sum(f["end"] - f["start"] for f in T["frames"] if t_open <= f["start"] <= t_drawn)
    out = dict(info, load_s=round(load, 3), scene_s=round(scene, 3), wire_bytes=wire_bytes,
               serialise_s=round(serialise, 3), boot_s=round(t_open - t_request, 3),
               transfer_s=round(last - t_open, 3), draw_s=round(t_drawn - last, 3),
               page_s=round(t_drawn - t_request, 3), js_frames_s=round(frames, 3),
               first_frame_js_s=round(first["end"] - first["start"], 3), triangles=int(tris),
               shader_programs=T["programs"], shader_compile_wait_s=round(T["compile_ms"] / 1000.0, 3))
    out["open_s"] = round(out["load_s"] + out["scene_s"] + out["page_s"], 3)
    return out, v


def slider_times(v: Viewer, browser: Browser, moves: int) -> list:
    """`moves` theta moves spread over the bins: per move the server-side time and the time until the page's
    first frame whose pixels differ from the frame before the move has been drawn (read back whole while
    watching)."""
    layer = v.surface_map
    bins = layer.smap.theta_bins
    browser.driver.execute_script("window.__octoreach_timing.watch = true;")
    out = []
    for k in range(0, bins, max(1, bins // moves)):
        time.sleep(1.0)  # an idle frame or two to read the scene before the move
        before = [f for f in _timing(browser)["frames"] if "hash" in f]
        t0 = time.time()
        t = time.perf_counter()
        layer.show(k)
        server = time.perf_counter() - t
        changed = None
        while changed is None and time.time() - t0 < 15.0:
            time.sleep(0.1)
            frames = [f for f in _timing(browser)["frames"] if "hash" in f and f["start"] >= t0]
            changed = next((f for f in frames if before and f["hash"] != before[-1]["hash"]), None)
        if changed is None:
            raise TimeoutError(f"theta bin {k}: the page did not change")
        out.append({"server_s": server, "page_s": changed["finished"] - t0,
                    "frame_js_s": changed["end"] - changed["start"], "frame_gpu_s": changed["finished"] - changed["end"],
                    "read_back_s": changed["read_back"] / 1000.0})
    browser.driver.execute_script("window.__octoreach_timing.watch = false;")
    return out


def trimesh_reference() -> dict:
    """Seconds a fresh process (octoreach imported, the PR2 loaded) takes to import trimesh and read the PR2's
    visual meshes with it (the viewer's old way), and to read them now (RobotMeshes through mesh_files)."""
    code = "import time, octoreach; r = octoreach.robots.pr2(); t = time.perf_counter(); {}; print(time.perf_counter() - t)"
    old = ("import trimesh; [trimesh.load(p, force='mesh') for p in "
           "{v.shape.mesh_path for vs in r.visuals.values() for v in vs if v.shape.mesh_path}]")
    new = "from octoreach.viewer.robot_meshes import RobotMeshes; RobotMeshes(r)"
    times = [float(subprocess.run([sys.executable, "-c", code.format(c)], capture_output=True, text=True,
                                  check=True).stdout.split()[-1]) for c in (old, new)]
    return {"trimesh_import_and_meshes_s": round(times[0], 3), "mesh_files_meshes_s": round(times[1], 3)}


def import_times() -> dict:
    """Seconds a fresh process takes to import octoreach, and then viser (not in the open times below)."""
    code = ("import time; t = time.perf_counter(); import octoreach; u = time.perf_counter(); import viser; "
            "print(u - t, time.perf_counter() - u)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    return {"octoreach_s": round(float(out[-2]), 3), "viser_s": round(float(out[-1]), 3)}


def _timed_load(path: str):
    t = time.perf_counter()
    m = map_files.load(path)
    return m, time.perf_counter() - t


def _median(rows: list) -> dict:
    """Field-wise medians of timing dicts (numbers), the page times listed; other fields from the first row."""
    out = dict(rows[0])
    for key, value in rows[0].items():
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            out[key] = round(float(np.median([r[key] for r in rows])), 4)
    out["repetitions"] = len(rows)
    out["page_s_all"] = [r["page_s"] for r in rows]
    out["open_s_all"] = [r["open_s"] for r in rows]
    return out


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--capability", help="capability map file (.orcm)")
    p.add_argument("--surface", help="surface map file (.orsm)")
    p.add_argument("--build", type=float, help="build PR2 maps at this resolution into --cache instead")
    p.add_argument("--cache", default=os.path.join("build", "viewer_bench"), help="folder for --build maps")
    p.add_argument("--repeat", type=int, default=5, help="openings of each scene (medians reported)")
    p.add_argument("--moves", type=int, default=4, help="theta moves timed per opening of the surface map")
    args = p.parse_args()
    json_out, sys.stdout = sys.stdout, sys.stderr  # viser prints to stdout from its threads: the JSON alone there
    cap_path, sm_path = args.capability, args.surface
    if args.build:
        cap_path, sm_path = build_maps(args.build, args.cache)
    result = {"machine": platform.processor() or platform.machine(), "cpus": os.cpu_count(),
              "browser": "headless Chromium, software WebGL (SwiftShader)", "window": [1280, 800],
              "flags": {"before": list(PREVIOUS_FLAGS), "after": list(FLAGS),
                        "after_no_antialiasing": list(FLAGS + NO_MSAA)},
              "targets": TARGETS, "load_average_at_start": [round(x, 2) for x in os.getloadavg()]}
    result["imports_in_a_fresh_process"] = import_times()
    result["reference_robot_meshes_trimesh_s"] = trimesh_reference()
    import viser  # noqa: F401  (imported before the timings: a running viewer has it)

    def build_cap(v):
        cap, load = _timed_load(cap_path)
        layer = v.capability_map = CapabilityMapLayer(v.scene, cap)
        v.frame_camera(layer.centres)
        return {"voxels": len(layer.centres), "below_cut": len(layer.shown), "drawn": len(layer.drawn),
                "load_s": load}

    def build_sm(v):
        sm, load = _timed_load(sm_path)
        layer = v.add_surface_map(sm)
        return {"cells": len(layer.centres), "theta_bins": sm.theta_bins, "load_s": load}

    def build_sm_labelled(v):  # main's scene: each sampled pose labelled with its R_S in 3D text
        info = build_sm(v)
        lift = v.samples.lift
        for i, (q, r) in enumerate(zip(v.samples.poses, v.samples.rs)):
            v.scene.add_label(f"/samples/label_{i}", f"R_S {r:.2f}", position=(q[0], q[1], q[2] + lift + 0.08))
        return info

    # Scenes of each configuration: (key, build, surface-map layer class or None). "before": main before this
    # round (Chromium compositing on SwiftShader, the recolour slider); "after": software compositing, one node a
    # theta; "after_flags_recolour_slider" separates the two changes' shares of the slider time.
    configs = {"before": (PREVIOUS_FLAGS, [("empty_page", None, None), ("capability_map", build_cap, None),
                                           ("surface_map", build_sm_labelled, RecolourLayer)]),
               "after": (FLAGS, [("empty_page", None, None), ("capability_map", build_cap, None),
                                 ("surface_map", build_sm, SurfaceMapLayer),
                                 ("surface_map_recolour_slider", build_sm, RecolourLayer)]),
               "after_no_antialiasing": (FLAGS + NO_MSAA, [("surface_map", build_sm, SurfaceMapLayer)])}
    rows = {c: {key: [] for key, _, _ in scenes} for c, (_, scenes) in configs.items()}
    moves = {c: {key: [] for key, build, cls in scenes if cls} for c, (_, scenes) in configs.items()}
    browsers = {c: Browser(1280, 800, flags=flags) for c, (flags, _) in configs.items()}
    try:
        for b in browsers.values():
            b.driver.execute_cdp_cmd("Page.addScriptToEvaluateOnNewDocument", {"source": TIMING_JS})
        for _ in range(args.repeat):  # configurations interleaved: the machine's load drifts alike for both
            for c, (_, scenes) in configs.items():
                for key, build, cls in scenes:
                    if build is None:
                        build = lambda v: {}  # noqa: E731
                    elif (build is build_cap and not cap_path) or (build is build_sm and not sm_path):
                        continue
                    app.SurfaceMapLayer = cls or SurfaceMapLayer
                    try:
                        out, v = open_scene(browsers[c], build, f"{c}/{key}")
                        try:
                            if cls is not None:
                                moves[c][key] += slider_times(v, browsers[c], args.moves)
                        finally:
                            v.close()
                            # a viewer's page keeps drawing after its server is closed (viser's client redraws its
                            # scene at least once a second, a SwiftShader frame of this scene takes 0.1-0.2 s): a
                            # blank page keeps this browser idle while the other configurations are timed
                            browsers[c].driver.get("about:blank")
                    finally:
                        app.SurfaceMapLayer = SurfaceMapLayer
                    rows[c][key].append(out)
    finally:
        for b in browsers.values():
            b.close()
    for c in configs:
        result[c] = {key: _median(r) for key, r in rows[c].items() if r}
        for key, m in moves[c].items():
            if m:
                result[c][key]["slider"] = {"moves": len(m), **{f"{f}_median": round(float(np.median([x[f] for x in m])), 4)
                                                                  for f in m[0]},
                                            "page_s_max": round(max(x["page_s"] for x in m), 3),
                                            "page_s_all": [round(x["page_s"], 3) for x in m]}
    result["load_average_at_end"] = [round(x, 2) for x in os.getloadavg()]
    print(json.dumps(result, indent=2), file=json_out)


if __name__ == "__main__":
    main()
