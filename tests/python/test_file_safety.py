"""Files octoreach writes and reads: a save cannot be redirected (a link planted at a temporary name or at the
target changes no other file; devices, FIFOs and links are refused, never replaced; nothing is left behind), a
read takes only a regular file under a stated size (a FIFO or /dev/zero fails at once instead of hanging or
filling memory), and a map file cannot make the reader inflate more than its header's counts declare. Calls
that could hang on a broken build run in a child process with a timeout and a memory cap."""
from __future__ import annotations

import os
import stat

import numpy as np
import pytest

import octoreach
from robust_util import forge, read_map, run_python, write_map

SAVERS = ["capability_save", "capability_octovis", "surface_save", "point_save", "write_bt", "write_srdf"]


@pytest.fixture(scope="module")
def maps(tmp_path_factory):
    d = tmp_path_factory.mktemp("safety")
    robot = octoreach.robots.test_arm()
    cap = octoreach.CapabilityMap.build(robot.chain("base_link", "tool0"), resolution=0.2, directions=16,
                                        progress=False, seed=1)
    sm = octoreach.SurfaceMap.build(robot, cap, octoreach.Surface.rectangle(0.6, 0.4, 0.4, x=0.55), resolution=0.2,
                                    theta_bins=8, z_range=(0, 0), progress=False)
    pm = octoreach.InversePointMap.build(robot, cap, theta_bins=8, progress=False)
    m = octoreach.ExplorationMap(resolution=0.1)
    m.insert(np.random.default_rng(0).uniform([1, -0.5, 0], [1.6, 0.5, 0.6], (500, 3)), [0, 0, 0.3])
    cap.save(str(d / "cap.orcm"), with_solutions=True)
    sm.save(str(d / "surf.orsm"))
    savers = {
        "capability_save": lambda p: cap.save(p, with_solutions=True),
        "capability_octovis": cap.export_octovis,
        "surface_save": sm.save,
        "point_save": pm.save,
        "write_bt": m.write_bt,
        "write_srdf": robot.write_srdf,
    }
    return dict(robot=robot, cap=cap, sm=sm, dir=d, savers=savers)


def _victim(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_bytes(b"the victim's own bytes")
    return victim


# ---- writes ----

@pytest.mark.parametrize("kind", SAVERS)
def test_links_planted_at_temporary_names_change_no_file(kind, maps, tmp_path):
    # The names a predictable writer would use (<path>.tmp.<pid>.<n>, <path>.tmp, <path>~) all point at a victim:
    # the save writes its own new file, the victim and the links stay as they were, no temporary file is left.
    victim = _victim(tmp_path)
    target = tmp_path / "out.bin"
    links = [f"{target}.tmp.{os.getpid()}.{n}" for n in range(64)] + [f"{target}.tmp", f"{target}~"]
    for name in links:
        os.symlink(victim, name)
    maps["savers"][kind](str(target))
    assert victim.read_bytes() == b"the victim's own bytes"
    assert stat.S_ISREG(os.lstat(target).st_mode) and target.stat().st_size > 0
    assert all(os.path.islink(name) for name in links)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        [victim.name, target.name] + [os.path.basename(n) for n in links])


@pytest.mark.parametrize("kind", SAVERS)
def test_a_link_at_the_target_is_refused(kind, maps, tmp_path):
    victim = _victim(tmp_path)
    target = tmp_path / "out.bin"
    os.symlink(victim, target)
    with pytest.raises(OSError, match="symbolic link"):
        maps["savers"][kind](str(target))
    assert os.path.islink(target) and victim.read_bytes() == b"the victim's own bytes"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([victim.name, target.name])


@pytest.mark.parametrize("kind", SAVERS)
def test_a_fifo_or_folder_at_the_target_is_refused(kind, maps, tmp_path):
    fifo, folder = tmp_path / "fifo", tmp_path / "folder"
    os.mkfifo(fifo)
    folder.mkdir()
    for target, what in ((fifo, "FIFO"), (folder, "directory")):
        with pytest.raises(OSError, match=what):
            maps["savers"][kind](str(target))
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode) and folder.is_dir()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fifo", "folder"]


def _device_node(tmp_path):
    """A character device like /dev/full in tmp_path (root can make one), or /dev/full itself when this user
    cannot replace it anyway; None otherwise."""
    node = tmp_path / "full"
    try:
        os.mknod(node, 0o666 | stat.S_IFCHR, os.makedev(1, 7))
        return node
    except (PermissionError, OSError):
        return "/dev/full" if not os.access("/dev", os.W_OK) else None


