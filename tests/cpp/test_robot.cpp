#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>

#include "kdl_chain.hpp"
#include "octoreach/chain.hpp"
#include "octoreach/robot.hpp"

using namespace octoreach;

namespace {
const std::string kArm = std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf";

std::shared_ptr<Robot> arm_robot() { return Robot::from_urdf(kArm); }
}  // namespace

TEST(Robot, ParsesTestArm) {
  auto r = arm_robot();
  EXPECT_EQ(r->name(), "octoreach_test_arm");
  EXPECT_EQ(r->dof(), 7);  // six arm joints and one finger; the mimic finger is left out
  ASSERT_EQ(r->mimic_joints().size(), 1u);
  EXPECT_EQ(r->mimic_joints()[0], "finger_right_joint");
  Chain c = r->chain("base_link", "tool0");
  EXPECT_EQ(c.dof(), 6);
  EXPECT_TRUE(c.continuous()[3]);
  EXPECT_TRUE(std::isinf(c.upper()[3]));
}

TEST(Robot, ForwardKinematicsByHand) {
  auto r = arm_robot();
  Chain c = r->chain("base_link", "tool0");
  Eigen::VectorXd q = Eigen::VectorXd::Zero(6);
  // Straight up: 0.1 + 0.1 + 0.4 + 0.3 + 0.05 + 0.05 + 0.05 = 1.05 m.
  Pose T = c.fk(q);
  EXPECT_NEAR((T.translation() - Eigen::Vector3d(0, 0, 1.05)).norm(), 0.0, 1e-12);
  EXPECT_TRUE(T.linear().isIdentity(1e-12));
  // Shoulder lift by +90 deg about y: the arm points along +x from the shoulder at z = 0.2.
  q[1] = M_PI / 2;
  T = c.fk(q);
  EXPECT_NEAR((T.translation() - Eigen::Vector3d(0.85, 0, 0.2)).norm(), 0.0, 1e-12);
  // Pan by 90 deg too: now along +y.
  q[0] = M_PI / 2;
  T = c.fk(q);
  EXPECT_NEAR((T.translation() - Eigen::Vector3d(0, 0.85, 0.2)).norm(), 0.0, 1e-12);
  // Elbow bent 90 deg with the arm up: forearm and wrist point along +x from z = 0.6.
  q.setZero();
  q[2] = M_PI / 2;
  T = c.fk(q);
  EXPECT_NEAR((T.translation() - Eigen::Vector3d(0.45, 0, 0.6)).norm(), 0.0, 1e-12);
}

TEST(Robot, ForwardKinematicsOfSomeLinks) {
  // link_poses(q, out, joints_placing(links)) gives exactly link_poses(q)'s poses for those links and
  // their ancestors, leaves the other entries alone, and rejects a bad link index.
  for (const auto& r : {arm_robot(), Robot::from_urdf(std::string(OCTOREACH_URDF_DIR) + "/explorer.urdf")}) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    const int n = static_cast<int>(r->links().size());
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::VectorXd q(r->dof());
      for (int i = 0; i < q.size(); ++i) q[i] = u(rng);
      const std::vector<Pose> all = r->link_poses(q);
      std::vector<int> some{static_cast<int>(rng() % n), static_cast<int>(rng() % n)};
      const std::vector<int> joints = r->joints_placing(some);
      EXPECT_TRUE(std::is_sorted(joints.begin(), joints.end()));
      std::vector<Pose> out(r->links().size(), Pose(Eigen::Translation3d(9, 9, 9)));
      r->link_poses(q, out, joints);
      std::vector<char> placed(n, 0);
      placed[r->root_link()] = 1;
      for (int j : joints) placed[r->joints()[j].child_link] = 1;
      for (int l : some) EXPECT_TRUE(placed[l]) << r->links()[l].name;
      for (int l = 0; l < n; ++l) {
        if (placed[l])
          EXPECT_TRUE(out[l].matrix() == all[l].matrix()) << r->links()[l].name;  // bit for bit
        else
          EXPECT_EQ(out[l].translation(), Eigen::Vector3d(9, 9, 9)) << r->links()[l].name;
      }
    }
    EXPECT_TRUE(r->joints_placing({r->root_link()}).empty());
    EXPECT_THROW(r->joints_placing({n}), std::out_of_range);
    EXPECT_THROW(r->joints_placing({-1}), std::out_of_range);
    const std::vector<int> two = r->joints_placing({n - 1});
    if (two.size() >= 2) {
      std::vector<Pose> out;
      EXPECT_THROW(r->link_poses(r->home(), out, {two[1], two[0]}), std::invalid_argument);
    }
  }
}

