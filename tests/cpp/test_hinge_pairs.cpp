// The hinge-pair certificates IK uses to skip self-collision tests (cpp/src/kinematics/hinge_pairs.hpp): a pair
// left out as certified free never collides, so the check answers as the plain check of every pair.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "collision/detail.hpp"
#include "kinematics/chain_checks.hpp"
#include "kinematics/chain_self_check.hpp"
#include "kinematics/hinge_pairs.hpp"
#include "octoreach/chain.hpp"
#include "octoreach/robot.hpp"

using namespace octoreach;

namespace {

// A body with a post beside the shoulder: the shoulder (joint 0) swings into the post, and a cover on
// the upper arm (joint 1) swings into the shoulder: two hinge pairs, one against a link the chain never
// moves and one between two moving links; the cover and the forearm are one joint (2) apart too. The
// forearm against the body or the post is not a hinge pair (three joints between them).
const char* kUrdf = R"(<robot name="hinge_test">
  <link name="base"><collision><origin xyz="0 0 0.5"/><geometry><box size="0.4 0.4 1.0"/></geometry></collision></link>
  <link name="post"><collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision></link>
  <joint name="post_joint" type="fixed"><parent link="base"/><child link="post"/><origin xyz="0.25 0.3 1.05"/></joint>
  <link name="shoulder"><collision><origin xyz="0.3 0 0"/><geometry><box size="0.12 0.12 0.12"/></geometry></collision></link>
  <joint name="j0" type="revolute"><parent link="base"/><child link="shoulder"/><origin xyz="0 0 1.05"/>
    <axis xyz="0 0 1"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
  <link name="upper"><collision><origin xyz="0 0 0.2"/><geometry><box size="0.06 0.06 0.4"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="shoulder"/><child link="upper"/><origin xyz="0.3 0 0.1"/>
    <axis xyz="0 1 0"/><limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
  <link name="cover"><collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision></link>
  <joint name="cover_joint" type="fixed"><parent link="upper"/><child link="cover"/><origin xyz="0.08 0 0.05"/></joint>
  <link name="fore"><collision><origin xyz="0 0 0.25"/><geometry><cylinder radius="0.03" length="0.5"/></geometry></collision></link>
  <joint name="j2" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="0 0 0.4"/>
    <axis xyz="0 1 0"/><limit lower="-2.8" upper="2.8" effort="1" velocity="1"/></joint>
</robot>)";

}  // namespace

TEST(HingePairs, SkipsOnlyPairsThatCannotCollide) {
  auto robot = Robot::from_urdf(kUrdf);
  Chain chain = robot->chain("base", "fore");
  std::vector<std::pair<int, int>> moving, fixed;
  chain.split_collision_pairs(moving, fixed);
  const Eigen::VectorXd reference = robot->home();
  detail::HingePairs hinges(chain, moving, reference);
  EXPECT_EQ(hinges.hinges(), 3u);  // post-shoulder (joint 0), shoulder-cover (joint 1), cover-fore (joint 2)

  std::mt19937_64 rng(7);
  std::vector<Pose> poses;
  int colliding = 0, skipped = 0, hinge_hits = 0;
  for (int i = 0; i < 4000; ++i) {
    const Eigen::VectorXd full = chain.to_robot_configuration(chain.random_configuration(rng), reference);
    robot->link_poses(full, poses);
    const bool plain = robot->in_self_collision_poses(poses, moving);
    std::vector<std::pair<int, int>> left;
    for (std::size_t p = 0; p < moving.size(); ++p) {
      const bool collides = robot->in_self_collision_poses(poses, {moving[p]});
      if (hinges.certified_pair(*robot, p, full)) {
        // A pair certified free is free on its own (the certificate never skips a colliding pair).
        ++skipped;
        EXPECT_FALSE(collides) << "pair " << moving[p].first << "-" << moving[p].second << " at " << i;
        continue;
      }
      left.push_back(moving[p]);
      if (collides && hinges.hinge_of(p) >= 0) ++hinge_hits;
    }
    EXPECT_EQ(detail::first_colliding_pair(*robot, poses, left) >= 0, plain) << "configuration " << i;
    colliding += plain;
  }
  // The test means something: configurations of both kinds, pairs skipped, hinge pairs that do collide.
  EXPECT_GT(colliding, 100);
  EXPECT_LT(colliding, 3900);
  EXPECT_GT(skipped, 2000);
  EXPECT_GT(hinge_hits, 20);
}

TEST(ChainSelfCheck, AnswersAsThePlainCheckOfEveryPair) {
  // The flat walk (kept boxes, certificates, the last hit first, passes) answers as the plain check,
  // on random configurations and on a path of small steps (the order and the certificates then carry over).
  auto robot = Robot::from_urdf(kUrdf);
  Chain chain = robot->chain("base", "fore");
  std::vector<std::pair<int, int>> moving, fixed;
  chain.split_collision_pairs(moving, fixed);
  const Eigen::VectorXd reference = robot->home();
  std::vector<Pose> poses;
  robot->link_poses(reference, poses);
  detail::ChainSelfCheck check(chain, moving, poses, reference);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> step(0.0, 0.05);
  Eigen::VectorXd q = chain.random_configuration(rng);
  int colliding = 0;
  for (int i = 0; i < 4000; ++i) {
    if (i % 2) {
      q = chain.random_configuration(rng);
    } else {
      for (int k = 0; k < q.size(); ++k) q[k] = std::clamp(q[k] + step(rng), chain.lower()[k], chain.upper()[k]);
    }
    const Eigen::VectorXd full = chain.to_robot_configuration(q, reference);
    robot->link_poses(full, poses);
    const bool plain = robot->in_self_collision_poses(poses, moving);
    EXPECT_EQ(check.collides(*robot, poses, full), plain) << "configuration " << i;
    colliding += plain;
  }
  EXPECT_GT(colliding, 100);
  EXPECT_LT(colliding, 3900);
}

