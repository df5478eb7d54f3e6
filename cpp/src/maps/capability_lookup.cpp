// The plain lookups of a capability map (CapabilityLookup vote, nearest cell and any, one pose or a batch) and the
// reachable-bit grid they read; the records, solutions and files are capability_map.cpp's.
#include "octoreach/capability_map.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "maps/batch.hpp"

namespace octoreach {

namespace {
// Largest plain-lookup grid: 200 orientations over a box of 2.7 million voxels (a 2 m cube at 0.015 m); finer maps
// answer from their records.
constexpr std::size_t kGridBytes = std::size_t(64) << 20;
}  // namespace

void CapabilityMap::build_grid_() {
  grid_.clear();
  grid_any_.clear();
  int lo[3], hi[3];
  if (!index_.key_box(lo, hi)) return;  // (index_ is built first)
  std::size_t bits = static_cast<std::size_t>(orientations_.size());
  for (int a = 0; a < 3; ++a) {
    grid_lo_[a] = lo[a] - 1;
    grid_dim_[a] = hi[a] - lo[a] + 3;
    if (bits > 8 * kGridBytes / static_cast<std::size_t>(grid_dim_[a])) return;  // too large (and no overflow)
    bits *= static_cast<std::size_t>(grid_dim_[a]);
  }
  grid_.assign((bits + 63) / 64, 0);
  grid_any_.assign((bits / static_cast<std::size_t>(orientations_.size()) + 63) / 64, 0);
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    if (it->payload == DenseIndex::kNone) continue;
    const std::uint64_t* w = bits_.data() + static_cast<std::size_t>(it->payload) * words_;
    const int x = it.getKey()[0] - grid_lo_[0], y = it.getKey()[1] - grid_lo_[1], z = it.getKey()[2] - grid_lo_[2];
    bool held = false;
    for (int k = 0; k < words_; ++k)
      for (std::uint64_t b = w[k]; b; b &= b - 1) {
        const std::size_t i = grid_index_(64 * k + __builtin_ctzll(b), x, y, z);
        grid_[i >> 6] |= 1ULL << (i & 63);
        held = true;
      }
    if (held) {
      const std::size_t v = grid_index_(0, x, y, z);
      grid_any_[v >> 6] |= 1ULL << (v & 63);
    }
  }
}

double CapabilityMap::reachability(const Eigen::Vector3d& p) const {
  std::uint32_t r = record(p);
  return r == DenseIndex::kNone ? 0.0 : d_[r];
}

namespace {

// Grid coordinates of p in voxels from the centre of voxel key 0 (octomap's voxel i spans [i, i + 1) * resolution,
// its centre is at (i + 0.5) * resolution): the lower corner's key and the fractions towards the upper ones.
// False when a corner falls outside the octree's keys.
bool corner_grid(const Eigen::Vector3d& p, double resolution, octomap::OcTreeKey& low, double frac[3]) {
  constexpr double kOffset = 32768.0;  // octomap's tree_max_val at depth 16: key = floor(x / res) + 32768
  const double inv = 1.0 / resolution;
  for (int a = 0; a < 3; ++a) {
    const double g = p[a] * inv - 0.5, base = std::floor(g);
    frac[a] = g - base;
    if (!(base + kOffset >= 0.0 && base + kOffset + 1.0 <= 65535.0)) return false;
    low[a] = static_cast<octomap::key_type>(base + kOffset);
  }
  return true;
}

// Corner k (bit a: one voxel up along axis a) of the 8 around a position: its key and trilinear weight.
inline double corner(const octomap::OcTreeKey& low, const double frac[3], int k, octomap::OcTreeKey& key) {
  double w = 1.0;
  key = low;
  for (int a = 0; a < 3; ++a) {
    const bool up = (k >> a) & 1;
    w *= up ? frac[a] : 1.0 - frac[a];
    key[a] = static_cast<octomap::key_type>(key[a] + up);
  }
  return w;
}

}  // namespace

void CapabilityMap::corners(const Eigen::Vector3d& p, std::uint32_t records[8], double weights[8]) const {
  octomap::OcTreeKey low;
  double frac[3];
  const bool inside = corner_grid(p, resolution_, low, frac);
  for (int k = 0; k < 8; ++k) {
    octomap::OcTreeKey key;
    weights[k] = corner(low, frac, k, key);
    records[k] = inside ? record_of_key(key) : DenseIndex::kNone;
  }
}

