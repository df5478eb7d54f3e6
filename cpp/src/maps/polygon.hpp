#pragma once
// Private: the 2D polygon algorithms of Surface: is a polygon simple, and its triangles.
#include <array>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace octoreach::detail {

/// z of the cross product of two 2D vectors.
inline double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// A pair of edges (i < j, not adjacent; edge i runs from vertex i to i + 1) that cross or touch within
/// `eps`, or {n, n} when there is none: polygons of up to kAllPairsEdges edges get all_pairs_crossing (the
/// first pair in (i, j) order), larger ones sweep_crossing.
std::pair<std::size_t, std::size_t> crossing_edges(const std::vector<Eigen::Vector2d>& polygon, double eps);
inline constexpr std::size_t kAllPairsEdges = 256;
/// Every pair tested in (i, j) order: n^2 / 2 tests.
std::pair<std::size_t, std::size_t> all_pairs_crossing(const std::vector<Eigen::Vector2d>& polygon, double eps);
/// A vertical line swept across the edges (Shamos and Hoey): O(n log n); some crossing pair, not
/// necessarily the first.
std::pair<std::size_t, std::size_t> sweep_crossing(const std::vector<Eigen::Vector2d>& polygon, double eps);

/// Throws std::invalid_argument unless the polygon is simple: no spike of zero width, no edges crossing
/// or touching (the message names them).
void check_simple(const std::vector<Eigen::Vector2d>& polygon, double eps);

/// Triangles (vertex indices) of a simple polygon by ear clipping (counter-clockwise, or `clockwise`).
std::vector<std::array<int, 3>> ear_clip(const std::vector<Eigen::Vector2d>& polygon, bool clockwise);

}  // namespace octoreach::detail
