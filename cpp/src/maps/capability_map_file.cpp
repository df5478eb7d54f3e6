// CapabilityMap files: save() and load(). Format 2 records per voxel its reachable and mixed cells and, with
// solutions, the reachable cells' solutions and quality and the mixed cells' configurations
// (maps/capability_cells.hpp); format 1 files (reachable cells and solutions only) still load, without them.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "octoreach/capability_map.hpp"
#include "octoreach/limits.hpp"
#include "maps/capability_cells.hpp"
#include "maps/map_io.hpp"

namespace octoreach {
namespace {

// The reference posture of a header: finite numbers separated by spaces (empty: none recorded).
Eigen::VectorXd header_reference(const detail::Header& h, const std::string& path) {
  std::istringstream in(detail::header_string(h, "reference", path));
  std::vector<double> values;
  double v;
  while (values.size() <= 100000 && in >> v) values.push_back(v);
  if (!in.eof() || values.size() > 100000 ||
      !std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); }))
    throw FileError("'" + path + "' has a malformed reference posture");
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace

void CapabilityMap::cells_of_(std::uint32_t rec, detail::VoxelCellData& cells) const {
  cells.clear(words_);
  const std::size_t at = std::size_t(rec) * words_;
  std::copy(bits_.begin() + at, bits_.begin() + at + words_, cells.bits.begin());
  if (cell_data_) std::copy(mixed_.begin() + at, mixed_.begin() + at + words_, cells.mixed.begin());
  const std::size_t n = cells.reachable_count(), m = cells.mixed_count();
  if (has_solutions()) {
    const auto first = solutions_.begin() + sol_offset_[rec] * dof_;
    cells.solutions.assign(first, first + n * dof_);
  }
  if (!quality_.empty()) {
    const auto first = quality_.begin() + sol_offset_[rec];
    cells.quality.assign(first, first + n);
  }
  if (!mixed_solutions_.empty()) {
    const auto first = mixed_solutions_.begin() + mixed_offset_[rec] * dof_;
    cells.mixed_solutions.assign(first, first + m * dof_);
  }
}

void CapabilityMap::save(const std::string& path, bool with_solutions) const {
  detail::Header h;
  for (auto& [k, v] : parameters()) h[k] = v;
  bool sols = with_solutions && has_solutions();
  h["solutions"] = sols ? "1" : "0";
  detail::ByteWriter w;
  w.put(static_cast<std::uint64_t>(voxel_count()));
  if (tree_->getRoot()) {
    w.put(std::uint8_t{1});
    detail::VoxelCellData cells;
    write_tree(*tree_, tree_->getRoot(), 0, w, [&](const VoxelNode& n) {
      cells_of_(n.payload, cells);
      cells.write(w, sols, cell_data_);
    });
  } else {
    w.put(std::uint8_t{0});
  }
  detail::write_map_file(path, kKind, h, w.bytes, orientations_.poles() ? kFormatVersion : kFormatVersionWithoutPoles);
}

