#include "maps/capability_build.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "common/random_mix.hpp"
#include "common/thread_pool.hpp"
#include "kinematics/chain_checks.hpp"
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
      rotations_(set.size()), seed_row_(box.cells, -1), status_(box.cells, kUntried), started_(box.cells, 0),
      sol_row_(box.cells, -1) {
  for (int i = 0; i < set.size(); ++i) rotations_[i] = set.rotation(i, approach_axis);
  base_ik_.mode = set.rolls() > 1 ? IkMode::Full : IkMode::Approach;
  base_ik_.position_tolerance = o.position_tolerance;
  base_ik_.orientation_tolerance = o.orientation_tolerance;
  base_ik_.approach_axis = approach_axis;
  base_ik_.check_self_collision = o.self_collision;
  base_ik_.check_fixed_pairs = false;  // checked once by CapabilityMap::build
  base_ik_.reference = reference;
  base_ik_.max_iterations = 25;  // seeds are near: a cell that needs more is almost always unreachable
  base_ik_.stall_window = 2;     // most cells tried are unreachable: stop their descents once they stall
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
  // Cells with a seed, one bit each: the samples' test reads these 1.4 MB (PR2 arm at 0.05 m), not seed_row_'s 45.
  std::vector<std::uint64_t> seeded((box_.cells + 63) / 64, 0);
  for (std::size_t c = 0; c < box_.cells; ++c)
    if (seed_row_[c] >= 0) seeded[c >> 6] |= 1ULL << (c & 63);
  const std::size_t nchunks = (samples + chunk - 1) / chunk;
  for (std::size_t round = 0; round * chunks_per_round < nchunks; ++round) {
    std::size_t c0 = round * chunks_per_round, c1 = std::min(nchunks, c0 + chunks_per_round);
    // Per chunk: the cells its samples hit that had no seed before this round, and their samples (dof
    // floats each, flat); a cell hit twice keeps its first sample when the chunks are merged in order.
    std::vector<std::vector<std::uint32_t>> hit(c1 - c0);
    std::vector<std::vector<float>> hit_q(c1 - c0);
    detail::parallel_for(c1 - c0, o_.threads, [&](std::size_t ci, int) {
      std::mt19937_64 r(detail::mix64(o_.seed, c0 + ci));
      std::size_t n = std::min(chunk, samples - (c0 + ci) * chunk);
      hit[ci].reserve(n);
      hit_q[ci].reserve(n * dof_);
      Eigen::VectorXd q(dof_);
      for (std::size_t s = 0; s < n; ++s) {
        chain_.random_configuration(r, q);
        const Pose T = chain_.fk_jacobian(q.data(), nullptr);
        std::size_t v;
        if (!box_.voxel_of(T.translation(), v)) continue;
        std::uint32_t cell = static_cast<std::uint32_t>(v * O + set_.nearest(T.linear(), base_ik_.approach_axis));
        if ((seeded[cell >> 6] >> (cell & 63)) & 1ULL) continue;
        hit[ci].push_back(cell);
        for (int k = 0; k < dof_; ++k) hit_q[ci].push_back(static_cast<float>(q[k]));
      }
    }, 1);
    for (std::size_t ci = 0; ci < hit.size(); ++ci)
      for (std::size_t i = 0; i < hit[ci].size(); ++i)
        if (seed_row_[hit[ci][i]] < 0) {
          seeded[hit[ci][i] >> 6] |= 1ULL << (hit[ci][i] & 63);
          seed_row_[hit[ci][i]] = static_cast<std::int32_t>(seed_pool_.size() / dof_);
          seed_pool_.insert(seed_pool_.end(), hit_q[ci].begin() + i * dof_, hit_q[ci].begin() + (i + 1) * dof_);
        }
    report(0.0, 0.15, double(c1) / nchunks);
  }
  return samples;
}

