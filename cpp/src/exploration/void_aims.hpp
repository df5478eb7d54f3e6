#pragma once
// Internal: camera poses aimed at void cells along lines of sight, found by walking rays out of the
// cells (the loop's looks besides Algorithm 1, void_aims.cpp).
#include <cstdint>
#include <utility>
#include <vector>

#include "octoreach/next_best_view.hpp"

namespace octoreach::detail {

class ViewChecker;
struct ExplorationState;

// Which void cells to aim at and how many rays to walk out of each.
struct AimRequest {
  std::size_t poses = 400;  // at most this many poses: a random sample of the eyes the rays give
  // Void cells the rays leave from: `cells` drawn at random (exposed cells first: all exposed ones drawn,
  // then unexposed ones with probability unexposed_share), or every void cell (at most max_cells, drawn at
  // random) with every_cell.
  std::size_t cells = 400;
  bool every_cell = false;
  std::size_t max_cells = 4096;
  double unexposed_share = 0.25;
  int directions = 8;                            // rays per cell, uniform over the sphere
  // aim_at_voids: half of the rays through the gates of the voids instead (observed-free cells with a void cell
  // across a face; at most max_cells of them), each from a void cell on its line
  bool through_gates = true;
  std::pair<double, double> distance{0.3, 1.0};  // metres from the cell to the eye
  double min_height = 0.05;                      // eyes stay above this height (map frame z)
  // aim_at_voids: radians the optical axis may turn away from the cell to one the arm can reach (a camera
  // sees a cell anywhere in its image; 0: it looks at the cell)
  double max_turn = 0;
  std::uint64_t seed = 0;
};

// The void cells a request aims at (req.cells of them, exposed ones first, or every cell with
// req.every_cell, at most req.max_cells), in a deterministic order for req.seed.
std::vector<CellKey> draw_void_cells(const ExplorationState& S, const AimRequest& req);

// Poses (camera -> map) looking from an eye at a void cell. The eye is found along a ray out of the cell:
// the ray crosses unknown cells, then observed-free ones (unknown cells outside the search space count as
// free, as in the camera clearance), and ends at the first occupied cell or at the first unknown cell of the
// search space after free space that is not a void cell (void cells past free space are crossed: a box's
// inside seen in patches, and also an unseen wall inside the hull; the score weighs what lies behind them).
// The eye is a cell of the free stretch `distance` from the cell (tried in random order) where the camera is
// clear (checker.camera_clear), inside opt's workspace box and sphere, above min_height and, with a capability
// map, reachable there. Its optical axis points at the cell or, when the capability map rules that axis out,
// is the map's reachable direction nearest to it within req.max_turn (checker.turned_axes, reachable_axis).
// The rays are walked in a random order of (cell, ray) until req.poses eyes are found (a random sample of all
// the rays' eyes). Deterministic for the seed whatever the thread count. The caller holds the map's lock.
std::vector<Pose> aim_at_voids(const ExplorationMap& map, const ViewChecker& checker, const NbvOptions& opt,
                               const AimRequest& req);

// The second look's poses: up to req.poses, each looking at one of req.cells void cells (drawn as
// aim_at_voids draws them) from an eye req.distance away in a random direction of the upper half sphere
// (a camera does not look up from under the floor), above min_height, inside opt's workspace box and
// sphere, with no occupied cell of the map on the segment past the cell's own (unknown cells may lie on
// it: they may be seen through; else aims at the last slivers of an open crate look through its wall).
// The eye's clearance and reach are left to the scoring. Deterministic for the seed; the caller holds
// the map's lock.
std::vector<Pose> aim_along_sight(const ExplorationMap& map, const NbvOptions& opt, const AimRequest& req);

}  // namespace octoreach::detail
