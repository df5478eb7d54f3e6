#include "octoreach/robot.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include "octoreach/chain.hpp"
#include "common/random_mix.hpp"

namespace octoreach {
namespace {

bool looks_like_xml(const std::string& s) {
  auto pos = s.find_first_not_of(" \t\r\n");
  return pos != std::string::npos && s[pos] == '<';
}

std::string dirname(const std::string& path) {
  auto pos = path.find_last_of('/');
  return pos == std::string::npos ? std::string(".") : path.substr(0, pos);
}

bool file_exists(const std::string& path) {
  std::ifstream f(path);
  return f.good();
}

std::string read_text_file(const std::string& path, const char* what) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw FileError(std::string("cannot read ") + what + " file '" + path + "'");
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

Pose to_pose(const urdf::Pose& p) {
  Pose T = Pose::Identity();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  Eigen::Quaterniond q(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z);
  if (q.norm() < 1e-12) q = Eigen::Quaterniond::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  return T;
}

std::string resolve_mesh(const std::string& uri, const std::vector<std::string>& package_dirs,
                         const std::string& urdf_dir, const std::string& link) {
  std::vector<std::string> candidates;
  const std::string pkg = "package://", file = "file://";
  if (uri.rfind(pkg, 0) == 0) {
    std::string rest = uri.substr(pkg.size());
    auto slash = rest.find('/');
    std::string package = rest.substr(0, slash);
    std::string inner = slash == std::string::npos ? "" : rest.substr(slash + 1);
    for (const auto& d : package_dirs) {
      candidates.push_back(d + "/" + rest);
      std::string base = d.substr(d.find_last_of('/') + 1);
      if (base == package) candidates.push_back(d + "/" + inner);
    }
  } else if (uri.rfind(file, 0) == 0) {
    candidates.push_back(uri.substr(file.size()));
  } else if (!uri.empty() && uri[0] == '/') {
    candidates.push_back(uri);
  } else {
    candidates.push_back(urdf_dir + "/" + uri);
    for (const auto& d : package_dirs) candidates.push_back(d + "/" + uri);
  }
  for (const auto& c : candidates)
    if (file_exists(c)) return c;
  std::string msg = "mesh '" + uri + "' of link '" + link + "' not found";
  if (uri.rfind(pkg, 0) == 0 && package_dirs.empty()) msg += " (no package_dirs given to resolve package:// URIs)";
  else if (!candidates.empty()) {
    msg += "; tried:";
    for (const auto& c : candidates) msg += " " + c;
  }
  throw FileError(msg);
}

}  // namespace

std::shared_ptr<Robot> Robot::from_urdf(const std::string& urdf_in, const std::vector<std::string>& package_dirs,
                                        const std::string& srdf_in) {
  std::string xml, urdf_dir = ".";
  if (looks_like_xml(urdf_in)) {
    xml = urdf_in;
  } else {
    if (urdf_in.empty()) throw std::invalid_argument("empty URDF: expected a file path or an XML string");
    xml = read_text_file(urdf_in, "URDF");
    urdf_dir = dirname(urdf_in);
  }
  {
    TiXmlDocument doc;
    doc.Parse(xml.c_str());
    if (doc.Error())
      throw std::invalid_argument(std::string("malformed URDF: XML error '") + doc.ErrorDesc() + "' at line " +
                                  std::to_string(doc.ErrorRow()));
    if (!doc.RootElement() || std::string(doc.RootElement()->Value()) != "robot")
      throw std::invalid_argument("malformed URDF: the root element must be <robot>");
  }
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("malformed URDF: ") + e.what());
  }
  if (!model) throw std::invalid_argument("malformed URDF: urdfdom rejected it (see the message above)");
  if (!model->getRoot()) throw std::invalid_argument("malformed URDF: no root link");

  std::shared_ptr<Robot> robot(new Robot());
  Robot& r = *robot;
  r.name_ = model->getName();
  r.urdf_hash_ = fnv1a(xml);

  // Links in breadth-first order from the root, so parents come first.
  std::deque<urdf::LinkConstSharedPtr> queue{model->getRoot()};
  std::map<std::string, std::pair<std::shared_ptr<fcl::CollisionGeometryd>, std::string>> mesh_cache;
  while (!queue.empty()) {
    auto ul = queue.front();
    queue.pop_front();
    Link link;
    link.name = ul->name;
    std::vector<urdf::CollisionSharedPtr> collisions = ul->collision_array;
    if (collisions.empty() && ul->collision) collisions.push_back(ul->collision);
    for (const auto& c : collisions) {
      if (!c || !c->geometry) continue;
      Shape s;
      s.origin = to_pose(c->origin);
      switch (c->geometry->type) {
        case urdf::Geometry::BOX: {
          auto b = std::static_pointer_cast<urdf::Box>(c->geometry);
          s.type = Shape::Type::Box;
          s.size = Eigen::Vector3d(b->dim.x, b->dim.y, b->dim.z);
          s.geometry = std::make_shared<fcl::Boxd>(s.size);
          break;
        }
        case urdf::Geometry::CYLINDER: {
          auto cy = std::static_pointer_cast<urdf::Cylinder>(c->geometry);
          s.type = Shape::Type::Cylinder;
          s.radius = cy->radius;
          s.length = cy->length;
          s.geometry = std::make_shared<fcl::Cylinderd>(cy->radius, cy->length);
          break;
        }
        case urdf::Geometry::SPHERE: {
          auto sp = std::static_pointer_cast<urdf::Sphere>(c->geometry);
          s.type = Shape::Type::Sphere;
          s.radius = sp->radius;
          s.geometry = std::make_shared<fcl::Sphered>(sp->radius);
          break;
        }
        case urdf::Geometry::MESH: {
          auto m = std::static_pointer_cast<urdf::Mesh>(c->geometry);
          s.type = Shape::Type::Mesh;
          s.scale = Eigen::Vector3d(m->scale.x, m->scale.y, m->scale.z);
          s.mesh_path = resolve_mesh(m->filename, package_dirs, urdf_dir, ul->name);
          std::ostringstream key;
          key << s.mesh_path << "|" << s.scale.transpose();
          auto it = mesh_cache.find(key.str());
          if (it == mesh_cache.end())
            it = mesh_cache.emplace(key.str(), std::make_pair(load_mesh(s.mesh_path, s.scale), s.mesh_path)).first;
          s.geometry = it->second.first;
          break;
        }
      }
      if (s.geometry) {
        s.geometry->computeLocalAABB();
        link.shapes.push_back(std::move(s));
      }
    }
    r.link_by_name_[link.name] = static_cast<int>(r.links_.size());
    r.links_.push_back(std::move(link));
    for (const auto& child : ul->child_links) queue.push_back(child);
  }
  r.root_link_ = 0;

  // Joints, in the same breadth-first order (by child link).
  for (std::size_t li = 1; li < r.links_.size(); ++li) {
    auto ul = model->getLink(r.links_[li].name);
    auto uj = ul->parent_joint;
    if (!uj) throw std::invalid_argument("malformed URDF: link '" + ul->name + "' has no parent joint");
    Joint j;
    j.name = uj->name;
    j.parent_link = r.link_index(uj->parent_link_name);
    j.child_link = static_cast<int>(li);
    j.origin = to_pose(uj->parent_to_joint_origin_transform);
    Eigen::Vector3d axis(uj->axis.x, uj->axis.y, uj->axis.z);
    switch (uj->type) {
      case urdf::Joint::REVOLUTE: j.type = JointType::Revolute; break;
      case urdf::Joint::CONTINUOUS: j.type = JointType::Continuous; break;
      case urdf::Joint::PRISMATIC: j.type = JointType::Prismatic; break;
      default: j.type = JointType::Fixed; break;  // fixed, floating and planar are held fixed
    }
    if (j.type != JointType::Fixed) {
      if (axis.norm() < 1e-12)
        throw std::invalid_argument("malformed URDF: joint '" + j.name + "' has a zero axis");
      j.axis = axis.normalized();
    }
    if (j.type == JointType::Continuous) {
      j.lower = -std::numeric_limits<double>::infinity();
      j.upper = std::numeric_limits<double>::infinity();
    } else if (j.type != JointType::Fixed) {
      if (!uj->limits)
        throw std::invalid_argument("malformed URDF: joint '" + j.name + "' needs <limit lower upper>");
      j.lower = uj->limits->lower;
      j.upper = uj->limits->upper;
      if (!(j.lower <= j.upper))
        throw std::invalid_argument("malformed URDF: joint '" + j.name + "' has lower limit " +
                                    std::to_string(j.lower) + " above upper limit " + std::to_string(j.upper));
    }
    int ji = static_cast<int>(r.joints_.size());
    r.joint_by_name_[j.name] = ji;
    r.links_[li].parent_joint = ji;
    r.links_[j.parent_link].child_joints.push_back(ji);
    r.joints_.push_back(j);
  }
  // Mimic joints: resolved after every joint is known.
  for (std::size_t ji = 0; ji < r.joints_.size(); ++ji) {
    auto uj = model->getJoint(r.joints_[ji].name);
    if (uj->mimic && r.joints_[ji].type != JointType::Fixed) {
      auto it = r.joint_by_name_.find(uj->mimic->joint_name);
      if (it == r.joint_by_name_.end())
        throw std::invalid_argument("malformed URDF: joint '" + uj->name + "' mimics unknown joint '" +
                                    uj->mimic->joint_name + "'");
      r.joints_[ji].mimic = it->second;
      r.joints_[ji].mimic_multiplier = uj->mimic->multiplier;
      r.joints_[ji].mimic_offset = uj->mimic->offset;
    }
  }
  for (std::size_t ji = 0; ji < r.joints_.size(); ++ji) {
    auto& j = r.joints_[ji];
    if (j.type != JointType::Fixed && j.mimic < 0) {
      j.index = static_cast<int>(r.active_joints_.size());
      r.active_joints_.push_back(static_cast<int>(ji));
    }
  }
  for (auto& j : r.joints_)
    if (j.mimic >= 0 && r.joints_[j.mimic].index < 0)
      throw std::invalid_argument("joint '" + j.name + "' mimics '" + r.joints_[j.mimic].name +
                                  "', which is fixed or itself a mimic joint (unsupported)");

  // SRDF: chain groups and disabled collision pairs.
  std::set<std::pair<int, int>> allowed;
  auto add_pair = [&](int a, int b) {
    if (a == b) return;
    allowed.insert({std::min(a, b), std::max(a, b)});
  };
  if (!srdf_in.empty()) {
    std::string sx = looks_like_xml(srdf_in) ? srdf_in : read_text_file(srdf_in, "SRDF");
    TiXmlDocument doc;
    doc.Parse(sx.c_str());
    if (doc.Error())
      throw std::invalid_argument(std::string("malformed SRDF: XML error '") + doc.ErrorDesc() + "' at line " +
                                  std::to_string(doc.ErrorRow()));
    TiXmlElement* root = doc.RootElement();
    if (!root || std::string(root->Value()) != "robot")
      throw std::invalid_argument("malformed SRDF: the root element must be <robot>");
    for (TiXmlElement* g = root->FirstChildElement("group"); g; g = g->NextSiblingElement("group")) {
      TiXmlElement* c = g->FirstChildElement("chain");
      if (!c || !g->Attribute("name") || !c->Attribute("base_link") || !c->Attribute("tip_link")) continue;
      r.groups_.push_back({g->Attribute("name"), c->Attribute("base_link"), c->Attribute("tip_link")});
    }
    for (TiXmlElement* g = root->FirstChildElement("group_state"); g; g = g->NextSiblingElement("group_state")) {
      const char* name = g->Attribute("name");
      if (!name) throw std::invalid_argument("malformed SRDF: <group_state> needs a name");
      auto& values = r.named_states_[name];
      for (TiXmlElement* j = g->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
        const char* jn = j->Attribute("name");
        double v = 0;
        if (!jn || j->QueryDoubleAttribute("value", &v) != TIXML_SUCCESS)
          throw std::invalid_argument(std::string("malformed SRDF: a joint of group_state '") + name +
                                      "' needs name and value");
        if (r.joint_by_name_.count(jn) && r.joints_[r.joint_by_name_[jn]].index >= 0) values[jn] = v;
      }
    }
    for (TiXmlElement* d = root->FirstChildElement("disable_collisions"); d;
         d = d->NextSiblingElement("disable_collisions")) {
      const char* a = d->Attribute("link1");
      const char* b = d->Attribute("link2");
      if (!a || !b) throw std::invalid_argument("malformed SRDF: <disable_collisions> needs link1 and link2");
      // Links the URDF does not have are ignored, as MoveIt does, so one SRDF serves URDF variants.
      if (r.has_link(a) && r.has_link(b)) add_pair(r.link_index(a), r.link_index(b));
    }
  }
  for (std::size_t i = 0; i < r.links_.size(); ++i)
    if (!r.links_[i].shapes.empty()) r.collision_links_.push_back(static_cast<int>(i));
  // Adjacent links: a link and its nearest ancestor that has geometry (fixed joints and
  // geometry-less links in between do not separate them).
  for (int li : r.collision_links_) {
    int cur = li;
    while (r.links_[cur].parent_joint >= 0) {
      int parent = r.joints_[r.links_[cur].parent_joint].parent_link;
      if (!r.links_[parent].shapes.empty()) {
        add_pair(li, parent);
        break;
      }
      add_pair(li, parent);
      cur = parent;
    }
  }
  r.allowed_.assign(allowed.begin(), allowed.end());
  r.rebuild_checked_();
  return robot;
}

