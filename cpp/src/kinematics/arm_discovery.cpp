// Finding the arms of a robot: from the SRDF (chain, joint-list, link-list groups, subgroups,
// end effectors) or, without one, from the kinematic tree; and the approach axis of a tool frame,
// inferred from the gripper with the reason. No robot-specific table: the PR2's arms come out of its
// SRDF groups with their tips moved to the gripper tool frames and +x inferred from the wrist.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "common/format.hpp"
#include "common/nearest_names.hpp"
#include "octoreach/arm_discovery.hpp"
#include "robot/link_names.hpp"

namespace octoreach {

const char kNoArmFound[] =
    "no SRDF arm group, and no branch ends in finger joints or a link named like a tool frame: tool0, tcp, grasp, "
    "ee_link, eef, gripper, hand, flange...";
namespace {

std::string quoted(const std::string& s) { return "'" + s + "'"; }

using detail::lowercase;

std::set<std::string> tokens(const std::string& name) { return detail::name_tokens(name); }

// Links that are no tool frame of an arm: fingers, feet, sensors, heads, wheels.
bool excluded_name(const std::string& name) {
  static const std::set<std::string> words = {
      "finger", "fingertip", "thumb", "knuckle", "index", "middle", "ring", "little", "pinky", "mrl", "foot", "sole",
      "toe", "ankle", "knee", "leg", "camera", "cam", "head", "laser", "imu", "safety", "range", "accelerometer", "led",
      "sensor", "optical", "depth", "rgb", "kinect", "xtion", "antenna", "wheel", "caster", "screen", "virtual"};
  const std::string low = lowercase(name);
  for (const std::string& t : tokens(name))
    if (words.count(t)) return true;
  return low.find("finger") != std::string::npos || low.find("camera") != std::string::npos ||
         low.find("phalan") != std::string::npos || low.find("thumb") != std::string::npos;
}

// How much a link's name says "tool frame of an arm" (0: not at all).
int tool_score(const std::string& name) {
  if (excluded_name(name)) return 0;
  const std::string low = lowercase(name);
  const std::set<std::string> t = tokens(name);
  auto has = [&](const char* s) { return low.find(s) != std::string::npos; };
  int score = 0;
  if (has("grasp") || has("tcp") || has("tool_frame") || has("tool0")) score = 6;
  else if (has("end_effector") || has("eef") || has("ee_link") || t.count("ee")) score = 5;
  else if (has("tool")) score = 4;
  else if (has("gripper")) score = 3;
  else if (has("hand") || has("palm") || has("flange")) score = 2;
  if (score && (t.count("wrist") || t.count("ft"))) score -= 2;  // force-torque sensors sit at the wrist
  return score;
}

// What find_arms needs to know about the tree, computed once.
struct Tree {
  const Robot& robot;
  std::vector<Pose> home;
  std::vector<int> rigid_root;      // per link: the link reached going up through fixed joints
  std::vector<char> moving_below;   // per link: a moving joint in its subtree

