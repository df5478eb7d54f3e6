// Void clustering: ellipsoid region growing (eq. 2, see VoidCluster), kept up to date incrementally
// after each insert, and frontier-voids.
//
// Seeds are taken in a fixed priority order of the cells (a mix of the key and the map's seed): a
// cluster is grown from the first cell in that order no cluster holds yet. So the clustering of a set
// of void cells does not depend on how it came about, and after an insert only the clusters the
// changes can reach are grown again. The seed positions are replayed in priority order (a heap of the
// old seeds, the added cells and the cells of every cluster that became dirty); a cluster whose seed
// comes up and which is not dirty is reused as it was, every other one is grown anew. A cluster becomes
// dirty (while its seed has not come up) when one of its cells or their 26-neighbours is marked: a
// void cell added or removed, a cell that joins a cluster of another seed than before, or a cell of an
// old cluster missing from its successor when that old cluster's seed comes up. The growth of a cluster
// reads only its cells, their neighbours, whether those are void and whether a cluster of an earlier
// seed holds them; none of that can have changed for a cluster that is not dirty when its seed comes
// up, so the result equals the clustering from scratch (void_clusters_from_scratch), cluster for
// cluster, in the same order. Cost: the changed region and the clusters it touches, plus copying the
// clusters out (no pass over every void cell's hash entry).
#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <vector>

#include <Eigen/Eigenvalues>

#include "exploration/cell_sets.hpp"
#include "common/random_mix.hpp"
#include "exploration/exploration_state.hpp"
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

std::uint64_t priority(CellKey k, std::uint64_t seed) { return detail::mix64(seed, k); }

