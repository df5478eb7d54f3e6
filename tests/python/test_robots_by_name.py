"""Any robot by name: every example-robot-data URDF loads, arms and approach axes are found without a
file of ours, the allowed-collision matrix is sampled as MoveIt's setup assistant does, bad names say
what exists."""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import octoreach
from octoreach import Arm, Robot, find_arms, robots

try:
    robots.data_dir()
except FileNotFoundError:  # pragma: no cover - the robots extra installs it
    pytest.skip("example-robot-data is not installed", allow_module_level=True)


def test_every_example_robot_data_urdf_loads_by_name():
    names = robots.available()
    files = {str(p) for p, _ in robots._index().values()}
    # Every URDF of the package has a name (robots/<x>/urdf/ and robots/<x>/robots/ alike).
    on_disk = {str(p) for p in (robots.data_dir() / "robots").glob("*/*/*.urdf") if p.parent.name in ("urdf", "robots")}
    assert on_disk <= files and len(on_disk) >= 60
    for name in ("tiago", "talos_reduced", "icub", "kinova", "solo12", "anymal_b_simple/anymal", "ur10", "panda"):
        assert name in names
    # Two URDFs of the package are malformed: loading them says what is wrong.
    broken = {"alex_psyonic_hands": "mimics unknown joint 'index_q1'; did you mean 'Left_index_q1'",
              "ur/ur3": "<robot> has no name"}
    for name in names:  # load only (meshes resolved, SRDF read): no sampling, no maps
        if name in broken:  # the package's URDF is malformed: the error says how
            with pytest.raises(ValueError, match=broken[name]):
                robots.load(name, allowed_collisions="srdf")
            continue
        robot = robots.load(name, allowed_collisions="srdf")
        assert len(robot.link_names) >= 1, name


def test_ambiguous_and_unknown_robot_names():
    with pytest.raises(ValueError, match="ambiguous.*anymal_b_simple/anymal"):
        robots.load("anymal")
    with pytest.raises(ValueError, match="did you mean 'tiago'"):
        robots.load("tiagoo")


def test_path_and_string_with_package_dirs_keep_working():
    urdf, srdf = robots._index()["panda"]
    dirs = robots.package_dirs()
    by_path = Robot.from_urdf(str(urdf), package_dirs=dirs, srdf=str(srdf))
    by_text = Robot.from_urdf(urdf.read_text(), package_dirs=dirs, srdf=srdf.read_text())
    assert by_path.model_hash == by_text.model_hash
    assert Arm.named(by_text, "arm").tip_link == "panda_hand_tcp"


# How the expected axes were decided (a human looking at the gripper):
# - TIAGo (Hey5 hand): hand_grasping_frame sits 0.13 m ahead of the palm along the palm's +x, and the
#   finger bases (hand_*_abd_joint at x = 0.09..0.13 m) lie along +x too: the hand closes around
#   an object ahead of it on +x. The user found +x by hand (R_S 0.249 vs 0.267 with +z).
# - Panda: panda_hand_tcp is 0.1034 m along +z of panda_hand, the fingers slide along y and reach
#   out along +z: +z (Franka's convention for the TCP).
# - PR2: r/l_gripper_tool_frame is 0.18 m along +x of the palm, the fingers reach along +x: +x, as the
#   old hand-written table said.
@pytest.mark.parametrize("name, arm, base, tip, axis, source", [
    ("tiago", "arm", "torso_lift_link", "hand_grasping_frame", (1, 0, 0), "kinematic tree"),
    ("panda", "arm", "panda_link0", "panda_hand_tcp", (0, 0, 1), "SRDF joint-list group"),
    ("pr2", "right_arm", "torso_lift_link", "r_gripper_tool_frame", (1, 0, 0), "SRDF chain group"),
    ("pr2", "left_arm", "torso_lift_link", "l_gripper_tool_frame", (1, 0, 0), "SRDF chain group"),
])
def test_arms_found_by_name_with_inferred_approach_axis(name, arm, base, tip, axis, source):
    robot = robots.load(name, allowed_collisions="srdf")
    a = Arm.named(robot, arm)
    assert (a.base_link, a.tip_link) == (base, tip)
    np.testing.assert_allclose(a.approach_axis, axis)
    assert a.source.startswith(source)
    assert "wrist joint" in a.reason and a.reason.startswith(("+x", "+z"))
    assert arm in [x.name for x in find_arms(robot)]


