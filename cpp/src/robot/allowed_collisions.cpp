// Setting the allowed-collision matrix up as MoveIt's setup assistant does: pairs never in
// collision over many random configurations, pairs always in collision, pairs in collision at the
// home posture. Sampled in rounds on the thread pool (sample i draws from mix64(seed, i); pairs
// seen both in and out of collision are dropped between rounds, so the result never depends on the
// thread count), cached on disk by model hash, written out as an SRDF.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <fcl/fcl.h>

#include "collision/detail.hpp"
#include "common/atomic_file.hpp"
#include "common/file_read.hpp"
#include "common/random_mix.hpp"
#include "common/thread_pool.hpp"
#include "octoreach/limits.hpp"
#include "octoreach/robot.hpp"
#include "robot/link_boxes.hpp"

namespace octoreach {
namespace {

using detail::LinkBoxes;
using Pairs = std::vector<std::pair<int, int>>;

std::string default_cache_dir() {
  if (const char* d = std::getenv("OCTOREACH_CACHE_DIR"); d && *d) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return std::string(d) + "/octoreach";
  if (const char* d = std::getenv("HOME"); d && *d) return std::string(d) + "/.cache/octoreach";
  return "";
}

std::string cache_path(const Robot& robot, const AllowedCollisionOptions& o) {
  const std::string dir = o.cache_dir.empty() ? default_cache_dir() : o.cache_dir == "none" ? "" : o.cache_dir;
  if (dir.empty()) return "";
  std::ostringstream name;
  name << dir << "/acm-" << std::hex << robot.model_hash() << std::dec << "-" << o.samples << "-" << o.seed
       << (o.default_posture ? "-d" : "") << ".txt";
  return name.str();
}

// Reads a cache file ("never|always|default link_a link_b" lines); false when absent or stale.
bool read_cache(const Robot& robot, const std::string& path, SampledCollisions& out) {
  std::istringstream in;
  try {  // a FIFO, device or oversized file in a shared cache folder counts as absent
    in.str(detail::read_file_bounded(path, "allowed-collision cache", limits::kRobotFileBytes));
  } catch (const FileError&) {
    return false;
  }
  std::string kind, a, b, header;
  if (!std::getline(in, header) || header != "octoreach allowed collisions 1") return false;
  while (in >> kind >> a >> b) {
    if (!robot.has_link(a) || !robot.has_link(b)) return false;
    std::pair<int, int> p{robot.link_index(a), robot.link_index(b)};
    if (p.first > p.second) std::swap(p.first, p.second);
    (kind == "never" ? out.never : kind == "always" ? out.always : out.default_posture).push_back(p);
  }
  out.from_cache = true;
  out.cache_file = path;
  return true;
}

void write_cache(const Robot& robot, const std::string& path, SampledCollisions& out) {
  try {
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    detail::write_file_atomically(path, [&](std::ostream& f) {
      f << "octoreach allowed collisions 1\n";
      const std::pair<const char*, const Pairs*> parts[] = {{"never", &out.never}, {"always", &out.always},
                                                            {"default", &out.default_posture}};
      for (const auto& [kind, pairs] : parts)
        for (auto [a, b] : *pairs) f << kind << " " << robot.links()[a].name << " " << robot.links()[b].name << "\n";
    }, "allowed-collision cache");
    out.cache_file = path;
  } catch (const std::exception&) {
    // The cache is an optimisation: an unwritable cache folder leaves the result as it is.
  }
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

}  // namespace

SampledCollisions Robot::sample_allowed_collisions(const AllowedCollisionOptions& o, const ProgressCallback& progress) const {
  if (o.samples < 1) throw std::invalid_argument("samples must be at least 1, got " + std::to_string(o.samples));
  SampledCollisions out;
  const std::string path = cache_path(*this, o);
  if (!path.empty() && read_cache(*this, path, out)) return out;

  const Pairs& pairs = checked_;
  std::vector<long> hits(pairs.size(), 0);
  std::vector<int> open(pairs.size());  // pairs not yet seen both in and out of collision
  for (std::size_t p = 0; p < pairs.size(); ++p) open[p] = static_cast<int>(p);
  const int threads = detail::default_threads(o.threads);
  std::vector<LinkBoxes> scratch(threads);
  std::vector<std::vector<int>> local(threads, std::vector<int>(pairs.size(), 0));
  const int round = 256;
  for (int start = 0; start < o.samples && !open.empty(); start += round) {
    const int end = std::min(o.samples, start + round);
    for (auto& l : local) std::fill(l.begin(), l.end(), 0);
    detail::parallel_for(static_cast<std::size_t>(end - start), threads, [&](std::size_t i, int tid) {
      LinkBoxes& lb = scratch[tid];
      Eigen::VectorXd q(dof());
      detail::random_configuration(*this, detail::mix64(o.seed, start + i), q);
      lb.update(*this, q);
      for (int p : open) local[tid][p] += lb.touch(*this, pairs[p].first, pairs[p].second);
    }, 4);
    for (const auto& l : local)
      for (int p : open) hits[p] += l[p];
    std::vector<int> still;
    for (int p : open)
      if (hits[p] == 0 || hits[p] == end) still.push_back(p);
    open.swap(still);
    if (progress && !progress(end, o.samples)) throw Cancelled("allowed-collision sampling cancelled");
  }
  for (int p : open) (hits[p] == 0 ? out.never : out.always).push_back(pairs[p]);
  if (o.default_posture) {
    LinkBoxes lb;
    lb.update(*this, home());
    for (std::size_t p = 0; p < pairs.size(); ++p)
      if (hits[p] != 0 && hits[p] != o.samples && lb.touch(*this, pairs[p].first, pairs[p].second))
        out.default_posture.push_back(pairs[p]);
  }
  if (!path.empty()) write_cache(*this, path, out);
  return out;
}

std::shared_ptr<Robot> Robot::with_sampled_collisions(const AllowedCollisionOptions& options,
                                                      const ProgressCallback& progress) const {
  SampledCollisions s = sample_allowed_collisions(options, progress);
  return with_allowed_collisions(s.never, AllowedSource::kNever)
      ->with_allowed_collisions(s.always, AllowedSource::kAlways)
      ->with_allowed_collisions(s.default_posture, AllowedSource::kDefaultPosture);
}

std::vector<std::pair<int, int>> Robot::compute_allowed_collisions(int samples, std::uint64_t seed,
                                                                   const ProgressCallback& progress) const {
  AllowedCollisionOptions o;
  o.samples = samples;
  o.seed = seed;
  o.default_posture = false;
  o.cache_dir = "none";
  SampledCollisions s = sample_allowed_collisions(o, progress);
  Pairs all = s.never;
  all.insert(all.end(), s.always.begin(), s.always.end());
  std::sort(all.begin(), all.end());
  return all;
}

std::vector<std::pair<int, int>> Robot::colliding_pairs(const std::vector<Pose>& poses, const Pairs& pairs,
                                                        std::size_t limit) const {
  LinkBoxes lb;
  lb.link_poses = poses;
  lb.update_shapes(*this);
  Pairs out;
  for (const auto& [a, b] : pairs)
    if (out.size() < limit && lb.touch(*this, a, b)) out.emplace_back(a, b);
  return out;
}

std::string Robot::srdf_text() const {
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n<!-- written by octoreach: groups, end effectors and group states as read,"
       " every allowed-collision pair -->\n<robot name=\"" << xml_escape(name_) << "\">\n";
  for (const SrdfGroup& g : srdf_groups_) {
    s << "  <group name=\"" << xml_escape(g.name) << "\">\n";
    for (const auto& [b, t] : g.chains) s << "    <chain base_link=\"" << xml_escape(b) << "\" tip_link=\"" << xml_escape(t) << "\"/>\n";
    for (const auto& j : g.joints) s << "    <joint name=\"" << xml_escape(j) << "\"/>\n";
    for (const auto& l : g.links) s << "    <link name=\"" << xml_escape(l) << "\"/>\n";
    for (const auto& sg : g.subgroups) s << "    <group name=\"" << xml_escape(sg) << "\"/>\n";
    s << "  </group>\n";
  }
  s.precision(17);
  for (const auto& [state, values] : named_states_) {
    s << "  <group_state name=\"" << xml_escape(state) << "\">\n";
    for (const auto& [j, v] : values) s << "    <joint name=\"" << xml_escape(j) << "\" value=\"" << v << "\"/>\n";
    s << "  </group_state>\n";
  }
  for (const EndEffector& e : end_effectors_) {
    s << "  <end_effector name=\"" << xml_escape(e.name) << "\" parent_link=\"" << xml_escape(e.parent_link) << "\"";
    if (!e.group.empty()) s << " group=\"" << xml_escape(e.group) << "\"";
    if (!e.parent_group.empty()) s << " parent_group=\"" << xml_escape(e.parent_group) << "\"";
    s << "/>\n";
  }
  auto reason = [](AllowedSource source) {
    switch (source) {
      case AllowedSource::kAdjacent: return "Adjacent";
      case AllowedSource::kNever: return "Never";
      case AllowedSource::kAlways: return "Always";
      case AllowedSource::kDefaultPosture: return "Default";
      case AllowedSource::kGiven: return "User";
      case AllowedSource::kSrdf: break;
    }
    return "Allowed";
  };
  for (std::size_t i = 0; i < allowed_.size(); ++i)
    s << "  <disable_collisions link1=\"" << xml_escape(links_[allowed_[i].first].name) << "\" link2=\""
      << xml_escape(links_[allowed_[i].second].name) << "\" reason=\"" << reason(allowed_sources_[i]) << "\"/>\n";
  s << "</robot>\n";
  return s.str();
}

void Robot::write_srdf(const std::string& path) const {
  const std::string text = srdf_text();
  detail::write_file_atomically(path, [&](std::ostream& f) { f << text; }, "SRDF");
}

}  // namespace octoreach
