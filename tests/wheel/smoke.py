"""The repaired wheel on a bare Linux: install it as a user would and touch every library it vendors.

    python3 smoke.py WHEEL [--extras-line]

Run by `make test-wheel` inside a bare Debian 12 root (debootstrap minbase + python3-venv: no compiler, no
-dev package, none of the C++ libraries), with Debian's python3. It makes a fresh virtual environment, times
`pip install WHEEL[robots]` (the downloads from PyPI without a pip cache, then the install from them) and the
first surface map from the command line, installs the viewer extra, then runs the checks of `--checks` with
the environment's interpreter:
a robot by name and a URDF with STL and DAE meshes (assimp, urdfdom, tinyxml, console_bridge), self-collision
(FCL, libccd), a capability map, a surface map of a room with a mesh obstacle, sampling, save and load of
every map kind (zlib), an OctoMap .bt written and read (OctoMap), an exploration insert with voids (Qhull)
and next_best_view, `octoreach --help` and `octoreach view --html`. Last, without example-robot-data:
`import octoreach` works and robots.load says to install the robots extra, whose advice then works.
--extras-line also installs the install page's line (docs/install.md: every extra) into a second environment. Prints the times
as JSON on the last line; exits non-zero on any failure.
"""
from __future__ import annotations

import json
import os
import resource
import shutil
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

FIRST_MAP = ["surface", "--robot", "pr2", "--arms", "right_arm", "--table", "1.4", "0.65", "0.72",
             "--resolution", "0.1"]


def run(cmd, **kwargs):
    print("+", " ".join(str(c) for c in cmd), flush=True)
    return subprocess.run([str(c) for c in cmd], check=True, **kwargs)


def timed(cmd, times: dict, key: str, **kwargs) -> None:
    """Runs cmd; times[key] = its wall seconds, times[key + '_cpu'] = its CPU seconds (user + system)."""
    c0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    run(cmd, **kwargs)
    c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    times[key] = time.perf_counter() - t0
    times[key + "_cpu"] = (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)


def outer(wheel: Path, extras_line: bool) -> int:
    work = Path(tempfile.mkdtemp(prefix="octoreach-smoke-"))
    env = dict(os.environ, HOME=str(work / "home"), PIP_NO_CACHE_DIR="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
    (work / "home").mkdir()
    venv = work / "venv"
    run([sys.executable, "-m", "venv", venv])
    py, pip, cli = venv / "bin" / "python", [venv / "bin" / "python", "-m", "pip"], venv / "bin" / "octoreach"
    times = {}
    # pip install WHEEL[robots], in two steps to tell the network from the machine: the downloads, then the
    # install from them alone.
    timed([*pip, "download", "-q", "-d", work / "wheels", f"{wheel}[robots]"], times, "download_s", env=env)
    timed([*pip, "install", "-q", "--no-index", "--find-links", work / "wheels", f"{wheel}[robots]"], times,
          "install_s", env=env)
    timed([cli, *FIRST_MAP, "--out", work / "first.orsm", "--quiet"], times, "first_map_s", env=env, cwd=work)
    times["total_s"] = times["download_s"] + times["install_s"] + times["first_map_s"]
    print(f"octoreach smoke: download {times['download_s']:.1f} s + install {times['install_s']:.1f} s + first "
          f"surface map {times['first_map_s']:.1f} s (CPU {times['first_map_s_cpu']:.1f} s) = "
          f"{times['total_s']:.1f} s", flush=True)
    timed([*pip, "install", "-q", f"{wheel}[viewer]"], times, "viewer_extra_s", env=env)
    run([py, Path(__file__).resolve(), "--checks", work / "first.orsm"], env=env, cwd=work)
    # Without example-robot-data: the package imports, robots.load names the extra, and its advice works.
    run([*pip, "uninstall", "-q", "-y", "example-robot-data"], env=env)
    run([py, "-c", "import octoreach\ntry:\n    octoreach.robots.load('pr2')\nexcept FileNotFoundError as e:\n"
         "    assert \"octoreach[robots]\" in str(e), e\n    print('without example-robot-data:', e)\n"
         "else:\n    raise SystemExit('robots.load worked without example-robot-data')"], env=env, cwd=work)
    run([*pip, "install", "-q", "octoreach[robots]"], env=env)
    run([py, "-c", "import octoreach; print('robots extra back:', octoreach.robots.load('pr2'))"], env=env, cwd=work)
    if extras_line:
        venv2 = work / "venv-all"
        run([sys.executable, "-m", "venv", venv2])
        timed([venv2 / "bin" / "python", "-m", "pip", "install", "-q", f"{wheel}[viewer,planning,cluster,robots]"],
              times, "all_extras_install_s", env=env)
        run([venv2 / "bin" / "python", "-c", "import octoreach.planning, octoreach.cluster, octoreach.viewer, ray, "
             "unified_planning; print('every extra imports')"], env=env, cwd=work)
    shutil.rmtree(work)
    print(json.dumps({k: round(v, 2) for k, v in times.items()}))
    return 0


# ---------------------------------------------------------------- the checks, run in the environment


def box_triangles(lo, hi):
    """12 outward-facing triangles of an axis-aligned box."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5), (2, 3, 7),
             (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    return v, faces


def write_stl(path: Path, lo, hi) -> None:
    v, faces = box_triangles(lo, hi)
    with open(path, "wb") as f:
        f.write(b"octoreach smoke box".ljust(80, b" ") + struct.pack("<I", len(faces)))
        for a, b, c in faces:
            f.write(struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *v[i]) for i in (a, b, c)) + b"\0\0")


def write_dae(path: Path, lo, hi) -> None:
    v, faces = box_triangles(lo, hi)
    pos = " ".join(f"{c:g}" for p in v for c in p)
    tri = " ".join(str(i) for t in faces for i in t)
    path.write_text(f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="box" name="box"><mesh>
    <source id="box-pos"><float_array id="box-pos-array" count="{len(v) * 3}">{pos}</float_array>
      <technique_common><accessor source="#box-pos-array" count="{len(v)}" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="box-vtx"><input semantic="POSITION" source="#box-pos"/></vertices>
    <triangles count="{len(faces)}"><input semantic="VERTEX" source="#box-vtx" offset="0"/><p>{tri}</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="box-node">
    <instance_geometry url="#box"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
""")


