// Void clustering: ellipsoid region growing (eq. 2, see VoidCluster), kept up to date incrementally
// after each insert, and frontier-voids.
//
// Seeds are taken in a fixed priority order of the cells (mix of the key and the map's seed), so the
// clustering of a set of void cells does not depend on how it came about. After an insert only the
// clusters the changes can reach are grown again: the order is replayed, a cluster whose seed comes up
// and which is not "dirty" is reused as it was, every other one is grown anew. A cluster is dirty when
// one of its cells or their 26-neighbours is "marked": a void cell added or removed, a cell that joins
// a cluster with another seed than before, or a cell of an old cluster not in its successor when that
// old cluster's seed comes up in the order. The growth of a cluster reads only its cells, their
// neighbours and whether those were void and taken by a cluster of an earlier seed; none of that can
// change for a cluster that is not dirty when its seed comes up, so the result equals the clustering
// from scratch (void_clusters_from_scratch), cluster for cluster, in the same order.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

#include "cell_sets.hpp"
#include "common/random_mix.hpp"
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

using Order = std::vector<std::pair<std::uint64_t, CellKey>>;

std::uint64_t priority(CellKey k, std::uint64_t seed) { return detail::mix64(seed, k); }

// Grows cluster `cid` from seed s over void 26-neighbours not taken yet while the score stays >=
// threshold. taken / tried: cluster index + 1 of the cell's cluster / of the last cluster that
// rejected it. Returns the members (seed first, in the order they joined).
std::vector<CellKey> grow(const detail::GridReader& g, CellKey s, int cid, double threshold,
                          detail::KeyTable<int>& taken, detail::KeyTable<int>& tried, Moments& m, double& score) {
  auto rel = [&](CellKey k) {
    return Eigen::Vector3d(int(key_x(k)) - int(key_x(s)), int(key_y(k)) - int(key_y(s)), int(key_z(k)) - int(key_z(s)));
  };
  taken.at(s) = cid + 1;
  std::vector<CellKey> members{s};
  score = m.score();
  for (std::size_t qi = 0; qi < members.size(); ++qi) {  // members double as the queue
    const CellKey k = members[qi];
    for (const auto& d : detail::kN26.d) {
      CellKey nb;
      if (!detail::neighbour(k, d[0], d[1], d[2], nb) || !(g.get(nb) & detail::kVoidFlag)) continue;
      const int* t = taken.find(nb);
      if (t && *t) continue;
      const int* r = tried.find(nb);
      if (r && *r == cid + 1) continue;
      Moments next = m.plus(rel(nb));
      double sc = next.score();
      if (sc >= threshold) {
        m = next;
        score = sc;
        taken.at(nb) = cid + 1;
        members.push_back(nb);
      } else {
        tried.at(nb) = cid + 1;
      }
    }
  }
  return members;
}

VoidCluster make_cluster(const detail::ExplorationState& st, CellKey seed, std::vector<CellKey> members,
                         const Moments& m, double score, double res) {
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
  vc.cells = std::move(members);
  std::sort(vc.cells.begin(), vc.cells.end());
  return vc;
}

// The clusters before an update (empty: from scratch) and the new ones being made.
struct Clustering {
  // before
  const std::vector<VoidCluster>& old_clusters;
  const std::vector<CellKey>& old_seeds;
  const detail::KeyTable<int>& old_of;  // cell -> old cluster index + 1
  std::vector<char> dirty;
  // after
  std::vector<VoidCluster> clusters;
  std::vector<CellKey> seeds;
  detail::KeyTable<int> taken, tried;  // cell -> new cluster index + 1
  std::size_t reused = 0;

  int old_index(CellKey k) const {
    const int* i = old_of.find(k);
    return i ? *i - 1 : -1;
  }
  // The old clusters holding k or a 26-neighbour of k become dirty.
  void mark(CellKey k) {
    if (old_clusters.empty()) return;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          CellKey nb;
          if (!detail::neighbour(k, dx, dy, dz, nb)) continue;
          const int j = old_index(nb);
          if (j >= 0) dirty[std::size_t(j)] = 1;
        }
  }
  // The seed of the new cluster holding k (~0 when none).
  CellKey new_seed(CellKey k) const {
    const int* t = taken.find(k);
    return t && *t ? seeds[std::size_t(*t - 1)] : ~CellKey(0);
  }
};

