"""A mobile manipulator written here, as a user would write one (no SRDF, no meshes): a box base, a prismatic
torso lift, a 6-DOF arm ending in a small gripper and a pan/tilt head with a camera link. Variants: the arm's
elbow made self-colliding (upper-arm and forearm cylinders that meet whenever the elbow bends past 1 rad, in
60 % of random configurations, with a link between them so they are not adjacent), cameras on the base and the
gripper, no camera, no head."""
from __future__ import annotations


def _link(name: str, geometry: str = "", xyz=(0, 0, 0), rpy=(0, 0, 0)) -> str:
    if not geometry:
        return f'  <link name="{name}"/>\n'
    origin = f'<origin xyz="{" ".join(map(str, xyz))}" rpy="{" ".join(map(str, rpy))}"/>'
    return f'  <link name="{name}"><collision>{origin}<geometry>{geometry}</geometry></collision></link>\n'


def _joint(name: str, kind: str, parent: str, child: str, xyz=(0, 0, 0), axis=(0, 0, 1), limits=(-3.0, 3.0),
           rpy=(0, 0, 0)) -> str:
    lim = f'<limit lower="{limits[0]}" upper="{limits[1]}" effort="10" velocity="1"/>' if kind != "fixed" else ""
    ax = f'<axis xyz="{" ".join(map(str, axis))}"/>' if kind != "fixed" else ""
    return (f'  <joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{" ".join(map(str, xyz))}" rpy="{" ".join(map(str, rpy))}"/>{ax}{lim}</joint>\n')


def cyl(radius: float, length: float) -> str:
    return f'<cylinder radius="{radius}" length="{length}"/>'


def box(x: float, y: float, z: float) -> str:
    return f'<box size="{x} {y} {z}"/>'


X = (0, 1.5708, 0)  # a cylinder along x


# A ROS optical frame: +z forward (along the camera link's +x), +x right, +y down.
OPTICAL_RPY = (-1.5708, 0, -1.5708)


def urdf(name: str = "own_robot", bad_elbow: bool = False, head: bool = True, camera: bool = True,
         extra_cameras: bool = False, optical: bool = False) -> str:
    """The robot's URDF text (see the module docstring); `optical`: camera_optical_frame is turned as a ROS
    optical frame (+z along the camera's view), else it is camera_link's frame."""
    parts = [_link("base_footprint"), _link("base_link", box(0.5, 0.5, 0.3), (0, 0, 0.15)),
             _joint("base_joint", "fixed", "base_footprint", "base_link"),
             _link("torso_link", box(0.16, 0.16, 0.5), (0, 0, 0.25)),
             _joint("torso_lift_joint", "prismatic", "base_link", "torso_link", (-0.1, 0, 0.3), (0, 0, 1), (0.0, 0.3)),
             _link("shoulder_link", cyl(0.05, 0.1), (0, 0, 0.05)),
             _joint("shoulder_pan_joint", "revolute", "torso_link", "shoulder_link", (0.14, 0, 0.4), (0, 0, 1), (-2.5, 2.5))]
    if bad_elbow:  # cylinders 2.5 cm either side of the elbow: they meet once it bends past 1 rad (a link between them)
        parts += [_link("upper_arm_link", cyl(0.045, 0.275), (0.1375, 0, 0), X),
                  _joint("shoulder_lift_joint", "revolute", "shoulder_link", "upper_arm_link", (0, 0, 0.1), (0, 1, 0), (-2.0, 2.0)),
                  _link("elbow_link", '<sphere radius="0.02"/>'),
                  _joint("elbow_joint", "revolute", "upper_arm_link", "elbow_link", (0.3, 0, 0), (0, 1, 0), (-2.5, 2.5)),
                  _link("forearm_link", cyl(0.045, 0.24), (0.145, 0, 0), X),
                  _joint("forearm_fixed", "fixed", "elbow_link", "forearm_link")]
    else:
        parts += [_link("upper_arm_link", cyl(0.045, 0.26), (0.15, 0, 0), X),
                  _joint("shoulder_lift_joint", "revolute", "shoulder_link", "upper_arm_link", (0, 0, 0.1), (0, 1, 0), (-2.0, 2.0)),
                  _link("forearm_link", cyl(0.04, 0.22), (0.14, 0, 0), X),
                  _joint("elbow_joint", "revolute", "upper_arm_link", "forearm_link", (0.3, 0, 0), (0, 1, 0), (-2.5, 2.5))]
    parts += [_link("wrist_1_link", cyl(0.035, 0.06), (0.0, 0, 0), X),
              _joint("wrist_1_joint", "revolute", "forearm_link", "wrist_1_link", (0.28, 0, 0), (1, 0, 0), (-3.0, 3.0)),
              _link("wrist_2_link", '<sphere radius="0.035"/>'),
              _joint("wrist_2_joint", "revolute", "wrist_1_link", "wrist_2_link", (0.05, 0, 0), (0, 1, 0), (-2.0, 2.0)),
              _link("wrist_3_link", cyl(0.03, 0.04), (0.03, 0, 0), X),
              _joint("wrist_3_joint", "revolute", "wrist_2_link", "wrist_3_link", (0.03, 0, 0), (1, 0, 0), (-3.0, 3.0)),
              _link("gripper_link", box(0.04, 0.08, 0.03), (0.02, 0, 0)),
              _joint("gripper_fixed", "fixed", "wrist_3_link", "gripper_link", (0.05, 0, 0)),
              _link("left_finger_link", box(0.05, 0.01, 0.02), (0.025, 0, 0)),
              _joint("left_finger_joint", "prismatic", "gripper_link", "left_finger_link", (0.04, 0.03, 0), (0, 1, 0), (-0.02, 0.0)),
              _link("right_finger_link", box(0.05, 0.01, 0.02), (0.025, 0, 0)),
              _joint("right_finger_joint", "prismatic", "gripper_link", "right_finger_link", (0.04, -0.03, 0), (0, 1, 0), (0.0, 0.02)),
              _link("tool_frame"),
              _joint("tool_fixed", "fixed", "gripper_link", "tool_frame", (0.08, 0, 0))]
    if head:
        parts += [_link("head_pan_link", cyl(0.03, 0.06), (0, 0, 0.03)),
                  _joint("head_pan_joint", "revolute", "torso_link", "head_pan_link", (0, 0, 0.5), (0, 0, 1), (-2.5, 2.5)),
                  _link("head_tilt_link", box(0.1, 0.2, 0.08), (0.02, 0, 0)),
                  _joint("head_tilt_joint", "revolute", "head_pan_link", "head_tilt_link", (0, 0, 0.1), (0, 1, 0), (-0.8, 1.2))]
        if camera:
            parts += [_link("camera_link"), _joint("camera_fixed", "fixed", "head_tilt_link", "camera_link", (0.07, 0, 0.02)),
                      _link("camera_optical_frame"),
                      _joint("camera_optical_fixed", "fixed", "camera_link", "camera_optical_frame",
                             rpy=OPTICAL_RPY if optical else (0, 0, 0))]
    if extra_cameras:  # a rear camera on the base and one on the gripper: two bodies, neither on a head
        parts += [_link("rear_camera_link"), _joint("rear_camera_fixed", "fixed", "base_link", "rear_camera_link", (-0.25, 0, 0.2)),
                  _link("wrist_camera_link"), _joint("wrist_camera_fixed", "fixed", "gripper_link", "wrist_camera_link", (0, 0, 0.03))]
    return f'<?xml version="1.0"?>\n<robot name="{name}">\n' + "".join(parts) + "</robot>\n"
