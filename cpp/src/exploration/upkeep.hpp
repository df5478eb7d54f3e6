#pragma once
// Internal: the incremental upkeep of frontiers and voids after the tree changed (steps 4 and 5
// of ExplorationMap::insert).
#include <vector>

#include "exploration/exploration_state.hpp"

namespace octoreach::detail {

// A free cell with an unknown 6-neighbour.
bool is_frontier_cell(const GridReader& g, CellKey k);

// Step 4: frontier flags and cluster labels after the cells in `changed` changed class. Only
// changed cells and the 6-neighbours of cells that stopped being unknown can change status (a
// neighbour can only lose it: it has one unknown neighbour fewer). Clusters that lost a cell or
// border a new one are reclustered.
void update_frontiers(ExplorationState& s, const std::vector<CellChange>& changed, int threads, InsertStats& stats);

// Gives each component a new cluster label.
void label_frontier_clusters(ExplorationState& s, std::vector<std::vector<CellKey>> components);

// Step 5: the hull from the previous hull's vertices plus the new occupied cells, and the void
// cells updated from the changed cells and from the hull's growth, column by column.
void update_voids(ExplorationState& s, const std::vector<CellChange>& changed, const std::vector<CellKey>& occupied,
                  const ExplorationOptions& options, int threads, InsertStats& stats);

// The sealed void cells (ExplorationState::sealed): the void components (6-connected) whose every
// 6-neighbour outside the component is occupied or lies under the search space's floor. A ray walks from
// cell to face-adjacent cell and stops at the first occupied cell, so no view's ray can reach such a cell
// (the inside of a solid whose faces have been seen): it is never worth a view. Recomputed after each insert.
void update_sealed(ExplorationState& s, const ExplorationOptions& options);

}  // namespace octoreach::detail