bool CapabilityMap::vote_(const Eigen::Vector3d& p, int o) const {
  octomap::OcTreeKey low;
  double frac[3];
  return corner_grid(p, resolution_, low, frac) && vote_corners_(low, frac, o);
}

bool CapabilityMap::vote_corners_(const octomap::OcTreeKey& low, const double frac[3], int o) const {
  if (!grid_.empty()) {
    // Every corner's weight added in corner order, unreachable ones as zero, without early ends and without a
    // branch on the map: the record path's answer below (its early ends only foresee the full sum's side of 1/2).
    int g[3];
    for (int a = 0; a < 3; ++a) {
      g[a] = low[a] - grid_lo_[a];
      // Both corners along an axis outside the grid's box (its rim is empty): no corner holds a record.
      if (g[a] < 0 || g[a] + 1 >= grid_dim_[a]) return false;
    }
    const double fx[2] = {1.0 - frac[0], frac[0]}, fy[2] = {1.0 - frac[1], frac[1]}, fz[2] = {1.0 - frac[2], frac[2]};
    double yes = 0.0;
    for (int k = 0; k < 8; ++k) {
      const int x = k & 1, y = (k >> 1) & 1, z = (k >> 2) & 1;
      const double w = fx[x] * fy[y] * fz[z];  // corner()'s product, in its order
      yes += grid_bit_(o, g[0] + x, g[1] + y, g[2] + z) ? w : 0.0;
    }
    return yes >= 0.5;
  }
  double yes = 0.0, left = 1.0;
  for (int k = 0; k < 8; ++k) {
    octomap::OcTreeKey key;
    const double w = corner(low, frac, k, key);
    if (w <= 0.0) continue;
    const std::uint32_t r = record_of_key(key);
    if (r != DenseIndex::kNone && bit(r, o)) yes += w;
    left -= w;
    if (yes >= 0.5) return true;
    if (yes + left < 0.5 - 1e-12) return false;  // the rest cannot reach one half
  }
  return yes >= 0.5;
}

bool CapabilityMap::nearest_cell_(const Eigen::Vector3d& p, int o) const {
  if (grid_.empty()) {
    const std::uint32_t r = record(p);
    return r != DenseIndex::kNone && bit(r, o);
  }
  octomap::OcTreeKey key;
  if (!tree_->coordToKeyChecked(p.x(), p.y(), p.z(), key)) return false;
  int g[3];
  for (int a = 0; a < 3; ++a) {
    g[a] = key[a] - grid_lo_[a];
    if (g[a] < 0 || g[a] >= grid_dim_[a]) return false;
  }
  return grid_bit_(o, g[0], g[1], g[2]);
}

bool CapabilityMap::any_corner_(const octomap::OcTreeKey& low, const double frac[3], int o) const {
  if (!grid_.empty()) {
    int g[3];
    for (int a = 0; a < 3; ++a) {
      g[a] = low[a] - grid_lo_[a];
      if (g[a] < 0 || g[a] + 1 >= grid_dim_[a]) return false;  // (as vote_corners_: the grid's rim is empty)
    }
    for (int k = 0; k < 8; ++k)
      if (grid_bit_(o, g[0] + (k & 1), g[1] + ((k >> 1) & 1), g[2] + ((k >> 2) & 1))) return true;
    return false;
  }
  for (int k = 0; k < 8; ++k) {
    octomap::OcTreeKey key;
    corner(low, frac, k, key);  // (every corner counts, whatever its weight)
    const std::uint32_t r = record_of_key(key);
    if (r != DenseIndex::kNone && bit(r, o)) return true;
  }
  return false;
}

bool CapabilityMap::lookup_(const Eigen::Vector3d& p, int o, CapabilityLookup lookup) const {
  switch (lookup) {
    case CapabilityLookup::vote: return vote_(p, o);
    case CapabilityLookup::any: {
      octomap::OcTreeKey low;
      double frac[3];
      return corner_grid(p, resolution_, low, frac) && any_corner_(low, frac, o);
    }
    case CapabilityLookup::nearest_cell: break;
  }
  return nearest_cell_(p, o);
}

bool CapabilityMap::reachable(const Eigen::Vector3d& p, int orientation, CapabilityLookup lookup) const {
  if (orientation < 0 || orientation >= orientations_.size())
    throw std::invalid_argument("orientation index " + std::to_string(orientation) + " out of range [0, " +
                                std::to_string(orientations_.size()) + ")");
  return lookup_(p, orientation, lookup);
}

