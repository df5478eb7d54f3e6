// A consumer of the installed octoreach package: loads a URDF, solves IK, and builds the capability map and
// surface map of the README's and the C++ guide's quick-start (the docs' test checks that their lines are
// these). Prints what it found; exits non-zero when something is off.
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
  auto robot = octoreach::Robot::from_urdf(argv[1]);              // a URDF path (package dirs: 2nd argument)
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
  o.resolution = 0.15;                                            // coarse and quick; 0.05 for real use
  o.directions = 24;
  auto cap = octoreach::CapabilityMap::build(arm, o);
  auto table = octoreach::Surface::rectangle(0.6, 0.4, 0.4, 0.55);  // 0.6 x 0.4 m, top at 0.4 m, centre x = 0.55
  octoreach::SurfaceMapOptions so;                                // defaults: the robot stands on the floor
  auto smap = octoreach::SurfaceMap::build(*robot, cap, table, so);
  double rs = smap.reachability(0.0, 0.0, 0.0, 0.0);               // R_S of base pose (x, y, z, theta)
  std::cout << "octoreach " << octoreach::version() << ": " << robot->name() << ", " << arm.dof()
            << " dof, IK position error " << error << " m, capability map " << cap.voxel_count()
            << " voxels, surface map best R_S " << smap.map().max_value() << ", R_S at the origin " << rs << "\n";
  return error < 1e-3 && cap.voxel_count() > 0 && smap.map().max_value() > 0 ? 0 : 1;
}
