"""The seeded scene families (octoreach.testing.scene_families): deterministic per seed, independent of what
was drawn before, every instance with interiors and a target that lies in one of them, clear of every solid
and hidden from the start view; the staircase and ring parts close (no gaps a ray could pass)."""
import numpy as np
import pytest

from octoreach import Scene
from octoreach import testing
from octoreach.testing import scene_families as sf
from octoreach.testing import scene_parts


def _fingerprint(inst):
    s = inst.scene
    return (np.array(s.boxes, float).tobytes(), np.array(s.interiors, float).tobytes(), inst.target.tobytes())


@pytest.mark.parametrize("family", testing.FAMILIES)
def test_families_are_deterministic_per_seed_and_independent_of_order(family):
    a = [testing.family_scene(family, k) for k in range(3)]
    b = [testing.family_scene(family, k) for k in (2, 1, 0)][::-1]
    assert [_fingerprint(x) for x in a] == [_fingerprint(x) for x in b]
    assert len({_fingerprint(x) for x in a}) == 3  # three different instances
    assert [x.name for x in a] == [f"{family}_{k}" for k in range(3)]


@pytest.mark.parametrize("family", testing.FAMILIES)
def test_every_instance_hides_its_target_in_an_interior(family):
    for inst in testing.family_instances(family, 5):
        s, t = inst.scene, inst.target
        assert s.interiors, inst.name
        centre = t.mean(axis=0)
        assert any(np.all(centre >= lo) and np.all(centre <= hi) for lo, hi in s.interiors), inst.name
        # the target is the scene's last box; nothing else overlaps it
        others = Scene()
        for lo, hi in s.boxes[:-1]:
            others.add_box(lo, hi)
        np.testing.assert_allclose(np.array(s.boxes[-1]), t)
        assert sf._target_clear(others, t), inst.name
        assert sf._hidden(s, t), inst.name
        # everything stands in front of the robot (its base reaches x = 0.3), on the floor, inside 1.3 m
        objs = np.array([b for b in s.boxes if np.max(np.subtract(b[1], b[0])[:2]) < 2.0])
        assert objs[:, 0, 0].min() >= 0.3 and objs[:, 1, 0].max() <= 1.35 and objs[:, 0, 2].min() >= 0.0, inst.name


def test_unknown_family_and_bad_seed_raise():
    with pytest.raises(ValueError, match="unknown family"):
        testing.family_scene("castles", 0)
    for bad in (-1, 1.5, True):
        with pytest.raises(ValueError, match="seed"):
            testing.family_scene("pipes", bad)


def _rays_through(scene, origins, direction):
    """How many of the rays from `origins` along `direction` meet no surface within 2 m."""
    return sum(scene.raycast(o, direction, 2.0) is None for o in origins)


def test_tilted_plate_and_turned_block_have_no_gaps():
    s = Scene()
    scene_parts.add_tilted_plate(s, 0, 0.5, 1.0, -0.2, 0.2, 0.0, 0.3, 0.02)
    # straight down through the plate anywhere over it: every ray meets it
    xs = np.linspace(0.505, 0.995, 60)
    assert _rays_through(s, [(x, 0.0, 1.0) for x in xs], (0.0, 0.0, -1.0)) == 0
    # along the slope, inside the plate's thickness: the steps leave no slit between them
    assert _rays_through(s, [(0.4, y, -0.05) for y in (-0.1, 0.0, 0.1)], (0.857, 0.0, 0.514)) == 0
    b = Scene()
    scene_parts.add_turned_block(b, (0.8, 0.0), (0.3, 0.1), 0.6, 0.0, 0.2)
    R = np.array([[np.cos(0.6), -np.sin(0.6)], [np.sin(0.6), np.cos(0.6)]])
    inside = [(0.8, 0.0) + R @ (u, v) for u in np.linspace(-0.14, 0.14, 8) for v in (-0.04, 0.0, 0.04)]
    assert np.all(b.solid([(x, y, 0.1) for x, y in inside]))


def test_round_pipe_is_closed_around_its_bore():
    s = Scene()
    scene_parts.add_round_pipe(s, 1, -0.3, 0.3, (0.8, 0.2), 0.1, 0.115)
    angles = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    # from the axis outwards, every ray meets the ring within its outer radius
    hits = [s.raycast((0.8, 0.0, 0.2), (np.cos(a), 0.0, np.sin(a)), 0.2) for a in angles]
    assert all(h is not None and 0.085 <= h <= 0.116 for h in hits)
    # along the axis the bore is open
    assert s.raycast((0.8, -0.5, 0.2), (0.0, 1.0, 0.0), 1.0) is None
