// The block build of a capability map (capability_blocks.hpp): plan, sample once, build blocks
// anywhere, merge. Byte strings between the steps:
//   seeds:  "ORBS" u64 fingerprint, u64 block, u64 samples, u64 n; n x (u32 local cell, dof floats)
//   result: "ORBR" u64 fingerprint, u64 block, u64 samples, u64 ik_calls, u64 voxels, u8 solutions;
//           per voxel: u32 local voxel, its cells as map files hold them (maps/capability_cells.hpp)
#include "octoreach/capability_blocks.hpp"

#include <algorithm>
#include <bitset>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "common/cancel.hpp"
#include "maps/map_io.hpp"
#include "maps/capability_build.hpp"
#include "maps/capability_cells.hpp"

namespace octoreach {
namespace {

constexpr std::uint32_t kSeedsMagic = 0x5342524FU;   // "ORBS"
constexpr std::uint32_t kResultMagic = 0x5242524FU;  // "ORBR"

std::uint64_t fnv(std::uint64_t h, const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001B3ULL;
  return h;
}

std::vector<char> bytes_of(const std::string& s) { return std::vector<char>(s.begin(), s.end()); }

}  // namespace

struct CapabilityBlocks::Plan {
  Plan(const Chain& c, const CapabilityMapOptions& o) : chain(c), options(o) {
    if (options.block_size == 0) options.block_size = default_block_size;
    shell = CapabilityMap::shell_(chain, options, reference);  // checks the options and the reference posture
    box = detail::CellBox::around_workspace(chain, *shell.tree_, shell.orientations_.size(), options.seed);
    B = options.block_size;
    gx = (box.nx + B - 1) / B;
    gy = (box.ny + B - 1) / B;
    gz = (box.nz + B - 1) / B;
    std::uint64_t h = 0xCBF29CE484222325ULL;
    for (const auto& [k, v] : shell.parameters()) {
      h = fnv(h, k.data(), k.size());
      h = fnv(h, v.data(), v.size());
    }
    const std::int64_t more[] = {options.keep_solutions, options.exhaustive_attempts, box.nx, box.ny, box.nz,
                                 box.kmin[0], box.kmin[1], box.kmin[2]};
    h = fnv(h, more, sizeof(more));
    h = fnv(h, reference.data(), sizeof(double) * reference.size());
    fingerprint = h;
  }

  std::size_t count() const { return static_cast<std::size_t>(gx) * gy * gz; }

  detail::CellBox block_box(std::size_t i) const {
    const int bz = static_cast<int>(i % gz), by = static_cast<int>((i / gz) % gy),
              bx = static_cast<int>(i / (static_cast<std::size_t>(gy) * gz));
    detail::CellBox b;
    b.tree = box.tree;
    b.kmin = octomap::OcTreeKey(box.kmin[0] + bx * B, box.kmin[1] + by * B, box.kmin[2] + bz * B);
    b.nx = std::min(B, box.nx - bx * B);
    b.ny = std::min(B, box.ny - by * B);
    b.nz = std::min(B, box.nz - bz * B);
    b.O = box.O;
    b.voxels = static_cast<std::size_t>(b.nx) * b.ny * b.nz;
    b.cells = b.voxels * b.O;
    return b;
  }

  /// Block and local voxel of voxel v of the whole box.
  void locate(std::size_t v, std::size_t& block, std::size_t& local) const {
    const int iz = static_cast<int>(v % box.nz), iy = static_cast<int>((v / box.nz) % box.ny),
              ix = static_cast<int>(v / (static_cast<std::size_t>(box.ny) * box.nz));
    block = (static_cast<std::size_t>(ix / B) * gy + iy / B) * gz + iz / B;
    const int bny = std::min(B, box.ny - (iy / B) * B), bnz = std::min(B, box.nz - (iz / B) * B);
    local = (static_cast<std::size_t>(ix % B) * bny + iy % B) * bnz + iz % B;
  }

  /// Voxel index in the whole box of local voxel `local` of block box `b`.
  std::size_t global(const detail::CellBox& b, std::size_t local) const {
    const octomap::OcTreeKey k = b.key(local);
    return (static_cast<std::size_t>(k[0] - box.kmin[0]) * box.ny + (k[1] - box.kmin[1])) * box.nz + (k[2] - box.kmin[2]);
  }