def mesh_robot(tmp: Path):
    """A two-joint arm: an STL base and a DAE forearm that folds back into the base."""
    import octoreach

    write_stl(tmp / "base.stl", (-0.1, -0.1, -0.1), (0.1, 0.1, 0.1))
    write_dae(tmp / "forearm.dae", (0.05, -0.02, -0.02), (0.35, 0.02, 0.02))
    limit = '<limit lower="-3" upper="3" effort="1" velocity="1"/>'
    urdf = tmp / "smoke_arm.urdf"
    urdf.write_text(f"""<robot name="smoke_arm">
  <link name="base_link"><collision><geometry><mesh filename="{tmp / 'base.stl'}"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base_link"/><child link="upper_arm"/>
    <origin xyz="0 0 0.15"/><axis xyz="0 0 1"/>{limit}</joint>
  <link name="upper_arm"><collision><origin xyz="0.15 0 0"/><geometry><box size="0.3 0.04 0.04"/></geometry>
  </collision></link>
  <joint name="j2" type="revolute"><parent link="upper_arm"/><child link="forearm"/>
    <origin xyz="0.3 0 0"/><axis xyz="0 1 0"/>{limit}</joint>
  <link name="forearm"><collision><geometry><mesh filename="{tmp / 'forearm.dae'}"/></geometry></collision></link>
</robot>""")
    robot = octoreach.Robot.from_urdf(str(urdf))
    assert robot.self_collisions([0.0, 0.0]) == [], robot.self_collisions([0.0, 0.0])
    folded = {frozenset(p) for p in robot.self_collisions([0.0, 2.68])}  # the forearm points into the base
    assert frozenset(("base_link", "forearm")) in folded, folded
    z, link = robot.lowest_point([0.0, 0.0])
    assert abs(z + 0.1) < 1e-6 and link == "base_link", (z, link)  # the STL box's bottom
    print("URDF with STL and DAE meshes: self-collision of the folded arm found")


