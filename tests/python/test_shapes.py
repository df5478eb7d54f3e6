"""One shape vocabulary: a Shape in a Scene is both seen by the simulated camera and an obstacle for every
collision check (Scene.obstacles(), the exploration's physical check, the oracle); Obstacles and Scene agree on
what is solid."""
from __future__ import annotations

import numpy as np
import pytest

import octoreach
from octoreach import DepthCamera, Obstacles, Scene, Shape
from octoreach.exploration import physics
from octoreach.exploration.robot import arm_base_pose, explorer_robot


def _rot(rx: float, rz: float) -> np.ndarray:
    cx, sx, cz, sz = np.cos(rx), np.sin(rx), np.cos(rz), np.sin(rz)
    return np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]) @ np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])


def _pose(p, rx: float = 0.0, rz: float = 0.0) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = _rot(rx, rz)
    T[:3, 3] = p
    return T


def _octahedron(centre, r: float):
    v = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float) * r + centre
    f = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    return v, f


def _box_triangles(size, T):
    h = np.asarray(size, float) / 2
    v = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float) * h
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v @ T[:3, :3].T + T[:3, 3], f


# ----------------------------------------------------------------- the exploration's physical check and the camera

@pytest.fixture(scope="module")
def arm_through():
    """The explorer at the origin, an arm configuration, and a point its upper arm passes through."""
    robot, chain = explorer_robot()
    base = arm_base_pose(robot, chain)
    q = np.clip(np.zeros(chain.dof), chain.lower, chain.upper)
    root = physics.robot_root(robot, chain, base)
    poses = robot.link_poses(chain.to_robot_configuration(q))
    # a point on the segment between two joint origins far apart along the arm: inside the arm's links
    origins = [(root @ poses[n])[:3, 3] for n in robot.link_names if n in chain.moved_links]
    a, b = max(zip(origins, origins[1:]), key=lambda ab: np.linalg.norm(ab[1] - ab[0]))
    return robot, chain, base, q, (a + b) / 2


def _obstacle_scenes(point):
    """Scenes holding only a tilted box, only a mesh, only a cylinder, only a sphere around `point`."""
    tilted, mesh, cylinder, sphere = Scene(), Scene(), Scene(), Scene()
    tilted.add_shape(Shape.box([0.12, 0.12, 0.12], _pose(point, rx=0.4, rz=0.6)))
    mesh.add_mesh(*_octahedron(point, 0.1))
    cylinder.add_shape(Shape.cylinder(0.06, 0.2, _pose(point, rx=1.2, rz=0.3)))
    sphere.add_shape(Shape.sphere(0.07, _pose(point)))
    return {"tilted box": tilted, "mesh": mesh, "cylinder": cylinder, "sphere": sphere}


def test_shapes_in_a_scene_block_the_physical_check_and_are_seen(arm_through):
    robot, chain, base, q, point = arm_through
    assert physics.PhysicalCheck(robot, chain, Scene(), True).valid(q, base)  # clear without the obstacle
    camera = DepthCamera(64, 48, 1.0, 4.0)
    eye = point + np.array([1.2, 0.4, 0.5])
    for kind, scene in _obstacle_scenes(point).items():
        assert len(scene.obstacles()) == len(scene.shapes) == 1, kind
        assert not physics.PhysicalCheck(robot, chain, scene, True).valid(q, base), kind
        seen = camera.capture(scene, octoreach._core.look_at(eye, point))
        assert len(seen) > 20, kind
        assert np.all(np.linalg.norm(seen - point, axis=1) < 0.13), kind  # on the obstacle, nowhere else
        # the oracle's collision checks take the same obstacles
        assert robot.in_collision(chain.to_robot_configuration(q), scene.obstacles(),
                                  physics.robot_root(robot, chain, base), links=chain.moved_links), kind


def test_the_convenience_calls_are_shapes_too():
    s = Scene()
    s.add_box([0, 0, 0], [1, 1, 1])
    s.add_board([2, 0, 0], [2.02, 1, 0.5])
    s.add_crate([3, 0, 0], [3.4, 0.4, 0.3], 0.02)
    s.add_closed_box([4, 0, 0], [4.4, 0.4, 0.4], 0.02, "-x", 0.1, 0.1)
    s.add_mesh(*_octahedron(np.array([6.0, 0, 0.5]), 0.2))
    kinds = [x.kind for x in s.shapes]
    assert kinds.count("box") == len(s.boxes) == 1 + 1 + 5 + 9 and kinds.count("mesh") == 1
    obstacles = s.obstacles()
    assert [x.kind for x in obstacles.shapes] == kinds
    for lo, hi in s.boxes:  # each (lo, hi) box is its shape: same centre, same extents
        centre = (np.asarray(lo) + np.asarray(hi)) / 2
        assert obstacles.collides_box([1e-3] * 3, _pose(centre))
    assert obstacles.collides_box([0.02] * 3, _pose(np.array([6.0, 0, 0.5]) + 0.2 / 3))  # on a face: meshes are surfaces
    assert not obstacles.collides_box([1e-3] * 3, _pose([5.0, 2.0, 0.5]))
    flat = Scene()
    flat.add_box([0, 0, 0], [1, 1, 0])  # a flat box is seen, but without volume it is no obstacle
    assert flat.raycast([0.5, 0.5, 1], [0, 0, -1]) == pytest.approx(1.0) and len(flat.shapes) == 0