TEST(HingePairs, BucketWidthBoundsTheMotion) {
  // Half a bucket turns a link of this radius by at most 1.5 mm.
  for (double r : {0.01, 0.1, 0.5, 2.0}) EXPECT_LE(0.5 * detail::HingePairs::bucket_width(r) * r, 1.5e-3 + 1e-15);
}

TEST(ShapeBoxes, KeptBoxesOfStillLinksAnswerAsFreshOnes) {
  // IK keeps the shape boxes of the links its chain never moves at the reference posture and refreshes
  // the others (detail::ShapeBoxes): the check answers, pair for pair, as boxes computed afresh.
  auto robot = Robot::from_urdf(kUrdf);
  Chain chain = robot->chain("base", "fore");
  std::vector<std::pair<int, int>> moving, fixed;
  chain.split_collision_pairs(moving, fixed);
  std::vector<std::pair<int, int>> all = moving;
  all.insert(all.end(), fixed.begin(), fixed.end());
  const Eigen::VectorXd reference = robot->home();
  std::vector<Pose> poses;
  robot->link_poses(reference, poses);
  detail::ShapeBoxes boxes;
  std::vector<int> moved;
  for (int li : robot->collision_links()) {
    boxes.update(*robot, poses, li);
    if (chain.link_mask(li) != 0) moved.push_back(li);
  }
  EXPECT_EQ(moved.size(), 4u);  // shoulder, upper, cover, fore
  EXPECT_EQ(chain.moved_collision_links(), moved);  // the chain's own list, in collision_links order
  std::mt19937_64 rng(11);
  int colliding = 0;
  for (int i = 0; i < 2000; ++i) {
    robot->link_poses(chain.to_robot_configuration(chain.random_configuration(rng), reference), poses);
    for (int li : moved) boxes.update(*robot, poses, li);
    for (const auto& p : all) {
      const std::vector<std::pair<int, int>> one{p};
      EXPECT_EQ(detail::first_colliding_pair(*robot, boxes, one), detail::first_colliding_pair(*robot, poses, one))
          << "pair " << p.first << "-" << p.second << " at " << i;
    }
    colliding += detail::first_colliding_pair(*robot, boxes, all) >= 0;
  }
  EXPECT_GT(colliding, 100);
  EXPECT_LT(colliding, 1900);
}

TEST(ShapeBoxes, IkSolutionsWithSelfCollisionAreFree) {
  // Chain::ik with check_self_collision accepts only solutions the robot's full check finds free
  // (IK checks them with kept boxes and hinge certificates).
  auto robot = Robot::from_urdf(kUrdf);
  Chain chain = robot->chain("base", "fore");
  IkOptions o;
  o.mode = IkMode::Position;
  o.check_self_collision = true;
  o.attempts = 5;
  std::mt19937_64 rng(5);
  int solved = 0;
  for (int i = 0; i < 300; ++i) {
    const Pose target = chain.fk(chain.random_configuration(rng));
    o.seed = static_cast<std::uint64_t>(i);
    auto q = chain.ik(target, o);
    if (!q) continue;
    ++solved;
    EXPECT_FALSE(robot->in_self_collision(chain.to_robot_configuration(*q, robot->home()))) << "target " << i;
  }
  EXPECT_GT(solved, 100);
}

TEST(ShapeBoxes, ShapesBelowFramesWithoutGeometryAreChecked) {
  // IK places only the moved links a check reads: those with shapes and the links above them. A hand hung below
  // a wrist frame without geometry (and a tool frame below it, without geometry too) is still placed and
  // checked: IK's check answers as the robot's full check at random configurations, collisions among them.
  std::string urdf = kUrdf;
  urdf.replace(urdf.rfind("</robot>"), 8, R"(
  <link name="wrist"/>
  <joint name="wrist_joint" type="fixed"><parent link="fore"/><child link="wrist"/><origin xyz="0 0 0.5"/></joint>
  <link name="hand"><collision><origin xyz="0 0 0.1"/><geometry><box size="0.25 0.25 0.2"/></geometry></collision></link>
  <joint name="hand_joint" type="fixed"><parent link="wrist"/><child link="hand"/></joint>
  <link name="tool"/>
  <joint name="tool_joint" type="fixed"><parent link="hand"/><child link="tool"/><origin xyz="0 0 0.2"/></joint>
</robot>)");
  auto robot = Robot::from_urdf(urdf);
  Chain chain = robot->chain("base", "tool");
  IkOptions o;
  o.check_self_collision = true;
  std::mt19937_64 rng(9);
  int colliding = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::VectorXd q = chain.random_configuration(rng);
    const bool full = robot->in_self_collision(chain.to_robot_configuration(q, robot->home()));
    ASSERT_EQ(detail::ik_solution_collides(chain, q, o), full) << "configuration " << i;
    colliding += full;
  }
  EXPECT_GT(colliding, 100);
  EXPECT_LT(colliding, 1900);
}

