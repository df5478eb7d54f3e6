// The certified lookup and the cell quality on the test arm (coarse map).
#include <gtest/gtest.h>

#include <random>

#include <Eigen/SVD>

#include "octoreach/capability_map.hpp"
#include "octoreach/certified_lookup.hpp"
#include "octoreach/manipulability.hpp"
#include "octoreach/robot.hpp"

using namespace octoreach;

namespace {

std::shared_ptr<Robot> arm() {
  static std::shared_ptr<Robot> robot = Robot::from_urdf(std::string(OCTOREACH_URDF_DIR) + "/test_arm.urdf");
  return robot;
}

const CapabilityMap& coarse_map() {
  static const CapabilityMap map = [] {
    CapabilityMapOptions o;
    o.resolution = 0.25;
    o.directions = 16;
    o.seed = 3;
    return CapabilityMap::build(arm()->chain("base_link", "tool0"), o);
  }();
  return map;
}

}  // namespace

TEST(Manipulability, IsTheProductOfTheSingularValues) {
  const Chain chain = arm()->chain("base_link", "tool0");
  ASSERT_EQ(jacobian_rank(chain), 6);
  std::mt19937_64 rng(5);
  for (int i = 0; i < 20; ++i) {
    const Eigen::VectorXd q = chain.random_configuration(rng);
    Eigen::Matrix<double, 6, Eigen::Dynamic> J;
    chain.fk_jacobian(q, J);
    const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(J).singularValues();
    EXPECT_NEAR(manipulability(chain, q), s.prod(), 1e-9 * std::max(1.0, s.prod()));
    EXPECT_NEAR(manipulability(chain, q, 5), s.head(5).prod(), 1e-9 * std::max(1.0, s.head(5).prod()));
    const double p = joint_limit_penalty(chain, q);
    EXPECT_GE(p, 0.0);
    EXPECT_LE(p, 1.0);
  }
  EXPECT_THROW(manipulability(chain, Eigen::VectorXd::Zero(2)), std::invalid_argument);
  EXPECT_THROW(manipulability(chain, Eigen::VectorXd::Zero(chain.dof()), 7), std::invalid_argument);
}

TEST(CertifiedLookup, AnswersWithSolutionsWhereTheCellsDisagree) {
  const CapabilityMap& m = coarse_map();
  ASSERT_TRUE(m.has_cell_data() && m.has_quality());
  const CertifiedLookup check(m, *arm());
  const Chain& chain = check.chain();
  std::mt19937_64 rng(11);
  const auto [lo, hi] = m.bounds();
  int uncertain = 0, yes = 0;
  for (int i = 0; i < 400; ++i) {
    Pose T = Pose::Identity();
    T.linear() = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    for (int a = 0; a < 3; ++a) T.translation()[a] = std::uniform_real_distribution<double>(lo[a], hi[a])(rng);
    if (check.certain(T)) continue;
    ++uncertain;
    Eigen::VectorXd q;
    if (!check.reachable(T, &q)) continue;
    ++yes;
    const Pose F = chain.fk(q);
    EXPECT_LE((F.translation() - T.translation()).norm(), m.position_tolerance() + 1e-12);
    const Eigen::Vector3d a = m.approach_axis();
    EXPECT_LE(std::acos(std::min(1.0, (F.linear() * a).dot(T.linear() * a))), m.orientation_tolerance() + 1e-9);
    EXPECT_TRUE(chain.within_limits(q));
    EXPECT_FALSE(arm()->in_self_collision(chain.to_robot_configuration(q, check.reference())));
  }
  EXPECT_GT(uncertain, 10);
  EXPECT_GT(yes, 0);
}

TEST(CertifiedLookup, RefusesAMapWithoutSolutions) {
  CapabilityMapOptions o;
  o.resolution = 0.3;
  o.directions = 8;
  o.keep_solutions = false;
  const CapabilityMap bare = CapabilityMap::build(arm()->chain("base_link", "tool0"), o);
  EXPECT_FALSE(bare.has_quality());
  EXPECT_THROW(CertifiedLookup(bare, *arm()), std::invalid_argument);
  EXPECT_THROW(bare.voxel_quality(), std::invalid_argument);
}

TEST(CertifiedLookup, RefusesBadOptions) {
  CertifiedLookupOptions o;
  o.branch_seeds = -1;
  EXPECT_THROW(CertifiedLookup(coarse_map(), *arm(), Eigen::VectorXd(), o), std::invalid_argument);
  o.branch_seeds = 0;
  o.seeds = 0;
  EXPECT_THROW(CertifiedLookup(coarse_map(), *arm(), Eigen::VectorXd(), o), std::invalid_argument);
}