@pytest.mark.parametrize("kind", SAVERS)
def test_a_device_at_the_target_is_refused(kind, maps, tmp_path):
    device = _device_node(tmp_path)
    if device is None:
        pytest.skip("cannot make a device node here")
    with pytest.raises(OSError, match="device"):
        maps["savers"][kind](str(device))
    assert stat.S_ISCHR(os.lstat(device).st_mode)


def test_a_failed_write_leaves_no_temporary_file(maps, tmp_path):
    # /dev/full-like failure: the file size limit makes every write past 1 kB fail (EFBIG).
    target = tmp_path / "cap.orcm"
    child = run_python(f"""
import os, resource, signal, octoreach as o
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
cap = o.CapabilityMap.load({str(maps['dir'] / 'cap.orcm')!r})
resource.setrlimit(resource.RLIMIT_FSIZE, (1024, 1024))
try:
    cap.save({str(target)!r}, with_solutions=True)
    print('NO ERROR')
except OSError as e:
    print('OSError', e)
print('LEFT', sorted(os.listdir({str(tmp_path)!r})))
""", timeout=120)
    assert child.returncode == 0, child.stderr[-2000:]
    assert "OSError" in child.stdout and "LEFT []" in child.stdout, child.stdout


# ---- reads ----

def _in_child(statement: str, mem: int = 1 << 30) -> str:
    """What `statement` (using `o` for octoreach, `np`) does in a child process of `mem` bytes of address space:
    LOADED, or OSError and its message."""
    child = run_python(f"""
import numpy as np, octoreach as o
try:
    {statement}
    print('LOADED')
except OSError as e:
    print('OSError', e)
""", timeout=60, mem_bytes=mem)
    assert not child.hung, f"still running after 60 s: {statement}"
    assert child.returncode == 0, (statement, child.stderr[-1500:])
    return child.stdout

def _readers():
    """(label, code reading PATH) for every reader of a file path."""
    return {
        "urdf": "o.Robot.from_urdf(PATH)",
        "srdf": f"o.Robot.from_urdf({str(octoreach.robots.project_urdf('test_arm'))!r}, srdf=PATH)",
        "point_map": "o.InversePointMap.load(PATH)",
        "mesh": "o.Obstacles().add_mesh(PATH, np.eye(4))",
        "bt": "o.ExplorationMap.from_file(PATH)",
        "scene_bt": "o.Scene().load_octomap(PATH)",
        "octree_ot": "o.Obstacles().add_octree_file(PATH + '.ot')",
        "octree_bt": "o.Obstacles().add_octree_file(PATH)",
        "capability_map": "o.CapabilityMap.load(PATH)",
        "surface_map": "o.SurfaceMap.load(PATH)",
    }


@pytest.mark.parametrize("special", ["fifo", "dev_zero", "folder", "oversized"])
def test_reads_take_only_regular_files_under_the_limit(special, tmp_path):
    # A FIFO with no writer used to block the open forever, /dev/zero to fill memory; a file over its size
    # limit (sparse: no disk used) is refused before it is read.
    path = tmp_path / "input"
    if special == "fifo":
        os.mkfifo(path)
        os.mkfifo(str(path) + ".ot")
    elif special == "dev_zero":
        os.symlink("/dev/zero", path)
        os.symlink("/dev/zero", str(path) + ".ot")
    elif special == "folder":
        path.mkdir()
        os.mkdir(str(path) + ".ot")
    else:
        for p in (path, str(path) + ".ot"):
            with open(p, "wb") as f:
                f.truncate(octoreach._core.limits["map_file_bytes"] + 1)
    expected = {"fifo": "FIFO", "dev_zero": "device", "folder": "directory", "oversized": "limit"}[special]
    for label, code in _readers().items():
        out = _in_child(code.replace("PATH", repr(str(path))), mem=2 << 30)
        assert "OSError" in out and expected in out, (label, out)


# ---- decompression ----