  explicit Tree(const Robot& r) : robot(r), home(r.link_poses(r.home())) {
    const auto& links = r.links();
    const auto& joints = r.joints();
    rigid_root.resize(links.size());
    for (std::size_t l = 0; l < links.size(); ++l) {  // parents come first
      const int pj = links[l].parent_joint;
      rigid_root[l] = (pj >= 0 && joints[pj].type == JointType::Fixed) ? rigid_root[joints[pj].parent_link] : int(l);
    }
    moving_below.assign(links.size(), 0);
    for (std::size_t k = joints.size(); k-- > 0;) {  // children last: walk backwards
      const Joint& j = joints[k];
      if (j.type != JointType::Fixed || moving_below[j.child_link]) moving_below[j.parent_link] = 1;
    }
  }
  // Moving joint that carries a link's rigid body (-1 for the root's body).
  int wrist_joint(int link) const { return robot.links()[rigid_root[link]].parent_joint; }
  bool is_ancestor(int a, int link) const {  // a == link counts
    for (int l = link;; l = robot.joints()[robot.links()[l].parent_joint].parent_link) {
      if (l == a) return true;
      if (robot.links()[l].parent_joint < 0) return false;
    }
  }
  // Links rigid with `link` at or below it (through fixed joints only).
  std::vector<int> rigid_below(int link) const {
    std::vector<int> out{link};
    for (std::size_t i = 0; i < out.size(); ++i)
      for (int j : robot.links()[out[i]].child_joints)
        if (robot.joints()[j].type == JointType::Fixed) out.push_back(robot.joints()[j].child_link);
    return out;
  }
  double distance(int a, int b) const { return (home[a].translation() - home[b].translation()).norm(); }
  // Where a branch leaves the body: going up from the wrist, the first link with two or more
  // subtrees that move (the PR2's and TIAGo's torso_lift_link), else the root.
  int branch_point(int wrist) const {
    int a = robot.joints()[wrist].parent_link;
    while (robot.links()[a].parent_joint >= 0) {
      int moving = 0;
      for (int j : robot.links()[a].child_joints)
        moving += robot.joints()[j].type != JointType::Fixed || moving_below[robot.joints()[j].child_link];
      if (moving >= 2) return a;
      a = robot.joints()[robot.links()[a].parent_joint].parent_link;
    }
    return a;
  }
  int configuration_joints(int base, int tip) const {
    int n = 0;
    for (int l = tip; l != base && robot.links()[l].parent_joint >= 0; l = robot.joints()[robot.links()[l].parent_joint].parent_link)
      n += robot.joints()[robot.links()[l].parent_joint].index >= 0;
    return n;
  }
  // The tool frame of an arm whose last moving link is `tip`: the end effector's parent link or the
  // link named most like a tool frame among the links rigid with `tip` below it (farthest wins ties).
  int tool_frame(int tip) const {
    int best = tip, best_score = tool_score(robot.links()[tip].name);
    for (int l : rigid_below(tip)) {
      int score = tool_score(robot.links()[l].name);
      for (const EndEffector& e : robot.end_effectors())
        if (e.parent_link == robot.links()[l].name) score += 3;
      if (score > best_score || (score == best_score && score > 0 && distance(l, tip) > distance(best, tip) + 1e-9))
        best = l, best_score = score;
    }
    return best;
  }
};

std::string axis_name(const Eigen::Vector3d& a) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(a[k]) > 0.5) return std::string(a[k] > 0 ? "+" : "-") + "xyz"[k];
  return detail::format_vector(a);
}

std::string how_to_give(const std::string& base, const std::string& tip) {
  return "give it: approach_axis=(x, y, z) in Python (or the tuple ('" + base + "', '" + tip +
         "', (x, y, z))), --approach-axis X Y Z on the command line";
}

std::string metres(double d) {
  std::ostringstream s;
  s.precision(3);
  s << d << " m";
  return s.str();
}

// Serial SRDF group -> (base link, last moving link), or false.
bool serial_group(const Robot& robot, const SrdfGroup& g, int& base, int& tip) {
  std::vector<int> joints;
  for (int j : robot.group_joints(g.name))
    if (robot.joints()[j].index >= 0) joints.push_back(j);
  if (joints.empty()) return false;
  // joints are in tree order: the last is the deepest; every other must lie on its path up.
  const int deepest = joints.back();
  std::set<int> path;
  for (int l = robot.joints()[deepest].child_link; robot.links()[l].parent_joint >= 0;
       l = robot.joints()[robot.links()[l].parent_joint].parent_link)
    path.insert(robot.links()[l].parent_joint);
  for (int j : joints)
    if (!path.count(j)) return false;
  tip = robot.joints()[deepest].child_link;
  base = robot.joints()[joints.front()].parent_link;
  if (!g.chains.empty() && g.chains.size() == 1) {  // a chain says its own ends
    base = robot.link_index(g.chains[0].first);
    tip = robot.link_index(g.chains[0].second);
  }
  return true;
}

bool leg_or_head(const std::string& group, const std::string& tip) {
  static const std::set<std::string> words = {"leg", "foot", "sole", "head", "torso", "neck", "ankle", "toe", "wheel"};
  for (const std::string& name : {group, tip})
    for (const std::string& t : tokens(name))
      if (words.count(t)) return true;
  return false;
}