TEST(Robot, MatchesKdlForwardKinematics) {
  auto r = arm_robot();
  Chain c = r->chain("base_link", "tool0");
  KDL::Chain kc = bench::to_kdl(bench::arrays_of(c));
  ASSERT_EQ(static_cast<int>(kc.getNrOfJoints()), c.dof());
  KDL::ChainFkSolverPos_recursive fk(kc);
  std::mt19937_64 rng(3);
  for (int i = 0; i < 50; ++i) {
    Eigen::VectorXd q = c.random_configuration(rng);
    KDL::JntArray jq(c.dof());
    jq.data = q;
    KDL::Frame F;
    ASSERT_GE(fk.JntToCart(jq, F), 0);
    Pose T = c.fk(q);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(F.p(k), T.translation()[k], 1e-12);
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(F.M(k, j), T.linear()(k, j), 1e-12);
    }
  }
}

TEST(Robot, JacobianMatchesFiniteDifferences) {
  auto r = arm_robot();
  Chain c = r->chain("base_link", "tool0");
  std::mt19937_64 rng(4);
  Eigen::VectorXd q = c.random_configuration(rng);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J;
  Pose T = c.fk_jacobian(q, J);
  const double h = 1e-7;
  for (int i = 0; i < c.dof(); ++i) {
    Eigen::VectorXd qh = q;
    qh[i] += h;
    Pose Th = c.fk(qh);
    Eigen::Vector3d dv = (Th.translation() - T.translation()) / h;
    Eigen::AngleAxisd aa(Th.linear() * T.linear().transpose());
    Eigen::Vector3d dw = aa.axis() * aa.angle() / h;
    EXPECT_NEAR((dv - J.col(i).head<3>()).norm(), 0.0, 1e-5);
    EXPECT_NEAR((dw - J.col(i).tail<3>()).norm(), 0.0, 1e-5);
  }
}

TEST(Robot, IkRoundTrip) {
  auto r = arm_robot();
  Chain c = r->chain("base_link", "tool0");
  std::mt19937_64 rng(5);
  IkOptions o;
  int solved = 0;
  for (int i = 0; i < 100; ++i) {
    Eigen::VectorXd q = c.random_configuration(rng);
    Pose T = c.fk(q);
    o.seed = i;
    auto sol = c.ik(T, o);
    if (!sol) continue;
    ++solved;
    EXPECT_TRUE(c.within_limits(*sol));
    Pose Ts = c.fk(*sol);
    EXPECT_LT((Ts.translation() - T.translation()).norm(), 1e-4);
    EXPECT_LT(Eigen::AngleAxisd(Ts.linear() * T.linear().transpose()).angle(), 1e-3);
  }
  EXPECT_GE(solved, 97);
}

