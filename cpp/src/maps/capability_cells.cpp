#include "maps/capability_cells.hpp"

#include <algorithm>
#include <bitset>
#include <cmath>

namespace octoreach::detail {
namespace {

std::size_t count_bits(const std::vector<std::uint64_t>& words) {
  std::size_t n = 0;
  for (std::uint64_t w : words) n += std::bitset<64>(w).count();
  return n;
}

}  // namespace

void VoxelCellData::clear(int words) {
  bits.assign(words, 0);
  mixed.assign(words, 0);
  solutions.clear();
  quality.clear();
  mixed_solutions.clear();
}

bool VoxelCellData::empty() const {
  return std::all_of(bits.begin(), bits.end(), [](std::uint64_t b) { return b == 0; }) &&
         std::all_of(mixed.begin(), mixed.end(), [](std::uint64_t b) { return b == 0; });
}

std::size_t VoxelCellData::reachable_count() const { return count_bits(bits); }
std::size_t VoxelCellData::mixed_count() const { return count_bits(mixed); }

void VoxelCellData::write(ByteWriter& w, bool with_solutions, bool cell_data) const {
  w.put_bytes(bits.data(), bits.size() * sizeof(std::uint64_t));
  if (cell_data) w.put_bytes(mixed.data(), mixed.size() * sizeof(std::uint64_t));
  if (!with_solutions) return;
  w.put_bytes(solutions.data(), solutions.size() * sizeof(float));
  if (!cell_data) return;
  for (const CellQuality& q : quality) {
    w.put(q.manipulability);
    w.put(q.penalty);
  }
  w.put_bytes(mixed_solutions.data(), mixed_solutions.size() * sizeof(float));
}

void VoxelCellData::read(ByteReader& r, int words, int orientations, int dof, bool with_solutions, bool cell_data) {
  clear(words);
  r.get_bytes(bits.data(), words * sizeof(std::uint64_t));
  if (cell_data) r.get_bytes(mixed.data(), words * sizeof(std::uint64_t));
  const std::size_t n = reachable_count(), m = mixed_count();
  bool overlap = false;
  for (int i = 0; i < words; ++i) overlap |= (bits[i] & mixed[i]) != 0;
  if (n + m == 0 || n + m > static_cast<std::size_t>(orientations) || overlap) r.fail("damaged map data (voxel record)");
  const std::uint64_t last = orientations % 64 ? ~0ULL << (orientations % 64) : 0;  // bits past the last orientation
  if ((bits[words - 1] | mixed[words - 1]) & last) r.fail("damaged map data (voxel record)");
  if (!with_solutions) return;
  const std::size_t row = sizeof(float) * static_cast<std::size_t>(dof);
  if (r.remaining() / row < n) r.fail("damaged map data (solutions end early)");
  solutions.resize(n * dof);
  r.get_bytes(solutions.data(), solutions.size() * sizeof(float));
  if (!cell_data) return;
  if (r.remaining() / (2 * sizeof(float)) < n) r.fail("damaged map data (quality ends early)");
  quality.resize(n);
  for (CellQuality& q : quality) {
    q.manipulability = r.get<float>();
    q.penalty = r.get<float>();
    if (!(q.manipulability >= 0) || !std::isfinite(q.manipulability) || !(q.penalty >= 0 && q.penalty <= 1))
      r.fail("damaged map data (cell quality)");
  }
  if (r.remaining() / row < m) r.fail("damaged map data (mixed-cell configurations end early)");
  mixed_solutions.resize(m * dof);
  r.get_bytes(mixed_solutions.data(), mixed_solutions.size() * sizeof(float));
}

}  // namespace octoreach::detail