// Arm of an SRDF group (tip moved to its tool frame); throws when the axis cannot be inferred.
Arm group_arm(const Robot& robot, const Tree& tree, const SrdfGroup& g, int base, int tip) {
  const std::string kind = !g.chains.empty() ? "chain" : !g.joints.empty() ? "joint-list" : !g.links.empty() ? "link-list" : "subgroup";
  Arm a = Arm::from_links(robot, robot.links()[base].name, robot.links()[tree.tool_frame(tip)].name);
  a.name = g.name;
  a.source = "SRDF " + kind + " group '" + g.name + "'";
  return a;
}

std::string side_name(const std::string& link, const std::string& joint) {
  for (const std::string& n : {link, joint}) {
    const std::string low = lowercase(n);
    const std::set<std::string> t = tokens(n);
    if (t.count("left") || low.rfind("l_", 0) == 0 || low.find("_l_") != std::string::npos) return "left_arm";
    if (t.count("right") || low.rfind("r_", 0) == 0 || low.find("_r_") != std::string::npos) return "right_arm";
  }
  return "";
}

// Arms from the tree: per wrist joint the best tool-like link; branches with at least 4 joints;
// a candidate hanging below another arm's tool body (a finger) is dropped.
std::vector<Arm> tree_arms(const Robot& robot, const Tree& tree, const std::vector<int>& forced_tips) {
  struct Candidate { int link, wrist, base; };
  std::map<int, Candidate> by_wrist;
  auto consider = [&](int l, bool forced) {
    const int w = tree.wrist_joint(l);
    if (w < 0 || (!forced && tool_score(robot.links()[l].name) == 0)) return;
    auto it = by_wrist.find(w);
    const int root = tree.rigid_root[l];
    if (it == by_wrist.end() || forced ||
        (tool_score(robot.links()[l].name) > tool_score(robot.links()[it->second.link].name)) ||
        (tool_score(robot.links()[l].name) == tool_score(robot.links()[it->second.link].name) &&
         tree.distance(l, root) > tree.distance(it->second.link, root) + 1e-9))
      by_wrist[w] = Candidate{l, w, tree.branch_point(w)};
  };
  for (std::size_t l = 0; l < robot.links().size(); ++l) consider(int(l), false);
  for (int l : forced_tips) consider(l, true);
  std::vector<Candidate> arms;
  for (const auto& [w, c] : by_wrist)
    if (tree.configuration_joints(c.base, c.link) >= 4) arms.push_back(c);
  std::vector<Arm> out;
  for (const Candidate& c : arms) {
    bool finger = false;
    for (const Candidate& o : arms)
      finger = finger || (&o != &c && tree.is_ancestor(tree.rigid_root[o.link], robot.joints()[c.wrist].parent_link));
    if (finger) continue;
    try {
      Arm a = Arm::from_links(robot, robot.links()[c.base].name, robot.links()[c.link].name);
      a.name = side_name(a.tip_link, robot.joints()[c.wrist].name);
      a.source = "kinematic tree (branch from '" + a.base_link + "' to the tool frame '" + a.tip_link + "')";
      out.push_back(a);
    } catch (const std::invalid_argument&) {
      // no approach axis: not listed; Arm::from_links with the links says why
    }
  }
  // Names: "arm" for one; left/right by side; else arm_<tip>.
  std::set<std::string> used;
  for (Arm& a : out) {
    if (out.size() == 1) a.name = "arm";
    if (a.name.empty() || used.count(a.name)) a.name = "arm_" + a.tip_link;
    used.insert(a.name);
  }
  return out;
}

}  // namespace