TEST(Robot, IkRelaxedModes) {
  auto r = arm_robot();
  Chain c = r->chain("base_link", "tool0");
  std::mt19937_64 rng(6);
  IkOptions o;
  for (int i = 0; i < 30; ++i) {
    Eigen::VectorXd q = c.random_configuration(rng);
    Pose T = c.fk(q);
    // Roll the target about its z axis: a full solution changes, the approach solution still fits.
    Pose Tr = T * Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ());
    o.mode = IkMode::Approach;
    o.seed = i;
    auto sol = c.ik(Tr, o);
    ASSERT_TRUE(sol.has_value());
    Pose Ts = c.fk(*sol);
    EXPECT_LT((Ts.translation() - T.translation()).norm(), 1e-4);
    double angle = std::acos(std::min(1.0, (Ts.linear().col(2)).dot(T.linear().col(2))));
    EXPECT_LT(angle, 1e-3);
    o.mode = IkMode::Position;
    sol = c.ik(T, o);
    ASSERT_TRUE(sol.has_value());
    EXPECT_LT((c.fk(*sol).translation() - T.translation()).norm(), 1e-4);
  }
  // Out of reach (1.05 m arm): no solution.
  Pose far = Pose::Identity();
  far.translation() = Eigen::Vector3d(2.0, 0, 0.5);
  o.mode = IkMode::Position;
  EXPECT_FALSE(c.ik(far, o).has_value());
}

TEST(Robot, IkApproachCone) {
  // A target whose approach axis is tilted 0.3 rad off one the arm reaches there: within a 0.35 rad cone the
  // configuration that reaches the untilted pose is a solution, so IK finds one, its axis within the cone.
  auto r = arm_robot();
  Chain c = r->chain("base_link", "tool0");
  std::mt19937_64 rng(8);
  IkOptions o;
  o.mode = IkMode::Approach;
  o.approach_cone = 0.35;
  int solved = 0;
  for (int i = 0; i < 40; ++i) {
    const Eigen::VectorXd q = c.random_configuration(rng);
    const Pose T = c.fk(q);
    Pose tilted = T;
    tilted.linear() = T.linear() * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix();
    o.seed = std::uint64_t(i);
    const auto sol = c.ik(tilted, o);
    if (!sol) continue;
    ++solved;
    const Pose Ts = c.fk(*sol);
    EXPECT_LT((Ts.translation() - T.translation()).norm(), 1e-4);
    const double off = std::acos(std::min(1.0, Ts.linear().col(2).dot(tilted.linear().col(2))));
    EXPECT_LT(off, o.approach_cone + o.orientation_tolerance);
  }
  EXPECT_GE(solved, 38);
  // the cone widens Approach mode only: a full pose is still matched exactly
  o.mode = IkMode::Full;
  const Eigen::VectorXd q = c.random_configuration(rng);
  const Pose T = c.fk(q);
  const auto sol = c.ik(T, o);
  ASSERT_TRUE(sol.has_value());
  EXPECT_LT(Eigen::AngleAxisd(c.fk(*sol).linear() * T.linear().transpose()).angle(), o.orientation_tolerance);
}

TEST(Robot, IkBatchIsDeterministic) {
  auto r = arm_robot();
  Chain c = r->chain("base_link", "tool0");
  std::mt19937_64 rng(7);
  std::vector<Pose> targets;
  for (int i = 0; i < 40; ++i) targets.push_back(c.fk(c.random_configuration(rng)));
  IkOptions o;
  o.seed = 11;
  Eigen::MatrixXd Q1, Q2;
  std::vector<bool> ok1, ok2;
  c.ik_batch(targets, o, Q1, ok1, nullptr, 1);
  c.ik_batch(targets, o, Q2, ok2, nullptr, 2);
  EXPECT_EQ(ok1, ok2);
  for (int i = 0; i < 40; ++i)
    if (ok1[i]) EXPECT_TRUE(Q1.row(i).isApprox(Q2.row(i), 0.0)) << i;
}

TEST(Robot, SelfCollision) {
  auto r = arm_robot();
  Eigen::VectorXd home = r->home();
  EXPECT_FALSE(r->in_self_collision(home));
  // Folded: shoulder leaned forward, elbow folded back so the wrist comes down onto the base
  // (tool0 ends at x = 0.076 m, z = -0.02 m, inside the base cylinder of radius 0.08 m).
  Eigen::VectorXd q = r->configuration({{"shoulder_lift", 1.3}, {"elbow", 2.6}});
  EXPECT_TRUE(r->in_self_collision(q));
}