void Robot::rebuild_checked_() {
  std::set<std::pair<int, int>> allowed(allowed_.begin(), allowed_.end());
  checked_.clear();
  for (std::size_t a = 0; a < collision_links_.size(); ++a)
    for (std::size_t b = a + 1; b < collision_links_.size(); ++b) {
      std::pair<int, int> p{std::min(collision_links_[a], collision_links_[b]),
                            std::max(collision_links_[a], collision_links_[b])};
      if (!allowed.count(p)) checked_.push_back(p);
    }
}

int Robot::link_index(const std::string& name) const {
  auto it = link_by_name_.find(name);
  if (it == link_by_name_.end())
    throw std::invalid_argument("robot '" + name_ + "' has no link named '" + name + "'");
  return it->second;
}

int Robot::joint_index(const std::string& name) const {
  auto it = joint_by_name_.find(name);
  if (it == joint_by_name_.end())
    throw std::invalid_argument("robot '" + name_ + "' has no joint named '" + name + "'");
  return it->second;
}

std::vector<std::string> Robot::joint_names() const {
  std::vector<std::string> out;
  for (int j : active_joints_) out.push_back(joints_[j].name);
  return out;
}

Eigen::VectorXd Robot::lower() const {
  Eigen::VectorXd v(dof());
  for (int i = 0; i < dof(); ++i) v[i] = joints_[active_joints_[i]].lower;
  return v;
}