ApproachAxis infer_approach_axis(const Robot& robot, const std::string& base_link, const std::string& tip_link) {
  const Chain chain = robot.chain(base_link, tip_link);  // names checked here
  const Tree tree(robot);
  const int tip = robot.link_index(tip_link);
  const int root = tree.rigid_root[tip];
  const int wrist = robot.links()[root].parent_joint;
  if (chain.dof() == 0 || wrist < 0)
    throw std::invalid_argument("cannot infer the approach axis of '" + tip_link + "': no joint moves it; " +
                                how_to_give(base_link, tip_link));
  const Pose& T = tree.home[tip];
  const Eigen::Vector3d pw = tree.home[root].translation();
  const Eigen::Vector3d to_tool = T.linear().transpose() * (T.translation() - pw);
  // Fingers: moving joints hanging off the tool's rigid body; their links' mean position.
  Eigen::Vector3d finger_sum = Eigen::Vector3d::Zero();
  int finger_links = 0;
  std::string finger_names;
  for (int l : tree.rigid_below(root))
    for (int j : robot.links()[l].child_joints) {
      if (robot.joints()[j].type == JointType::Fixed) continue;
      std::vector<int> sub{robot.joints()[j].child_link};
      bool arm_goes_on = false;  // a tool frame further down: the arm continues, these are no fingers
      for (std::size_t i = 0; i < sub.size(); ++i) {
        arm_goes_on = arm_goes_on || tool_score(robot.links()[sub[i]].name) >= 4;
        for (int c : robot.links()[sub[i]].child_joints) sub.push_back(robot.joints()[c].child_link);
      }
      if (arm_goes_on) continue;
      finger_names += (finger_names.empty() ? "" : ", ") + quoted(robot.joints()[j].name);
      for (int s : sub) finger_sum += tree.home[s].translation(), ++finger_links;
    }
  const Eigen::Vector3d to_fingers =
      finger_links ? Eigen::Vector3d(T.linear().transpose() * (finger_sum / finger_links - pw)) : Eigen::Vector3d::Zero();
  const std::string wrist_name = quoted(robot.joints()[wrist].name);
  Eigen::Vector3d dir;
  std::string why;
  if (to_tool.norm() >= 0.02) {
    dir = to_tool;
    why = "the tool frame lies " + metres(to_tool.norm()) + " from the wrist joint " + wrist_name + " along it";
  } else if (to_fingers.norm() >= 0.02) {
    dir = to_fingers;
    why = "the fingers (" + finger_names + ") reach " + metres(to_fingers.norm()) + " from the wrist joint " +
          wrist_name + " along it";
  } else {
    // A bare flange: the last joint's axis, pointing away from the joint before it.
    const Joint& w = robot.joints()[wrist];
    const Eigen::Vector3d axis = T.linear().transpose() * tree.home[w.child_link].linear() * w.axis;
    const std::vector<std::string>& names = chain.joint_names();
    const Eigen::Vector3d prev =
        names.size() >= 2 ? tree.home[robot.joints()[robot.joint_index(names[names.size() - 2])].child_link].translation()
                          : tree.home[robot.link_index(base_link)].translation();
    const double along = axis.dot(T.linear().transpose() * (pw - prev));
    if (w.type == JointType::Prismatic || std::abs(along) < 1e-3)
      throw std::invalid_argument("cannot infer the approach axis of '" + tip_link + "': no gripper (no tool frame away from the wrist joint " +
                                  wrist_name + ", no fingers) and the last joint's axis does not point away from the arm; " +
                                  how_to_give(base_link, tip_link));
    dir = along > 0 ? axis : Eigen::Vector3d(-axis);
    why = "no gripper: the flange axis (the last joint " + wrist_name + ") points away from the arm along it";
  }
  Eigen::Vector3d snapped = Eigen::Vector3d::Zero();
  int k;
  dir.cwiseAbs().maxCoeff(&k);
  snapped[k] = dir[k] > 0 ? 1.0 : -1.0;
  const double angle = std::acos(std::min(1.0, std::abs(dir[k]) / dir.norm())) * 180.0 / kPi;
  if (angle > 30.0)
    throw std::invalid_argument("cannot infer the approach axis of '" + tip_link + "': " + why + ", but that direction (" +
                                detail::format_point(dir.normalized()) + ") is " + std::to_string(int(angle)) +
                                " degrees from every axis of the frame; " + how_to_give(base_link, tip_link));
  if (finger_links && to_tool.norm() >= 0.02 && to_fingers.norm() >= 0.02)
    why += snapped.dot(to_fingers.normalized()) > 0.5 ? " (the fingers agree)" : " (the fingers point elsewhere)";
  return ApproachAxis{snapped, axis_name(snapped) + " of '" + tip_link + "': " + why};
}

