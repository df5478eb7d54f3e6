// The SRDF part of Robot::from_urdf: groups (chains, joint lists, link lists, subgroups), end
// effectors, group states and disabled collision pairs. Names the URDF lacks are an error that
// says which (and the nearest names), or with SrdfMismatch::kLeaveOut leave the groups and end effectors
// that use them out (recorded in srdf_left_out()), except in <disable_collisions>, which MoveIt also lets name
// links of other variants of the robot. Names under the robot's name as a namespace ("baxter/left_s0") are read
// without it when the URDF has the plain name.
#include <algorithm>
#include <map>
#include <set>

#include <tinyxml.h>

#include "octoreach/robot.hpp"
#include "common/nearest_names.hpp"
#include "robot/robot_builder.hpp"

namespace octoreach::detail {
namespace {

using NamedStates = std::map<std::string, std::map<std::string, double>>;

std::string attribute(TiXmlElement* e, const char* name, const std::string& where) {
  const char* v = e->Attribute(name);
  if (!v) throw std::invalid_argument("malformed SRDF: " + where + " needs the attribute '" + name + "'");
  return v;
}

// Names of <virtual_joint>s: joints of the SRDF (world -> root link), not of the URDF.
std::set<std::string> virtual_joints(TiXmlElement* root) {
  std::set<std::string> out;
  for (TiXmlElement* v = root->FirstChildElement("virtual_joint"); v; v = v->NextSiblingElement("virtual_joint"))
    if (v->Attribute("name")) out.insert(v->Attribute("name"));
  return out;
}

// Every <group> as written (virtual joints left out of joint lists).
std::vector<SrdfGroup> read_all_groups(TiXmlElement* root) {
  const std::set<std::string> virtuals = virtual_joints(root);
  std::vector<SrdfGroup> groups;
  for (TiXmlElement* g = root->FirstChildElement("group"); g; g = g->NextSiblingElement("group")) {
    SrdfGroup group;
    group.name = attribute(g, "name", "<group>");
    const std::string where = "group '" + group.name + "'";
    for (TiXmlElement* c = g->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string kind = c->Value();
      if (kind == "chain")
        group.chains.emplace_back(attribute(c, "base_link", "<chain> of " + where), attribute(c, "tip_link", "<chain> of " + where));
      else if (kind == "joint") {
        std::string name = attribute(c, "name", "<joint> of " + where);
        if (!virtuals.count(name)) group.joints.push_back(name);
      }
      else if (kind == "link") group.links.push_back(attribute(c, "name", "<link> of " + where));
      else if (kind == "group") group.subgroups.push_back(attribute(c, "name", "<group> of " + where));
    }
    groups.push_back(std::move(group));
  }
  return groups;
}

std::vector<EndEffector> read_end_effectors(TiXmlElement* root) {
  std::vector<EndEffector> out;
  for (TiXmlElement* e = root->FirstChildElement("end_effector"); e; e = e->NextSiblingElement("end_effector")) {
    EndEffector ee;
    ee.name = attribute(e, "name", "<end_effector>");
    ee.parent_link = attribute(e, "parent_link", "end_effector '" + ee.name + "'");
    ee.group = e->Attribute("group") ? e->Attribute("group") : "";
    ee.parent_group = e->Attribute("parent_group") ? e->Attribute("parent_group") : "";
    out.push_back(std::move(ee));
  }
  return out;
}

// Names an SRDF's groups and end effectors use that the URDF (or the SRDF's groups) lacks, each as
// (owner, "link 'x' (group 'g'; did you mean ...)"), owner being "group 'g'" or "end_effector 'e'".
struct Disagreements {
  const Robot& robot;
  std::vector<std::pair<std::string, std::string>> problems;
  std::vector<std::string> link_names, joint_names, group_names;
  std::set<std::string> virtuals;
  void link(const std::string& name, const std::string& where) {
    if (!robot.has_link(name)) problems.emplace_back(where, "link '" + name + "' (" + where + detail::did_you_mean(name, link_names) + ")");
  }
  void joint(const std::string& name, const std::string& where) {
    if (!virtuals.count(name) && std::find(joint_names.begin(), joint_names.end(), name) == joint_names.end())
      problems.emplace_back(where, "joint '" + name + "' (" + where + detail::did_you_mean(name, joint_names) + ")");
  }
  void group(const std::string& name, const std::string& where) {
    if (std::find(group_names.begin(), group_names.end(), name) == group_names.end())
      problems.emplace_back(where, "group '" + name + "' (" + where + detail::did_you_mean(name, group_names) + ")");
  }
};

Disagreements disagreements(const Robot& robot, const std::vector<SrdfGroup>& groups, const std::vector<EndEffector>& ees,
                            const std::set<std::string>& virtuals) {
  Disagreements d{robot, {}, {}, {}, {}, virtuals};
  for (const Link& l : robot.links()) d.link_names.push_back(l.name);
  for (const Joint& j : robot.joints()) d.joint_names.push_back(j.name);
  for (const SrdfGroup& g : groups) d.group_names.push_back(g.name);
  for (const SrdfGroup& g : groups) {
    const std::string where = "group '" + g.name + "'";
    for (const auto& [base, tip] : g.chains) d.link(base, where), d.link(tip, where);
    for (const std::string& j : g.joints) d.joint(j, where);
    for (const std::string& l : g.links) d.link(l, where);
    for (const std::string& s : g.subgroups) d.group(s, where);
  }
  for (const EndEffector& e : ees) {
    const std::string where = "end_effector '" + e.name + "'";
    d.link(e.parent_link, where);
    if (!e.group.empty()) d.group(e.group, where);
    if (!e.parent_group.empty()) d.group(e.parent_group, where);
  }
  // Group states may name free-flyer joints ("root_joint") that are no URDF joint: skipped, as MoveIt does.
  return d;
}

// kError: throws naming what the URDF lacks. kLeaveOut: removes every group and end effector that names
// something the URDF lacks, then those that name a group so removed, and so on; returns what was left out
// (one line per entry).
std::vector<std::string> fit_to_urdf(const Robot& robot, std::vector<SrdfGroup>& groups, std::vector<EndEffector>& ees,
                                     TiXmlElement* root, SrdfMismatch mismatch) {
  const std::set<std::string> virtuals = virtual_joints(root);
  std::vector<std::string> left_out;
  for (;;) {
    const Disagreements d = disagreements(robot, groups, ees, virtuals);
    if (d.problems.empty()) return left_out;
    if (mismatch == SrdfMismatch::kError) {
      std::string msg = "the SRDF does not match the URDF of robot '" + robot.name() + "': it names " +
                        std::to_string(d.problems.size()) + " thing(s) the URDF does not have: ";
      for (std::size_t i = 0; i < d.problems.size() && i < 6; ++i) msg += (i ? "; " : "") + d.problems[i].second;
      if (d.problems.size() > 6) msg += "; ...";
      throw std::invalid_argument(msg + " (is it the SRDF of another variant of the robot?)");
    }
    std::map<std::string, std::string> why;  // owner -> its problems
    for (const auto& [owner, text] : d.problems) why[owner] += (why[owner].empty() ? "" : "; ") + text;
    for (const auto& [owner, text] : why) left_out.push_back(owner + " left out: " + text);
    groups.erase(std::remove_if(groups.begin(), groups.end(),
                                [&why](const SrdfGroup& g) { return why.count("group '" + g.name + "'") > 0; }),
                 groups.end());
    ees.erase(std::remove_if(ees.begin(), ees.end(),
                             [&why](const EndEffector& e) { return why.count("end_effector '" + e.name + "'") > 0; }),
              ees.end());
  }
}

// The groups declared by a chain, as ChainGroup (their first chain).
std::vector<ChainGroup> chain_groups(const std::vector<SrdfGroup>& groups) {
  std::vector<ChainGroup> out;
  for (const SrdfGroup& g : groups)
    if (!g.chains.empty()) out.push_back({g.name, g.chains[0].first, g.chains[0].second});
  return out;
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

// Some SRDFs name joints and links with the robot's name as a namespace (example-robot-data's Baxter:
// "baxter/left_s0" in its groups and states, plain names in its disabled pairs). A name the URDF lacks whose
// "<robot name>/" prefix (the URDF's or the SRDF's robot name), once removed, names a URDF link or joint is
// read without it; every other name is left as written (and checked as before).
void strip_robot_prefix(TiXmlElement* e, const Robot& robot, const std::vector<std::string>& prefixes) {
  static const char* const kAttributes[] = {"name", "link1", "link2", "base_link", "tip_link", "parent_link"};
  auto known = [&robot](const std::string& n) {
    if (robot.has_link(n)) return true;
    for (const Joint& j : robot.joints())
      if (j.name == n) return true;
    return false;
  };
  for (const char* a : kAttributes) {
    const char* v = e->Attribute(a);
    if (!v) continue;
    const std::string s(v);
    for (const std::string& p : prefixes)
      if (s.size() > p.size() && s.compare(0, p.size(), p) == 0 && !known(s) && known(s.substr(p.size()))) {
        e->SetAttribute(a, s.substr(p.size()));
        break;
      }
  }
  for (TiXmlElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) strip_robot_prefix(c, robot, prefixes);
}

}  // namespace

void RobotBuilder::read_srdf(const std::string& srdf, SrdfMismatch mismatch, PairSet& allowed) {
  std::string sx = looks_like_xml(srdf) ? srdf : read_text_file(srdf, "SRDF");
  TiXmlDocument doc;
  doc.Parse(sx.c_str());
  if (doc.Error())
    throw std::invalid_argument(std::string("malformed SRDF: XML error '") + doc.ErrorDesc() + "' at line " +
                                std::to_string(doc.ErrorRow()));
  TiXmlElement* root = doc.RootElement();
  if (!root || std::string(root->Value()) != "robot")
    throw std::invalid_argument("malformed SRDF: the root element must be <robot>");
  std::vector<std::string> prefixes{r.name() + "/"};
  if (const char* n = root->Attribute("name"); n && std::string(n) + "/" != prefixes[0]) prefixes.push_back(std::string(n) + "/");
  for (TiXmlElement* c = root->FirstChildElement(); c; c = c->NextSiblingElement()) strip_robot_prefix(c, r, prefixes);
  r.srdf_groups_ = read_all_groups(root);
  r.end_effectors_ = read_end_effectors(root);
  r.srdf_left_out_ = fit_to_urdf(r, r.srdf_groups_, r.end_effectors_, root, mismatch);
  r.groups_ = chain_groups(r.srdf_groups_);
  r.named_states_ = read_group_states(root, r);
  read_disabled_pairs(root, r, allowed);
}

}  // namespace octoreach::detail
