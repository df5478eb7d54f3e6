#include "kdl_chain.hpp"

#include <stdexcept>
#include <string>

namespace octoreach::bench {

KDL::Chain to_kdl(const ChainArrays& c) {
  const std::size_t n = c.origins.size();
  if (c.axes.size() != n || c.prismatic.size() != n || c.continuous.size() != n ||
      static_cast<std::size_t>(c.lower.size()) != n || static_cast<std::size_t>(c.upper.size()) != n)
    throw std::invalid_argument("chain description: origins, axes, prismatic, continuous, lower and upper must "
                                "have one entry per joint (" + std::to_string(n) + ")");
  auto frame = [](const Pose& T) {
    KDL::Rotation R(T(0, 0), T(0, 1), T(0, 2), T(1, 0), T(1, 1), T(1, 2), T(2, 0), T(2, 1), T(2, 2));
    return KDL::Frame(R, KDL::Vector(T(0, 3), T(1, 3), T(2, 3)));
  };
  KDL::Chain chain;
  for (std::size_t i = 0; i < n; ++i) {
    KDL::Frame F = frame(c.origins[i]);
    KDL::Vector axis = F.M * KDL::Vector(c.axes[i].x(), c.axes[i].y(), c.axes[i].z());
    KDL::Joint::JointType type = c.prismatic[i] ? KDL::Joint::TransAxis : KDL::Joint::RotAxis;
    const std::string name = "joint" + std::to_string(i);
    chain.addSegment(KDL::Segment("link" + std::to_string(i), KDL::Joint(name, F.p, axis, type), F));
  }
  if (!c.tip_offset.matrix().isIdentity(1e-12) || n == 0)
    chain.addSegment(KDL::Segment("tip_fixed", KDL::Joint(KDL::Joint::None), frame(c.tip_offset)));
  return chain;
}

}  // namespace octoreach::bench
