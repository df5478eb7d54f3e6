// Look-at IK (aim.hpp) on a torso lift + pan/tilt head whose camera frame is a ROS optical frame (+z forward):
// reachable targets are hit by the optical axis, targets out of the head's aim fail clearly; the search
// aims such a chain by default.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "octoreach/aim.hpp"
#include "octoreach/next_best_view.hpp"
#include "octoreach/robot.hpp"

using namespace octoreach;

namespace {

const char* kHead = R"(<robot name="head">
  <link name="base"/><link name="torso"/><link name="pan"/><link name="tilt"/><link name="camera"/>
  <joint name="lift" type="prismatic"><parent link="base"/><child link="torso"/><origin xyz="0 0 1.0"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="0.3" effort="1" velocity="1"/></joint>
  <joint name="pan" type="revolute"><parent link="torso"/><child link="pan"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/><limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
  <joint name="tilt" type="revolute"><parent link="pan"/><child link="tilt"/><origin xyz="0 0 0.1"/>
    <axis xyz="0 1 0"/><limit lower="-0.8" upper="1.2" effort="1" velocity="1"/></joint>
  <joint name="optical" type="fixed"><parent link="tilt"/><child link="camera"/>
    <origin xyz="0.07 0 0.02" rpy="-1.5708 0 -1.5708"/></joint>
</robot>)";

Chain head() { return Robot::from_urdf(kHead)->chain("base", "camera"); }

// Distance (m) from `target` to the optical axis (the ray along +z from the camera's origin).
double miss(const Chain& c, const Eigen::VectorXd& q, const Eigen::Vector3d& target) {
  const Pose T = c.fk(q);
  const Eigen::Vector3d d = target - T.translation(), a = T.linear().col(2);
  return a.dot(d) > 0 ? (d - a.dot(d) * a).norm() : d.norm();
}

}  // namespace

TEST(Aim, OpticalAxisHitsReachableTargets) {
  const Chain c = head();
  ASSERT_EQ(c.dof(), 3);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> x(0.5, 2.0), y(-1.5, 1.5), z(0.2, 1.6);
  for (int i = 0; i < 40; ++i) {
    const Eigen::Vector3d t(x(rng), y(rng), z(rng));  // in front, from below the table to above the head
    AimOptions o;
    o.seed = std::uint64_t(i);
    const AimResult r = aim(c, t, o);
    ASSERT_TRUE(r.reached) << "target " << t.transpose() << " missed by " << r.error << " rad";
    EXPECT_TRUE(c.within_limits(r.q));
    EXPECT_LE(r.error, o.tolerance);
    EXPECT_NEAR(aim_error(c, r.q, t), r.error, 1e-9);
    EXPECT_LT(miss(c, r.q, t), 1e-3 * (t - c.fk(r.q).translation()).norm() + 1e-9);
  }
}

TEST(Aim, TargetsOutOfTheHeadsAimFailClearly) {
  const Chain c = head();
  // straight below the camera (the tilt stops 69 degrees down) and straight behind (the pan stops at 143 degrees)
  for (const Eigen::Vector3d& t : {Eigen::Vector3d(0.07, 0.0, 0.2), Eigen::Vector3d(-2.0, 0.0, 1.3)}) {
    const AimResult r = aim(c, t);
    EXPECT_FALSE(r.reached) << t.transpose();
    EXPECT_GT(r.error, 0.3) << t.transpose();
    EXPECT_TRUE(c.within_limits(r.q));  // the best it can do, inside the limits
    EXPECT_NEAR(aim_error(c, r.q, t), r.error, 1e-9);
  }
}

TEST(Aim, RefusesBadInput) {
  const Chain c = head();
  EXPECT_THROW(aim(c, Eigen::Vector3d(NAN, 0, 0)), std::invalid_argument);
  AimOptions o;
  o.axis = Eigen::Vector3d::Zero();
  EXPECT_THROW(aim(c, Eigen::Vector3d(1, 0, 1), o), std::invalid_argument);
  o = AimOptions();
  o.tolerance = -1;
  EXPECT_THROW(aim(c, Eigen::Vector3d(1, 0, 1), o), std::invalid_argument);
  const Eigen::VectorXd start = Eigen::VectorXd::Zero(2);
  EXPECT_THROW(aim(c, Eigen::Vector3d(1, 0, 1), AimOptions(), &start), std::invalid_argument);
}

TEST(Aim, TheSearchAimsChainsOfFewerThanFiveJoints) {
  const Chain c = head();
  NbvOptions o;
  EXPECT_FALSE(looks_at(o));  // no chain: a free camera
  o.chain = &c;
  EXPECT_TRUE(looks_at(o));
  o.aiming = CameraAiming::Pose;
  EXPECT_FALSE(looks_at(o));
  const auto arm = Robot::from_urdf(std::string(OCTOREACH_URDF_DIR) + "/explorer.urdf");
  const Chain five = arm->chain("arm_base_link", "camera_optical_frame");
  o.chain = &five;
  o.aiming = CameraAiming::Auto;
  EXPECT_FALSE(looks_at(o));
  o.aiming = CameraAiming::LookAt;
  EXPECT_TRUE(looks_at(o));
  EXPECT_EQ(aiming_from_name("look_at"), CameraAiming::LookAt);
  EXPECT_THROW(aiming_from_name("aim"), std::invalid_argument);
}
