#include "kdl_chain.hpp"

#include "octoreach/robot.hpp"

namespace octoreach::bench {

KDL::Chain to_kdl(const Chain& c) {
  auto frame = [](const Pose& T) {
    KDL::Rotation R(T(0, 0), T(0, 1), T(0, 2), T(1, 0), T(1, 1), T(1, 2), T(2, 0), T(2, 1), T(2, 2));
    return KDL::Frame(R, KDL::Vector(T(0, 3), T(1, 3), T(2, 3)));
  };
  KDL::Chain chain;
  for (std::size_t i = 0; i < c.segments().size(); ++i) {
    const Chain::Segment& s = c.segments()[i];
    KDL::Frame F = frame(s.origin);
    KDL::Vector axis = F.M * KDL::Vector(s.axis.x(), s.axis.y(), s.axis.z());
    KDL::Joint::JointType type =
        s.type == JointType::Prismatic ? KDL::Joint::TransAxis : KDL::Joint::RotAxis;
    const std::string& name = c.robot().joints()[s.robot_joint].name;
    chain.addSegment(KDL::Segment(c.robot().links()[c.robot().joints()[s.robot_joint].child_link].name,
                                  KDL::Joint(name, F.p, axis, type), F));
  }
  if (!c.tip_offset().matrix().isIdentity(1e-12) || c.segments().empty())
    chain.addSegment(KDL::Segment(c.tip_link() + "_fixed", KDL::Joint(KDL::Joint::None), frame(c.tip_offset())));
  return chain;
}

}  // namespace octoreach::bench