def maps(tmp: Path, first_map: Path):
    import numpy as np

    import octoreach
    from octoreach import arms, map_files

    pr2 = octoreach.robots.load("pr2")
    assert pr2.self_collisions(pr2.home()) == []
    cap = arms.capability_map(pr2, "right_arm", resolution=0.15, progress=False, cache=False)
    write_stl(tmp / "bin.stl", (-0.15, -0.15, 0.0), (0.15, 0.15, 0.5))
    room = octoreach.Room()
    room.add_table("table", 1.4, 0.65, 0.72)
    room.add_mesh("bin", str(tmp / "bin.stl"), xyz=(0.0, -0.9, 0.0))
    smap = room.surface_maps(pr2, cap, progress=False, resolution=0.15)["table"]
    poses = octoreach.PoseSampler(smap, seed=1, in_collision=(pr2, room.obstacles())).sample(3)
    assert len(poses) == 3 and np.all(smap.reachability(np.asarray(poses)) > 0), poses
    near_bin = np.array([[0.0, -0.9, 0.0, 1.57]])
    assert smap.reachability(near_bin)[0] == 0, "a base pose inside the mesh obstacle has R_S > 0"
    pmap = octoreach.InversePointMap.build(pr2, cap, progress=False)
    for name, m in (("cap.orcm", cap), ("points.orpm", pmap), ("table.orsm", smap)):
        (m.save(str(tmp / name), with_solutions=True) if name.endswith(".orcm") else m.save(str(tmp / name)))
        back = map_files.load(tmp / name)
        assert type(back) is type(m), (name, type(back))
        m.export_octovis(str(tmp / (name + ".ot")))
    first = map_files.load(first_map)
    print(f"maps: capability, inverse point and surface maps saved and loaded; sampled {len(poses)} poses; "
          f"first map {first}")


def exploration(tmp: Path):
    import numpy as np

    from octoreach import DepthCamera, ExplorationMap, Scene, next_best_view
    from octoreach import exploration as ex

    scene = ex.closed_box_scene("+y", 0.16)
    emap = ExplorationMap(resolution=0.04, search_space=ex.scene_region(scene))
    cam = DepthCamera(160, 120, np.deg2rad(58.0), 3.0)
    for eye in [(0.0, -0.3, 0.9), (1.6, -0.3, 0.9), (0.8, -0.9, 0.9), (0.0, 0.6, 0.9), (1.6, 0.6, 0.9)]:
        T = ex.look_at(eye, (0.8, 0.0, 0.2))
        emap.insert(cam.capture(scene, T), T[:3, 3], cam.max_range)
    assert emap.void_clusters() and emap.void_cell_count > 100, emap.void_cell_count
    r = next_best_view(emap, cam, workspace_sphere=((0.8, 0.0, 0.3), 1.0), min_distance=0.05)
    assert r.best_pose is not None and r.void_cells > 0, r.void_cells
    emap.write_bt(str(tmp / "scan.bt"))
    back = ExplorationMap.from_file(str(tmp / "scan.bt"), search_space=ex.scene_region(scene))
    assert back.occupancy_digest()["occupied"] == emap.occupancy_digest()["occupied"]
    world = Scene()
    world.load_octomap(str(tmp / "scan.bt"))
    print(f"exploration: {len(emap.void_clusters())} void(s), next best view sees {r.void_cells} void cells; "
          ".bt written and read")


def command_line(first_map: Path, tmp: Path):
    cli = Path(sys.executable).parent / "octoreach"
    run([cli, "--help"], stdout=subprocess.DEVNULL)
    run([cli, "sample", first_map, "--count", "3"])
    page = tmp / "view.html"
    run([cli, "view", first_map, "--robot", "pr2", "--html", page, "--no-serve"])
    text = page.read_text()
    assert text.lstrip().lower().startswith("<!doctype html") or "<html" in text[:2000], text[:200]
    print(f"command line: --help, sample, view --html ({len(text) // 1024} kB page)")


def checks(first_map: Path) -> int:
    t0 = time.perf_counter()
    import octoreach

    print(f"octoreach {octoreach.__version__} from {Path(octoreach.__file__).parent} "
          f"(import {time.perf_counter() - t0:.2f} s)")
    tmp = Path(tempfile.mkdtemp(prefix="octoreach-checks-"))
    mesh_robot(tmp)
    maps(tmp, first_map)
    exploration(tmp)
    command_line(first_map, tmp)
    shutil.rmtree(tmp)
    print("octoreach smoke: every check passed")
    return 0


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--checks":
        sys.exit(checks(Path(sys.argv[2])))
    if len(sys.argv) in (2, 3) and sys.argv[1].endswith(".whl") and sys.argv[2:] in ([], ["--extras-line"]):
        sys.exit(outer(Path(sys.argv[1]).resolve(), sys.argv[2:] == ["--extras-line"]))
    sys.exit(__doc__)
