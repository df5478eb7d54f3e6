// The SRDF part of Robot::from_urdf: chain groups, group states and disabled collision pairs.
#include <map>

#include <tinyxml.h>

#include "octoreach/robot.hpp"
#include "robot_builder.hpp"

namespace octoreach::detail {
namespace {

using NamedStates = std::map<std::string, std::map<std::string, double>>;

// <group><chain base_link tip_link/></group>; groups of other kinds (joints, links) are skipped.
std::vector<ChainGroup> read_groups(TiXmlElement* root) {
  std::vector<ChainGroup> groups;
  for (TiXmlElement* g = root->FirstChildElement("group"); g; g = g->NextSiblingElement("group")) {
    TiXmlElement* c = g->FirstChildElement("chain");
    if (!c || !g->Attribute("name") || !c->Attribute("base_link") || !c->Attribute("tip_link")) continue;
    groups.push_back({g->Attribute("name"), c->Attribute("base_link"), c->Attribute("tip_link")});
  }
  return groups;
}

// <group_state name><joint name value/></group_state>; joints that are not in the configuration
// vector (unknown, fixed, mimic) are left out.
NamedStates read_group_states(TiXmlElement* root, const Robot& robot) {
  NamedStates states;
  for (TiXmlElement* g = root->FirstChildElement("group_state"); g; g = g->NextSiblingElement("group_state")) {
    const char* name = g->Attribute("name");
    if (!name) throw std::invalid_argument("malformed SRDF: <group_state> needs a name");
    auto& values = states[name];
    for (TiXmlElement* j = g->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
      const char* jn = j->Attribute("name");
      double v = 0;
      if (!jn || j->QueryDoubleAttribute("value", &v) != TIXML_SUCCESS)
        throw std::invalid_argument(std::string("malformed SRDF: a joint of group_state '") + name +
                                    "' needs name and value");
      for (const Joint& joint : robot.joints())
        if (joint.name == jn && joint.index >= 0) values[jn] = v;
    }
  }
  return states;
}

void read_disabled_pairs(TiXmlElement* root, const Robot& robot, PairSet& allowed) {
  for (TiXmlElement* d = root->FirstChildElement("disable_collisions"); d;
       d = d->NextSiblingElement("disable_collisions")) {
    const char* a = d->Attribute("link1");
    const char* b = d->Attribute("link2");
    if (!a || !b) throw std::invalid_argument("malformed SRDF: <disable_collisions> needs link1 and link2");
    // Links the URDF does not have are ignored, as MoveIt does, so one SRDF serves URDF variants.
    if (robot.has_link(a) && robot.has_link(b)) add_pair(allowed, robot.link_index(a), robot.link_index(b));
  }
}

}  // namespace

void RobotBuilder::read_srdf(const std::string& srdf, PairSet& allowed) {
  std::string sx = looks_like_xml(srdf) ? srdf : read_text_file(srdf, "SRDF");
  TiXmlDocument doc;
  doc.Parse(sx.c_str());
  if (doc.Error())
    throw std::invalid_argument(std::string("malformed SRDF: XML error '") + doc.ErrorDesc() + "' at line " +
                                std::to_string(doc.ErrorRow()));
  TiXmlElement* root = doc.RootElement();
  if (!root || std::string(root->Value()) != "robot")
    throw std::invalid_argument("malformed SRDF: the root element must be <robot>");
  r.groups_ = read_groups(root);
  r.named_states_ = read_group_states(root, r);
  read_disabled_pairs(root, r, allowed);
}

}  // namespace octoreach::detail
