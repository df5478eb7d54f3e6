#pragma once
/// \file certified_lookup.hpp
/// \brief Reachability of tool poses from a capability map, answered by IK where the map's cells disagree.

#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "octoreach/capability_map.hpp"
#include "octoreach/chain.hpp"
#include "octoreach/robot.hpp"

namespace octoreach {

/// \brief Options of CertifiedLookup (defaults defined here only).
struct CertifiedLookupOptions {
  /// Stored configurations IK starts from at most, nearest cells first (each a single descent).
  int seeds = 8;
  /// Iterations per descent: the map's own build settles a cell from a neighbour's solution within this many.
  int max_iterations = 25;
  /// Configurations of other IK branches IK starts from at most when the seeds fail (0: none): stored in the
  /// 4 x 4 x 4 cells around the pose (its 8 corners and one voxel further) under the approach directions within
  /// two direction spacings of the pose's, nearest first, each more than 1 rad (1 m for a prismatic joint) from
  /// every configuration tried in some joint.
  int branch_seeds = 4;
  /// Configurations of other branches tried at most (instead of branch_seeds) when a descent reached the pose in
  /// self-collision: the pose lies where the arm's collision-free configurations end, and another branch or elbow
  /// posture often reaches it free, which the nearby stored configurations, collision-free themselves, do not lead
  /// to. A descent that does not reach the pose says nothing of collisions and keeps branch_seeds; branch_seeds 0
  /// tries no other branch either way.
  int collided_branch_seeds = 16;
};

/// \brief The certified lookup: a pose's answer comes from the map where the cells around it agree, and from
/// IK at the exact pose where they do not.
///
/// The cells around a tool pose (base link frame) are the 8 voxel centres whose trilinear weights span its
/// position, each with the orientation nearest the pose's. When all are reachable the pose is (the reachable
/// set holds the cells' centres all around it); when none is reachable or mixed it is not. Otherwise the pose
/// lies where the reachable set ends between the cells, or in a mixed cell (a thin reachable set passes through
/// it), and IK answers: single descents from the configurations stored in those cells, nearest first, with the
/// map's criteria (tolerances, approach axis, self-collision at the reference posture). A yes from IK is a
/// solution; the map's cells decide only where they agree. When those descents fail, the pose may lie in another
/// IK branch (elbow or wrist flipped) than every configuration the corners store: a few configurations of other
/// branches stored in the cells around them are tried too (CertifiedLookupOptions::branch_seeds; more,
/// collided_branch_seeds, once a descent reached the pose in self-collision). Needs a map
/// built with solutions by this version (CapabilityMap::has_cell_data()). The map must outlive the lookup. Const
/// and thread-safe.
class CertifiedLookup {
 public:
  /// \brief The lookup of `map` for `robot` (the model the map was built for) at `reference` (the full robot
  /// configuration for the joints off the chain; empty: the map's own, else default_reference(robot, chain)).
  /// \throws std::invalid_argument when the map holds no cell data or solutions (saying how to rebuild), the robot
  /// is another model, or the reference has the wrong size or puts links the chain does not move in collision.
  CertifiedLookup(const CapabilityMap& map, const Robot& robot, const Eigen::VectorXd& reference = Eigen::VectorXd(),
                  const CertifiedLookupOptions& options = {});

  /// \brief True when the tool pose T is reachable; with a yes from IK, `solution` (if given) receives it.
  /// \throws std::invalid_argument unless T is a finite rigid transform (check_rigid); so does certain().
  bool reachable(const Pose& T, Eigen::VectorXd* solution = nullptr) const;
  /// \brief reachable() of n row-major 4x4 poses (16 n doubles) into `out` on `threads` threads (0: every core);
  /// the answers do not depend on the thread count. Throws std::invalid_argument naming the first pose that is not
  /// a finite rigid transform.
  void reachable(const double* poses, std::size_t n, bool* out, int threads = 0) const;
  /// \brief True when the map's cells decide T without IK.
  bool certain(const Pose& T) const;
  /// \brief certain() of n row-major 4x4 poses into `out`.
  void certain(const double* poses, std::size_t n, bool* out) const;

  const CapabilityMap& map() const { return map_; }
  const Chain& chain() const { return chain_; }
  const Eigen::VectorXd& reference() const { return ik_.reference; }
  const CertifiedLookupOptions& options() const { return options_; }

 private:
  enum class Cells : std::uint8_t { reachable, unreachable, mixed };
  static constexpr int kMaxSeeds = 16;
  // reachable() of a pose already known to be rigid (is_rigid, check_rigid's rule: the batch tests each row).
  bool answer(const Pose& T, Eigen::VectorXd* solution) const;
  // True when stored configurations a and b are within gap_max of each other in every joint (continuous joints
  // modulo 2 pi).
  bool near(const float* a, const float* b, double gap_max) const;
  // The cells around T; for mixed cells, up to options_.seeds stored configurations, nearest first.
  Cells cells(const Pose& T, const float** seeds, int& n_seeds) const;
  // One descent from q0; true with a collision-free solution. `collided`: set when the descent reached the pose
  // in collision.
  bool descend(const Pose& T, const Eigen::VectorXd& q0, Eigen::VectorXd* solution, bool& collided) const;
  // IK from up to options_.branch_seeds configurations of other branches than `tried`, collided_branch_seeds once
  // a descent reached the pose in collision (see the options).
  bool other_branches(const Pose& T, const float* const* tried, int n_tried, Eigen::VectorXd* solution,
                      bool collided) const;

  const CapabilityMap& map_;
  Chain chain_;
  IkOptions ik_;       // the map's criteria
  IkOptions reach_ik_;  // the same without the collision check: a descent's solution is then checked by itself
  CertifiedLookupOptions options_;
};

}  // namespace octoreach
