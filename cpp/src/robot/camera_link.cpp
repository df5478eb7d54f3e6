// Finding a robot's head camera from its link names and SRDF (camera_link.hpp states the rule). No robot table:
// an unambiguous camera is found, anything else is an error that asks for the link.
#include "octoreach/camera_link.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>
#include <vector>

#include "robot/link_names.hpp"

namespace octoreach {

namespace {

bool camera_name(const std::string& name) {
  static const std::set<std::string> words = {"camera", "cam", "kinect", "xtion", "rgb", "rgbd", "depth", "optical",
                                              "stereo", "realsense", "prosilica", "openni", "astra", "zed"};
  for (const std::string& t : detail::name_tokens(name))
    if (words.count(t)) return true;
  return detail::lowercase(name).find("camera") != std::string::npos;
}

bool head_name(const std::string& name) {
  const std::set<std::string> t = detail::name_tokens(name);
  return t.count("head") > 0 || t.count("neck") > 0;
}

// The robot's links as bodies: each link's rigid root (up through fixed joints) and whether it is on the head.
struct Bodies {
  std::vector<int> root;     // per link: the link reached going up through fixed joints
  std::vector<char> head;    // per link: named head/neck, moved by an SRDF head group's joint, or below such a link
  std::vector<char> named;   // per link: named head/neck itself, or moved by an SRDF head group's joint

  explicit Bodies(const Robot& robot) {
    const auto& links = robot.links();
    const auto& joints = robot.joints();
    std::set<std::string> head_joints;
    for (const SrdfGroup& g : robot.srdf_groups())
      if (head_name(g.name))
        for (int j : robot.group_joints(g.name)) head_joints.insert(joints[j].name);
    root.resize(links.size());
    head.assign(links.size(), 0);
    named.assign(links.size(), 0);
    for (std::size_t i = 0; i < links.size(); ++i) {  // parents come first
      const int pj = links[i].parent_joint;
      named[i] = head_name(links[i].name) || (pj >= 0 && head_joints.count(joints[pj].name));
      if (pj < 0) {
        root[i] = static_cast<int>(i);
        head[i] = named[i];
        continue;
      }
      const int parent = joints[pj].parent_link;
      root[i] = joints[pj].type == JointType::Fixed ? root[parent] : static_cast<int>(i);
      head[i] = named[i] || head[parent];
    }
  }
};

std::string listed(const Robot& robot, const std::vector<int>& links) {
  std::string out;
  for (std::size_t k = 0; k < links.size() && k < 8; ++k) out += (k ? ", " : "") + robot.links()[links[k]].name;
  if (links.size() > 8) out += ", ...";
  return out.empty() ? "none" : out;
}

// Distinct rigid bodies of `links`, in link order.
std::vector<int> bodies_of(const Bodies& b, const std::vector<int>& links) {
  std::vector<int> out;
  for (int l : links)
    if (std::find(out.begin(), out.end(), b.root[l]) == out.end()) out.push_back(b.root[l]);
  return out;
}

}  // namespace

CameraLink find_camera_link(const Robot& robot) {
  const Bodies b(robot);
  const int n = static_cast<int>(robot.links().size());
  std::vector<int> cameras, heads;
  for (int i = 0; i < n; ++i) {
    if (camera_name(robot.links()[i].name)) cameras.push_back(i);
    if (b.named[i]) heads.push_back(i);
  }
  std::vector<int> bodies = bodies_of(b, cameras);
  std::string how = "the only body with camera links";
  if (bodies.size() > 1) {
    bodies.erase(std::remove_if(bodies.begin(), bodies.end(), [&](int body) { return !b.head[body]; }), bodies.end());
    how = "the camera links on the head";
  }
  if (bodies.size() == 1)
    for (int l : cameras)
      if (b.root[l] == bodies[0]) return {robot.links()[l].name, how};
  if (cameras.empty()) {  // no camera link: the end of the head, where its camera would be
    std::vector<int> ends;
    for (int body : bodies_of(b, heads)) {
      bool below = false;
      for (int h : heads) {
        int cur = b.root[h];
        while (!below && cur != body && robot.links()[cur].parent_joint >= 0)
          below = (cur = b.root[robot.joints()[robot.links()[cur].parent_joint].parent_link]) == body;
      }
      if (!below) ends.push_back(body);
    }
    if (ends.size() == 1) return {robot.links()[ends[0]].name, "the end of the head (no link is named like a camera)"};
  }
  throw std::invalid_argument(
      "robot '" + robot.name() + "' has no link that is unambiguously its camera (links named like a camera: " +
      listed(robot, cameras) + "; head links: " + listed(robot, heads) +
      "): name the camera's link, camera_link='LINK' in Python or --camera-link LINK on the command line");
}

CameraLink camera_link(const Robot& robot, const std::string& given) {
  if (given.empty()) return find_camera_link(robot);
  robot.link_index(given);  // throws naming the nearest links
  return {given, "given"};
}

}  // namespace octoreach