  /// Reads and checks the fixed part of a seed list or result: magic, fingerprint, block index.
  void check_head(detail::ByteReader& r, std::uint32_t magic, std::size_t block, const char* what) const {
    if (r.remaining() < sizeof(std::uint32_t) || r.get<std::uint32_t>() != magic)
      r.fail(std::string("not a ") + what + " of a capability block build");
    if (r.get<std::uint64_t>() != fingerprint)
      r.fail(std::string("this ") + what + " belongs to another plan (robot, options or octoreach build differ)");
    const auto b = r.get<std::uint64_t>();
    if (b != block)
      r.fail(std::string("this ") + what + " is of block " + std::to_string(b) + ", expected block " + std::to_string(block));
  }

  Chain chain;
  CapabilityMapOptions options;
  Eigen::VectorXd reference;
  CapabilityMap shell;  // parameters, orientations, approach axis and the tree the boxes index
  detail::CellBox box;
  int B = 0, gx = 0, gy = 0, gz = 0;
  std::uint64_t fingerprint = 0;
};

CapabilityBlocks::CapabilityBlocks(const Chain& chain, const CapabilityMapOptions& options)
    : plan_(std::make_shared<const Plan>(chain, options)) {}

CapabilityBlocks::CapabilityBlocks(const Robot& robot, const Arm& arm, const CapabilityMapOptions& options) {
  CapabilityMapOptions o = options;
  o.approach_axis = arm.approach_axis;
  plan_ = std::make_shared<const Plan>(robot.chain(arm.base_link, arm.tip_link), o);
}

std::size_t CapabilityBlocks::count() const { return plan_->count(); }
int CapabilityBlocks::block_size() const { return plan_->B; }
const CapabilityMapOptions& CapabilityBlocks::options() const { return plan_->options; }
std::uint64_t CapabilityBlocks::fingerprint() const { return plan_->fingerprint; }

std::vector<std::string> CapabilityBlocks::sample(const ProgressCallback& progress) const {
  detail::CancellableScope cancellable;
  const Plan& p = *plan_;
  const int O = p.box.O, dof = p.chain.dof();
  detail::CapabilityBuilder builder(p.chain, p.options, p.shell.orientations_, p.shell.approach_axis_, p.reference,
                                    p.box, progress);
  const std::size_t samples = builder.sample();
  std::vector<detail::ByteWriter> body(p.count());
  std::vector<std::uint64_t> n(p.count(), 0);
  for (std::size_t c = 0; c < p.box.cells; ++c) {
    const float* q = builder.seed(c);
    if (!q) continue;
    std::size_t block, local;
    p.locate(c / O, block, local);
    body[block].put(static_cast<std::uint32_t>(local * O + c % O));
    body[block].put_bytes(q, sizeof(float) * dof);
    ++n[block];
  }
  std::vector<std::string> out(p.count());
  for (std::size_t b = 0; b < p.count(); ++b) {
    detail::ByteWriter w;
    w.put(kSeedsMagic);
    w.put(p.fingerprint);
    w.put(static_cast<std::uint64_t>(b));
    w.put(static_cast<std::uint64_t>(samples));
    w.put(n[b]);
    out[b].reserve(w.bytes.size() + body[b].bytes.size());
    out[b].append(w.bytes.data(), w.bytes.size()).append(body[b].bytes.data(), body[b].bytes.size());
    body[b].bytes = {};
  }
  return out;
}

std::size_t CapabilityBlocks::seed_count(const std::string& seeds) {
  const std::size_t at = sizeof(std::uint32_t) + 3 * sizeof(std::uint64_t);
  std::uint64_t n = 0;
  if (seeds.size() < at + sizeof(n)) throw std::invalid_argument("not a seed list of a capability block build");
  std::memcpy(&n, seeds.data() + at, sizeof(n));
  return static_cast<std::size_t>(n);
}

std::string CapabilityBlocks::build_block(std::size_t block, const std::string& seeds,
                                          const ProgressCallback& progress) const {
  detail::CancellableScope cancellable;
  const Plan& p = *plan_;
  if (block >= p.count())
    throw std::invalid_argument("block " + std::to_string(block) + " out of range [0, " + std::to_string(p.count()) + ")");
  const std::vector<char> data = bytes_of(seeds);
  detail::ByteReader r(data, "seed list of block " + std::to_string(block));
  p.check_head(r, kSeedsMagic, block, "seed list");
  const auto samples = r.get<std::uint64_t>(), n = r.get<std::uint64_t>();
  const int dof = p.chain.dof();
  const std::size_t row = sizeof(std::uint32_t) + sizeof(float) * dof;
  if (n > r.remaining() / row || r.remaining() != n * row) r.fail("damaged (its length does not match its seed count)");

  const detail::CellBox bb = p.block_box(block);
  detail::ByteWriter w;
  w.put(kResultMagic);
  w.put(p.fingerprint);
  w.put(static_cast<std::uint64_t>(block));
  w.put(samples);
  if (n == 0 && !p.options.exhaustive) {  // nothing to start from: what solve() would find, without the sweep
    w.put(std::uint64_t{0});
    w.put(std::uint64_t{0});
    w.put(static_cast<std::uint8_t>(p.options.keep_solutions));
    return std::string(w.bytes.begin(), w.bytes.end());
  }
  detail::CapabilityBuilder builder(p.chain, p.options, p.shell.orientations_, p.shell.approach_axis_, p.reference, bb,
                                    progress);
  std::vector<float> q(dof);
  for (std::uint64_t i = 0; i < n; ++i) {
    const auto cell = r.get<std::uint32_t>();
    if (cell >= bb.cells) r.fail("damaged (a cell outside the block)");
    r.get_bytes(q.data(), sizeof(float) * dof);
    builder.add_seed(cell, q.data());
  }
  builder.solve();
  builder.rate();

  detail::ByteWriter cells;
  std::uint64_t voxels = 0;
  detail::VoxelCellData record;
  for (std::size_t v = 0; v < bb.voxels; ++v) {
    builder.collect(v, record);
    if (record.empty()) continue;
    ++voxels;
    cells.put(static_cast<std::uint32_t>(v));
    record.write(cells, p.options.keep_solutions);
  }
  w.put(static_cast<std::uint64_t>(builder.ik_calls()));
  w.put(voxels);
  w.put(static_cast<std::uint8_t>(p.options.keep_solutions));
  w.put_bytes(cells.bytes.data(), cells.bytes.size());
  return std::string(w.bytes.begin(), w.bytes.end());
}

CapabilityMap CapabilityBlocks::merge(const std::vector<std::string>& results) const {
  const Plan& p = *plan_;
  if (results.size() != p.count())
    throw std::invalid_argument("merge needs the results of all " + std::to_string(p.count()) + " blocks, got " +
                                std::to_string(results.size()));
  Eigen::VectorXd reference;
  CapabilityMap m = CapabilityMap::shell_(p.chain, p.options, reference);
  const int dof = p.chain.dof(), words = m.words_;
  struct Voxel {
    std::size_t global;
    detail::VoxelCellData cells;
  };
  std::vector<Voxel> voxels;
  std::uint64_t samples = 0, ik_calls = 0;
  for (std::size_t b = 0; b < results.size(); ++b) {
    const std::vector<char> data = bytes_of(results[b]);
    detail::ByteReader r(data, "result of block " + std::to_string(b));
    p.check_head(r, kResultMagic, b, "result");
    const auto s = r.get<std::uint64_t>();
    if (b > 0 && s != samples) r.fail("its sampling differs from block 0's");
    samples = s;
    ik_calls += r.get<std::uint64_t>();
    const auto n = r.get<std::uint64_t>();
    const bool sols = r.get<std::uint8_t>() != 0;
    if (sols != p.options.keep_solutions) r.fail("damaged (solutions flag)");
    const detail::CellBox bb = p.block_box(b);
    if (n > bb.voxels) r.fail("damaged (more voxels than the block holds)");
    for (std::uint64_t i = 0; i < n; ++i) {
      Voxel v;
      const auto local = r.get<std::uint32_t>();
      if (local >= bb.voxels) r.fail("damaged (a voxel outside the block)");
      v.global = p.global(bb, local);
      v.cells.read(r, words, p.box.O, dof, sols, true);
      voxels.push_back(std::move(v));
    }
    if (!r.done()) r.fail("damaged (trailing bytes)");
  }
  std::sort(voxels.begin(), voxels.end(), [](const Voxel& a, const Voxel& b) { return a.global < b.global; });
  for (const Voxel& v : voxels) m.add_voxel_(p.box.key(v.global), v.cells);
  m.finish_build_(samples, ik_calls, p.box.cells, 0.0);
  return m;
}

CapabilityMap CapabilityBlocks::build(const ProgressCallback& progress) const {
  detail::CancellableScope cancellable;
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::string> seeds = sample(progress);  // reports the first 15 % (as the plain build's sampling)
  std::size_t all = 0, finished = 0;
  for (const auto& s : seeds) all += seed_count(s);
  std::vector<std::string> results(count());
  for (std::size_t b = 0; b < count(); ++b) {  // each block runs on every core; the blocks share 15-95 % by seeds
    finished += seed_count(seeds[b]);
    results[b] = build_block(b, seeds[b]);
    seeds[b] = {};
    if (progress && !progress(150 + 800 * finished / std::max<std::size_t>(1, all), 1000))
      throw Cancelled("capability map build cancelled");
  }
  CapabilityMap m = merge(results);
  m.stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (progress) progress(1000, 1000);
  return m;
}

}  // namespace octoreach
