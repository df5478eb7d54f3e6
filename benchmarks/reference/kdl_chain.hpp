#pragma once
/// \file kdl_chain.hpp
/// \brief Benchmark and test support (not part of the octoreach library): an octoreach Chain as a
/// KDL::Chain, for the plain-KDL reference solvers that octoreach's own IK and FK are measured against.

#include <kdl/chain.hpp>

#include "octoreach/chain.hpp"

namespace octoreach::bench {

/// \brief The same chain as a KDL::Chain (built by octoreach, not by kdl_parser).
KDL::Chain to_kdl(const Chain& chain);

}  // namespace octoreach::bench
