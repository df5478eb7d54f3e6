// Counting self-collisions over random configurations: the share free of them and the pairs that collide
// most often. Sample i draws from mix64(seed, i) and the counts are summed over threads, so the report is
// the same on any number of cores.
#include "octoreach/self_collision_report.hpp"

#include <algorithm>
#include <stdexcept>

#include "common/random_mix.hpp"
#include "common/thread_pool.hpp"
#include "robot/link_boxes.hpp"

namespace octoreach {

namespace {

// Configuration indices of the joints to draw (all when `names` is empty).
std::vector<int> drawn_joints(const Robot& robot, const std::vector<std::string>& names) {
  std::vector<int> out;
  if (names.empty()) {
    for (int i = 0; i < robot.dof(); ++i) out.push_back(i);
    return out;
  }
  for (const auto& name : names) {
    const int index = robot.joints()[robot.joint_index(name)].index;
    if (index < 0)
      throw std::invalid_argument("joint '" + name + "' of robot '" + robot.name() +
                                  "' does not move (fixed or mimic): it cannot be drawn at random");
    out.push_back(index);
  }
  return out;
}

}  // namespace

SelfCollisionReport self_collision_report(const Robot& robot, const SelfCollisionOptions& o,
                                          const ProgressCallback& progress) {
  if (o.samples < 1) throw std::invalid_argument("samples must be at least 1, got " + std::to_string(o.samples));
  const Eigen::VectorXd reference = o.reference.size() ? o.reference : robot.home();
  if (reference.size() != robot.dof())
    throw std::invalid_argument("reference configuration has " + std::to_string(reference.size()) +
                                " entries, robot '" + robot.name() + "' has " + std::to_string(robot.dof()));
  const std::vector<int> joints = drawn_joints(robot, o.joints);
  std::vector<std::pair<int, int>> pairs = robot.checked_pairs();
  if (!o.links.empty()) {
    std::vector<char> in(robot.links().size(), 0);
    for (const auto& name : o.links) in[robot.link_index(name)] = 1;
    pairs.erase(std::remove_if(pairs.begin(), pairs.end(), [&](const auto& p) { return !in[p.first] || !in[p.second]; }),
                pairs.end());
  }
  const int threads = detail::default_threads(o.threads);
  std::vector<detail::LinkBoxes> scratch(threads);
  std::vector<std::vector<int>> hits(threads, std::vector<int>(pairs.size(), 0));
  std::vector<int> free(threads, 0);
  const int round = 256;  // samples between progress reports
  for (int start = 0; start < o.samples; start += round) {
    const int end = std::min(o.samples, start + round);
    detail::parallel_for(static_cast<std::size_t>(end - start), threads, [&](std::size_t i, int tid) {
      Eigen::VectorXd q = reference;
      detail::random_configuration(robot, detail::mix64(o.seed, start + i), q, &joints);
      detail::LinkBoxes& lb = scratch[tid];
      lb.update(robot, q);
      bool clear = true;
      for (std::size_t p = 0; p < pairs.size(); ++p)
        if (lb.touch(robot, pairs[p].first, pairs[p].second)) {
          ++hits[tid][p];
          clear = false;
        }
      free[tid] += clear;
    }, 4);
    if (progress && !progress(end, o.samples)) throw Cancelled("self-collision report cancelled");
  }
  SelfCollisionReport report;
  report.samples = o.samples;
  for (int f : free) report.free += f;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    int total = 0;
    for (const auto& h : hits) total += h[p];
    if (total > 0)
      report.pairs.push_back({robot.links()[pairs[p].first].name, robot.links()[pairs[p].second].name, total});
  }
  std::stable_sort(report.pairs.begin(), report.pairs.end(),
                   [](const PairHits& a, const PairHits& b) { return a.hits > b.hits; });
  return report;
}

}  // namespace octoreach
