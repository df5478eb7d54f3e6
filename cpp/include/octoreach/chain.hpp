#pragma once
/// \file chain.hpp
/// \brief A serial kinematic chain between two links of a robot: FK, Jacobian and IK, with the IK options.

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "octoreach/types.hpp"

namespace octoreach {

class Robot;
class Obstacles;

/// \brief Joint kinds understood by octoreach (URDF planar and floating joints are kept fixed).
enum class JointType { Fixed, Revolute, Continuous, Prismatic };

/// \brief What an IK solution must match.
enum class IkMode {
  Full,      ///< position and orientation
  Position,  ///< position only
  Approach,  ///< position and the approach axis (any roll about it)
};

/// \brief Options of the damped least-squares (Levenberg-Marquardt) IK with random restarts.
struct IkOptions {
  IkMode mode = IkMode::Full;
  double position_tolerance = 1e-4;     ///< metres
  double orientation_tolerance = 1e-3;  ///< radians
  int max_iterations = 100;             ///< per attempt (stalled attempts stop early)
  int attempts = 20;                    ///< seed (or first random start) plus random restarts
  /// Stop a descent whose error fell by less than 10 % over this many iterations while still above
  /// the tolerances (0: never; the capability-map build, which tries many unreachable cells, uses 2).
  int stall_window = 0;
  std::uint64_t seed = 0;               ///< random restarts are deterministic for a seed
  Eigen::Vector3d approach_axis = Eigen::Vector3d::UnitZ();  ///< tip-frame axis used in Approach mode
  /// Approach mode: radians the approach axis may lie from the target's and count as reached, orientation_tolerance
  /// beyond them (0: exact); a camera aimed at a point sees it with the axis anywhere within half its field
  double approach_cone = 0.0;
  bool check_self_collision = false;    ///< reject solutions in self-collision
  /// With check_self_collision: also check the link pairs the chain never moves relative to each
  /// other (a caller that checked the reference posture once may switch this off).
  bool check_fixed_pairs = true;
  std::shared_ptr<const Obstacles> obstacles;  ///< reject solutions touching these (world frame)
  std::vector<int> obstacle_links;      ///< links checked against the obstacles (empty: every link)
  Pose base_pose = Pose::Identity();    ///< robot root pose in the world (for obstacles)
  /// Full robot configuration for joints outside the chain (empty: Robot::home()).
  Eigen::VectorXd reference;
};

/// \brief A serial chain between two links of a robot, with FK, Jacobian and IK.
///
/// Immutable and cheap to copy; safe to share between threads. Holds its robot as a
/// shared_ptr<const Robot>, so the robot lives as long as any of its chains. Each IK call owns its
/// scratch (the solver is a per-call workspace), so concurrent calls need no lock.
class Chain {
 public:
  /// \brief One moving or fixed step of the chain.
  struct Segment {
    Pose origin = Pose::Identity();  ///< previous frame -> joint frame
    JointType type = JointType::Fixed;
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    int robot_joint = -1;  ///< index into Robot::joints()
  };

  const std::string& base_link() const { return base_link_; }
  const std::string& tip_link() const { return tip_link_; }
  /// \brief Number of moving joints.
  int dof() const { return static_cast<int>(joint_names_.size()); }
  const std::vector<std::string>& joint_names() const { return joint_names_; }
  /// \brief Positions of the chain's joints in the robot configuration vector.
  const std::vector<int>& robot_indices() const { return robot_indices_; }
  const Eigen::VectorXd& lower() const { return lower_; }
  const Eigen::VectorXd& upper() const { return upper_; }
  /// \brief True for continuous (unbounded, wrapped) joints.
  const std::vector<bool>& continuous() const { return continuous_; }
  const std::vector<Segment>& segments() const { return segments_; }
  const Robot& robot() const { return *robot_; }
  std::shared_ptr<const Robot> robot_ptr() const { return robot_; }

