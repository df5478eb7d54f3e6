// A consumer of the installed octoreach package: loads a URDF, solves IK, and builds the README's
// capability map and surface map. Prints what it found; exits non-zero when something is off.
#include <iostream>

#include <octoreach/capability_map.hpp>
#include <octoreach/chain.hpp>
#include <octoreach/robot.hpp>
#include <octoreach/surface_map.hpp>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: consumer ROBOT.urdf\n";
    return 2;
  }
  auto robot = octoreach::Robot::from_urdf(argv[1]);
  octoreach::Chain arm = robot->chain("base_link", "tool0");
  Eigen::VectorXd q = Eigen::VectorXd::Constant(arm.dof(), 0.3);
  octoreach::Pose target = arm.fk(q);
  auto solution = arm.ik(target, octoreach::IkOptions());
  if (!solution) {
    std::cerr << "IK failed\n";
    return 1;
  }
  double error = (arm.fk(*solution).translation() - target.translation()).norm();

  octoreach::CapabilityMapOptions o;
  o.resolution = 0.15;
  o.directions = 24;
  auto cap = octoreach::CapabilityMap::build(arm, o);
  auto table = octoreach::Surface::rectangle(0.6, 0.4, 0.4, 0.55);
  octoreach::SurfaceMapOptions so;
  so.z_min = so.z_max = 0.0;
  auto smap = octoreach::SurfaceMap::build(*robot, cap, table, so);
  std::cout << "octoreach " << octoreach::version() << ": " << robot->name() << ", " << arm.dof()
            << " dof, IK position error " << error << " m, capability map " << cap.voxel_count()
            << " voxels, surface map best R_S " << smap.map().max_value() << "\n";
  return error < 1e-3 && cap.voxel_count() > 0 && smap.map().max_value() > 0 ? 0 : 1;
}