void CapabilityBuilder::run_wave(const std::vector<Item>& wave, const std::vector<float>& pool, int attempts,
                                 std::vector<std::uint32_t>& newly) {
  const int O = box_.O, dof = dof_;
  std::vector<float> results(wave.size() * dof);
  std::vector<char> ok(wave.size(), 0);
  // Per thread: the options (copied once per wave, not per call: they hold the reference posture) and the seed.
  const int threads = detail::default_threads(o_.threads);
  std::vector<IkOptions> options(threads, base_ik_);
  std::vector<Eigen::VectorXd> seeds(threads, Eigen::VectorXd(dof));
  detail::parallel_for(wave.size(), threads, [&](std::size_t i, int tid) {
    const Item& it = wave[i];
    IkOptions& opt = options[tid];
    opt.attempts = attempts;
    opt.seed = detail::mix64(o_.seed ^ 0xC0FFEEULL, it.cell);
    Pose target = Pose::Identity();
    target.linear() = rotations_[it.cell % O];
    target.translation() = box_.centre(it.cell / O);
    Eigen::VectorXd& s = seeds[tid];
    if (it.seed >= 0)
      s = Eigen::Map<const Eigen::VectorXf>(pool.data() + static_cast<std::size_t>(it.seed) * dof, dof).cast<double>();
    auto q = detail::ik_checked(chain_, target, opt, it.seed >= 0 ? &s : nullptr);
    if (q) {
      Eigen::Map<Eigen::VectorXf>(results.data() + i * dof, dof) = q->cast<float>();
      ok[i] = 1;
    }
  }, 8);
  ik_calls_ += wave.size();
  newly.clear();
  for (std::size_t i = 0; i < wave.size(); ++i) {
    std::uint32_t c = wave[i].cell;
    if (ok[i]) {
      status_[c] = kReachable;
      ++reachable_;
      sol_row_[c] = static_cast<std::int32_t>(sol_pool_.size() / dof);
      sol_pool_.insert(sol_pool_.end(), results.begin() + i * dof, results.begin() + (i + 1) * dof);
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
  const int threads = detail::default_threads(o_.threads);
  constexpr std::size_t kSpan = 4096;  // frontier cells per task of the neighbour search
  std::vector<std::vector<Item>> found;
  std::vector<std::vector<std::uint32_t>> nb(threads);
  while (!frontier.empty()) {
    // The untried neighbours of the frontier cells, found on every core; then claimed in frontier order, so that a
    // cell named by several frontier cells gets the first one's solution whatever the thread count.
    found.resize((frontier.size() + kSpan - 1) / kSpan);
    detail::parallel_for(found.size(), threads, [&](std::size_t t, int tid) {
      found[t].clear();
      for (std::size_t i = t * kSpan; i < std::min(frontier.size(), (t + 1) * kSpan); ++i) {
        box_.neighbours(frontier[i], set_, nb[tid]);
        for (std::uint32_t n : nb[tid])
          if (status_[n] == kUntried) found[t].push_back({n, sol_row_[frontier[i]]});
      }
    }, 1);
    std::vector<Item> wave;
    for (const std::vector<Item>& items : found)
      for (const Item& it : items)
        if (status_[it.cell] == kUntried) {
          status_[it.cell] = kQueued;
          wave.push_back(it);
        }
    // Every cell of a wave gets its neighbour's solution; a sampled cell that fails keeps its sample for the retries.
    run_wave(wave, sol_pool_, 1, frontier);
    report(0.15, 0.8, std::min(1.0, double(reachable_) / std::max<std::size_t>(1, seed_pool_.size() / dof_) * 0.9));
  }
}

// The retries of the cells the floods failed, in two passes. First (samples) the own forward-kinematics sample
// that no descent started from yet of every failed cell with at least a quarter of its neighbours reachable: a
// configuration in the cell, often of another IK branch than the neighbour's the cell failed with, in which the
// cell is reachable (without these retries the test arm's maps miss twice as many of the cells IK reaches). A cell
// with fewer reachable neighbours lies where the set ends, and its sample rarely reaches it (under 1 % with at
// most 2 of 12 on the PR2 arm at 0.05 m, against 3 % with 3 and 77 % with 7 or more): it stays a mixed cell, whose
// sample the certified lookup starts IK from. Then (neighbours) a failed cell most of whose neighbours are
// reachable gets another reachable neighbour's solution than the one it failed with (IK from the same seed at the
// same target repeats the same descent): inside the reachable set a cell is likely reachable itself, and its seed
// sat on the wrong side of a joint limit or a collision; a cell with fewer reachable neighbours than unreachable
// ones lies where the set ends. On the PR2 arm at 0.05 m a neighbour's solution recovers about 75 % of the cells
// inside the set and under 2 % of the others, cells the certified lookup answers by IK anyway (their neighbours
// disagree).
std::vector<CapabilityBuilder::Item> CapabilityBuilder::retry_items(bool samples) const {
  std::vector<Item> retry;
  std::vector<std::uint32_t> nb;
  for (std::uint32_t c = 0; c < box_.cells; ++c) {
    if (status_[c] != kFailed) continue;
    if (samples && (seed_row_[c] < 0 || started_[c])) continue;
    box_.neighbours(c, set_, nb);
    std::size_t k = 0;
    std::int32_t seed = -1;
    for (std::uint32_t n : nb)
      if (status_[n] == kReachable) {
        ++k;
        if (seed < 0 && sol_row_[n] != sol_row_[c]) seed = sol_row_[n];
      }
    if (samples) {
      if (4 * k >= nb.size()) retry.push_back({c, seed_row_[c]});
      continue;
    }
    if (2 * k > nb.size() && seed >= 0) retry.push_back({c, seed});
  }
  return retry;
}

// The flood starts from a sparse share of the cells forward-kinematics sampling hit, each with its own sample as
// the seed, and the flood then reaches most of the others from a reachable neighbour: a neighbour's solution is
// collision-free and one cell away, so its descent converges in two or three steps and rarely ends in collision,
// where a random sample often does (a seed in self-collision leads IK to a solution in collision). Each start's IK
// branch spreads only as far as the next start's: the configurations stored around a pose then come from several
// branches, and the certified lookup starts its descents from them (with one start in 64 the held-out G1 arm's
// certified false negatives were 0.6 %, above the 0.5 % target; with one in 16, 0.2-0.3 %, as with every sample a
// start). Passes over the sampled cells the floods have not reached go on while they find reachable cells (a piece
// of the reachable set that no earlier start lay in); a pass that finds none ends the starts. Those cells keep
// their samples as mixed cells, which the certified lookup answers by IK.
void CapabilityBuilder::start_floods() {
  std::vector<std::uint32_t> untried, newly;
  for (std::uint32_t c = 0; c < box_.cells; ++c)
    if (seed_row_[c] >= 0) untried.push_back(c);
  for (bool first = true; !untried.empty(); first = false) {
    // One cell in kStartShare; the first pass at least kStartMin (or all: a small map starts from every sample,
    // for as many branches as the cells can store), a later one at least kPassMin, so that a pass that finds
    // nothing has looked.
    const std::size_t floor = first ? kStartMin : kPassMin;
    const std::size_t want = std::min(untried.size(), std::max(untried.size() / kStartShare, floor));
    std::vector<Item> wave;
    wave.reserve(want);
    for (std::size_t i = 0; i < want; ++i) {
      const std::uint32_t c = untried[i * untried.size() / want];
      wave.push_back({c, seed_row_[c]});
      status_[c] = kQueued;
      started_[c] = 1;
    }
    run_wave(wave, seed_pool_, 1, newly);
    // A start its sample did not reach stays open to the floods: a neighbour's solution may reach it.
    for (const Item& it : wave)
      if (status_[it.cell] == kFailed) status_[it.cell] = kUntried;
    if (newly.empty()) break;
    flood(newly);
    untried.erase(std::remove_if(untried.begin(), untried.end(),
                                 [&](std::uint32_t c) { return status_[c] != kUntried || started_[c]; }),
                  untried.end());
  }
  for (std::uint32_t c = 0; c < box_.cells; ++c)  // starts no flood reached
    if (started_[c] && status_[c] == kUntried) status_[c] = kFailed;
}

void CapabilityBuilder::stage(const std::string& what) const {
  if (debug_)
    std::fprintf(stderr, "capability map: %s (%.2f s)\n", what.c_str(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
}

void CapabilityBuilder::solve() {
  start_floods();
  stage("after the floods " + std::to_string(ik_calls_) + " calls");
  std::vector<std::uint32_t> newly;
  // The retries (retry_items): samples, then neighbours' solutions; a second round of the neighbours' recovered
  // about 1 % of what it tried on the PR2 arm.
  for (const bool samples : {true, false}) {
    const std::vector<Item> retry = retry_items(samples);
    if (retry.empty()) continue;
    // A failed sample keeps the row of the neighbour's solution the cell failed with (run_wave stores -1 for
    // a seed from seed_pool_), so that the second pass does not repeat that descent.
    std::vector<std::int32_t> failed_with(retry.size());
    for (std::size_t i = 0; i < retry.size(); ++i) failed_with[i] = sol_row_[retry[i].cell];
    run_wave(retry, samples ? seed_pool_ : sol_pool_, 1, newly);
    if (samples)
      for (std::size_t i = 0; i < retry.size(); ++i)
        if (status_[retry[i].cell] == kFailed) sol_row_[retry[i].cell] = failed_with[i];
    stage(std::string("retry with ") + (samples ? "samples: " : "neighbours: ") + std::to_string(retry.size()) +
          " cells, " + std::to_string(newly.size()) + " recovered");
    if (!newly.empty()) flood(newly);
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
