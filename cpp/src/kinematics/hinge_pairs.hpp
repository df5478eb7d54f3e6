#pragma once
// Internal: self-collision pairs whose relative pose one chain joint alone sets ("hinge pairs"): a
// link the chain's first joint turns against the links the chain never moves (the PR2's shoulder
// against its tucked other arm), or two links one joint apart. Their check is skipped where its
// answer is certain: the joint's range is cut into buckets, and a bucket is certified free when the
// pair's distance at the bucket's centre exceeds what turning by half a bucket can close (every point
// of the turned link moves at most radius * angle, radius = its farthest point from the joint axis).
// A bucket is measured (one FCL distance query per shape pair) the first time a configuration falls
// in it; the answer of a check never changes, only its cost (ChainSelfCheck asks it per pair).
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "octoreach/chain.hpp"
#include "octoreach/types.hpp"

namespace octoreach::detail {

class HingePairs {
 public:
  HingePairs() = default;
  /// `pairs`: the checked pairs (link indices) of `chain`'s robot; `reference`: a full robot
  /// configuration (the joints off the chain stay there).
  HingePairs(const Chain& chain, const std::vector<std::pair<int, int>>& pairs, const Eigen::VectorXd& reference);

  /// The hinge certificate of pair `p` (index into the pairs given), or -1 when it has none.
  int hinge_of(std::size_t p) const { return hinge_of_[p]; }
  /// True when pair `p` has a hinge certificate and is certified free at the full robot configuration `full`
  /// (off-chain joints at the reference).
  bool certified_pair(const Robot& robot, std::size_t p, const Eigen::VectorXd& full) {
    const int h = hinge_of_[p];
    return h >= 0 && certified(robot, static_cast<std::size_t>(h), full[hinges_[h].config_index]);
  }

  /// Number of hinge pairs found (the others are always returned).
  std::size_t hinges() const { return hinges_.size(); }
  /// True when the hinge pair `h` is certified free at joint value `v` (measures its bucket if new).
  bool certified(const Robot& robot, std::size_t h, double v);

  /// Bucket width (rad or m) for a turned link of this radius: half a bucket moves it at most 1 mm.
  static double bucket_width(double radius);

 private:
  struct Hinge {
    int pair = -1;         // index into pairs_
    int config_index = -1; // the joint's entry in the full configuration
    double lo = 0, hi = 0, width = 0, radius = 0;
    std::vector<std::int8_t> bucket;  // -1 not measured, 0 uncertain, 1 certified free
  };
  double distance(const Robot& robot, const Hinge& h, double v);

  std::vector<std::pair<int, int>> pairs_;
  std::vector<int> hinge_of_;  // per pair: index into hinges_, or -1
  std::vector<Hinge> hinges_;
  Eigen::VectorXd base_;       // full configuration the buckets are measured at (only the hinge joint varies)
  std::vector<Pose> poses_;    // scratch
};

}  // namespace octoreach::detail