def test_approach_axis_override_and_errors():
    robot = robots.load("tiago", allowed_collisions="srdf")
    a = Arm.resolve(robot, "arm", approach_axis=(0, 0, 2))
    np.testing.assert_allclose(a.approach_axis, (0, 0, 1))
    assert a.reason == "given"
    # A tool frame at a prismatic wrist, no fingers: nothing to infer from; raise and say how to give it.
    slider = """<robot name="slider">
      <link name="base"/><link name="l1"/><link name="l2"/>
      <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="j2" type="prismatic"><parent link="l1"/><child link="l2"/><origin xyz="0.3 0 0"/><axis xyz="1 0 0"/>
        <limit lower="0" upper="0.2" effort="1" velocity="1"/></joint></robot>"""
    with pytest.raises(ValueError, match=r"cannot infer the approach axis of 'l2'.*approach_axis=\(x, y, z\).*--approach-axis X Y Z"):
        Arm.from_links(Robot.from_urdf(slider), "base", "l2")
    # ... and the axis the message asks for is taken, as a keyword too (nothing is inferred first).
    given = Arm.resolve(Robot.from_urdf(slider), ("base", "l2"), approach_axis=(1, 0, 0))
    assert given.reason == "given" and tuple(given.approach_axis) == (1, 0, 0)


def test_arm_name_error_lists_the_arms():
    robot = robots.load("pr2", allowed_collisions="srdf")
    with pytest.raises(ValueError, match=r"no arm 'rigth_arm'; did you mean 'right_arm'.*Its arms: 'left_arm' \(torso_lift_link -> l_gripper_tool_frame\)"):
        Arm.named(robot, "rigth_arm")


def test_link_name_error_suggests_nearest_names():
    robot = robots.load("tiago", allowed_collisions="srdf")
    with pytest.raises(ValueError, match="no link named 'hand_grasp_frame'; did you mean 'hand_grasping_frame'"):
        Arm.resolve(robot, ("torso_lift_link", "hand_grasp_frame"))


def test_srdf_that_disagrees_with_the_urdf_says_which():
    urdf, _ = robots._index()["panda"]
    srdf = """<robot name="panda"><group name="arm"><chain base_link="panda_link0" tip_link="panda_hnd"/></group>
              <group name="x"><joint name="panda_joint9"/></group></robot>"""
    with pytest.raises(ValueError, match=r"link 'panda_hnd'.*did you mean 'panda_hand'.*joint 'panda_joint9'"):
        Robot.from_urdf(str(urdf), package_dirs=robots.package_dirs(), srdf=srdf)


def test_srdf_entries_the_urdf_does_not_fit_are_left_out_on_request_and_the_rest_is_read():
    urdf = robots.project_urdf("test_arm")
    plain = Robot.from_urdf(str(urdf))
    name, joint, link = plain.name, plain.joint_names[0], plain.link_names[1]
    # g_bad names a link the URDF lacks; g_sub has it as a subgroup; the end effector uses g_sub: all three go,
    # the rest (g_ok, its state, the disabled pair) stays.
    srdf = f"""<robot name="{name}">
      <group name="g_ok"><joint name="{joint}"/></group>
      <group name="g_bad"><link name="r_foot"/></group>
      <group name="g_sub"><group name="g_bad"/></group>
      <end_effector name="ee" parent_link="{link}" group="g_sub"/>
      <group_state name="s" group="g_ok"><joint name="{joint}" value="0.25"/></group_state>
      <disable_collisions link1="{plain.link_names[0]}" link2="{link}" reason="Adjacent"/></robot>"""
    with pytest.raises(ValueError, match="link 'r_foot'"):
        Robot.from_urdf(str(urdf), srdf=srdf)  # the default: an error naming it
    robot = Robot.from_urdf(str(urdf), srdf=srdf, srdf_mismatch="leave_out")
    assert list(robot.srdf_groups) == ["g_ok"] and robot.end_effectors == []
    assert robot.named_states["s"][joint] == pytest.approx(0.25)
    assert (plain.link_names[0], link) in {tuple(p) for p in robot.allowed_collisions} | \
        {tuple(reversed(p)) for p in robot.allowed_collisions}
    left = robot.srdf_left_out
    assert len(left) == 3 and any("group 'g_bad' left out: link 'r_foot'" in x for x in left)
    assert any(x.startswith("group 'g_sub' left out: group 'g_bad'") for x in left)
    assert any(x.startswith("end_effector 'ee' left out: group 'g_sub'") for x in left)
    assert Robot.from_urdf(str(urdf), srdf=srdf.replace("r_foot", link), srdf_mismatch="leave_out").srdf_left_out == []
    with pytest.raises(ValueError, match="srdf_mismatch must be 'error' or 'leave_out'"):
        Robot.from_urdf(str(urdf), srdf=srdf, srdf_mismatch="skip")