// Grows a cluster from seed s over void 26-neighbours that are still free while the score stays >=
// threshold. is_free(k) / take(k): whether a cell is taken by no cluster yet / takes it; tried: the
// cluster number (+1) that last rejected a cell. Returns the members (seed first, in joining order).
template <class IsFree, class Take>
std::vector<CellKey> grow(const detail::GridReader& g, CellKey s, int cid, double threshold, IsFree&& is_free,
                          Take&& take, detail::KeyTable<int>& tried, Moments& m, double& score) {
  auto rel = [&](CellKey k) {
    return Eigen::Vector3d(int(key_x(k)) - int(key_x(s)), int(key_y(k)) - int(key_y(s)), int(key_z(k)) - int(key_z(s)));
  };
  take(s);
  std::vector<CellKey> members{s};
  score = m.score();
  for (std::size_t qi = 0; qi < members.size(); ++qi) {  // members double as the queue
    const CellKey k = members[qi];
    for (const auto& d : detail::kN26.d) {
      CellKey nb;
      if (!detail::neighbour(k, d[0], d[1], d[2], nb) || !(g.get(nb) & detail::kVoidFlag) || !is_free(nb)) continue;
      const int* r = tried.find(nb);
      if (r && *r == cid + 1) continue;
      Moments next = m.plus(rel(nb));
      double sc = next.score();
      if (sc >= threshold) {
        m = next;
        score = sc;
        take(nb);
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

// The clusters kept in slots (the map's, or empty ones for a clustering from scratch).
struct Slots {
  std::vector<VoidCluster>& cluster;
  std::vector<CellKey>& seed;
  detail::KeyTable<int>& of;  // cell -> slot + 1 (0: none)
};

// One update of the kept clusters: the seed positions are replayed in priority order from a heap that
// holds the old seeds, the added cells and the cells of every cluster that became dirty.
class Replay {
 public:
  Replay(const detail::ExplorationState& I, const ExplorationOptions& o, double res, Slots slots)
      : I_(I), g_(I.grid), o_(o), res_(res), s_(slots), dirty_(slots.cluster.size(), 0),
        passed_(slots.cluster.size(), 0), reused_(slots.cluster.size(), 0) {
    for (std::size_t j = 0; j < s_.cluster.size(); ++j)
      if (!s_.cluster[j].cells.empty()) push(s_.seed[j]);
  }
  void added(CellKey k) {
    push(k);
    mark(k);
  }
  void removed(CellKey k) { mark(k); }
  // Runs the replay and stores the result in the slots; returns the clusters in seed order.
  std::vector<VoidCluster> run();
  std::size_t reused() const { return std::size_t(std::count(reused_.begin(), reused_.end(), 1)); }

 private:
  using Entry = std::pair<std::uint64_t, CellKey>;
  void push(CellKey k) { heap_.emplace(priority(k, o_.seed), k); }
  int old_slot(CellKey k) const {
    const int* j = s_.of.find(k);
    return j ? *j - 1 : -1;
  }
  // The old clusters holding k or a 26-neighbour of k whose seed has not come up yet become dirty;
  // their cells may now start clusters, so they join the heap.
  void mark(CellKey k) {
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          CellKey nb;
          if (!detail::neighbour(k, dx, dy, dz, nb)) continue;
          const int j = old_slot(nb);
          if (j < 0 || dirty_[std::size_t(j)] || passed_[std::size_t(j)]) continue;
          dirty_[std::size_t(j)] = 1;
          for (CellKey c : s_.cluster[std::size_t(j)].cells) push(c);
        }
  }
  // The seed of the cluster holding k now (~0: none yet).
  CellKey seed_now(CellKey k) const {
    if (const int* n = now_.find(k); n && *n) return new_seed_[std::size_t(*n - 1)];
    const int j = old_slot(k);
    return j >= 0 && reused_[std::size_t(j)] ? s_.seed[std::size_t(j)] : ~CellKey(0);
  }
  bool intact(std::size_t j) const {  // a safeguard: the replay's argument says it always holds
    for (CellKey k : s_.cluster[j].cells)
      if (seed_now(k) != ~CellKey(0) || !(g_.get(k) & detail::kVoidFlag)) return false;
    return true;
  }
  void grow_from(CellKey s);

  const detail::ExplorationState& I_;
  const detail::GridReader g_;
  const ExplorationOptions& o_;
  const double res_;
  Slots s_;
  std::vector<char> dirty_, passed_, reused_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap_;
  detail::KeyTable<int> now_, tried_;  // cell -> new cluster + 1; cell -> rejecting cluster + 1
  std::vector<VoidCluster> new_clusters_;
  std::vector<CellKey> new_seed_;
};

void Replay::grow_from(CellKey s) {
  const int cid = int(new_clusters_.size());
  new_seed_.push_back(s);
  Moments m;
  double score = 0;
  std::vector<CellKey> members =
      grow(g_, s, cid, o_.void_fit_threshold, [&](CellKey k) { return seed_now(k) == ~CellKey(0); },
           [&](CellKey k) { now_.at(k) = cid + 1; }, tried_, m, score);
  for (CellKey k : members) {  // cells that joined a cluster of another seed than before
    const int j = old_slot(k);
    if (j < 0 || s_.seed[std::size_t(j)] != s) mark(k);
  }
  new_clusters_.push_back(make_cluster(I_, s, std::move(members), m, score, res_));
}

std::vector<VoidCluster> Replay::run() {
  Entry last{0, ~CellKey(0)};
  bool first = true;
  while (!heap_.empty()) {
    const Entry e = heap_.top();
    heap_.pop();
    if (!first && e == last) continue;
    first = false;
    last = e;
    const CellKey k = e.second;
    const int j = old_slot(k);
    const bool old_seed = j >= 0 && s_.seed[std::size_t(j)] == k && !s_.cluster[std::size_t(j)].cells.empty();
    if (old_seed) passed_[std::size_t(j)] = 1;
    if ((g_.get(k) & detail::kVoidFlag) && seed_now(k) == ~CellKey(0)) {
      if (old_seed && !dirty_[std::size_t(j)] && intact(std::size_t(j)))
        reused_[std::size_t(j)] = 1;
      else
        grow_from(k);
    }
    if (old_seed && !reused_[std::size_t(j)]) {  // its cells not in its successor are marked
      if (!dirty_[std::size_t(j)]) {  // (only when the safeguard failed) its cells may start clusters
        dirty_[std::size_t(j)] = 1;
        for (CellKey c : s_.cluster[std::size_t(j)].cells) push(c);
      }
      for (CellKey c : s_.cluster[std::size_t(j)].cells)
        if (seed_now(c) != k) mark(c);
    }
  }
  // the slots: free the clusters not reused, then place the new ones
  std::vector<int> free;
  for (std::size_t j = 0; j < s_.cluster.size(); ++j) {
    if (reused_[j]) continue;
    for (CellKey c : s_.cluster[j].cells) s_.of.at(c) = 0;
    s_.cluster[j] = VoidCluster();
    free.push_back(int(j));
  }
  std::reverse(free.begin(), free.end());
  for (std::size_t i = 0; i < new_clusters_.size(); ++i) {
    int j;
    if (free.empty()) {
      j = int(s_.cluster.size());
      s_.cluster.emplace_back();
      s_.seed.push_back(0);
    } else {
      j = free.back();
      free.pop_back();
    }
    for (CellKey c : new_clusters_[i].cells) s_.of.at(c) = j + 1;
    s_.cluster[std::size_t(j)] = std::move(new_clusters_[i]);
    s_.seed[std::size_t(j)] = new_seed_[i];
  }
  // the clusters in seed order (the order of a clustering from scratch)
  std::vector<Entry> order;
  for (std::size_t j = 0; j < s_.cluster.size(); ++j)
    if (!s_.cluster[j].cells.empty()) order.emplace_back(priority(s_.seed[j], o_.seed), CellKey(j));
  std::sort(order.begin(), order.end());
  std::vector<VoidCluster> out;
  out.reserve(order.size());
  for (const auto& e : order) out.push_back(s_.cluster[std::size_t(e.second)]);
  return out;
}

}  // namespace

std::vector<VoidCluster> ExplorationMap::void_clusters() const {
  detail::MapGuard guard(*state_, false);
  return detail::cached_void_clusters(*this);
}

std::vector<VoidCluster> ExplorationMap::void_clusters_from_scratch() const {
  detail::MapGuard guard(*state_, false);
  std::vector<VoidCluster> clusters;
  std::vector<CellKey> seeds;
  detail::KeyTable<int> of;
  Replay r(*state_, options_, resolution_, Slots{clusters, seeds, of});
  for (CellKey k : state_->void_set) r.added(k);
  return r.run();
}

const std::vector<VoidCluster>& detail::cached_void_clusters(const ExplorationMap& map) {
  auto& I = detail::state(map);
  std::lock_guard<std::mutex> lock(I.cache_mutex);
  if (!I.voids_dirty) return I.void_clusters;
  Replay r(I, map.options(), map.resolution(), Slots{I.void_slots, I.void_slot_seed, I.void_slot_of});
  for (CellKey k : I.void_added)
    if (I.grid.get(k) & detail::kVoidFlag) r.added(k);
  for (CellKey k : I.void_removed) r.removed(k);
  I.void_clusters = r.run();
  I.void_added.clear();
  I.void_removed.clear();
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
