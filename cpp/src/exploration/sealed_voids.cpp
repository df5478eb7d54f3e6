// Sealed void cells: the void components no ray can enter (upkeep.hpp, docs/design/unseeable_voids.md).
#include <vector>

#include "exploration/cell_sets.hpp"
#include "exploration/upkeep.hpp"

namespace octoreach::detail {

void update_sealed(ExplorationState& s, const ExplorationOptions& options) {
  s.sealed = KeyTable<std::uint8_t>();
  if (s.void_set.empty()) return;
  const GridReader g(s.grid);
  const double floor = options.search_lo.z();
  KeyTable<std::uint8_t> seen(s.void_set.size());
  std::vector<CellKey> component, stack;
  for (CellKey start : s.void_set) {
    if (seen.find(start)) continue;
    component.clear();
    stack.assign(1, start);
    seen.at(start) = 1;
    bool open = false;
    while (!stack.empty()) {
      const CellKey k = stack.back();
      stack.pop_back();
      component.push_back(k);
      for (const auto& d : kN6) {
        CellKey nb;
        if (!neighbour(k, d[0], d[1], d[2], nb)) continue;
        const std::uint8_t f = g.get(nb);
        if (f & kVoidFlag) {
          if (!seen.find(nb)) {
            seen.at(nb) = 1;
            stack.push_back(nb);
          }
          continue;
        }
        const auto st = CellState(f & kStateMask);
        if (st == CellState::Occupied) continue;
        if (st == CellState::Unknown && s.center(nb).z() < floor) continue;  // the ground under the search space
        open = true;  // observed free space, or unknown space outside the voids that may lead to it
      }
    }
    if (!open)
      for (CellKey k : component) s.sealed.at(k) = 1;
  }
}

}  // namespace octoreach::detail
