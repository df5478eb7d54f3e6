// Loads a URDF through the installed octoreach package, solves one IK problem, prints the result.
#include <iostream>

#include <octoreach/ik.hpp>
#include <octoreach/robot.hpp>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: consumer ROBOT.urdf\n";
    return 2;
  }
  auto robot = octoreach::Robot::from_urdf(argv[1]);
  octoreach::Chain arm = robot->chain("base_link", "tool0");
  Eigen::VectorXd q = Eigen::VectorXd::Constant(arm.dof(), 0.3);
  octoreach::Pose target = arm.fk(q);
  octoreach::IkOptions options;
  auto solution = arm.ik(target, options);
  if (!solution) {
    std::cerr << "IK failed\n";
    return 1;
  }
  double error = (arm.fk(*solution).translation() - target.translation()).norm();
  std::cout << "octoreach " << octoreach::version() << ": " << robot->name() << ", " << arm.dof()
            << " dof, IK position error " << error << " m\n";
  return error < 1e-3 ? 0 : 1;
}
