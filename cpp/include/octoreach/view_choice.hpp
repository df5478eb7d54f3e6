#pragma once
/// \file view_choice.hpp
/// \brief The exploration loop's whole choice of the next view: the search (next_best_view or a baseline's
/// sampled poses), the second looks aimed at void cells, the last-chance look along rays out of every void
/// cell, and the stop decision. explore() and the Explorer call it once per view; what it must remember
/// between views (low views in a row, what the last view saw, cameras of views not taken) is a ChoiceMemory the
/// caller keeps.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "octoreach/next_best_view.hpp"

namespace octoreach {

/// \brief How views are picked: frontier-void (ours) or one of the baselines, in the same harness.
enum class ViewStrategy {
  FrontierVoid,  ///< next_best_view ranked by expected void cells, with the second looks
  Random,        ///< the first valid of sampled reachable poses (stops on the best void gain on offer)
  Frontiers,     ///< the valid sampled pose with the most expected frontier cells
  Unknown,       ///< the valid sampled pose with the most expected unknown cells (nbvplanner's gain)
};
/// \brief "frontier_void", "random", "frontiers" or "unknown".
const char* strategy_name(ViewStrategy s);
/// \brief The strategy of a name; \throws std::invalid_argument naming the four choices.
ViewStrategy strategy_from_name(const std::string& name);

/// \brief Where the camera's carrier may stand: chain base poses (chain base -> map; the camera's chain is
/// ExploreOptions::search.chain) and, with a chain and no workspace in the search, the reach (m) around
/// each base's origin that bounds the camera positions (0: no bound). Without a chain: one identity base.
struct ViewSites {
  std::vector<Pose> bases{Pose::Identity()};
  double reach = 0.0;
};

/// \brief What the loop remembers between choices (plain data, copyable).
struct ChoiceMemory {
  int choices = 0;    ///< views chosen so far
  /// Choices in a row whose utility was <= min_utility (frontier-void's utility, also where a view beyond the
  /// voids was taken instead).
  int low_views = 0;
  /// Void cells the last view taken took off the void set (InsertStats::void_removed of its inserts: cells it
  /// turned known, and rarely cells the hull's numerical merging left out), set by the caller after the insert
  /// (Explorer::integrate adds them up): for frontier-void and random, whose utility counts void cells, a low
  /// view that saw more than the stop threshold breaks the row of low views, since what a view saw outweighs
  /// what it was expected to see. Read and cleared by the next choice.
  std::optional<std::size_t> last_void_seen;
  /// Cameras of views that were chosen and not taken (a motion that failed): no view is chosen within
  /// ExploreOptions::failed_view_radius of them again.
  std::vector<Eigen::Vector3d> failed_views;
  /// Unknown cells of the search space the last view taken made known (InsertStats::space_known of its inserts),
  /// set by the caller after the insert like last_void_seen (Explorer::integrate adds them up); read and cleared
  /// by the next choice. Frontier-void only: see beyond_misses.
  std::optional<std::size_t> last_space_seen;
  /// frontier-void: views beyond the voids (ViewChoice::beyond) in a row that saw no more than the stop threshold
  /// of the search space's unknown cells; at ExploreOptions::patience no view beyond the voids is chosen until a
  /// view sees more than that (what views saw outweighs what they were expected to see)
  int beyond_misses = 0;
  bool last_beyond = false;  ///< the last choice was a view beyond the voids
};

/// \brief The answer of choose_view: the view (when found), its utility and whether the loop stops.
struct ViewChoice {
  bool found = false;     ///< a valid view was found (view, base are set)
  ViewCandidate view;     ///< camera pose, joints q, gains
  int base = 0;           ///< index of the base in ViewSites::bases the view is taken from
  double utility = 0.0;   ///< the gain the stop rule looks at (the strategy's: expected void cells for ours)
  std::size_t candidates = 0, valid = 0;  ///< poses scored and of them valid (of those checked: see choose_view)
  bool aimed = false;     ///< found by a look aimed at void cells, not by the search
  bool harder = false;    ///< found by the looks before a low view (more aims, the last chance)
  /// frontier-void (ExploreOptions::beyond_voids): a view beyond the voids, the sampled view expecting the most
  /// unknown cells of the search space, whose expected_unknown is then the utility; taken where it expects more
  /// of them than frontier-void's view expects void cells, or where frontier-void's own choice would end the loop
  bool beyond = false;
  bool stop = false;      ///< the loop ends here (the view, when found, is a low view that need not be taken)
  std::string stop_reason;  ///< "nothing to explore", "no valid view", "utility 0", "utility below min_utility"
  NbvResult search;       ///< frontier_void: next_best_view's answer from the chosen base
};

/// \brief The next view of `strategy` from any of the sites' bases (the current one first, so ties keep it),
/// with options.search (its seed: this choice's; the loop's view k searches with the run's seed + k). Updates memory
/// (choices, low_views) and decides the stop: no void cell ("nothing to explore"; but while no cell of a finite search
/// space is known, the sampled view expected to see the most of its unknown cells comes first, as the unknown
/// baseline picks it), no valid view, a utility
/// of 0, or a utility <= min_utility for `patience` choices in a row (frontier-void and random: a low view taken
/// that saw more void cells than min_utility, memory.last_void_seen, breaks the row). Frontier-void: next_best_view, then
/// (second_look) aimed_poses poses aimed at void cells; when the better still expects <= min_utility,
/// low_aimed_poses more and, when the choice would end the loop (that low view is patience's last, or no valid
/// view or only views of utility 0 were found), last_poses found along rays out of every void cell, their optical
/// axes turned by up to half the camera's narrower field angle to one the capability map reaches (at roll 0, as
/// score_views checks a pose). With options.search.rescore_best = n > 0 (and a chain that does more than aim its
/// camera), each aimed look scores its poses with the coarse grid first and checks IK in that order until n are
/// valid, those n scored in full (`valid` counts the valid ones among the poses checked); more than 16 n poses
/// are ranked first with every fourth ray and go through those steps in chunks of 16 n in that order. With
/// options.beyond_voids, frontier-void's view gives way to a view beyond the voids (ViewChoice::beyond; memory's
/// last_beyond, beyond_misses) where that expects more unknown cells of the search space than it expects void cells.
/// \throws std::invalid_argument for bad options, sites or a current index out of range.
ViewChoice choose_view(const ExplorationMap& map, const CameraIntrinsics& camera, const ViewSites& sites,
                       int current, const ExploreOptions& options, ChoiceMemory& memory,
                       ViewStrategy strategy = ViewStrategy::FrontierVoid);

}  // namespace octoreach
