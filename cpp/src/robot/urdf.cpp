// Robot::from_urdf: URDF text -> urdfdom model -> links, joints, collision shapes and visuals; mesh URIs
// (package://, file://, relative paths) resolved to files. The SRDF part is in srdf.cpp.
#include <sys/stat.h>

#include <cerrno>
#include <deque>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>

#include <fcl/fcl.h>
#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include "octoreach/limits.hpp"
#include "octoreach/robot.hpp"
#include "common/file_read.hpp"
#include "common/nearest_names.hpp"
#include "robot/robot_builder.hpp"

namespace octoreach {
namespace detail {

bool looks_like_xml(const std::string& s) {
  auto pos = s.find_first_not_of(" \t\r\n");
  return pos != std::string::npos && s[pos] == '<';
}

std::string read_text_file(const std::string& path, const char* what) {
  return read_file_bounded(path, std::string(what) + " file", limits::kRobotFileBytes);
}

}  // namespace detail

namespace {

std::string dirname(const std::string& path) {
  auto pos = path.find_last_of('/');
  return pos == std::string::npos ? std::string(".") : path.substr(0, pos);
}

bool file_exists(const std::string& path) {  // without opening it (opening a FIFO blocks)
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
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

// The URDF as XML text (read from a file when it is a path) and the folder relative mesh paths
// start from.
struct UrdfText {
  std::string xml, dir = ".", path;  // path: the file's absolute path ("" for XML text)
};

std::string absolute_path(const std::string& path) {
  return std::filesystem::absolute(std::filesystem::path(path)).lexically_normal().string();
}

std::vector<std::string> absolute_paths(const std::vector<std::string>& paths) {
  std::vector<std::string> out;
  for (const auto& p : paths) out.push_back(p.empty() ? p : absolute_path(p));
  return out;
}

UrdfText read_urdf_text(const std::string& urdf) {
  UrdfText t;
  if (detail::looks_like_xml(urdf)) {
    t.xml = urdf;
  } else {
    if (urdf.empty()) throw std::invalid_argument("empty URDF: expected a file path or an XML string");
    t.xml = detail::read_text_file(urdf, "URDF");
    t.dir = dirname(urdf);
    t.path = absolute_path(urdf);
  }
  return t;
}

// urdfdom reports parse errors through console_bridge: while one parse runs, its errors are collected
// here instead of printed (console_bridge's handler is process-wide, hence the mutex).
class CaptureConsole : public console_bridge::OutputHandler {
 public:
  CaptureConsole() : lock_(mutex()) { console_bridge::useOutputHandler(this); }
  ~CaptureConsole() override { console_bridge::restorePreviousOutputHandler(); }
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level < console_bridge::CONSOLE_BRIDGE_LOG_ERROR) return;
    errors_ += (errors_.empty() ? "" : "; ") + text;
  }
  const std::string& errors() const { return errors_; }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  std::string errors_;
};

// The XML is checked with tinyxml first (its error names the line); urdfdom's own reasons are captured.
urdf::ModelInterfaceSharedPtr parse_urdf(const std::string& xml) {
  {
    TiXmlDocument doc;
    doc.Parse(xml.c_str());
    if (doc.Error())
      throw std::invalid_argument(std::string("malformed URDF: XML error '") + doc.ErrorDesc() + "' at line " +
                                  std::to_string(doc.ErrorRow()));
    if (!doc.RootElement() || std::string(doc.RootElement()->Value()) != "robot")
      throw std::invalid_argument("malformed URDF: the root element must be <robot>");
    if (!doc.RootElement()->Attribute("name") || !*doc.RootElement()->Attribute("name"))
      throw std::invalid_argument("malformed URDF: <robot> has no name attribute");
  }
  urdf::ModelInterfaceSharedPtr model;
  std::string reason;
  try {
    CaptureConsole capture;  // urdfdom's errors go into the exception, not to stderr
    model = urdf::parseURDF(xml);
    reason = capture.errors();
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("malformed URDF: ") + e.what());
  }
  if (!model)
    throw std::invalid_argument("malformed URDF: " + (reason.empty() ? std::string("urdfdom rejected it") : reason));
  if (!model->getRoot()) throw std::invalid_argument("malformed URDF: no root link");
  return model;
}

// Meshes already loaded, by resolved path and scale: links that share a mesh share its BVH.
using MeshCache = std::map<std::string, std::shared_ptr<fcl::CollisionGeometryd>>;

// What a URDF <geometry> describes, at `origin` (link frame), without collision geometry; `uri` gets a
// mesh's filename.
Shape describe(const urdf::Geometry& g, const urdf::Pose& origin, std::string& uri) {
  Shape s;
  s.origin = to_pose(origin);
  switch (g.type) {
    case urdf::Geometry::BOX: {
      const auto& b = static_cast<const urdf::Box&>(g);
      s.type = Shape::Type::Box;
      s.size = Eigen::Vector3d(b.dim.x, b.dim.y, b.dim.z);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(g);
      s.type = Shape::Type::Cylinder;
      s.radius = c.radius;
      s.length = c.length;
      break;
    }
    case urdf::Geometry::SPHERE:
      s.type = Shape::Type::Sphere;
      s.radius = static_cast<const urdf::Sphere&>(g).radius;
      break;
    case urdf::Geometry::MESH: {
      const auto& m = static_cast<const urdf::Mesh&>(g);
      s.type = Shape::Type::Mesh;
      s.scale = Eigen::Vector3d(m.scale.x, m.scale.y, m.scale.z);
      uri = m.filename;
      break;
    }
  }
  return s;
}

