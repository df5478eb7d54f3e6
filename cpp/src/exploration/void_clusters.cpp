// Void clustering: ellipsoid region growing (eq. 2, see VoidCluster) and frontier-voids.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <unordered_map>

#include <Eigen/Eigenvalues>

#include "cell_sets.hpp"
#include "exploration_state.hpp"
#include "octoreach/types.hpp"

namespace octoreach {

namespace {

// Running moments of a cluster's cell centres, in cells relative to its seed cell.
struct Moments {
  double count = 1;
  Eigen::Vector3d s1 = Eigen::Vector3d::Zero();
  Eigen::Matrix3d s2 = Eigen::Matrix3d::Zero();

  Moments plus(const Eigen::Vector3d& p) const { return {count + 1, s1 + p, s2 + p * p.transpose()}; }
  // Covariance of the cells as unit cubes, not points (so a flat layer is not singular).
  Eigen::Matrix3d covariance() const {
    Eigen::Vector3d mu = s1 / count;
    Eigen::Matrix3d cov = s2 / count - mu * mu.transpose();
    cov.diagonal().array() += 1.0 / 12.0;
    return cov;
  }
  // eq. (2) with semi-axes sqrt(5 lambda): the share of the ellipsoid filled by the cells.
  double score() const {
    double det = std::max(covariance().determinant(), 1e-12);
    return count / (4.0 / 3.0 * kPi * std::sqrt(125.0 * det));
  }
};

// The sorted void cells and the index of each.
struct VoidIndex {
  std::vector<CellKey> cells;
  std::unordered_map<CellKey, int> index;
};

// Grows cluster `cid` from seed cell s over 26-neighbours while the score stays >= threshold;
// returns its member indices and fills `m` and `score`.
std::vector<int> grow(const VoidIndex& v, int s, int cid, double threshold, std::vector<int>& assigned,
                      std::vector<int>& tried, Moments& m, double& score) {
  const CellKey seed = v.cells[s];
  auto rel = [&](CellKey k) {
    return Eigen::Vector3d(int(key_x(k)) - int(key_x(seed)), int(key_y(k)) - int(key_y(seed)),
                           int(key_z(k)) - int(key_z(seed)));
  };
  assigned[s] = cid;
  std::vector<int> members{s};
  score = m.score();
  for (std::size_t qi = 0; qi < members.size(); ++qi) {  // members double as the queue
    CellKey k = v.cells[members[qi]];
    for (const auto& d : detail::kN26.d) {
      CellKey nb;
      if (!detail::neighbour(k, d[0], d[1], d[2], nb)) continue;
      auto it = v.index.find(nb);
      if (it == v.index.end()) continue;
      int j = it->second;
      if (assigned[j] >= 0 || tried[j] == cid) continue;
      Moments next = m.plus(rel(nb));
      double sc = next.score();
      if (sc >= threshold) {
        m = next;
        score = sc;
        assigned[j] = cid;
        members.push_back(j);
      } else {
        tried[j] = cid;
      }
    }
  }
  return members;
}

VoidCluster make_cluster(const detail::ExplorationState& st, const VoidIndex& v, CellKey seed,
                         const std::vector<int>& members, const Moments& m, double score, double res) {
  VoidCluster vc;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(m.covariance());
  for (int j = 0; j < 3; ++j) {
    vc.eigenvalues[j] = std::max(es.eigenvalues()[2 - j], 0.0) * res * res;
    vc.axes.col(j) = es.eigenvectors().col(2 - j);
  }
  if (vc.axes.determinant() < 0) vc.axes.col(2) *= -1;
  vc.semi_axes = (5.0 * vc.eigenvalues.array()).sqrt();
  vc.centroid = st.center(seed) + (m.s1 / m.count) * res;
  vc.score = score;
  for (int i : members) vc.cells.push_back(v.cells[i]);
  std::sort(vc.cells.begin(), vc.cells.end());
  return vc;
}

// Region growing from seeded random start cells over all void cells.
std::vector<VoidCluster> clusters_from_scratch(const detail::ExplorationState& I, const ExplorationOptions& options,
                                               double resolution) {
  std::vector<VoidCluster> out;
  VoidIndex v;
  v.cells.assign(I.void_set.begin(), I.void_set.end());
  std::sort(v.cells.begin(), v.cells.end());
  const std::size_t n = v.cells.size();
  v.index.reserve(n * 2);
  for (std::size_t i = 0; i < n; ++i) v.index.emplace(v.cells[i], int(i));
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(options.seed);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<int> assigned(n, -1), tried(n, -1);
  for (int s : order) {
    if (assigned[s] >= 0) continue;
    const int cid = int(out.size());
    Moments m;
    double score = 0;
    std::vector<int> members = grow(v, s, cid, options.void_fit_threshold, assigned, tried, m, score);
    out.push_back(make_cluster(I, v, v.cells[s], members, m, score, resolution));
  }
  return out;
}

}  // namespace

std::vector<VoidCluster> ExplorationMap::void_clusters() const {
  detail::MapGuard guard(*state_, false);
  return detail::cached_void_clusters(*this);
}

std::vector<VoidCluster> ExplorationMap::void_clusters_from_scratch() const {
  detail::MapGuard guard(*state_, false);
  return clusters_from_scratch(*state_, options_, resolution_);
}

const std::vector<VoidCluster>& detail::cached_void_clusters(const ExplorationMap& map) {
  auto& I = detail::state(map);
  std::lock_guard<std::mutex> lock(I.cache_mutex);
  if (!I.voids_dirty) return I.void_clusters;
  I.void_clusters = clusters_from_scratch(I, map.options(), map.resolution());
  I.voids_dirty = false;
  return I.void_clusters;
}

std::vector<FrontierVoid> ExplorationMap::frontier_voids() const {
  detail::MapGuard guard(*state_, false);
  const auto& fcs = detail::cached_frontier_clusters(*state_);
  const auto& vcs = detail::cached_void_clusters(*this);
  (void)fcs;
  auto& I = *state_;
  std::vector<FrontierVoid> out;
  detail::GridReader g(I.grid);
  for (std::size_t v = 0; v < vcs.size(); ++v) {
    FrontierVoid fv;
    fv.void_index = int(v);
    for (CellKey k : vcs[v].cells)
      for (const auto& d : detail::kN26.d) {
        CellKey nb;
        if (!detail::neighbour(k, d[0], d[1], d[2], nb)) continue;
        if (!(g.get(nb) & detail::kFrontierFlag)) continue;
        fv.frontier_cells.push_back(nb);
        auto it = I.frontier_label.find(nb);
        if (it != I.frontier_label.end()) {
          auto jt = I.label_to_cluster.find(it->second);
          if (jt != I.label_to_cluster.end()) fv.frontier_clusters.push_back(jt->second);
        }
      }
    if (fv.frontier_cells.empty()) continue;
    std::sort(fv.frontier_cells.begin(), fv.frontier_cells.end());
    fv.frontier_cells.erase(std::unique(fv.frontier_cells.begin(), fv.frontier_cells.end()), fv.frontier_cells.end());
    std::sort(fv.frontier_clusters.begin(), fv.frontier_clusters.end());
    fv.frontier_clusters.erase(std::unique(fv.frontier_clusters.begin(), fv.frontier_clusters.end()),
                               fv.frontier_clusters.end());
    fv.utility = vcs[v].volume(resolution_);
    out.push_back(std::move(fv));
  }
  return out;
}

}  // namespace octoreach