# ----------------------------------------------------------------- ray casting agrees with the shapes

def test_a_tilted_box_casts_as_its_triangles():
    T = _pose([0.3, -0.2, 0.5], rx=0.5, rz=1.1)
    solid, triangles = Scene(), Scene()
    solid.add_shape(Shape.box([0.4, 0.2, 0.3], T))
    triangles.add_mesh(*_box_triangles([0.4, 0.2, 0.3], T))
    rng = np.random.default_rng(3)
    hits = 0
    for _ in range(300):
        o = rng.uniform(-1.5, 1.5, 3) + [0.3, -0.2, 0.5]
        if solid.solid(o[None])[0]:
            continue
        d = T[:3, 3] + rng.uniform(-0.2, 0.2, 3) - o
        d /= np.linalg.norm(d)
        a, b = solid.raycast(o, d, normal=True), triangles.raycast(o, d, normal=True)
        assert (a is None) == (b is None)
        if a is not None:
            hits += 1
            assert a[0] == pytest.approx(b[0], abs=1e-9) and np.allclose(a[1], b[1], atol=1e-6)
    assert hits > 100  # most rays hit, some miss


@pytest.mark.parametrize("shape", [Shape.sphere(0.3, _pose([0.1, 0.2, 0.3])),
                                   Shape.cylinder(0.2, 0.5, _pose([0.1, 0.2, 0.3], rx=0.7, rz=0.4)),
                                   Shape.box([0.3, 0.5, 0.2], _pose([0.1, 0.2, 0.3], rx=0.3, rz=-0.8))],
                         ids=["sphere", "cylinder", "tilted box"])
def test_first_hits_lie_on_the_surface_with_outward_normals(shape):
    scene, obstacles = Scene(), Obstacles()
    scene.add_shape(shape)
    obstacles.add_shape(shape)
    rng = np.random.default_rng(5)
    centre = shape.pose[:3, 3]
    for _ in range(200):
        o = centre + rng.normal(size=3) * 0.8
        if scene.solid(o[None])[0]:
            continue
        d = centre + rng.uniform(-0.3, 0.3, 3) - o
        d /= np.linalg.norm(d)
        hit = scene.raycast(o, d, normal=True)
        if hit is None:
            assert not scene.solid(o + d * np.linspace(0, 3, 400)[:, None]).any()
            continue
        t, n = hit
        assert not scene.solid(o + d * np.linspace(0, t - 1e-6, 50)[:, None]).any()  # nothing solid before
        assert np.linalg.norm(n) == pytest.approx(1.0) and n @ d < 0
        if n @ d > -0.05:
            continue  # grazing: too little inside right after the hit to tell
        after = o + d * (t + 1e-5)
        assert scene.solid(after[None])[0]
        # the obstacle set agrees on what is solid
        assert obstacles.collides_box([1e-4] * 3, _pose(after)) and not obstacles.collides_box([1e-4] * 3,
                                                                                             _pose(o))


def test_bounds_hold_every_shape():
    s = Scene()
    s.add_shape(Shape.cylinder(0.2, 1.0, _pose([1, 0, 0], rx=np.pi / 2)))  # lying along y
    s.add_shape(Shape.sphere(0.5, _pose([-1, 0, 0])))
    lo, hi = s.bounds()
    assert np.allclose(lo, [-1.5, -0.5, -0.5]) and np.allclose(hi, [1.2, 0.5, 0.5])


def test_shape_descriptions_and_errors(tmp_path):
    box = Shape.box([0.1, 0.2, 0.3], _pose([1, 2, 3]))
    assert box.kind == "box" and np.allclose(box.size, [0.1, 0.2, 0.3]) and np.allclose(box.pose[:3, 3], [1, 2, 3])
    v, f = _octahedron(np.zeros(3), 1.0)
    mesh = Shape.triangle_mesh(v, f)
    mv, mf = mesh.mesh_triangles()
    assert np.allclose(mv, v) and np.array_equal(mf, f)
    with pytest.raises(ValueError, match="not a triangle mesh"):
        box.mesh_triangles()
    for bad in (lambda: Shape.box([0.1, -1, 0.1]), lambda: Shape.sphere(0.0), lambda: Shape.cylinder(0.1, np.nan),
                lambda: Shape.box([1, 1, 1], np.full((4, 4), np.nan))):
        with pytest.raises(ValueError):
            bad()
    with pytest.raises(OSError):
        Shape.mesh_file(str(tmp_path / "missing.stl"))
    obstacles = Obstacles()
    obstacles.add_shape(box, "b")
    obstacles.add_sphere(0.1, _pose([0, 0, 0]))
    assert [s.kind for s in obstacles.shapes] == ["box", "sphere"] and obstacles.names[0] == "b"
    scene = Scene()
    scene.add_obstacles(obstacles)
    assert [s.kind for s in scene.shapes] == ["box", "sphere"]
    assert scene.raycast([1, 2, 5], [0, 0, -1]) == pytest.approx(5 - 3.15)