Arm Arm::from_links(const Robot& robot, const std::string& base_link, const std::string& tip_link,
                    const Eigen::Vector3d& approach_axis) {
  for (const std::string* link : {&base_link, &tip_link}) robot.link_index(*link);  // names the nearest links
  Arm a{base_link, tip_link, approach_axis, "given", "", "links"};
  return a.with_approach_axis(approach_axis);
}

Arm Arm::from_links(const Robot& robot, const std::string& base_link, const std::string& tip_link) {
  for (const std::string* link : {&base_link, &tip_link}) robot.link_index(*link);
  ApproachAxis ax = infer_approach_axis(robot, base_link, tip_link);
  return Arm{base_link, tip_link, ax.axis, ax.reason, "", "links"};
}

Arm Arm::with_approach_axis(const Eigen::Vector3d& axis) const {
  if (!axis.allFinite() || axis.norm() < 1e-9)
    throw std::invalid_argument("approach_axis must be a finite non-zero vector, got " + detail::format_point(axis));
  Arm a = *this;
  a.approach_axis = axis.normalized();
  a.reason = "given";
  return a;
}

std::vector<Arm> find_arms(const Robot& robot) {
  const Tree tree(robot);
  std::vector<Arm> arms;
  std::vector<int> arm_tips;  // last moving links of SRDF arms, to drop the groups that extend them (hands)
  for (const SrdfGroup& g : robot.srdf_groups()) {
    int base, tip;
    if (!serial_group(robot, g, base, tip) || tree.configuration_joints(base, tip) < 3 ||
        leg_or_head(g.name, robot.links()[tip].name))
      continue;
    try {
      arms.push_back(group_arm(robot, tree, g, base, tip));
    } catch (const std::invalid_argument&) {
      // no approach axis: Arm::named says why
    }
  }
  // A group that goes on past another arm's tool body (Panda's "arm_and_hand") is that arm plus fingers.
  std::vector<Arm> kept;
  for (const Arm& a : arms) {
    bool longer = false;
    for (const Arm& o : arms)
      if (&o != &a && o.base_link == a.base_link && o.tip_link != a.tip_link &&
          tree.is_ancestor(tree.rigid_root[robot.link_index(o.tip_link)], robot.link_index(a.tip_link)))
        longer = true;
    if (!longer) kept.push_back(a);
  }
  if (!kept.empty()) return kept;
  // No SRDF arm: end effectors' parent links are tips, then the tree.
  std::vector<int> forced;
  for (const EndEffector& e : robot.end_effectors())
    if (!leg_or_head(e.name, e.parent_link)) forced.push_back(robot.link_index(e.parent_link));
  return tree_arms(robot, tree, forced);
}

std::vector<std::string> arm_names(const Robot& robot) {
  std::vector<std::string> names;
  for (const Arm& a : find_arms(robot)) names.push_back(a.name);
  std::sort(names.begin(), names.end());
  return names;
}

Arm Arm::named(const Robot& robot, const std::string& name) {
  const std::vector<Arm> arms = find_arms(robot);
  for (const Arm& a : arms)
    if (a.name == name) return a;
  const Tree tree(robot);
  for (const SrdfGroup& g : robot.srdf_groups()) {
    int base, tip;
    if (g.name == name && serial_group(robot, g, base, tip)) return group_arm(robot, tree, g, base, tip);
  }
  std::vector<std::string> names;
  for (const Arm& a : arms) names.push_back(a.name);
  std::string known;
  for (const Arm& a : arms) known += (known.empty() ? "" : ", ") + quoted(a.name) + " (" + a.base_link + " -> " + a.tip_link + ")";
  throw std::invalid_argument("robot " + quoted(robot.name()) + " has no arm " + quoted(name) + detail::did_you_mean(name, names) +
                              " Its arms: " +
                              (known.empty() ? std::string("none found (") + kNoArmFound +
                                                   "); give the arm by its links: (base_link, tip_link)"
                                             : known));
}

}  // namespace octoreach
