#include "maps/capability_build.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <unordered_set>

#include "common/random_mix.hpp"
#include "common/thread_pool.hpp"
#include "maps/map_io.hpp"
#include "octoreach/manipulability.hpp"

namespace octoreach::detail {

CellBox CellBox::around_workspace(const Chain& chain, const VoxelOcTree& tree, int orientations, std::uint64_t seed) {
  const double res = tree.getResolution();
  std::mt19937_64 rng(seed);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = Eigen::Vector3d::Constant(-1e9);
  for (int i = 0; i < 20000; ++i) {
    Eigen::Vector3d p = chain.fk(chain.random_configuration(rng)).translation();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo.array() -= 1.5 * res;
  hi.array() += 1.5 * res;
  CellBox b;
  b.tree = &tree;
  octomap::OcTreeKey kmax;
  if (!tree.coordToKeyChecked(lo.x(), lo.y(), lo.z(), b.kmin) || !tree.coordToKeyChecked(hi.x(), hi.y(), hi.z(), kmax))
    throw std::invalid_argument("the arm's workspace does not fit an octree at this resolution");
  b.nx = kmax[0] - b.kmin[0] + 1;
  b.ny = kmax[1] - b.kmin[1] + 1;
  b.nz = kmax[2] - b.kmin[2] + 1;
  b.O = orientations;
  b.voxels = static_cast<std::size_t>(b.nx) * b.ny * b.nz;
  b.cells = b.voxels * orientations;
  if (b.cells > limits::kCapabilityCells)
    throw std::invalid_argument("resolution " + format_number(res) + " with " + std::to_string(orientations) +
                                " orientations gives " + std::to_string(b.cells) + " cells: too many");
  return b;
}

bool CellBox::voxel_of(const Eigen::Vector3d& p, std::size_t& v) const {
  octomap::OcTreeKey k;
  if (!tree->coordToKeyChecked(p.x(), p.y(), p.z(), k)) return false;
  int ix = k[0] - kmin[0], iy = k[1] - kmin[1], iz = k[2] - kmin[2];
  if (ix < 0 || iy < 0 || iz < 0 || ix >= nx || iy >= ny || iz >= nz) return false;
  v = (static_cast<std::size_t>(ix) * ny + iy) * nz + iz;
  return true;
}

octomap::OcTreeKey CellBox::key(std::size_t v) const {
  int iz = v % nz, iy = (v / nz) % ny, ix = v / (static_cast<std::size_t>(ny) * nz);
  return octomap::OcTreeKey(kmin[0] + ix, kmin[1] + iy, kmin[2] + iz);
}

Eigen::Vector3d CellBox::centre(std::size_t v) const {
  octomap::point3d c = tree->keyToCoord(key(v));
  return Eigen::Vector3d(c.x(), c.y(), c.z());
}

void CellBox::neighbours(std::uint32_t cell, const OrientationSet& set, std::vector<std::uint32_t>& out) const {
  out.clear();
  std::size_t v = cell / O;
  int oi = cell % O;
  int di = oi / set.rolls(), ri = oi % set.rolls();
  int iz = v % nz, iy = (v / nz) % ny, ix = v / (static_cast<std::size_t>(ny) * nz);
  const int d[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& s : d) {
    int jx = ix + s[0], jy = iy + s[1], jz = iz + s[2];
    if (jx < 0 || jy < 0 || jz < 0 || jx >= nx || jy >= ny || jz >= nz) continue;
    out.push_back(static_cast<std::uint32_t>(((static_cast<std::size_t>(jx) * ny + jy) * nz + jz) * O + oi));
  }
  for (int dn : set.neighbours(di)) out.push_back(static_cast<std::uint32_t>(v * O + dn * set.rolls() + ri));
  if (set.rolls() > 1) {
    out.push_back(static_cast<std::uint32_t>(v * O + di * set.rolls() + (ri + 1) % set.rolls()));
    out.push_back(static_cast<std::uint32_t>(v * O + di * set.rolls() + (ri + set.rolls() - 1) % set.rolls()));
  }
}

CapabilityBuilder::CapabilityBuilder(const Chain& chain, const CapabilityMapOptions& o, const OrientationSet& set,
                                     const Eigen::Vector3d& approach_axis, const Eigen::VectorXd& reference,
                                     const CellBox& box, const ProgressCallback& progress)
    : chain_(chain), o_(o), set_(set), box_(box), progress_(progress), dof_(chain.dof()),
      rotations_(set.size()), seed_row_(box.cells, -1), status_(box.cells, kUntried), sol_row_(box.cells, -1) {
  for (int i = 0; i < set.size(); ++i) rotations_[i] = set.rotation(i, approach_axis);
  base_ik_.mode = set.rolls() > 1 ? IkMode::Full : IkMode::Approach;
  base_ik_.position_tolerance = o.position_tolerance;
  base_ik_.orientation_tolerance = o.orientation_tolerance;
  base_ik_.approach_axis = approach_axis;
  base_ik_.check_self_collision = o.self_collision;
  base_ik_.check_fixed_pairs = false;  // checked once by CapabilityMap::build
  base_ik_.reference = reference;
  base_ik_.max_iterations = 25;  // seeds are near: a cell that needs more is almost always unreachable
  base_ik_.stall_window = 3;     // most cells tried are unreachable: stop their descents once they stall
}

void CapabilityBuilder::report(double start, double share, double fraction) const {
  if (!progress_) return;
  auto done = static_cast<std::size_t>(1000.0 * (start + share * std::min(1.0, fraction)));
  if (!progress_(done, 1000)) throw Cancelled("capability map build cancelled");
}

std::size_t CapabilityBuilder::sample() {
  const int O = box_.O;
  const std::size_t samples = o_.fk_samples ? o_.fk_samples : 40 * box_.voxels;
  if (samples > limits::kFkSamples)
    throw std::invalid_argument("40 forward-kinematics samples per voxel of the workspace box (" +
                                std::to_string(box_.voxels) + " voxels) are more than the limit of " +
                                std::to_string(limits::kFkSamples) + ": use a coarser resolution or give fk_samples");
  const std::size_t chunk = 8192, chunks_per_round = 16;
  const std::size_t nchunks = (samples + chunk - 1) / chunk;
  for (std::size_t round = 0; round * chunks_per_round < nchunks; ++round) {
    std::size_t c0 = round * chunks_per_round, c1 = std::min(nchunks, c0 + chunks_per_round);
    std::vector<std::vector<std::pair<std::uint32_t, Eigen::VectorXf>>> found(c1 - c0);
    detail::parallel_for(c1 - c0, o_.threads, [&](std::size_t ci, int) {
      std::mt19937_64 r(detail::mix64(o_.seed, c0 + ci));
      std::size_t n = std::min(chunk, samples - (c0 + ci) * chunk);
      std::unordered_set<std::uint32_t> local;
      for (std::size_t s = 0; s < n; ++s) {
        Eigen::VectorXd q = chain_.random_configuration(r);
        Pose T = chain_.fk(q);
        std::size_t v;
        if (!box_.voxel_of(T.translation(), v)) continue;
        std::uint32_t cell = static_cast<std::uint32_t>(v * O + set_.nearest(T.linear(), base_ik_.approach_axis));
        if (seed_row_[cell] >= 0 || !local.insert(cell).second) continue;
        found[ci].emplace_back(cell, q.cast<float>());
      }
    }, 1);
    for (auto& list : found)
      for (auto& [cell, q] : list)
        if (seed_row_[cell] < 0) {
          seed_row_[cell] = static_cast<std::int32_t>(seed_pool_.size() / dof_);
          seed_pool_.insert(seed_pool_.end(), q.data(), q.data() + dof_);
        }
    report(0.0, 0.15, double(c1) / nchunks);
  }
  return samples;
}

void CapabilityBuilder::run_wave(const std::vector<Item>& wave, const std::vector<float>& pool, int attempts,
                                 std::vector<std::uint32_t>& newly) {
  const int O = box_.O, dof = dof_;
  std::vector<Eigen::VectorXf> results(wave.size());
  std::vector<char> ok(wave.size(), 0);
  detail::parallel_for(wave.size(), o_.threads, [&](std::size_t i, int) {
    const Item& it = wave[i];
    IkOptions opt = base_ik_;
    opt.attempts = attempts;
    opt.seed = detail::mix64(o_.seed ^ 0xC0FFEEULL, it.cell);
    Pose target = Pose::Identity();
    target.linear() = rotations_[it.cell % O];
    target.translation() = box_.centre(it.cell / O);
    Eigen::VectorXd s;
    if (it.seed >= 0)
      s = Eigen::Map<const Eigen::VectorXf>(pool.data() + static_cast<std::size_t>(it.seed) * dof, dof).cast<double>();
    auto q = chain_.ik(target, opt, it.seed >= 0 ? &s : nullptr);
    if (q) {
      results[i] = q->cast<float>();
      ok[i] = 1;
    }
  }, 8);
  ik_calls_ += wave.size();
  newly.clear();
  for (std::size_t i = 0; i < wave.size(); ++i) {
    std::uint32_t c = wave[i].cell;
    if (ok[i]) {
      status_[c] = kReachable;
      sol_row_[c] = static_cast<std::int32_t>(sol_pool_.size() / dof);
      sol_pool_.insert(sol_pool_.end(), results[i].data(), results[i].data() + dof);
      newly.push_back(c);
    } else {
      status_[c] = kFailed;
      // The solution row tried (flood), kept so that the retry pass does not repeat a call that fails
      // again (the same seed gives the same descent); -1 after wave 0 (its seed is an FK sample).
      sol_row_[c] = &pool == &sol_pool_ ? wave[i].seed : -1;
    }
  }
}

void CapabilityBuilder::flood(std::vector<std::uint32_t> frontier) {
  std::vector<std::uint32_t> nb;
  while (!frontier.empty()) {
    std::vector<Item> wave;
    for (std::uint32_t c : frontier) {
      box_.neighbours(c, set_, nb);
      for (std::uint32_t n : nb)
        if (status_[n] == kUntried) {
          status_[n] = kQueued;
          wave.push_back({n, sol_row_[c]});
        }
    }
    // Cells sampled by FK but not tried yet keep their own seed in wave 0; here the neighbour's solution is used.
    run_wave(wave, sol_pool_, 1, frontier);
    std::size_t reachable = std::count(status_.begin(), status_.end(), kReachable);
    report(0.15, 0.8, std::min(1.0, double(reachable) / std::max<std::size_t>(1, seed_pool_.size() / dof_) * 0.9));
  }
}

// A failed cell next to at least two reachable ones gets another neighbour's solution as its seed (a single
// neighbour's seed can sit on the wrong side of a joint limit or a collision): the first reachable neighbour's
// whose solution is not the seed the cell failed with (IK from the same seed at the same target repeats the same
// descent). One seed: on the PR2 arm at 0.05 m it recovers 74,000 cells in 450,000 calls; three more seeds per
// cell recovered 15,000 more in 560,000 more calls, cells that CertifiedLookup answers by IK anyway (their
// neighbours disagree).
std::vector<CapabilityBuilder::Item> CapabilityBuilder::retry_items() const {
  std::vector<Item> retry;
  std::vector<std::uint32_t> nb;
  for (std::uint32_t c = 0; c < box_.cells; ++c) {
    if (status_[c] != kFailed) continue;
    box_.neighbours(c, set_, nb);
    int k = 0;
    std::int32_t seed = -1;
    for (std::uint32_t n : nb)
      if (status_[n] == kReachable) {
        ++k;
        if (seed < 0 && sol_row_[n] != sol_row_[c]) seed = sol_row_[n];
      }
    if (k >= 2 && seed >= 0) retry.push_back({c, seed});
  }
  return retry;
}

void CapabilityBuilder::solve() {
  const auto t0 = std::chrono::steady_clock::now();  // stage times for OCTOREACH_DEBUG
  auto secs = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  std::vector<Item> wave0;
  for (std::uint32_t c = 0; c < box_.cells; ++c)
    if (seed_row_[c] >= 0) {
      wave0.push_back({c, seed_row_[c]});
      status_[c] = kQueued;
    }
  std::vector<std::uint32_t> newly;
  run_wave(wave0, seed_pool_, 1, newly);
  const char* debug = std::getenv("OCTOREACH_DEBUG");
  if (debug) std::fprintf(stderr, "capability map: wave0 %zu calls, %zu reachable (%.2f s)\n", wave0.size(), newly.size(), secs());
  report(0.15, 0.5, 1.0);
  flood(newly);
  if (debug) std::fprintf(stderr, "capability map: after flood %zu calls (%.2f s)\n", ik_calls_, secs());
  // One retry pass: a second recovered about 1% of what it tried on the PR2 arm.
  std::vector<Item> retry = retry_items();
  if (!retry.empty()) {
    run_wave(retry, sol_pool_, 1, newly);
    if (debug) std::fprintf(stderr, "capability map: retry pass 0: %zu cells, %zu recovered (%.2f s)\n", retry.size(), newly.size(), secs());
    if (!newly.empty()) flood(newly);
    if (debug) std::fprintf(stderr, "capability map: flood after retry: %zu calls (%.2f s)\n", ik_calls_, secs());
  }
  if (o_.exhaustive) {
    std::vector<Item> rest;
    for (std::uint32_t c = 0; c < box_.cells; ++c)
      if (status_[c] == kUntried) rest.push_back({c, -1});
    run_wave(rest, sol_pool_, std::max(1, o_.exhaustive_attempts), newly);
    flood(newly);
  }
  report(0.95, 0.0, 1.0);
}

void CapabilityBuilder::rate() {
  if (!o_.keep_solutions) return;
  const std::size_t rows = sol_pool_.size() / dof_;
  quality_.assign(rows, CellQuality{});
  const int rank = jacobian_rank(chain_);
  // From the stored (float) solution, so that the quality is the one its solution gives when read back.
  detail::parallel_for(rows, o_.threads, [&](std::size_t row, int) {
    const Eigen::VectorXd q =
        Eigen::Map<const Eigen::VectorXf>(sol_pool_.data() + row * dof_, dof_).cast<double>();
    quality_[row].manipulability = static_cast<float>(manipulability(chain_, q, rank));
    quality_[row].penalty = static_cast<float>(joint_limit_penalty(chain_, q));
  }, 256);
}

void CapabilityBuilder::collect(std::size_t v, VoxelCellData& out) const {
  const int O = box_.O;
  out.clear((O + 63) / 64);
  for (int oi = 0; oi < O; ++oi) {
    const std::size_t c = v * O + oi;
    if (status_[c] == kReachable) {
      out.bits[oi >> 6] |= 1ULL << (oi & 63);
      if (!o_.keep_solutions) continue;
      out.solutions.insert(out.solutions.end(), solution(c), solution(c) + dof_);
      out.quality.push_back(quality_.empty() ? CellQuality{} : quality_[sol_row_[c]]);
    } else if (seed_row_[c] >= 0) {
      out.mixed[oi >> 6] |= 1ULL << (oi & 63);
    }
  }
  if (!o_.keep_solutions) return;
  for (int oi = 0; oi < O; ++oi)
    if ((out.mixed[oi >> 6] >> (oi & 63)) & 1ULL) {
      const float* q = seed(v * O + oi);
      out.mixed_solutions.insert(out.mixed_solutions.end(), q, q + dof_);
    }
}

}  // namespace octoreach::detail