bool CapabilityMap::reachable(const Pose& T, CapabilityLookup lookup) const {
  check_rigid(T, "pose");
  return lookup_(T.translation(), orientations_.nearest(T.linear(), approach_axis_), lookup);
}

void CapabilityMap::reachability(const double* points, std::size_t n, double* out) const {
  detail::batch_lookup_valid(points, n, 3, "point", " (NaN or inf)", [&](std::size_t i) {
    const double* p = points + 3 * i;
    out[i] = reachability(Eigen::Vector3d(p[0], p[1], p[2]));
  });
}

void CapabilityMap::reachable(const double* poses, std::size_t n, bool* out, CapabilityLookup lookup) const {
  if (grid_.empty()) {
    detail::batch_lookup_valid(poses, n, 16, "pose", "", [&](std::size_t i) {  // (rows checked as they are read)
      const double* m = poses + 16 * i;
      Eigen::Matrix3d R;
      R << m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10];
      const int o = orientations_.nearest(R, approach_axis_);
      out[i] = lookup_(Eigen::Vector3d(m[3], m[7], m[11]), o, lookup);
    });
    return;
  }
  // In groups: every pose's corners (or voxel) and orientation first, its grid words prefetched, then the lookups.
  constexpr std::size_t kGroup = 32;
  // OrientationSet::nearest's own steps with its normalised axis made once: a single roll needs only the
  // direction of the approach axis.
  const Eigen::Vector3d axis = approach_axis_.normalized();
  const bool one_roll = orientations_.rolls() == 1;
  const bool by_corners = lookup != CapabilityLookup::nearest_cell;
  detail::batch_lookup_valid_groups(poses, n, 16, "pose", "", kGroup,
                                    [&](std::size_t i0, std::size_t i1, const bool* valid) {
    int o[kGroup];
    octomap::OcTreeKey low[kGroup];
    double frac[kGroup][3];
    bool keyed[kGroup];
    for (std::size_t i = i0; i < i1; ++i) {
      const std::size_t k = i - i0;
      keyed[k] = false;
      if (!valid[k]) continue;
      const double* m = poses + 16 * i;
      // vote and any: the lower of the 8 corners (the grid words of its x and x + 1 planes); nearest cell: the voxel
      keyed[k] = by_corners
                     ? corner_grid(Eigen::Vector3d(m[3], m[7], m[11]), resolution_, low[k], frac[k])
                     : tree_->coordToKeyChecked(m[3], m[7], m[11], low[k]);
      if (!keyed[k]) continue;
      int g[3];
      bool inside = true;
      for (int a = 0; a < 3; ++a) {
        g[a] = low[k][a] - grid_lo_[a];
        // the voxel, or both corners along the axis, in the grid's box (its rim is empty: vote_corners_)
        inside &= g[a] >= 0 && g[a] + int(by_corners) < grid_dim_[a];
      }
      bool held = inside && grid_any_bit_(g[0], g[1], g[2]);  // a voxel that can answer yes
      for (int c = 1; by_corners && inside && !held && c < 8; ++c)
        held = grid_any_bit_(g[0] + (c & 1), g[1] + ((c >> 1) & 1), g[2] + ((c >> 2) & 1));
      keyed[k] = held;  // else no: the orientation is not needed
      if (!held) continue;
      Eigen::Matrix3d R;
      R << m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10];
      o[k] = one_roll ? orientations_.nearest_direction(R * axis) : orientations_.nearest(R, approach_axis_);
      const std::size_t b = grid_index_(o[k], g[0], g[1], g[2]);
      __builtin_prefetch(grid_.data() + (b >> 6));
      if (by_corners)
        __builtin_prefetch(grid_.data() + ((b + static_cast<std::size_t>(grid_dim_[1]) * grid_dim_[2]) >> 6));
    }
    for (std::size_t i = i0; i < i1; ++i) {
      const std::size_t k = i - i0;
      if (!valid[k]) continue;
      if (lookup == CapabilityLookup::vote) {
        out[i] = keyed[k] && vote_corners_(low[k], frac[k], o[k]);
      } else if (lookup == CapabilityLookup::any) {
        out[i] = keyed[k] && any_corner_(low[k], frac[k], o[k]);
      } else {
        out[i] = keyed[k] && grid_bit_(o[k], low[k][0] - grid_lo_[0], low[k][1] - grid_lo_[1], low[k][2] - grid_lo_[2]);
      }
    }
  });
}

}  // namespace octoreach