Eigen::VectorXd Robot::upper() const {
  Eigen::VectorXd v(dof());
  for (int i = 0; i < dof(); ++i) v[i] = joints_[active_joints_[i]].upper;
  return v;
}

Eigen::VectorXd Robot::home() const {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(dof());
  for (int i = 0; i < dof(); ++i) {
    const Joint& j = joints_[active_joints_[i]];
    q[i] = std::min(std::max(0.0, j.lower), j.upper);
  }
  return q;
}

std::vector<std::string> Robot::mimic_joints() const {
  std::vector<std::string> out;
  for (const auto& j : joints_)
    if (j.mimic >= 0) out.push_back(j.name);
  return out;
}

Eigen::VectorXd Robot::configuration(const std::map<std::string, double>& values) const {
  Eigen::VectorXd q = home();
  for (const auto& [name, value] : values) {
    const Joint& j = joints_[joint_index(name)];
    if (j.index < 0) throw std::invalid_argument("joint '" + name + "' is fixed or a mimic joint");
    if (!std::isfinite(value)) throw std::invalid_argument("joint '" + name + "' value must be finite");
    if (value < j.lower - 1e-9 || value > j.upper + 1e-9)
      throw std::invalid_argument("joint '" + name + "' value " + std::to_string(value) + " is outside its limits [" +
                                  std::to_string(j.lower) + ", " + std::to_string(j.upper) + "]");
    q[j.index] = value;
  }
  return q;
}