// One URDF collision element as a Shape with its FCL geometry (sizes as the URDF gives them).
Shape make_shape(const urdf::Collision& c, const std::vector<std::string>& package_dirs, const std::string& urdf_dir,
                 const std::string& link, MeshCache& meshes) {
  std::string uri;
  Shape s = describe(*c.geometry, c.origin, uri);
  switch (s.type) {
    case Shape::Type::Box: s.geometry = std::make_shared<fcl::Boxd>(s.size); break;
    case Shape::Type::Cylinder: s.geometry = std::make_shared<fcl::Cylinderd>(s.radius, s.length); break;
    case Shape::Type::Sphere: s.geometry = std::make_shared<fcl::Sphered>(s.radius); break;
    case Shape::Type::Mesh: {
      s.mesh_path = resolve_mesh(uri, package_dirs, urdf_dir, link);
      std::ostringstream key;
      key << s.mesh_path << "|" << s.scale.transpose();
      auto it = meshes.find(key.str());
      if (it == meshes.end()) it = meshes.emplace(key.str(), load_mesh(s.mesh_path, s.scale)).first;
      s.geometry = it->second;
      break;
    }
    case Shape::Type::Octree: break;
  }
  return s;
}

// One URDF visual element: its shape (meshes resolved, not read: a missing visual mesh leaves mesh_path ""), its
// material and colour (a named material of the robot when the visual only names it).
Visual make_visual(const urdf::Visual& v, const urdf::ModelInterface& model, const std::vector<std::string>& package_dirs,
                   const std::string& urdf_dir, const std::string& link) {
  Visual out;
  out.shape = describe(*v.geometry, v.origin, out.mesh_uri);
  if (out.shape.type == Shape::Type::Mesh) {
    try {
      out.shape.mesh_path = resolve_mesh(out.mesh_uri, package_dirs, urdf_dir, link);
    } catch (const FileError&) {
      out.shape.mesh_path.clear();
    }
  }
  out.material = v.material_name;
  urdf::MaterialSharedPtr material = v.material;
  if (!material && !v.material_name.empty()) material = model.getMaterial(v.material_name);
  if (material) out.rgba = std::array<double, 4>{material->color.r, material->color.g, material->color.b, material->color.a};
  return out;
}

}  // namespace

namespace detail {

void RobotBuilder::add_links(const urdf::ModelInterface& model, const std::vector<std::string>& package_dirs,
                             const std::string& urdf_dir) {
  std::deque<urdf::LinkConstSharedPtr> queue{model.getRoot()};
  MeshCache meshes;
  while (!queue.empty()) {
    auto ul = queue.front();
    queue.pop_front();
    Link link;
    link.name = ul->name;
    std::vector<urdf::CollisionSharedPtr> collisions = ul->collision_array;
    if (collisions.empty() && ul->collision) collisions.push_back(ul->collision);
    for (const auto& c : collisions) {
      if (!c || !c->geometry) continue;
      Shape s = make_shape(*c, package_dirs, urdf_dir, ul->name, meshes);
      if (s.geometry) {
        s.geometry->computeLocalAABB();
        link.shapes.push_back(std::move(s));
      }
    }
    std::vector<urdf::VisualSharedPtr> visuals = ul->visual_array;
    if (visuals.empty() && ul->visual) visuals.push_back(ul->visual);
    for (const auto& v : visuals)
      if (v && v->geometry) link.visuals.push_back(make_visual(*v, model, package_dirs, urdf_dir, ul->name));
    r.link_by_name_[link.name] = static_cast<int>(r.links_.size());
    r.links_.push_back(std::move(link));
    for (const auto& child : ul->child_links) queue.push_back(child);
  }
  r.root_link_ = 0;
}

void RobotBuilder::add_joints(const urdf::ModelInterface& model) {
  for (std::size_t li = 1; li < r.links_.size(); ++li) {
    auto ul = model.getLink(r.links_[li].name);
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
}

void RobotBuilder::add_mimics_and_number_joints(const urdf::ModelInterface& model) {
  // Mimic joints: resolved after every joint is known.
  for (std::size_t ji = 0; ji < r.joints_.size(); ++ji) {
    auto uj = model.getJoint(r.joints_[ji].name);
    if (uj->mimic && r.joints_[ji].type != JointType::Fixed) {
      auto it = r.joint_by_name_.find(uj->mimic->joint_name);
      if (it == r.joint_by_name_.end())
      {
        std::vector<std::string> names;
        for (const Joint& j : r.joints_) names.push_back(j.name);
        throw std::invalid_argument("malformed URDF: joint '" + uj->name + "' mimics unknown joint '" +
                                    uj->mimic->joint_name + "'" + did_you_mean(uj->mimic->joint_name, names));
      }
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
}

}  // namespace detail

std::shared_ptr<Robot> Robot::from_urdf(const std::string& urdf, const std::vector<std::string>& package_dirs,
                                        const std::string& srdf, SrdfMismatch mismatch) {
  UrdfText text = read_urdf_text(urdf);
  urdf::ModelInterfaceSharedPtr model = parse_urdf(text.xml);
  std::shared_ptr<Robot> robot(new Robot());
  robot->name_ = model->getName();
  robot->source_ = {text.path, absolute_paths(package_dirs), ""};
  if (!srdf.empty() && !detail::looks_like_xml(srdf)) robot->source_.srdf = absolute_path(srdf);
  robot->urdf_hash_ = fnv1a(text.xml);
  detail::RobotBuilder build{*robot};
  build.add_links(*model, package_dirs, text.dir);
  build.add_joints(*model);
  build.add_mimics_and_number_joints(*model);
  detail::PairSet allowed;
  if (!srdf.empty()) build.read_srdf(srdf, mismatch, allowed);
  build.finish_collision_model(std::move(allowed));
  return robot;
}

}  // namespace octoreach
