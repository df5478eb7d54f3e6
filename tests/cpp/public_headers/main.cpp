// A consumer that includes only octoreach's robot-side public headers and Eigen: it must compile
// without FCL, OctoMap, urdfdom or KDL headers (check.cmake proves none is pulled in).
// OCTOREACH_VERSION comes from the exported target's compile definitions in a real consumer.
#define OCTOREACH_VERSION "public-headers-test"

#include <octoreach/arm_discovery.hpp>
#include <octoreach/camera_link.hpp>
#include <octoreach/chain.hpp>
#include <octoreach/collision.hpp>
#include <octoreach/manipulability.hpp>
#include <octoreach/robot.hpp>
#include <octoreach/shape.hpp>
#include <octoreach/self_collision_report.hpp>
#include <octoreach/types.hpp>

#include <iostream>

// Uses the headers' types the way a consumer would; compiled with -fsyntax-only, never linked.
int use(const std::string& urdf) {
  std::shared_ptr<const octoreach::Robot> robot = octoreach::Robot::from_urdf(urdf);
  octoreach::Chain arm = robot->chain(robot->groups().at(0).base_link, robot->groups().at(0).tip_link);
  octoreach::IkOptions options;
  options.mode = octoreach::IkMode::Position;
  auto q = arm.ik(arm.fk(Eigen::VectorXd::Zero(arm.dof())), options);
  octoreach::Obstacles obstacles;
  obstacles.add_box(Eigen::Vector3d::Ones(), octoreach::Pose::Identity());
  obstacles.add(octoreach::Shape::sphere(0.1), "ball");
  auto pairs = robot->compute_allowed_collisions(10, 0);
  auto wider = robot->with_allowed_collisions(pairs);
  octoreach::SelfCollisionReport report = octoreach::self_collision_report(*robot);
  for (const octoreach::Arm& a : octoreach::find_arms(*robot)) std::cout << a.name << " " << a.reason << "\n";
  std::cout << octoreach::camera_link(*robot).link << " " << report.free_share() << "\n";
  std::cout << robot->links().at(0).shapes.size() << " " << robot->links().at(0).visuals.size() << " "
            << robot->source().urdf << " " << octoreach::kPi << " "
            << octoreach::manipulability(arm, *q, octoreach::jacobian_rank(arm)) << "\n";
  return q && !wider->in_collision(*q, obstacles) ? 0 : 1;
}

int main() { return 0; }
