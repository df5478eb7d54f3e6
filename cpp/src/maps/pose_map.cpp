#include "octoreach/pose_map.hpp"

#include "maps/batch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>


#include "common/checks.hpp"
#include "maps/map_io.hpp"

namespace octoreach {

PoseMap::PoseMap(double resolution, int theta_bins) : resolution_(resolution), theta_bins_(theta_bins) {
  detail::check_map_resolution(resolution);  // builds and load() alike
  if (theta_bins < 1 || theta_bins > limits::kThetaBins)
    throw std::invalid_argument("theta_bins must be in [1, " + std::to_string(limits::kThetaBins) + "], got " +
                                std::to_string(theta_bins));
  tree_ = std::make_shared<VoxelOcTree>(resolution);
}

int PoseMap::theta_bin(double theta) const {
  double step = 2.0 * M_PI / theta_bins_;
  long k = std::lround(std::remainder(theta, 2.0 * M_PI) / step);
  k %= theta_bins_;
  if (k < 0) k += theta_bins_;
  return static_cast<int>(k);
}

const float* PoseMap::voxel_values(double x, double y, double z) const {
  if (!tree_) return nullptr;
  if (index_.active()) {
    std::uint32_t r = index_.find(*tree_, x, y, z);
    return r == DenseIndex::kNone ? nullptr : values_.data() + static_cast<std::size_t>(r) * theta_bins_;
  }
  const VoxelNode* n = tree_->find(x, y, z);
  if (!n || n->payload == std::numeric_limits<std::uint32_t>::max()) return nullptr;
  return values_.data() + static_cast<std::size_t>(n->payload) * theta_bins_;
}

double PoseMap::value(double x, double y, double z, double theta) const {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || !std::isfinite(theta)) return 0.0;
  const float* v = voxel_values(x, y, z);
  return v ? v[theta_bin(theta)] : 0.0;
}

void PoseMap::values(const double* rows, std::size_t n, double* out) const {
  detail::batch_lookup_valid(rows, n, 4, "pose", " (x, y, z, theta in m and rad)", [&](std::size_t i) {
    const double* r = rows + 4 * i;
    out[i] = value(r[0], r[1], r[2], r[3]);
  });
}

void PoseMap::set_voxel(const octomap::OcTreeKey& key, const float* values) {
  index_ = DenseIndex();  // stale once the tree changes; finalize() rebuilds it
  VoxelNode* n = tree_->touch(key);
  if (n->payload == std::numeric_limits<std::uint32_t>::max()) {
    n->payload = static_cast<std::uint32_t>(voxel_count());
    values_.insert(values_.end(), values, values + theta_bins_);
  } else {
    std::copy(values, values + theta_bins_, values_.begin() + static_cast<std::size_t>(n->payload) * theta_bins_);
  }
  n->setValue(*std::max_element(values, values + theta_bins_));
}

void PoseMap::finalize() {
  // Rebuild without all-zero voxels, records renumbered in tree order (deterministic files).
  auto old_tree = tree_;
  auto old_values = std::move(values_);
  tree_ = std::make_shared<VoxelOcTree>(resolution_);
  values_.clear();
  for (auto it = old_tree->begin_leafs(), end = old_tree->end_leafs(); it != end; ++it) {
    if (it->payload == std::numeric_limits<std::uint32_t>::max()) continue;
    const float* v = old_values.data() + static_cast<std::size_t>(it->payload) * theta_bins_;
    if (*std::max_element(v, v + theta_bins_) <= 0.0f) continue;
    set_voxel(it.getKey(), v);
  }
  tree_->update_inner_values();
  index_.build(*tree_);
}

void PoseMap::voxels(std::vector<Eigen::Vector3d>& centres, std::vector<float>& values) const {
  centres.clear();
  values.clear();
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    if (it->payload == std::numeric_limits<std::uint32_t>::max()) continue;
    centres.emplace_back(it.getX(), it.getY(), it.getZ());
    const float* v = values_.data() + static_cast<std::size_t>(it->payload) * theta_bins_;
    values.insert(values.end(), v, v + theta_bins_);
  }
}

