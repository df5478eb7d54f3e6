#pragma once
/// \file kdl_chain.hpp
/// \brief Benchmark and test support (not part of the octoreach library): a serial chain as plain
/// arrays, and the same chain as a KDL::Chain, for the plain-KDL reference solvers that octoreach's own
/// IK and FK are measured against. The reference code links no octoreach code: its Python module gets
/// the arrays from a bound octoreach.Chain's description, the C++ tests from arrays_of(chain).

#include <vector>

#include <kdl/chain.hpp>

#include "octoreach/chain.hpp"

namespace octoreach::bench {

/// \brief A chain of moving joints: joint i's frame in joint i-1's (the base link's for i = 0), its
/// axis in its own frame, prismatic or rotational, its limits; then the fixed tip offset.
struct ChainArrays {
  std::vector<Pose> origins;
  std::vector<Eigen::Vector3d> axes;
  std::vector<bool> prismatic;
  std::vector<bool> continuous;  ///< unbounded rotational joints (their limits are not used)
  Eigen::VectorXd lower, upper;
  Pose tip_offset = Pose::Identity();

  int dof() const { return static_cast<int>(origins.size()); }
};

/// \brief The description of an octoreach Chain (header-only: reads the chain's inline accessors).
inline ChainArrays arrays_of(const Chain& c) {
  ChainArrays a;
  for (const Chain::Segment& s : c.segments()) {
    a.origins.push_back(s.origin);
    a.axes.push_back(s.axis);
    a.prismatic.push_back(s.type == JointType::Prismatic);
  }
  a.continuous = c.continuous();
  a.lower = c.lower();
  a.upper = c.upper();
  a.tip_offset = c.tip_offset();
  return a;
}

/// \brief The same chain as a KDL::Chain (built from the arrays, not by kdl_parser).
/// \throws std::invalid_argument when the arrays disagree in length.
KDL::Chain to_kdl(const ChainArrays& chain);

}  // namespace octoreach::bench