void Robot::allow_collision(const std::string& a, const std::string& b) {
  int ia = link_index(a), ib = link_index(b);
  if (ia == ib) return;
  std::pair<int, int> p{std::min(ia, ib), std::max(ia, ib)};
  if (std::find(allowed_.begin(), allowed_.end(), p) == allowed_.end()) {
    allowed_.insert(std::lower_bound(allowed_.begin(), allowed_.end(), p), p);
    rebuild_checked_();
  }
}

namespace {
inline Pose joint_motion(const Joint& j, double q) {
  Pose m = Pose::Identity();
  if (j.type == JointType::Prismatic) m.translation() = j.axis * q;
  else if (j.type == JointType::Revolute || j.type == JointType::Continuous)
    m.linear() = Eigen::AngleAxisd(q, j.axis).toRotationMatrix();
  return m;
}
}  // namespace

void Robot::link_poses(const Eigen::VectorXd& q, std::vector<Pose>& out) const {
  if (q.size() != dof())
    throw std::invalid_argument("configuration has " + std::to_string(q.size()) + " entries, robot '" + name_ +
                                "' expects " + std::to_string(dof()));
  out.resize(links_.size());
  out[root_link_] = Pose::Identity();
  // joints_ are stored in breadth-first order of their child links: parents first.
  for (const Joint& j : joints_) {
    double v = 0.0;
    if (j.index >= 0) v = q[j.index];
    else if (j.mimic >= 0) v = q[joints_[j.mimic].index] * j.mimic_multiplier + j.mimic_offset;
    out[j.child_link] = out[j.parent_link] * j.origin * joint_motion(j, v);
  }
}

