#pragma once
// Internal: the joint-vector size check shared by the chain's kinematics (chain.cpp) and IK (ik.cpp).

#include <stdexcept>
#include <string>

#include "octoreach/chain.hpp"

namespace octoreach::detail {

/// Raises std::invalid_argument unless q has one entry per moving joint of the chain.
inline void check_joint_vector(const Chain& c, const Eigen::VectorXd& q) {
  if (q.size() != c.dof())
    throw std::invalid_argument("joint vector has " + std::to_string(q.size()) + " entries, chain '" + c.base_link() +
                                "' -> '" + c.tip_link() + "' has " + std::to_string(c.dof()) + " joints");
}

}  // namespace octoreach::detail