  /// \brief Pose of the tip link in the base link frame.
  Pose fk(const Eigen::VectorXd& q) const;
  /// \brief Tip poses (base frame) for joint rows `q_rows` (N x dof), in row order.
  std::vector<Pose> fk_batch(const Eigen::MatrixXd& q_rows) const;
  /// \brief Pose of the tip and its 6 x dof geometric Jacobian (rows: linear, angular), base frame.
  Pose fk_jacobian(const Eigen::VectorXd& q, Eigen::Matrix<double, 6, Eigen::Dynamic>& jacobian) const;
  /// \brief The same without checks or allocation (the IK's inner loop): q holds dof() values; the
  /// Jacobian is written column-major to `jacobian` (6 x dof doubles) unless it is null.
  Pose fk_jacobian(const double* q, double* jacobian) const;
  /// \brief True when q has dof entries, all finite and inside the limits (continuous joints excepted).
  bool within_limits(const Eigen::VectorXd& q, double tolerance = 1e-9) const;
  /// \brief Wraps continuous joints into [-pi, pi) and revolute joints by 2 pi into their limits where possible.
  Eigen::VectorXd wrap(const Eigen::VectorXd& q) const;
  /// \brief Uniform random configuration inside the limits (continuous joints in [-pi, pi)).
  template <class Rng>
  Eigen::VectorXd random_configuration(Rng& rng) const;
  /// \brief The same draw into `q` (resized to dof()), for loops that reuse one vector.
  template <class Rng>
  void random_configuration(Rng& rng, Eigen::VectorXd& q) const;
  /// \brief n uniform random configurations (rows) from std::mt19937_64(seed), drawn in row order:
  /// row 0 equals random_configuration() of a fresh generator with the same seed.
  Eigen::MatrixXd random_configurations(int n, std::uint64_t seed) const;

  /// \brief Inverse kinematics of the tip pose `target` (base frame); returns q or nothing.
  std::optional<Eigen::VectorXd> ik(const Pose& target, const IkOptions& options,
                                    const Eigen::VectorXd* seed = nullptr) const;
  /// \brief IK of many poses on every core; row i of the result solves targets[i] where ok[i].
  void ik_batch(const std::vector<Pose>& targets, const IkOptions& options, Eigen::MatrixXd& solutions,
                std::vector<bool>& ok, const Eigen::MatrixXd* seeds = nullptr, int threads = 0) const;

  /// \brief Full robot configuration with this chain's joints set to q and the rest from `reference`.
  Eigen::VectorXd to_robot_configuration(const Eigen::VectorXd& q, const Eigen::VectorXd& reference) const;

  /// \brief Fixed transform from the last joint's frame to the tip link (identity when the tip moves).
  const Pose& tip_offset() const { return tip_offset_; }

  /// \brief Bit i set when chain joint i moves robot link `link` (0: the chain does not move it;
  /// all dof bits: rigidly attached to the tip, e.g. a gripper).
  std::uint64_t link_mask(int link) const { return link_masks_.at(link); }

  /// \brief The robot's collision links (indices, in Robot::collision_links order) that this chain's
  /// joints move: its arm links and what they carry. The links it does not move stand where the robot
  /// was placed (a base standing on the floor touches it without any arm motion being at fault).
  std::vector<int> moved_collision_links() const;

  /// \brief Splits the robot's checked self-collision pairs into those whose relative pose this
  /// chain's joints change (`moving`) and those it never changes (`fixed`).
  void split_collision_pairs(std::vector<std::pair<int, int>>& moving, std::vector<std::pair<int, int>>& fixed) const;

 private:
  friend class Robot;  // Robot::chain cuts chains out of its tree
  std::shared_ptr<const Robot> robot_;
  std::string base_link_, tip_link_;
  std::vector<Segment> segments_;
  Pose tip_offset_ = Pose::Identity();
  std::vector<std::string> joint_names_;
  std::vector<int> robot_indices_;
  Eigen::VectorXd lower_, upper_;
  std::vector<bool> continuous_;
  std::vector<std::uint64_t> link_masks_;  // per robot link: bit i set if chain joint i moves it
  std::vector<std::int8_t> axis_kind_;     // per joint: 0-2 = +x, +y, +z; 3-5 = -x, -y, -z; -1 any other axis
  std::vector<char> turned_origin_;        // per joint: its origin rotates (not the identity)
};

template <class Rng>
Eigen::VectorXd Chain::random_configuration(Rng& rng) const {
  Eigen::VectorXd q(dof());
  random_configuration(rng, q);
  return q;
}

template <class Rng>
void Chain::random_configuration(Rng& rng, Eigen::VectorXd& q) const {
  q.resize(dof());
  for (int i = 0; i < dof(); ++i) {
    double lo = continuous_[i] ? -kPi : lower_[i];
    double hi = continuous_[i] ? kPi : upper_[i];
    std::uniform_real_distribution<double> u(lo, hi);
    q[i] = u(rng);
  }
}

}  // namespace octoreach