std::vector<Pose> Robot::link_poses(const Eigen::VectorXd& q) const {
  std::vector<Pose> out;
  link_poses(q, out);
  return out;
}

Chain Robot::chain(const std::string& base_link, const std::string& tip_link) const {
  int base = link_index(base_link), tip = link_index(tip_link);
  std::vector<int> path;  // joints from tip up to base
  int cur = tip;
  while (cur != base) {
    int pj = links_[cur].parent_joint;
    if (pj < 0)
      throw std::invalid_argument("no chain from '" + base_link + "' to '" + tip_link + "': '" + base_link +
                                  "' is not an ancestor of '" + tip_link + "'");
    path.push_back(pj);
    cur = joints_[pj].parent_link;
  }
  std::reverse(path.begin(), path.end());
  Chain c;
  c.robot_ = shared_from_this();
  c.base_link_ = base_link;
  c.tip_link_ = tip_link;
  std::vector<double> lo, hi;
  Pose pending = Pose::Identity();
  for (int ji : path) {
    const Joint& j = joints_[ji];
    if (j.type == JointType::Fixed || j.mimic >= 0) {
      if (j.mimic >= 0)
        throw std::invalid_argument("chain '" + base_link + "' -> '" + tip_link + "' passes mimic joint '" + j.name +
                                    "' (mimic joints are left out of chains)");
      pending = pending * j.origin;
      continue;
    }
    Chain::Segment s;
    s.origin = pending * j.origin;
    s.type = j.type;
    s.axis = j.axis;
    s.robot_joint = ji;
    pending = Pose::Identity();
    c.segments_.push_back(s);
    c.joint_names_.push_back(j.name);
    c.robot_indices_.push_back(j.index);
    lo.push_back(j.lower);
    hi.push_back(j.upper);
    c.continuous_.push_back(j.type == JointType::Continuous);
  }
  c.tip_offset_ = pending;
  if (c.segments_.size() > 64)
    throw std::invalid_argument("chains of more than 64 moving joints are not supported");
  // Which chain joints move each link: a link below chain joint i moves with it.
  c.link_masks_.assign(links_.size(), 0);
  for (std::size_t li = 0; li < links_.size(); ++li) {
    int cur = static_cast<int>(li);
    while (links_[cur].parent_joint >= 0) {
      int pj = links_[cur].parent_joint;
      for (std::size_t i = 0; i < c.segments_.size(); ++i)
        if (c.segments_[i].robot_joint == pj) c.link_masks_[li] |= (1ULL << i);
      cur = joints_[pj].parent_link;
    }
  }
  c.lower_ = Eigen::Map<Eigen::VectorXd>(lo.data(), lo.size());
  c.upper_ = Eigen::Map<Eigen::VectorXd>(hi.data(), hi.size());
  return c;
}

std::uint64_t Robot::model_hash() const {
  std::uint64_t h = urdf_hash_;
  for (const auto& [a, b] : allowed_) h = detail::mix64(h, (std::uint64_t(a) << 32) | std::uint64_t(b));
  return h;
}

}  // namespace octoreach