CapabilityMap CapabilityMap::load(const std::string& path) {
  detail::Header h;
  std::vector<char> payload;
  // The contents the header declares: per voxel a bit per orientation (and one per mixed cell with cell data);
  // with solutions, a joint vector per cell (and a quality per reachable cell with cell data). The counts are
  // checked before they are multiplied.
  detail::read_map_file(path, kKind, h, payload, [&](const detail::Header& head) {
    const long long dirs = detail::header_int(head, "directions", path), rolls = detail::header_int(head, "rolls", path),
                    dof = detail::header_int(head, "dof", path);
    if (dirs < 1 || dirs > OrientationSet::kMaxDirections || rolls < 1 || rolls > OrientationSet::kMaxRolls ||
        dof < 1 || dof > 64)
      throw FileError("'" + path + "' has implausible map parameters");
    const bool cell_data = head.count("cell_data") && detail::header_int(head, "cell_data", path) != 0;
    const std::uint64_t O = std::uint64_t(dirs) * std::uint64_t(rolls);
    std::uint64_t record = (cell_data ? 2 : 1) * ((O + 63) / 64) * sizeof(std::uint64_t);
    if (detail::header_int(head, "solutions", path) != 0)
      record += O * (std::uint64_t(dof) * sizeof(float) + (cell_data ? 2 * sizeof(float) : 0));
    return detail::payload_bound(detail::header_voxels(head, path), record);
  });
  CapabilityMap m;
  using detail::header_double;
  using detail::header_int;
  using detail::header_string;
  m.provenance_ = detail::header_provenance(h, path);
  m.base_link_ = header_string(h, "base_link", path);
  m.tip_link_ = header_string(h, "tip_link", path);
  m.resolution_ = header_double(h, "resolution", path);
  // counts checked at full width before they are narrowed
  const auto dof64 = header_int(h, "dof", path), dirs64 = header_int(h, "directions", path),
             rolls64 = header_int(h, "rolls", path), sym64 = header_int(h, "symmetry", path);
  if (!(m.resolution_ >= limits::kMinMapResolution && m.resolution_ <= limits::kMaxMapResolution) || dirs64 < 1 ||
      dirs64 > OrientationSet::kMaxDirections || rolls64 < 1 || rolls64 > OrientationSet::kMaxRolls || sym64 < 1 ||
      sym64 > 64 || dof64 < 1 || dof64 > 64)
    throw FileError("'" + path + "' has implausible map parameters");
  m.dof_ = static_cast<int>(dof64);
  const int dirs = static_cast<int>(dirs64), rolls = static_cast<int>(rolls64), sym = static_cast<int>(sym64);
  {
    std::istringstream axis(header_string(h, "approach_axis", path));
    if (!(axis >> m.approach_axis_.x() >> m.approach_axis_.y() >> m.approach_axis_.z()))
      throw FileError("'" + path + "' has a malformed approach_axis");
    if (!m.approach_axis_.allFinite() || std::abs(m.approach_axis_.norm() - 1.0) > 1e-6)
      throw FileError("'" + path + "' has an approach_axis that is not a unit vector");
  }
  m.self_collision_ = header_int(h, "self_collision", path) != 0;
  m.seed_ = detail::header_u64(h, "seed", path);
  m.fk_samples_ = static_cast<std::size_t>(header_int(h, "fk_samples", path));
  m.exhaustive_ = header_int(h, "exhaustive", path) != 0;
  m.position_tolerance_ = header_double(h, "position_tolerance", path);
  m.orientation_tolerance_ = header_double(h, "orientation_tolerance", path);
  // Files hold no timing (the same build gives the same bytes); files of older versions recorded one.
  m.stats_.seconds = h.count("build_seconds") ? header_double(h, "build_seconds", path) : 0.0;
  m.cell_data_ = h.count("cell_data") && header_int(h, "cell_data", path) != 0;
  m.jacobian_rank_ = h.count("jacobian_rank") ? static_cast<int>(std::clamp<long long>(header_int(h, "jacobian_rank", path), 0, 6)) : 0;
  if (h.count("reference")) m.reference_ = header_reference(h, path);
  m.block_size_ = h.count("block_size") ? static_cast<int>(std::clamp<long long>(header_int(h, "block_size", path), 0, 1 << 20)) : 0;
  bool sols = header_int(h, "solutions", path) != 0;
  m.keeps_solutions_ = sols;
  const bool poles = h.count("poles") && header_int(h, "poles", path) != 0;
  m.orientations_ = OrientationSet::sphere(dirs, rolls, sym, poles);
  if (m.orientations_.directions() != dirs) throw FileError("'" + path + "' has an inconsistent direction count");
  const int O = m.orientations_.size();
  m.words_ = (O + 63) / 64;
  m.tree_ = std::make_shared<VoxelOcTree>(m.resolution_);
  detail::ByteReader r(payload, "'" + path + "'");
  const auto count = r.get<std::uint64_t>();
  if (count > payload.size()) r.fail("damaged map data (voxel count)");
  if (r.get<std::uint8_t>()) {
    VoxelOcTree& tree = *m.tree_;
    detail::VoxelCellData cells;
    read_tree(tree, tree.ensure_root(), 0, r, [&](VoxelNode& n) {
      if (m.sol_offset_.size() >= count) r.fail("damaged map data (more voxels than recorded)");
      cells.read(r, m.words_, O, m.dof_, sols, m.cell_data_);
      m.append_record_(n, cells);
    });
  }
  if (!r.done()) r.fail("damaged map data (trailing bytes)");
  if (m.sol_offset_.size() != count) r.fail("damaged map data (voxel count mismatch)");
  m.tree_->update_inner_values();
  m.finish_();
  return m;
}


}  // namespace octoreach