def test_declared_payload_beyond_the_header_counts_is_refused_before_inflating(maps, tmp_path):
    # The raw size is not covered by the checksum: a 2.5 MB file (2 MB of noise after the real contents, so that
    # 2 GB stays under zlib's largest ratio) declaring 2 GB of contents used to allocate 2 GB before it was
    # refused. Now the header's counts bound it first: the child, capped at 1 GB of address space, gets an
    # OSError, never a MemoryError.
    import zlib
    for src in ("cap.orcm", "surf.orsm"):
        m = read_map(maps["dir"] / src)
        m.compressed = zlib.compress(m.payload() + os.urandom(2 << 20))
        m.raw_size = 2 << 30
        write_map(tmp_path / src, m)
        load = "CapabilityMap" if src.endswith("orcm") else "SurfaceMap"
        out = _in_child(f"o.{load}.load({str(tmp_path / src)!r})")
        assert "OSError" in out and "header's counts" in out, out


def test_a_real_bomb_with_honest_counts_is_refused_before_inflating(maps, tmp_path):
    # 2 MB of zlib data inflating to 2 GB, under a header whose voxel count is the real map's: refused by
    # the declared contents, inflated never (the child has 1 GB of address space).
    import zlib
    m = read_map(maps["dir"] / "surf.orsm")
    comp = zlib.compressobj(9)
    chunk = bytes(1 << 24)
    parts = [comp.compress(chunk) for _ in range(128)] + [comp.flush()]
    m.compressed = b"".join(parts)
    m.raw_size = 128 << 24
    write_map(tmp_path / "bomb.orsm", m)
    assert (tmp_path / "bomb.orsm").stat().st_size < 4 << 20
    out = _in_child(f"o.SurfaceMap.load({str(tmp_path / 'bomb.orsm')!r})")
    assert "OSError" in out and "header's counts" in out, out


@pytest.mark.parametrize("voxels", [2**31 + 1, 2**40, 2**64 - 1])
def test_absurd_voxel_counts_in_a_header_are_refused(voxels, maps, tmp_path):
    for src, load in (("cap.orcm", octoreach.CapabilityMap.load), ("surf.orsm", octoreach.SurfaceMap.load)):
        forge(maps["dir"] / src, tmp_path / src, voxels=voxels)
        with pytest.raises(OSError, match="voxels"):
            load(str(tmp_path / src))


def test_honest_maps_still_load(maps):
    cap = octoreach.CapabilityMap.load(str(maps["dir"] / "cap.orcm"))
    assert cap.voxel_count == maps["cap"].voxel_count
    assert octoreach.SurfaceMap.load(str(maps["dir"] / "surf.orsm")).resolution == maps["sm"].resolution


_VISUAL_URDF = """<robot name="visual_only">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="tool"><visual><geometry><mesh filename="{mesh}"/></geometry></visual></link>
  <joint name="turn" type="revolute"><parent link="base"/><child link="tool"/><origin xyz="0 0 0.1"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>
"""


@pytest.mark.parametrize("mesh", ["tool.stl", "tool.dae"])
@pytest.mark.parametrize("special", ["fifo", "dev_zero", "oversized"])
def test_visual_meshes_the_viewer_reads_are_bounded(tmp_path, mesh, special):
    # The loader resolves a visual mesh without reading it; the viewer reads it to draw the robot. A FIFO there
    # used to block the viewer for good, /dev/zero to fill its memory: both are refused, as oversized files are.
    path = tmp_path / mesh
    if special == "fifo":
        os.mkfifo(path)
    elif special == "dev_zero":
        os.symlink("/dev/zero", path)
    else:
        with open(path, "wb") as f:
            f.truncate(octoreach._core.limits["mesh_file_bytes"] + 1)
    (tmp_path / "robot.urdf").write_text(_VISUAL_URDF.format(mesh=mesh))
    child = run_python(f"""
import octoreach as o
from octoreach.viewer.robot_meshes import RobotMeshes
robot = o.Robot.from_urdf({str(tmp_path / 'robot.urdf')!r})
assert robot.visuals['tool'][0].shape.mesh_path, 'the loader resolves the visual mesh'
try:
    RobotMeshes(robot)
    print('DRAWN')
except OSError as e:
    print('OSError', e)
""", timeout=60, mem_bytes=1 << 30)
    assert not child.hung, "the viewer still reads the visual mesh after 60 s"
    assert child.returncode == 0, child.stderr[-2000:]
    expected = {"fifo": "FIFO", "dev_zero": "character device", "oversized": "mesh_file_bytes"}[special]
    assert "OSError" in child.stdout and expected in child.stdout and mesh in child.stdout, child.stdout
