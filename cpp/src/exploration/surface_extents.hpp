#pragma once
// Internal: where the surface inside an occupied cell lies.
//
// A cell is occupied when a point hit it anywhere inside, so the rim of an opening or the edge of a board fills only
// part of the cells it occupies: an 8 cm opening in 2.5 cm cells keeps one free column in the map while real rays
// pass through the whole of it. Each insert records, per cell its points hit, the box of those points
// (SurfaceExtents) and how many hit it. A line meets a cell's surface when it meets that box grown across every face
// the surface goes on past:
// - into an occupied cell (which has a record of its own) or unknown space: grown to the face;
// - into a free cell the box comes within the hits' spacing of (sqrt(area / hits)), or a free cell points hit too:
//   grown through that cell as well, since rays grazing a surface free the cells it fills in part, and a line that
//   crosses the surface there must still stop;
// - into a free cell no point hit and the box stays clear of: rays have crossed it, so the surface ends inside this
//   cell, within the hits' spacing of its last hit, and a line through the rest passes.
// A cell without a record (a map read from a file) stops every line.
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <octomap/OcTree.h>

#include "exploration/cell_sets.hpp"
#include "octoreach/exploration.hpp"

namespace octoreach::detail {

struct ExplorationState;

// Per cell points hit, the box of those points and their count, packed in 64 bits (surface_extents.cpp), and the
// grown boxes of the cells whose surface goes on past a face (update_grown after each insert: lines are tested far
// more often than cells change, so each box is worked out once per insert, not once per line). A grown box depends
// on the cell's record and on its 6 face neighbours' states (free or not) and records, so an insert changes only the
// boxes of the cells it recorded and of the face neighbours of those and of the cells whose free state it changed.
class SurfaceExtents {
 public:
  // Records the hits of one cloud (points within max_range of origin; <= 0 or inf: every point).
  void record(const octomap::OcTree& tree, const std::vector<octomap::point3d>& cloud, const octomap::point3d& origin,
              double max_range);
  // Works out again the grown boxes the cells recorded since the last call and the cell changes `changed` can have
  // changed, from S's cells (S.surface is this; the caller holds the write lock, after the insert's cell states
  // are set).
  void update_grown(const ExplorationState& S, const std::vector<CellChange>& changed);
  // True when every recorded cell's grown box is the one its record and S's cells give now (a check for tests).
  bool grown_current(const ExplorationState& S) const;
  const std::uint64_t* find(CellKey k) const { return boxes_.find(k); }
  // The grown box of cell k, packed (surface_extents.cpp); null when its surface goes on past no face.
  const std::uint64_t* grown(CellKey k) const {
    const std::uint64_t* g = grown_.find(k);
    return g && *g != kNotGrown ? g : nullptr;
  }
  std::size_t size() const { return boxes_.size(); }

 private:
  // A grown_ entry of a cell whose box grew once and no longer does (KeyTable has no erase; no packed box is all
  // ones).
  static constexpr std::uint64_t kNotGrown = ~std::uint64_t(0);
  KeyTable<std::uint64_t> boxes_;
  KeyTable<std::uint64_t> grown_;
  std::vector<CellKey> recorded_;  // cells recorded since the last update_grown (repeats allowed)
};

// True when the line o + t d (any t) meets the surface in occupied cell k (see above).
bool surface_meets_line(const ExplorationState& S, CellKey k, const Eigen::Vector3d& o, const Eigen::Vector3d& d);

}  // namespace octoreach::detail