TEST(Robot, AllowedCollisionsMakeANewRobot) {
  auto r = arm_robot();
  const auto allowed = r->allowed_pairs();
  const auto checked = r->checked_pairs();
  const std::uint64_t hash = r->model_hash();
  Eigen::VectorXd folded = r->configuration({{"shoulder_lift", 1.3}, {"elbow", 2.6}});
  std::vector<std::pair<int, int>> sampled = r->compute_allowed_collisions(500, 1);
  ASSERT_FALSE(sampled.empty());
  EXPECT_TRUE(std::is_sorted(sampled.begin(), sampled.end()));
  // Sampling is a query: the robot keeps its pairs.
  EXPECT_EQ(r->allowed_pairs(), allowed);
  EXPECT_EQ(r->compute_allowed_collisions(500, 1), sampled);
  std::shared_ptr<const Robot> wider = r->with_allowed_collisions(sampled);
  EXPECT_EQ(wider->allowed_pairs().size(), allowed.size() + sampled.size());
  EXPECT_EQ(wider->checked_pairs().size(), checked.size() - sampled.size());
  EXPECT_NE(wider->model_hash(), hash);
  EXPECT_EQ(wider->urdf_hash(), r->urdf_hash());
  EXPECT_EQ(r->model_hash(), hash);
  EXPECT_TRUE(wider->compute_allowed_collisions(500, 1).empty());
  EXPECT_TRUE(wider->in_self_collision(folded));  // the wrist on the base collides somewhere: still checked
  // Allowing every checked pair silences self-collision on the new robot only.
  auto silent = r->with_allowed_collisions(r->checked_pairs());
  EXPECT_FALSE(silent->in_self_collision(folded));
  EXPECT_TRUE(r->in_self_collision(folded));
  // By name, either order; a pair already allowed or of one link changes nothing.
  auto by_name = r->with_allowed_collisions(
      std::vector<std::pair<std::string, std::string>>{{"tool0", "tool0"}});
  EXPECT_EQ(by_name->model_hash(), hash);
  EXPECT_THROW(r->with_allowed_collisions(std::vector<std::pair<std::string, std::string>>{{"base_link", "nope"}}),
               std::invalid_argument);
  EXPECT_THROW(r->with_allowed_collisions(std::vector<std::pair<int, int>>{{0, 1000}}), std::invalid_argument);
  EXPECT_THROW(r->compute_allowed_collisions(0, 1), std::invalid_argument);
  // Chains keep the robot they were cut from alive.
  Chain c = wider->chain("base_link", "tool0");
  wider.reset();
  EXPECT_EQ(c.robot().model_hash(), r->with_allowed_collisions(sampled)->model_hash());
}

TEST(Robot, Obstacles) {
  auto r = arm_robot();
  Obstacles obs;
  Pose p = Pose::Identity();
  p.translation() = Eigen::Vector3d(0, 0, 0.8);  // around the straight-up forearm
  obs.add_box(Eigen::Vector3d(0.2, 0.2, 0.05), p);
  EXPECT_TRUE(r->in_collision(r->home(), obs));
  Pose away = Pose::Identity();
  away.translation() = Eigen::Vector3d(3, 0, 0);
  EXPECT_FALSE(r->in_collision(r->home(), obs, away));
}

TEST(Robot, BadInput) {
  EXPECT_THROW(Robot::from_urdf("<robot name='x'><link name='a'/>"), std::invalid_argument);
  EXPECT_THROW(Robot::from_urdf("/nonexistent/robot.urdf"), FileError);
  EXPECT_THROW(Robot::from_urdf("<robot name='x'><link name='a'/><link name='b'/></robot>"), std::invalid_argument);
  auto r = arm_robot();
  EXPECT_THROW(r->chain("base_link", "no_such_link"), std::invalid_argument);
  EXPECT_THROW(r->chain("tool0", "base_link"), std::invalid_argument);
  EXPECT_THROW(r->in_self_collision(Eigen::VectorXd::Zero(3)), std::invalid_argument);
}
