// Robot diagnostics: where allowed pairs came from, the self-collision report, the arm report, the camera link.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "octoreach/arm.hpp"
#include "octoreach/arm_report.hpp"
#include "octoreach/camera_link.hpp"
#include "octoreach/robot.hpp"
#include "octoreach/self_collision_report.hpp"

using namespace octoreach;

namespace {
const std::string kArm = std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf";
const std::string kExplorer = std::string(OCTOREACH_URDF_DIR) + "/explorer.urdf";

int count(const Robot& r, AllowedSource s) {
  return static_cast<int>(std::count(r.allowed_sources().begin(), r.allowed_sources().end(), s));
}
}  // namespace

TEST(RobotDiagnostics, AllowedPairsKeepTheirSource) {
  auto r = Robot::from_urdf(kArm);
  ASSERT_EQ(r->allowed_sources().size(), r->allowed_pairs().size());
  EXPECT_EQ(count(*r, AllowedSource::kAdjacent), static_cast<int>(r->allowed_pairs().size()));  // no SRDF
  AllowedCollisionOptions o;
  o.samples = 300;
  o.cache_dir = "none";
  auto sampled = r->with_sampled_collisions(o);
  const SampledCollisions s = r->sample_allowed_collisions(o);
  EXPECT_EQ(count(*sampled, AllowedSource::kNever), static_cast<int>(s.never.size()));
  EXPECT_EQ(count(*sampled, AllowedSource::kAlways), static_cast<int>(s.always.size()));
  EXPECT_EQ(count(*sampled, AllowedSource::kDefaultPosture), static_cast<int>(s.default_posture.size()));
  ASSERT_FALSE(r->checked_pairs().empty());
  auto given = r->with_allowed_collisions({r->checked_pairs().front()});
  EXPECT_EQ(count(*given, AllowedSource::kGiven), 1);
  EXPECT_NE(given->srdf_text().find("reason=\"User\""), std::string::npos);
  // a pair already allowed keeps its first reason
  auto again = given->with_allowed_collisions({r->allowed_pairs().front()});
  EXPECT_EQ(count(*again, AllowedSource::kGiven), 1);
  EXPECT_EQ(again->model_hash(), given->model_hash());
  EXPECT_STREQ(allowed_source_name(AllowedSource::kDefaultPosture), "in collision at home");
}

TEST(RobotDiagnostics, SelfCollisionReportIsTheSameOnAnyNumberOfThreads) {
  auto r = Robot::from_urdf(kArm);
  SelfCollisionOptions o;
  o.samples = 500;
  o.seed = 3;
  o.threads = 1;
  const SelfCollisionReport one = self_collision_report(*r, o);
  o.threads = 3;
  const SelfCollisionReport three = self_collision_report(*r, o);
  EXPECT_EQ(one.samples, 500);
  EXPECT_EQ(one.free, three.free);
  ASSERT_EQ(one.pairs.size(), three.pairs.size());
  for (std::size_t i = 0; i < one.pairs.size(); ++i) {
    EXPECT_EQ(one.pairs[i].link_a, three.pairs[i].link_a);
    EXPECT_EQ(one.pairs[i].hits, three.pairs[i].hits);
    if (i) EXPECT_GE(one.pairs[i - 1].hits, one.pairs[i].hits);
  }
  EXPECT_LE(one.free, one.samples);
  o.samples = 0;
  EXPECT_THROW(self_collision_report(*r, o), std::invalid_argument);
}

TEST(RobotDiagnostics, DrawingTheFingersOnlyLeavesTheArmFree) {
  auto r = Robot::from_urdf(kArm);
  SelfCollisionOptions o;
  o.samples = 50;
  o.joints = {"finger_left_joint"};  // the fingers only, the arm at home
  const SelfCollisionReport rep = self_collision_report(*r, o);
  EXPECT_EQ(rep.free, rep.samples);
  EXPECT_FALSE(rep.suspicious());
}

TEST(RobotDiagnostics, ArmReportNamesItsJoints) {
  auto r = Robot::from_urdf(kArm);
  const Arm arm = Arm::from_links(*r, "shoulder_link", "tool0");
  const ArmReport rep = arm_report(*r, arm);
  ASSERT_EQ(rep.held.size(), 1u);  // the shoulder pan carries the arm from base_link
  EXPECT_EQ(rep.base_to_include_held, "base_link");
  EXPECT_EQ(rep.moving.size(), 5u);
  EXPECT_GE(rep.self_collision.free_share(), rep.with_body.free_share());
  EXPECT_TRUE(arm_report(*r, Arm::from_links(*r, "base_link", "tool0")).held.empty());
}

TEST(RobotDiagnostics, CameraLinkFoundOrGiven) {
  auto explorer = Robot::from_urdf(kExplorer);
  EXPECT_EQ(find_camera_link(*explorer).link, "camera_link");
  EXPECT_EQ(camera_link(*explorer, "wrist_link").reason, "given");
  EXPECT_THROW(camera_link(*explorer, "no_such_link"), std::invalid_argument);
  auto arm = Robot::from_urdf(kArm);  // no camera, no head
  try {
    find_camera_link(*arm);
    FAIL() << "a robot without camera or head has no camera link";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("camera_link='LINK'"), std::string::npos) << e.what();
  }
}