def test_example_robot_data_srdf_of_another_variant_keeps_what_fits():
    # z1.srdf's one group names a link 'base' its URDF lacks (and its end effector uses that group): the whole
    # SRDF used to be left out; now those two entries are, with a warning that says so, and its states stay.
    with pytest.warns(UserWarning, match=r"z1: 2 group\(s\)/end effector\(s\) of z1.srdf .*"
                                         r"group 'end_effector' left out: link 'base'"):
        z1 = robots.load("z1", allowed_collisions="srdf")
    assert z1.srdf_groups == {} and z1.end_effectors == []
    assert z1.named_states["arm_up"]["joint2"] == pytest.approx(0.26178)


def test_srdf_names_under_the_robots_name_as_a_namespace_are_read():
    # example-robot-data's Baxter SRDF names its group's joints "baxter/left_s0" (its URDF: "left_s0") and its
    # disabled pairs plainly: it used to be left out whole, and Baxter's arms then collided with themselves at
    # 9 random configurations in 10 (its coarse cylinders overlap where the SRDF disables the pairs).
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        baxter = robots.load("baxter", allowed_collisions="srdf")
    assert "neutral" in baxter.named_states
    assert ("left_upper_elbow", "left_upper_shoulder") in {tuple(sorted(p)) for p in baxter.allowed_collisions}
    # The rule on a small robot: "<robot name>/x" is x when the URDF has x; names it lacks still fail.
    urdf = robots.project_urdf("test_arm")
    name = Robot.from_urdf(str(urdf)).name
    joint = Robot.from_urdf(str(urdf)).joint_names[0]
    srdf = f"""<robot name="{name}"><group name="g"><joint name="{name}/{joint}"/></group>
               <group_state name="s" group="g"><joint name="{name}/{joint}" value="0.25"/></group_state></robot>"""
    robot = Robot.from_urdf(str(urdf), srdf=srdf)
    assert robot.named_states["s"][joint] == pytest.approx(0.25)
    with pytest.raises(ValueError, match=f"joint 'other/{joint}'"):
        Robot.from_urdf(str(urdf), srdf=srdf.replace(f"{name}/{joint}", f"other/{joint}"))


def _srdf_pairs(robot, path):
    import xml.etree.ElementTree as ET

    names = set(robot.collision_links)  # pairs of links without geometry are never checked
    pairs = set()
    for d in ET.parse(path).getroot().iter("disable_collisions"):
        a, b = d.get("link1"), d.get("link2")
        if a in names and b in names:
            pairs.add(tuple(sorted((a, b))))
    return pairs


def test_pr2_sampled_matrix_contains_its_srdf_pairs_that_never_collide(tmp_path):
    bare = robots.load("pr2", srdf=False, allowed_collisions="srdf")
    sampled = bare.sample_allowed_collisions(samples=1500, seed=3, cache_dir="none")
    ours = {tuple(sorted(p)) for kind in ("never", "always", "default") for p in sampled[kind]}
    adjacent = {tuple(sorted(p)) for p in bare.allowed_collisions}
    theirs = _srdf_pairs(bare, robots._index()["pr2"][1]) - adjacent
    missed = theirs - ours
    overlap = len(theirs & ours) / len(theirs)
    print(f"PR2: SRDF disables {len(theirs)} non-adjacent pairs, sampling finds {len(ours)}; "
          f"{len(theirs & ours)} in common ({overlap:.1%}), {len(missed)} SRDF pairs seen in collision")
    assert overlap > 0.8
    # Every SRDF pair the sampling left checked really does collide somewhere: an independent run (another
    # seed, every other pair allowed) sees each of them in collision too (so none is "never in collision").
    links = bare.collision_links
    every = {tuple(sorted((a, b))) for i, a in enumerate(links) for b in links[i + 1:]}
    only_missed = bare.with_allowed_collisions(sorted(every - missed))
    check = only_missed.sample_allowed_collisions(samples=30000, seed=99, cache_dir="none", default_posture=False)
    never = {tuple(sorted(p)) for p in check["never"]}
    assert not (missed & never), f"SRDF pairs never in collision but left checked: {sorted(missed & never)[:5]}"


def test_sampling_is_deterministic_cached_and_written_as_srdf(tmp_path):
    arm = robots.test_arm()
    a = arm.sample_allowed_collisions(samples=600, seed=2, cache_dir=str(tmp_path), threads=1)
    b = arm.sample_allowed_collisions(samples=600, seed=2, cache_dir=str(tmp_path), threads=2)
    c = arm.sample_allowed_collisions(samples=600, seed=2, cache_dir="none", threads=2)
    assert not a["from_cache"] and b["from_cache"] and a["cache_file"].startswith(str(tmp_path))
    for kind in ("never", "always", "default"):
        assert a[kind] == b[kind] == c[kind]
    robot = arm.with_sampled_collisions(samples=600, seed=2, cache_dir=str(tmp_path))
    path = tmp_path / "arm.srdf"
    robot.write_srdf(str(path))
    again = Robot.from_urdf(str(robots.project_urdf("test_arm")), srdf=str(path))
    assert again.model_hash == robot.model_hash
    assert "reason=\"Adjacent\"" in path.read_text()