std::size_t PoseMap::pose_count() const {
  std::vector<Eigen::Vector3d> c;
  std::vector<float> v;
  voxels(c, v);
  return static_cast<std::size_t>(std::count_if(v.begin(), v.end(), [](float x) { return x > 0; }));
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> PoseMap::bounds() const {
  std::vector<Eigen::Vector3d> c;
  std::vector<float> v;
  voxels(c, v);
  if (c.empty()) return {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  Eigen::Vector3d lo = c[0], hi = c[0];
  for (const auto& p : c) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo.array() - resolution_ / 2, hi.array() + resolution_ / 2};
}

double PoseMap::max_value() const { return values_.empty() ? 0.0 : *std::max_element(values_.begin(), values_.end()); }


void PoseMap::save(const std::string& path, const std::string& kind, const std::map<std::string, std::string>& header,
                   std::uint32_t format_version, const MapSections& sections) const {
  detail::Header h(header.begin(), header.end());
  h["resolution"] = detail::format_number(resolution_);
  h["theta_bins"] = std::to_string(theta_bins_);
  h["voxels"] = std::to_string(voxel_count());
  h["octoreach_version"] = version();
  detail::ByteWriter w;
  w.put(static_cast<std::uint64_t>(voxel_count()));
  if (tree_->getRoot() && voxel_count()) {
    w.put(std::uint8_t{1});
    write_tree(*tree_, tree_->getRoot(), 0, w, [&](const VoxelNode& n) {
      w.put_bytes(values_.data() + static_cast<std::size_t>(n.payload) * theta_bins_, theta_bins_ * sizeof(float));
    });
  } else {
    w.put(std::uint8_t{0});
  }
  detail::write_map_file(path, kind, h, w.bytes, format_version, sections);
}

PoseMap PoseMap::load(const std::string& path, const std::string& kind, std::map<std::string, std::string>& header,
                      MapSections* sections) {
  detail::Header h;
  std::vector<char> payload;
  detail::read_map_file(path, kind, h, payload, [&](const detail::Header& head) {  // a value per theta bin per voxel
    const long long bins = detail::header_int(head, "theta_bins", path);
    if (bins < 1 || bins > limits::kThetaBins) throw FileError("'" + path + "' has implausible map parameters");
    return detail::payload_bound(detail::header_voxels(head, path), std::uint64_t(bins) * sizeof(float));
  }, sections);
  double res = detail::header_double(h, "resolution", path);
  long long bins = detail::header_int(h, "theta_bins", path);
  if (!(res >= limits::kMinMapResolution) || !(res <= limits::kMaxMapResolution) || bins < 1 ||
      bins > limits::kThetaBins)
    throw FileError("'" + path + "' has implausible map parameters");
  PoseMap m(res, static_cast<int>(bins));
  detail::ByteReader r(payload, "'" + path + "'");
  auto count = r.get<std::uint64_t>();
  if (count > payload.size()) r.fail("damaged map data (voxel count)");
  if (r.get<std::uint8_t>()) {
    VoxelNode* root = m.tree_->ensure_root();
    read_tree(*m.tree_, root, 0, r, [&](VoxelNode& n) {
      if (m.voxel_count() >= count) r.fail("damaged map data (more voxels than recorded)");
      n.payload = static_cast<std::uint32_t>(m.voxel_count());
      std::size_t off = m.values_.size();
      m.values_.resize(off + m.theta_bins_);
      r.get_bytes(m.values_.data() + off, m.theta_bins_ * sizeof(float));
      float best = 0;
      for (int k = 0; k < m.theta_bins_; ++k) {
        float v = m.values_[off + k];
        if (!std::isfinite(v) || v < 0 || v > 1.0001f) r.fail("damaged map data (value out of [0, 1])");
        best = std::max(best, v);
      }
      n.setValue(best);
    });
    m.tree_->update_inner_values();
  }
  if (!r.done()) r.fail("damaged map data (trailing bytes)");
  m.index_.build(*m.tree_);
  if (m.voxel_count() != count) r.fail("damaged map data (voxel count mismatch)");
  header.clear();
  header.insert(h.begin(), h.end());
  return m;
}

void PoseMap::export_octovis(const std::string& path) const {
  detail::write_color_octree(*tree_, std::max(1e-9, max_value()), path);
}

}  // namespace octoreach
