// Python binding of Chain: FK, Jacobian, IK (keyword options converted to IkOptions).
#include "common.hpp"
#include "octoreach/aim.hpp"
#include "octoreach/chain.hpp"
#include "octoreach/manipulability.hpp"
#include "octoreach/collision.hpp"
#include "octoreach/robot.hpp"
#include "robot/robot_args.hpp"

namespace octoreach::py_bindings {

namespace {

IkMode parse_mode(const std::string& mode) {
  if (mode == "full") return IkMode::Full;
  if (mode == "position") return IkMode::Position;
  if (mode == "approach") return IkMode::Approach;
  throw std::invalid_argument("IK mode must be 'full', 'position' or 'approach', got '" + mode + "'");
}

IkOptions make_options(const Chain& c, const std::string& mode, double pos_tol, double rot_tol, int attempts,
                       int max_iterations, std::uint64_t seed, const Eigen::Vector3d& approach_axis,
                       double approach_cone, bool self_collision, std::shared_ptr<Obstacles> obstacles,
                       const py::object& base_pose, const py::object& reference, const py::object& obstacle_links) {
  IkOptions o;
  if (!obstacle_links.is_none())
    for (const auto& name : cast_arg<std::vector<std::string>>(obstacle_links, "obstacle_links", "a list of link names"))
      o.obstacle_links.push_back(c.robot().link_index(name));
  o.mode = parse_mode(mode);
  o.position_tolerance = pos_tol;
  o.orientation_tolerance = rot_tol;
  o.attempts = attempts;
  o.max_iterations = max_iterations;
  o.seed = seed;
  if (!approach_axis.allFinite() || approach_axis.norm() < 1e-9)
    throw std::invalid_argument("approach_axis must be a finite non-zero vector");
  o.approach_axis = approach_axis;
  o.approach_cone = approach_cone;
  o.check_self_collision = self_collision;
  o.obstacles = obstacles;
  if (!base_pose.is_none()) o.base_pose = pose_from(base_pose, "base_pose");
  if (!reference.is_none()) {
    o.reference = cast_arg<Eigen::VectorXd>(reference, "reference", "a vector of joint values");
    if (o.reference.size() != c.robot().dof())
      throw std::invalid_argument("reference must have " + std::to_string(c.robot().dof()) + " entries (the robot's dof)");
  }
  return o;
}

Eigen::VectorXd q_from(const Chain& c, const py::handle& q, const char* what = "q") {
  Array a = array_arg(q, what, "a vector of " + std::to_string(c.dof()) + " joint values");
  if (a.ndim() != 1 || a.shape(0) != c.dof())
    throw std::invalid_argument(std::string(what) + " must be a vector of " + std::to_string(c.dof()) + " joint values");
  Eigen::VectorXd q_vec = Eigen::Map<const Eigen::VectorXd>(a.data(), c.dof());
  if (!q_vec.allFinite()) throw std::invalid_argument(std::string(what) + " must be finite (got NaN or inf)");
  return q_vec;
}

const char* mode_name(IkMode mode) {
  return mode == IkMode::Full ? "full" : mode == IkMode::Position ? "position" : "approach";
}

// The keyword arguments of ik and ik_batch; their defaults are IkOptions' (defined once, in C++).
const IkOptions kIkDefaults;
#define IK_ARGS                                                                                               \
  py::arg("mode") = mode_name(kIkDefaults.mode), py::arg("position_tolerance") = kIkDefaults.position_tolerance, \
  py::arg("orientation_tolerance") = kIkDefaults.orientation_tolerance, py::arg("attempts") = kIkDefaults.attempts, \
  py::arg("max_iterations") = kIkDefaults.max_iterations, py::arg("rng_seed") = kIkDefaults.seed,             \
  py::arg("approach_axis") = kIkDefaults.approach_axis, py::arg("approach_cone") = kIkDefaults.approach_cone,   \
  py::arg("self_collision") = kIkDefaults.check_self_collision,                                               \
  py::arg("obstacles") = nullptr, py::arg("base_pose") = py::none(), py::arg("reference") = py::none(),      \
  py::arg("obstacle_links") = py::none()

// The chain's description as plain arrays (what the benchmark references build their KDL chain from).
void def_description(py::class_<Chain>& cls) {
  cls.def_property_readonly("joint_origins", [](const Chain& c) {
         std::vector<Pose> out;
         for (const Chain::Segment& s : c.segments()) out.push_back(s.origin);
         return poses_to_array(out);
       }, "(dof, 4, 4): joint i's frame in joint i-1's frame (the base link's for joint 0), fixed joints\n"
          "folded in. With joint_axes, prismatic, the limits and tip_offset: the chain's description.")
      .def_property_readonly("joint_axes", [](const Chain& c) {
             RowMatrixXd axes(c.dof(), 3);
             for (int i = 0; i < c.dof(); ++i) axes.row(i) = c.segments()[i].axis.transpose();
             return axes;
           }, "(dof, 3): each joint's axis in its own frame (unit vectors).")
      .def_property_readonly("prismatic", [](const Chain& c) {
             std::vector<bool> out;
             for (const Chain::Segment& s : c.segments()) out.push_back(s.type == JointType::Prismatic);
             return out;
           }, "True for prismatic joints (the others rotate about their axis).")
      .def_property_readonly("tip_offset", [](const Chain& c) { return pose_to_array(c.tip_offset()); },
                             "Fixed transform (4x4) from the last joint's frame to the tip link.");
}

// Look-at IK: aim and aim_error (aim.hpp).
void def_aim(py::class_<Chain>& cls) {
  cls
      .def("aim", [](const Chain& c, const py::object& target, const Eigen::Vector3d& axis, double tolerance,
                     int attempts, int iters, std::uint64_t rng_seed, const py::object& seed) -> py::object {
             AimOptions o;
             o.axis = axis;
             o.tolerance = tolerance;
             o.attempts = attempts;
             o.max_iterations = iters;
             o.seed = rng_seed;
             const Eigen::Vector3d t = vec3_from(target, "target");
             Eigen::VectorXd s;
             if (!seed.is_none()) s = q_from(c, seed, "seed");
             AimResult r;
             {
               py::gil_scoped_release release;
               r = aim(c, t, o, seed.is_none() ? nullptr : &s);
             }
             return r.reached ? py::cast(r.q) : py::object(py::none());
           }, py::arg("target"), py::arg("axis") = AimOptions().axis, py::arg("tolerance") = AimOptions().tolerance,
           py::arg("attempts") = AimOptions().attempts, py::arg("max_iterations") = AimOptions().max_iterations,
           py::arg("rng_seed") = AimOptions().seed, py::arg("seed") = py::none(),
           "Joints (inside the limits) that point the tip's `axis` (a camera's optical axis) at `target` (a point,\n"
           "base link frame) within `tolerance` radians, the tip's position following from the chain (look-at IK for\n"
           "a pan/tilt head); None when the chain cannot aim there (aim_error tells by how much it misses).")
      .def("aim_error", [](const Chain& c, const py::object& q, const py::object& target, const Eigen::Vector3d& axis) {
             return aim_error(c, q_from(c, q, "q"), vec3_from(target, "target"), axis);
           }, py::arg("q"), py::arg("target"), py::arg("axis") = AimOptions().axis,
           "Radians between the tip's `axis` at joints q and the ray from the tip's origin to `target` (base link frame).");
}

}  // namespace

void wrap_chain(py::module_& m) {
  py::class_<Chain> cls(m, "Chain", "Serial chain between two links: FK, Jacobian and IK (poses in the base link frame).");
  def_description(cls);
  def_aim(cls);
  cls
      .def_property_readonly("base_link", &Chain::base_link)
      .def_property_readonly("tip_link", &Chain::tip_link)
      .def_property_readonly("dof", &Chain::dof)
      .def_property_readonly("joint_names", &Chain::joint_names)
      .def_property_readonly("lower", &Chain::lower, "Lower joint limits (-inf for continuous joints).")
      .def_property_readonly("upper", &Chain::upper, "Upper joint limits (+inf for continuous joints).")
      .def_property_readonly("continuous", &Chain::continuous)
      .def_property_readonly("robot_indices", &Chain::robot_indices,
                             "Positions of this chain's joints in the robot configuration vector.")
      .def("fk", [](const Chain& c, const py::object& q) { return pose_to_array(c.fk(q_from(c, q))); }, py::arg("q"),
           "Pose (4x4) of the tip link in the base link frame.")
      .def("fk_batch", [](const Chain& c, const py::object& Q) {
             Eigen::MatrixXd M = finite_matrix_from(Q, c.dof(), "Q");
             std::vector<Pose> out;
             {
               py::gil_scoped_release release;
               out = c.fk_batch(M);
             }
             return poses_to_array(out);
           }, py::arg("Q"), "Tip poses (N, 4, 4) in the base link frame for joint rows Q (N, dof).")
      .def("jacobian", [](const Chain& c, const py::object& q) {
             Eigen::Matrix<double, 6, Eigen::Dynamic> J;
             c.fk_jacobian(q_from(c, q), J);
             return Eigen::MatrixXd(J);
           }, py::arg("q"), "Geometric Jacobian (6, dof), rows vx vy vz wx wy wz, in the base link frame.")
      .def("manipulability", [](const Chain& c, const py::object& q, const py::object& rank) {
             return manipulability(c, q_from(c, q), rank.is_none() ? jacobian_rank(c) : cast_arg<int>(rank, "rank", "an int or None"));
           }, py::arg("q"), py::arg("rank") = py::none(),
           "Yoshikawa's manipulability of q: sqrt(det(J J^T)), the product of the Jacobian's singular values; for a chain\n"
           "of Jacobian rank r < 6 (rank None: jacobian_rank) the product of its r largest.")
      .def_property_readonly("jacobian_rank", [](const Chain& c) { return jacobian_rank(c); },
                             "Generic rank of the 6 x dof Jacobian (6 for six or more independent joints).")
      .def("joint_limit_penalty", [](const Chain& c, const py::object& q) { return joint_limit_penalty(c, q_from(c, q)); },
           py::arg("q"),
           "Joint-limit penalty of q in [0, 1] (Tsai; Vahrenkamp et al.): 1 - exp(-4^n prod (q - l)(u - q) / (u - l)^2)\n"
           "over the n bounded joints; 1 - 1/e in the middle of every range, 0 at a limit.")
      .def("link_mask", [](const Chain& c, const std::string& link) { return c.link_mask(c.robot().link_index(link)); },
           py::arg("link"),
           "Bit i set when chain joint i moves `link`: 0 for links the chain does not move, all bits for links\n"
           "rigid with the tip (a gripper).")
      .def_property_readonly("moved_links", [](const Chain& c) {
             std::vector<std::string> names;
             for (int li : c.moved_collision_links()) names.push_back(c.robot().links()[li].name);
             return names;
           }, "The robot's collision links that this chain's joints move (its arm links and what they carry), in\n"
              "Robot.collision_links order.")
      .def("within_limits", [](const Chain& c, const py::object& q) { return c.within_limits(q_from(c, q)); })
      .def("wrap", [](const Chain& c, const py::object& q) { return c.wrap(q_from(c, q)); },
           "Continuous joints wrapped into [-pi, pi), revolute joints shifted by 2 pi into their limits where possible.")
      .def("random_configuration", [](const Chain& c, std::uint64_t seed) {
             return Eigen::VectorXd(c.random_configurations(1, seed).row(0).transpose());
           }, py::arg("seed") = 0, "One uniform random configuration inside the limits (continuous joints in [-pi, pi)).")
      .def("random_configurations", &Chain::random_configurations, py::arg("n"), py::arg("seed") = 0,
           "(n, dof) uniform random configurations inside the limits (continuous joints in [-pi, pi)), one per row;\n"
           "row 0 equals random_configuration(seed).")
      .def("to_robot_configuration", [](const Chain& c, const py::object& q, const py::object& reference) {
             Eigen::VectorXd ref = reference.is_none() ? Eigen::VectorXd() : robot_q(c.robot(), reference, "reference");
             return c.to_robot_configuration(q_from(c, q), ref);
           }, py::arg("q"), py::arg("reference") = py::none(),
           "Full robot configuration with this chain's joints set to q, the rest from `reference` (default home).")
      .def("ik", [](const Chain& c, const py::object& T, const py::object& seed, const std::string& mode, double pt,
                    double rt, int attempts, int iters, std::uint64_t rng_seed, const Eigen::Vector3d& axis,
                    double cone, bool self_col, std::shared_ptr<Obstacles> obstacles, const py::object& base_pose,
                    const py::object& reference, const py::object& obstacle_links) -> py::object {
             Pose target = pose_from(T, "T (the target pose)");
             IkOptions o = make_options(c, mode, pt, rt, attempts, iters, rng_seed, axis, cone, self_col, obstacles,
                                        base_pose, reference, obstacle_links);
             Eigen::VectorXd s;
             if (!seed.is_none()) s = q_from(c, seed, "seed");
             std::optional<Eigen::VectorXd> q;
             {
               py::gil_scoped_release release;
               q = c.ik(target, o, seed.is_none() ? nullptr : &s);
             }
             if (!q) return py::none();
             return py::cast(*q);
           }, py::arg("T"), py::arg("seed") = py::none(), IK_ARGS,
           "Joint vector reaching the 4x4 tip pose T (base link frame), or None.\n\n"
           "mode: 'full' (position and orientation), 'position', or 'approach' (position and the tip's\n"
           "approach_axis within approach_cone radians, any roll about it). Random restarts inside the limits;\n"
           "deterministic for rng_seed. self_collision / obstacles reject colliding solutions (obstacles in the\n"
           "world frame, the robot's root at base_pose; obstacle_links restricts that check to the named links);\n"
           "joints outside the chain take their values from `reference` (default robot.home()).")
      .def("ik_batch", [](const Chain& c, const py::object& Ts, const py::object& seeds, const std::string& mode,
                          double pt, double rt, int attempts, int iters, std::uint64_t rng_seed,
                          const Eigen::Vector3d& axis, double cone, bool self_col,
                          std::shared_ptr<Obstacles> obstacles, const py::object& base_pose,
                          const py::object& reference, const py::object& obstacle_links, int threads) {
             std::vector<Pose> targets = poses_from(Ts, "Ts");
             IkOptions o = make_options(c, mode, pt, rt, attempts, iters, rng_seed, axis, cone, self_col, obstacles,
                                        base_pose, reference, obstacle_links);
             Eigen::MatrixXd S;
             bool has_seeds = !seeds.is_none();
             if (has_seeds) {
               S = finite_matrix_from(seeds, c.dof(), "seeds");
               if (S.rows() != static_cast<Eigen::Index>(targets.size()))
                 throw std::invalid_argument("seeds must have one row per target");
             }
             Eigen::MatrixXd Q;
             std::vector<bool> ok;
             {
               py::gil_scoped_release release;
               c.ik_batch(targets, o, Q, ok, has_seeds ? &S : nullptr, threads);
             }
             py::array_t<bool> mask(static_cast<py::ssize_t>(ok.size()));
             auto w = mask.mutable_unchecked<1>();
             for (std::size_t i = 0; i < ok.size(); ++i) w(i) = ok[i];
             return py::make_tuple(Q, mask);
           }, py::arg("Ts"), py::arg("seeds") = py::none(), IK_ARGS, py::arg("threads") = 0,
           "IK of poses Ts (N, 4, 4) on every core. Returns (Q of shape (N, dof) with NaN rows where it failed,\n"
           "success mask (N,)). Item i uses a random stream derived from rng_seed and i.")
      .def("__repr__", [](const Chain& c) {
        return "<octoreach.Chain '" + c.base_link() + "' -> '" + c.tip_link() + "', " + std::to_string(c.dof()) + " dof>";
      });
}

}  // namespace octoreach::py_bindings