// At the position of seed s in the order: reuse its old cluster or grow a new one.
void seed_at(const detail::ExplorationState& I, const detail::GridReader& g, const ExplorationOptions& o, double res,
             CellKey s, Clustering& c) {
  const int cid = int(c.clusters.size());
  const int j = c.old_index(s);
  auto intact = [&](const VoidCluster& v) {  // a safeguard: the argument above says it always holds
    for (CellKey k : v.cells) {
      const int* t = c.taken.find(k);
      if ((t && *t) || !(g.get(k) & detail::kVoidFlag)) return false;
    }
    return true;
  };
  if (j >= 0 && c.old_seeds[std::size_t(j)] == s && !c.dirty[std::size_t(j)] && intact(c.old_clusters[std::size_t(j)])) {
    for (CellKey k : c.old_clusters[std::size_t(j)].cells) c.taken.at(k) = cid + 1;
    c.clusters.push_back(c.old_clusters[std::size_t(j)]);
    c.seeds.push_back(s);
    ++c.reused;
    return;
  }
  Moments m;
  double score = 0;
  c.seeds.push_back(s);
  std::vector<CellKey> members = grow(g, s, cid, o.void_fit_threshold, c.taken, c.tried, m, score);
  for (CellKey k : members) {  // cells that joined a cluster of another seed than before
    const int oj = c.old_index(k);
    if (oj < 0 || c.old_seeds[std::size_t(oj)] != s) c.mark(k);
  }
  c.clusters.push_back(make_cluster(I, s, std::move(members), m, score, res));
}

// Brings the kept clusters up to date with the void cells added and removed since (all of them when
// there were none before).
void update_clusters(const detail::ExplorationState& I, const ExplorationOptions& o, double res) {
  const detail::GridReader g(I.grid);
  // the void cells in priority order: the old order without the cells no longer void, plus the new ones
  Order add;
  for (CellKey k : I.void_added)
    if (g.get(k) & detail::kVoidFlag) add.emplace_back(priority(k, o.seed), k);
  std::sort(add.begin(), add.end());
  Order order;
  order.reserve(I.void_order.size() + add.size());
  for (const auto& e : I.void_order)
    if (g.get(e.second) & detail::kVoidFlag) order.push_back(e);
  const std::size_t mid = order.size();
  order.insert(order.end(), add.begin(), add.end());
  std::inplace_merge(order.begin(), order.begin() + std::ptrdiff_t(mid), order.end());
  order.erase(std::unique(order.begin(), order.end()), order.end());

  Clustering c{I.void_clusters, I.void_seeds, I.void_cluster_of, std::vector<char>(I.void_clusters.size(), 0),
               {}, {}, detail::KeyTable<int>(order.size()), detail::KeyTable<int>(order.size() / 4)};
  for (CellKey k : I.void_added) c.mark(k);
  for (CellKey k : I.void_removed) c.mark(k);
  // the old seeds in priority order: at each one's position, its cells not in its successor are marked
  Order old;
  for (CellKey s : I.void_seeds) old.emplace_back(priority(s, o.seed), s);
  std::sort(old.begin(), old.end());
  std::size_t oi = 0;
  auto close_old = [&](const std::pair<std::uint64_t, CellKey>& upto, bool inclusive) {
    for (; oi < old.size() && (old[oi] < upto || (inclusive && old[oi] == upto)); ++oi) {
      const CellKey s = old[oi].second;
      for (CellKey k : I.void_clusters[std::size_t(c.old_index(s))].cells)
        if (c.new_seed(k) != s) c.mark(k);
    }
  };
  for (const auto& e : order) {
    close_old(e, false);  // old seeds before this cell
    const int* t = c.taken.find(e.second);
    if (!(t && *t)) seed_at(I, g, o, res, e.second, c);
    close_old(e, true);
  }
  I.void_clusters = std::move(c.clusters);
  I.void_seeds = std::move(c.seeds);
  detail::KeyTable<int> of(order.size());
  for (std::size_t i = 0; i < I.void_clusters.size(); ++i)
    for (CellKey k : I.void_clusters[i].cells) of.at(k) = int(i) + 1;
  I.void_cluster_of = std::move(of);
  I.void_order = std::move(order);
  I.void_added.clear();
  I.void_removed.clear();
}

}  // namespace

std::vector<VoidCluster> ExplorationMap::void_clusters() const {
  detail::MapGuard guard(*state_, false);
  return detail::cached_void_clusters(*this);
}

std::vector<VoidCluster> ExplorationMap::void_clusters_from_scratch() const {
  detail::MapGuard guard(*state_, false);
  const auto& I = *state_;
  const detail::GridReader g(I.grid);
  Order order;
  for (CellKey k : I.void_set) order.emplace_back(priority(k, options_.seed), k);
  std::sort(order.begin(), order.end());
  const std::vector<VoidCluster> none;
  const std::vector<CellKey> no_seeds;
  const detail::KeyTable<int> no_cells;
  Clustering c{none, no_seeds, no_cells, {}, {}, {}, detail::KeyTable<int>(order.size()),
               detail::KeyTable<int>(order.size() / 4)};
  for (const auto& e : order) {
    const int* t = c.taken.find(e.second);
    if (!(t && *t)) seed_at(I, g, options_, resolution_, e.second, c);
  }
  return std::move(c.clusters);
}

const std::vector<VoidCluster>& detail::cached_void_clusters(const ExplorationMap& map) {
  auto& I = detail::state(map);
  std::lock_guard<std::mutex> lock(I.cache_mutex);
  if (!I.voids_dirty) return I.void_clusters;
  update_clusters(I, map.options(), map.resolution());
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
