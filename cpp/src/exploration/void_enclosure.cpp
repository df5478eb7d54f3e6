// How enclosed each void cell is: the share of the six axis directions that meet a surface before
// free space (see void_enclosure.hpp).
#include "exploration/void_enclosure.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "exploration/cell_sets.hpp"
#include "common/thread_pool.hpp"
#include "exploration/exploration_state.hpp"
#include "octoreach/next_best_view.hpp"

namespace octoreach::detail {

namespace {

std::uint8_t closed_halves(const GridReader& g, CellKey k, int steps, bool exposure) {
  const int x = int(key_x(k)), y = int(key_y(k)), z = int(key_z(k));
  static constexpr int kDirs[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  int halves = 0;
  for (const auto& d : kDirs) {
    int h = 1;  // unknown all the way
    for (int s = 1; s <= steps; ++s) {
      const int a = x + s * d[0], b = y + s * d[1], c = z + s * d[2];
      if (a < 0 || b < 0 || c < 0 || a > 0xffff || b > 0xffff || c > 0xffff) break;
      const std::uint8_t st = g.get(pack_key(std::uint32_t(a), std::uint32_t(b), std::uint32_t(c))) & kStateMask;
      if (st == std::uint8_t(CellState::Occupied)) {
        h = 2;
        break;
      }
      if (st == std::uint8_t(CellState::Free)) {
        h = 0;
        break;
      }
    }
    halves += h;
  }
  return std::uint8_t(exposure && has_free_neighbour(g, k) ? halves | kExposed : halves);
}

}  // namespace

bool has_free_neighbour(const GridReader& g, CellKey k) {
  for (const auto& d : kN26.d) {
    CellKey nb;
    if (neighbour(k, d[0], d[1], d[2], nb) && (g.get(nb) & kStateMask) == std::uint8_t(CellState::Free)) return true;
  }
  return false;
}

VoidWeights::VoidWeights(std::shared_ptr<const EnclosureTable> table, double power, double unexposed_weight)
    : table_(std::move(table)) {
  for (int h = 0; h <= 12; ++h) {
    weight_[h] = std::pow(h / 12.0, power) * unexposed_weight;
    weight_[h | kExposed] = std::pow(h / 12.0, power);
  }
}

std::shared_ptr<const EnclosureTable> cached_void_enclosure(const ExplorationState& s, double resolution,
                                                            double range, bool exposure) {
  std::lock_guard<std::mutex> lock(s.cache_mutex);
  if (s.enclosure && s.enclosure_range == range && (s.enclosure_exposure || !exposure)) return s.enclosure;
  const int steps = std::max(1, int(std::ceil(range / resolution - 1e-9)));
  const std::vector<CellKey> keys(s.void_set.begin(), s.void_set.end());
  std::vector<std::uint8_t> halves(keys.size());
  parallel_for(keys.size(), 0, [&](std::size_t i, int) {
    const GridReader g(s.grid);
    halves[i] = closed_halves(g, keys[i], steps, exposure);
  }, 256);
  auto table = std::make_shared<EnclosureTable>(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) table->at(keys[i]) = halves[i];
  s.enclosure = table;
  s.enclosure_range = range;
  s.enclosure_exposure = exposure;
  return table;
}

VoidWeights void_weights(const ExplorationState& s, double resolution, double power, double range,
                         double unexposed_weight) {
  if (power <= 0 && unexposed_weight == 1) return {};
  return VoidWeights(cached_void_enclosure(s, resolution, range, unexposed_weight != 1), power, unexposed_weight);
}

}  // namespace octoreach::detail

namespace octoreach {

std::vector<bool> exposed_cells(const ExplorationMap& map, const std::vector<CellKey>& keys) {
  auto guard = detail::read_guard(map);
  const detail::GridReader g(detail::state(map).grid);
  std::vector<bool> out(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) out[i] = detail::has_free_neighbour(g, keys[i]);
  return out;
}

std::vector<std::pair<CellKey, double>> void_enclosure(const ExplorationMap& map, double range) {
  if (!(range > 0) || !std::isfinite(range))
    throw std::invalid_argument("void_enclosure: range must be a positive number of metres, got " + std::to_string(range));
  auto guard = detail::read_guard(map);
  const auto table = detail::cached_void_enclosure(detail::state(map), map.resolution(), range);
  std::vector<std::pair<CellKey, double>> out;
  out.reserve(table->size());
  table->for_each([&](CellKey k, std::uint8_t h) { out.emplace_back(k, (h & detail::kHalvesMask) / 12.0); });
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace octoreach