def test_tiago_by_name_builds_a_capability_map_with_no_file_of_ours(tmp_path, monkeypatch):
    monkeypatch.setenv("OCTOREACH_CACHE_DIR", str(tmp_path))
    from octoreach import arms, default_reference

    tiago = robots.load("tiago")  # no SRDF: the allowed-collision matrix is sampled (and cached)
    arm = Arm.named(tiago, "arm")
    q = default_reference(tiago, tiago.chain(arm.base_link, arm.tip_link))
    assert not tiago.self_collisions(q)
    assert not tiago.in_self_collision(q)
    cap = arms.capability_map(tiago, "arm", resolution=0.2, directions=20, progress=False)
    assert cap.stats["reachable_cells"] > 0
    np.testing.assert_allclose(cap.approach_axis, (1, 0, 0))
    assert list(tmp_path.glob("acm-*.txt"))  # cached for the next load


def test_self_collision_error_names_the_links():
    tiago = robots.load("tiago", allowed_collisions="srdf")
    with pytest.raises(ValueError, match=r"self-collision among links the chain does not move \(.*/.*\).*with_sampled_collisions"):
        from octoreach import arms

        arms.capability_map(tiago, "arm", resolution=0.3, directions=8, progress=False)


def test_cli_robot_by_name_prints_links_joints_groups_end_effectors_and_arms(tmp_path):
    out = tmp_path / "panda.srdf"
    r = subprocess.run([sys.executable, "-m", "octoreach.cli", "robot", "panda", "--write-srdf", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    text = r.stdout
    assert "links:\n  panda_link0" in text
    assert "  panda_joint1: [-2.897, 2.897]" in text
    assert "  arm: joints panda_joint1, panda_joint2" in text and "  arm_and_hand: subgroups arm, hand" in text
    assert "end effector end_effector: parent link panda_hand_tcp, group arm" in text
    assert "  arm: panda_link0 -> panda_hand_tcp, approach axis (0.0, 0.0, 1.0) (+z of 'panda_hand_tcp'" in text
    assert Robot.from_urdf(str(robots._index()["panda"][0]), package_dirs=robots.package_dirs(),
                           srdf=str(out)).srdf_groups["arm"]["joints"][0] == "panda_joint1"


def test_default_arm_is_right_arm_or_the_only_arm(monkeypatch):
    from octoreach import arms

    assert arms.default_arm(robots.pr2()) == "right_arm"
    xarm = robots.load("xarm7")
    assert arms.default_arm(xarm) == octoreach.arm_names(xarm)[0] and len(octoreach.arm_names(xarm)) == 1

    class Named:
        def __init__(self, name):
            self.name = name

    monkeypatch.setattr(arms, "find_arms", lambda robot: [Named("arm_left"), Named("arm_right")])
    with pytest.raises(ValueError, match="2 arms .*arm_left, arm_right.*--arm"):
        arms.default_arm(xarm)
    monkeypatch.setattr(arms, "find_arms", lambda robot: [])
    with pytest.raises(ValueError, match="no arm .*--base LINK --tip LINK"):
        arms.default_arm(xarm)


def test_catalogue_name_of_a_urdf_robot_name():
    xarm = robots.load("xarm7")
    assert xarm.name == "UF_ROBOT"  # what a map records
    assert robots.catalogue_name("UF_ROBOT") == "xarm7"
    assert robots.catalogue_name("UF_ROBOT", xarm.urdf_hash) == "xarm7"
    assert robots.catalogue_name("UF_ROBOT", "0") is None  # another model of that name
    assert robots.catalogue_name("no_such_robot") is None
    assert robots.loadable_name("xarm7") == "xarm7" and robots.loadable_name("UF_ROBOT", xarm.urdf_hash) == "xarm7"
    with pytest.raises(ValueError, match="unknown robot 'no_such_robot'"):
        robots.loadable_name("no_such_robot")


def test_cli_single_arm_robot_needs_no_arm_name(tmp_path):
    out = tmp_path / "xarm7.orsm"
    r = subprocess.run([sys.executable, "-m", "octoreach.cli", "surface", "--robot", "xarm7", "--resolution", "0.2",
                        "--directions", "12", "--quiet", "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert octoreach.SurfaceMap.load(str(out)).voxel_count > 0
