"""How long the simulated PR2 takes for each action: one table, with where each figure comes from.

The paper (Hertle & Nebel, IROS 2017, Table II) reports per run the total time T, the planning time t_p and
the number of moves and other actions, but no per-action durations. From its averages the robot spends
(T - t_p) / (moves + other) = (38.0 - 7.0) min / (3.9 + 28.3) = 58 s (predefined poses) and
(32.0 - 7.42) min / (2.1 + 28.6) = 48 s (sampled poses) per executed action, 53 s on the mean of both.
The durations below are chosen so that a typical run of our domain (one move of ~2 m per three other
actions) spends about that per action; the base speeds are the PR2's navigation limits.

Sources:
  [paper]  A. Hertle, B. Nebel, "Identifying good poses when doing your household chores", IROS 2017, Table II.
  [pr2]    Willow Garage, PR2 specifications: omnidirectional base, maximum speed 1.0 m/s; the PR2 navigation
           stack (pr2_navigation_config, base_local_planner) limits it to 0.55 m/s and 1.0 rad/s in rooms.
  [ours]   assumed, matched to [paper]'s 53 s per action: the split among the manipulation actions is ours.
"""
from __future__ import annotations

import math

#: action -> (seconds, source). A move takes MOVE_OVERHEAD_S + distance / BASE_SPEED + turn / TURN_SPEED.
DURATIONS = {
    "move-robot": (25.0, "[ours] fixed part: tuck the arms, plan the path, localise at the goal"),
    "inspect-surface": (30.0, "[ours] point the head, take and segment Kinect images, recognise objects"),
    "pickup-object": (75.0, "[ours] grasp planning, approach, close the gripper, lift (the paper's slowest skill)"),
    "inspect-object": (30.0, "[ours] hold the object in front of the head camera and recognise it"),
    "putdown-object": (55.0, "[ours] find a free place, approach, release, retreat"),
}
BASE_SPEED = 0.55  # m/s, [pr2] navigation limit (the hardware allows 1.0 m/s)
TURN_SPEED = 1.0  # rad/s, [pr2] navigation limit
SOURCES = __doc__


def duration(action: str) -> float:
    """Seconds an action other than a move takes (KeyError naming the known ones for an unknown action)."""
    try:
        return DURATIONS[action][0]
    except KeyError:
        raise KeyError(f"no duration for action {action!r} (known: {', '.join(DURATIONS)})") from None


def move_duration(start, goal) -> float:
    """Seconds for the base to drive from pose (x, y, z, theta) `start` to `goal`: the fixed part, the straight
    distance at BASE_SPEED and the heading change at TURN_SPEED (turning while driving is not credited)."""
    dx, dy = float(goal[0]) - float(start[0]), float(goal[1]) - float(start[1])
    turn = abs((float(goal[3]) - float(start[3]) + math.pi) % (2 * math.pi) - math.pi)
    return DURATIONS["move-robot"][0] + math.hypot(dx, dy) / BASE_SPEED + turn / TURN_SPEED


# Grasp failures (the simulation draws them; the planner's cost attachment expects them): a grasp fails with
# FAIL_BASE + FAIL_RP * max(0, 1 - R_P / RP_EASY) + FAIL_FAR * clip((d - NEAR) / (FAR - NEAR), 0, 1), at most
# FAIL_MAX, R_P being the share of grasps the arm reaches from the pose and d the horizontal base-object
# distance: easy grasps fail 5 % of the time, grasps at the edge of the workspace up to 55 % [ours].
FAIL_BASE, FAIL_RP, FAIL_FAR, FAIL_MAX = 0.05, 0.35, 0.15, 0.6
RP_EASY = 0.5  # share of grasps from which a grasp counts as easy
NEAR, FAR = 0.55, 0.95  # m, horizontal base-object distances where the distance term starts and saturates


def grasp_failure_probability(rp: float, distance: float) -> float:
    """Probability that a grasp with grasp share `rp` at horizontal distance `distance` (m) fails."""
    p = FAIL_BASE + FAIL_RP * max(0.0, 1.0 - rp / RP_EASY) + FAIL_FAR * min(1.0, max(0.0, (distance - NEAR) / (FAR - NEAR)))
    return min(FAIL_MAX, p)


def expected_pickup_duration(rp: float, distance: float) -> float:
    """Expected seconds until a grasp succeeds (retrying after each failure): duration / (1 - p_fail)."""
    return duration("pickup-object") / (1.0 - grasp_failure_probability(rp, distance))
